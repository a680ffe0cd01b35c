// The blending modes (document 001): two curves deformed one into the other with C^k contact
// (POST /api/blend/deform), every corner of a polyline rounded (POST /api/blend/corners), and
// the curve through points by blending local parabolas (POST /api/blend/spline). Each answer
// carries the library's continuity of the result; the info line names the result as the library
// does: its kind and degree, its pieces and how smoothly they join.
import { $, plural } from '../screen.js';
import { state } from '../state.js';
import { post } from '../api.js';
import { bezierObject } from './bezier.js';
import { bindNumber } from './common.js';

// curve B shares the end points of curve A
export function blendCurves() {
  const a = state.blend.a, b = state.blend.b;
  return [bezierObject(a), bezierObject([a[0], ...b, a[a.length - 1]])];
}

// what the drawing asks of a blend: its samples and, when ticked, the curvature comb (the
// blending modes have no basis panel)
function drawn(view) { return { samples: view.samples, comb: view.comb }; }

// the polynomial pieces of the drawn curve: one between consecutive distinct knots
function pieces(v) { return plural(Math.max(1, v.knot_marks.length - 1), 'polynomial piece'); }

function kindAndDegree(v) {
  const kind = { bezier_curve: 'Bezier curve', bspline_curve: 'B-spline curve', nurbs_curve: 'NURBS curve' }[v.curve.type];
  return `${kind} of degree ${v.degree}`;
}

export const blend = {
  fewest: 0,
  point: 'point',
  help: 'Curve A (white points, grey dashed polygon) and curve B (pink points, red dashed polygon) share their end points; the solid curve is the C^k deformation of A into B. Click to add a point to B.',
  compute(s, view) {
    const [first, second] = blendCurves();
    return post('/api/blend/deform', { first, second, continuity: s.blend.k, ...drawn(view) })
      .then((v) => ({ view: v }));
  },
  others() { return { polygon: state.blend.a, dashed: blendCurves()[1].control }; },
  // one polynomial: a Bezier curve has no knots
  describe(answer) {
    const v = answer.view;
    return `${kindAndDegree(v)} (one polynomial piece, ${plural(v.control.length, 'control point')}): ` +
      `the deformation of A into B, C^${v.continuity} contact with A at the start and with B at the end`;
  },
  sync(s) { $('bl-k').value = s.blend.k; },
  bind(act) { bindNumber(act, $('bl-k'), (v) => { state.blend.k = v; }); },
};

export const corners = {
  fewest: 3,
  point: 'point',
  help: 'Click to add a point of the polyline (dashed), drag to move, Alt+click to delete; each corner is rounded over a window with C^k, turning one way.',
  compute(s, view) {
    const c = s.corners;
    return post('/api/blend/corners', { points: c.points, continuity: c.k, fraction: c.window / 100, ...drawn(view) })
      .then((v) => ({ view: v }));
  },
  others() { return { dashed: state.corners.points }; },
  describe(answer) {
    const v = answer.view;
    return `${kindAndDegree(v)} in ${pieces(v)} (straight parts and one per corner), C^${v.continuity} at every join`;
  },
  sync(s) { $('co-k').value = s.corners.k; $('co-window').value = s.corners.window; },
  bind(act) {
    bindNumber(act, $('co-k'), (v) => { state.corners.k = v; });
    bindNumber(act, $('co-window'), (v) => { state.corners.window = v; });
  },
};

export const spline = {
  fewest: 2,
  point: 'point',
  help: 'Click to add a point, drag to move, Alt+click to delete; the curve through the points blends local parabolas with C^k.',
  compute(s, view) {
    const c = s.spline;
    return post('/api/blend/spline', { points: c.points, continuity: c.k, closed: c.closed, ...drawn(view) })
      .then((v) => ({ view: v }));
  },
  others() { return { dashed: state.spline.points, closed: state.spline.closed }; },
  describe(answer) {
    const v = answer.view;
    return `${kindAndDegree(v)} in ${pieces(v)} (one between consecutive points), C^${v.continuity} at every join`;
  },
  sync(s) { $('sp-k').value = s.spline.k; $('sp-closed').checked = s.spline.closed; },
  bind(act) {
    bindNumber(act, $('sp-k'), (v) => { state.spline.k = v; });
    $('sp-closed').addEventListener('change', () => { state.spline.closed = $('sp-closed').checked; act.commit(); act.update(); });
  },
};
