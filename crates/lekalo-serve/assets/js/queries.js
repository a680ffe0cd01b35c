// Queries on the drawn curve (checkbox "closest point, length & self-intersections"): the point
// closest to the pointer (POST /api/project), the arc length and the point at a typed length
// from the start (POST /api/measure), and the points where the curve meets itself, each marked
// with the kind of contact the library names (POST /api/intersect without a second curve); the
// last two are asked by the computation loop with every drawing.
import { $, el, sx, sy } from './screen.js';
import { state, ui } from './state.js';
import { post } from './api.js';
import { showError } from './errors.js';
import { begin, end } from './idle.js';

// at most one projection in flight; pointer moves during it collapse into the next one
let projTarget = null, projRunning = false, projection = null;

export function projectTo(p) {
  projTarget = p;
  if (projRunning) return;
  projRunning = true;
  begin();
  (async () => {
    try {
      while (projTarget) {
        const q = projTarget;
        projTarget = null;
        if (!ui.last || !ui.last.view) break;
        try {
          const r = await post('/api/project', { curve: ui.last.view.curve, point: q });
          projection = { from: q, ...r };
          drawProjection();
        } catch (e) { showError(e); }
      }
    } finally { projRunning = false; end(); }
  })();
}

// the pointer left the canvas: no projection is asked for until it comes back
export function forgetTarget() { projTarget = null; hideProjection(); }

export function hideProjection() {
  projection = null;
  for (const id of ['proj-line', 'proj-foot']) $(id).setAttribute('visibility', 'hidden');
}

function drawProjection() {
  if (!projection || !state.query) { hideProjection(); return; }
  const { from, point } = projection;
  const line = $('proj-line');
  line.setAttribute('x1', sx(from[0])); line.setAttribute('y1', sy(from[1]));
  line.setAttribute('x2', sx(point[0])); line.setAttribute('y2', sy(point[1]));
  line.setAttribute('visibility', 'visible');
  const foot = $('proj-foot');
  foot.setAttribute('cx', sx(point[0])); foot.setAttribute('cy', sy(point[1]));
  foot.setAttribute('visibility', 'visible');
  $('query-info').dataset.projection = JSON.stringify(projection);
  drawQueryText();
}

// the measure answer of the last drawing and the closest point, as text
function drawQueryText() {
  const m = ui.last && ui.last.measure;
  let text = '';
  if (m && !m.error) text = `arc length ${m.length.toPrecision(8)} (error estimate ${m.error_estimate.toExponential(1)})`;
  if (projection) {
    text += `${text ? '; ' : ''}closest point t = ${projection.t.toPrecision(6)} at (${projection.point.map((x) => x.toFixed(4)).join(', ')}), distance ${projection.distance.toPrecision(4)}`;
  }
  $('query-info').textContent = text;
}

// the measure request that goes with a drawing: the length, and the point at the typed length
// once the curve has two control points (a curve of one is a point)
export function measure(view) {
  const along = (view.curve.control || []).length > 1 ? [state.queryLength] : [];
  return post('/api/measure', { curve: view.curve, at_length: along }).catch((e) => ({ error: e }));
}

// the self-intersections of a drawing: no request for a curve of fewer than two control points
export function selfIntersections(view) {
  if ((view.curve.control || []).length < 2) return Promise.resolve({ intersections: [] });
  return post('/api/intersect', { curve: view.curve }).catch((e) => ({ error: e }));
}

// a circle on every self-intersection point (data-kind: crossing, tangent, end or near-miss),
// and the kinds and parameters of all, overlaps (intervals) included, as text
function drawCrossings(answer) {
  const g = $('crossing-marks');
  g.textContent = '';
  const c = answer.crossings;
  if (!c || c.error || state.mode === 'quasi') {
    $('query-crossings').textContent = '';
    if (c && c.error) showError(c.error);
    return;
  }
  const words = [];
  for (const h of c.intersections) {
    const p = h.point;
    if (p) {
      el('circle', { class: 'crossing-mark', 'data-kind': h.kind, r: 7, cx: sx(p[0]), cy: sy(p[1]) }, g);
      const order = h.order ? ` of order ${h.order}` : '';
      const gap = h.gap ? ` (gap ${h.gap.toPrecision(3)})` : '';
      words.push(`${h.kind}${order}${gap} at t = ${h.t_a.toPrecision(6)} and ${h.t_b.toPrecision(6)}`);
    } else {
      words.push(`${h.kind} of t in [${h.a.map((t) => t.toPrecision(6)).join(', ')}] with [${h.b.map((t) => t.toPrecision(6)).join(', ')}]`);
    }
  }
  $('query-crossings').textContent = words.length
    ? `Self-intersections: ${words.join('; ')}.`
    : 'The curve does not meet itself.';
}

export function drawQuery(answer) {
  const mark = $('length-mark');
  const m = answer.measure;
  drawCrossings(answer);
  if (!m || state.mode === 'quasi') { mark.setAttribute('visibility', 'hidden'); hideProjection(); $('query-at').textContent = ''; return; }
  if (m.error) {
    mark.setAttribute('visibility', 'hidden');
    $('query-at').textContent = '';
    showError(m.error);
  } else if (!m.at_length.length) {
    mark.setAttribute('visibility', 'hidden');
    $('query-at').textContent = 'Place a second point to find a length along the curve.';
  } else {
    const a = m.at_length[0];
    mark.setAttribute('cx', sx(a.point[0])); mark.setAttribute('cy', sy(a.point[1]));
    mark.setAttribute('visibility', 'visible');
    $('query-at').textContent = `length ${a.length} from the start at t = ${a.t.toPrecision(8)}`;
  }
  // the curve changed: the closest point is stale until the pointer moves again
  hideProjection();
  drawQueryText();
}
