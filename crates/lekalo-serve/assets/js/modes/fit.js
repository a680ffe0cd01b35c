// Mode "Fitting: smoothing noisy points" (POST /api/fit): the penalty λ, λ by cross-validation
// or the residual target s, a slider over log λ or log s, and the shape of y(x) (increasing,
// decreasing, convex, concave, y ≥ a, y ≤ b), drawn with the bounds the fit is held within.
import { $, plural } from '../screen.js';
import { noisyPoints, state } from '../state.js';
import { post } from '../api.js';

const SHAPES = ['increasing', 'decreasing', 'convex', 'concave'];

// the bounds ticked, as numbers (an empty field is no bound)
function bounds(shape) {
  const out = {};
  for (const k of ['min', 'max']) if (shape[k] !== undefined && shape[k] !== '') out[k] = Number(shape[k]);
  return out;
}

export const mode = {
  fewest: 3,
  point: 'data point',
  help: 'Noisy points (click to add, drag, Alt+click to delete) smoothed by the library: move the slider to trade the residual against smoothness; tick a shape to make the fit of y(x) keep it everywhere; a bound y ≥ a or y ≤ b is drawn as a dashed line.',
  compute(s, view) {
    const f = s.fit;
    const req = Object.assign({ points: f.points, smoothing: f.smoothing }, view);
    if (f.smoothing === 'lambda') req.lambda = Math.pow(10, f.lambda);
    if (f.smoothing === 's') req.s = Math.pow(10, f.s);
    // shape constraints: the points are samples y(x) of a function (the server says so)
    const shape = f.shape || {};
    for (const k of SHAPES) if (shape[k]) req[k] = true;
    Object.assign(req, bounds(shape));
    return post('/api/fit', req);
  },
  // the bounds of the request that was drawn
  others() {
    const b = bounds(state.fit.shape || {});
    const out = [];
    // `outside`: the side of the line the fit never goes to (+1 below, -1 above)
    if (b.min !== undefined) out.push({ y: b.min, text: `y ≥ ${b.min}`, outside: 1 });
    if (b.max !== undefined) out.push({ y: b.max, text: `y ≤ ${b.max}`, outside: -1 });
    return { bounds: out };
  },
  show(answer) {
    const r = answer.report;
    $('fit-info').textContent = `residual max ${r.max_residual.toPrecision(4)} (point ${r.max_index}), RMS ${r.rms.toPrecision(4)}; ` +
      `${plural(r.interior_knots, 'interior knot')}, ${plural(r.control_points, 'control point')}` +
      (r.lambda !== null ? `; λ = ${r.lambda.toPrecision(4)}` : '');
  },
  sync(s) {
    $('fit-mode').value = s.fit.smoothing;
    $('fit-slider-label').hidden = s.fit.smoothing === 'gcv';
    $('fit-name').textContent = s.fit.smoothing === 's' ? 's' : 'λ';
    // log10 λ from -9 to 1 (λ weighs ∫|f''|² against the squared residuals), log10 s from -2 to 2
    $('fit-slider').min = s.fit.smoothing === 's' ? -2 : -9;
    $('fit-slider').max = s.fit.smoothing === 's' ? 2 : 1;
    $('fit-slider').value = s.fit.smoothing === 's' ? s.fit.s : s.fit.lambda;
    $('fit-value').textContent = '= ' + Math.pow(10, Number($('fit-slider').value)).toPrecision(3);
    const shape = s.fit.shape || {};
    for (const k of SHAPES) $(`fit-${k}`).checked = !!shape[k];
    for (const k of ['min', 'max']) $(`fit-${k}`).value = shape[k] === undefined ? '' : shape[k];
  },
  bind(act) {
    $('fit-mode').addEventListener('change', () => { state.fit.smoothing = $('fit-mode').value; act.commit(); act.syncControls(); act.update(); });
    $('fit-slider').addEventListener('input', () => {
      state.fit[state.fit.smoothing === 's' ? 's' : 'lambda'] = Number($('fit-slider').value);
      $('fit-value').textContent = '= ' + Math.pow(10, Number($('fit-slider').value)).toPrecision(3);
      act.update();
    });
    $('fit-slider').addEventListener('change', act.commit);
    for (const k of SHAPES) {
      $(`fit-${k}`).addEventListener('change', () => {
        state.fit.shape = Object.assign({}, state.fit.shape, { [k]: $(`fit-${k}`).checked });
        act.commit(); act.syncControls(); act.update();
      });
    }
    for (const k of ['min', 'max']) {
      $(`fit-${k}`).addEventListener('change', () => {
        state.fit.shape = Object.assign({}, state.fit.shape, { [k]: $(`fit-${k}`).value });
        act.commit(); act.syncControls(); act.update();
      });
    }
    $('fit-noise').addEventListener('click', () => {
      state.fit.points = noisyPoints(1 + Math.floor(Math.random() * 1e9));
      act.commit(); act.update();
    });
  },
};
