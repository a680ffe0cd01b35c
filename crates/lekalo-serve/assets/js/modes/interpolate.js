// Mode "Interpolation" (POST /api/interpolate): data points, degree, parametrisation, knot
// placement, end condition; with end tangents, two handles dragged on the canvas.
import { $ } from '../screen.js';
import { state } from '../state.js';
import { post } from '../api.js';
import { bindNumber, degreeNote } from './common.js';

export const mode = {
  fewest: 2,
  point: 'data point',
  help: 'Click to add a data point, drag to move, Alt+click to delete. With end tangents, drag the two handles.',
  compute(s, view, n) {
    const it = s.interpolate;
    const degree = Math.min(it.degree, n - 1);
    // natural and end-tangent conditions are for cubics: a lower degree is drawn with free ends
    const end = degree < it.degree && (it.end === 'natural' || it.end === 'derivatives') ? 'free' : it.end;
    const req = Object.assign({ points: it.points, degree, parametrization: it.param,
      knots: it.knots, end }, view);
    if (end === 'derivatives') { req.start_derivative = it.d0; req.end_derivative = it.d1; }
    const note = degreeNote(n, it.degree, degree, this.point) +
      (end !== it.end ? ` The ${it.end} end condition applies from degree ${it.degree}.` : '');
    return post('/api/interpolate', req).then((v) => ({ view: v, note }));
  },
  others() { return {}; },
  sync(s) {
    $('in-degree').value = s.interpolate.degree;
    $('in-param').value = s.interpolate.param;
    $('in-knots').value = s.interpolate.knots;
    $('in-end').value = s.interpolate.end;
  },
  bind(act) {
    bindNumber(act, $('in-degree'), (v) => { state.interpolate.degree = v; });
    for (const [id, key] of [['in-param', 'param'], ['in-knots', 'knots'], ['in-end', 'end']]) {
      $(id).addEventListener('change', () => { state.interpolate[key] = $(id).value; act.commit(); act.update(); });
    }
  },
};
