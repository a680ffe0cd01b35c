// Mode "Bezier order change" (POST /api/bezier/build to draw, POST /api/bezier to change the
// order): elevation, exact reduction to the real degree, approximate reduction with the
// deviation the library proves and samples.
import { $ } from '../screen.js';
import { commit, state } from '../state.js';
import { post } from '../api.js';
import { showError } from '../errors.js';
import { tracked } from '../idle.js';
import { currentCurve } from './common.js';

// the deviation of the last approximate reduction, shown until the next one
let deviation = null;

export function bezierObject(control) { return { lekalo: 1, type: 'bezier_curve', control }; }

export const mode = {
  fewest: 1,
  point: 'control point',
  help: 'Click to add a control point, drag to move, Alt+click to delete; then change the order.',
  compute(s, view) {
    return post('/api/bezier/build', Object.assign({ control: s.bezier.control }, view));
  },
  others(answer) { return { polygon: answer.view.control }; },
  describe(answer, text) { return `${text}; real degree ${answer.real_degree}`; },
  show(answer) {
    $('bz-info').textContent = `degree ${answer.degree}, real degree ${answer.real_degree}` +
      (deviation ? `; last approximate reduction: max deviation ${deviation.sampled.toExponential(3)} (bound ${deviation.bound.toExponential(3)})` : '');
  },
  sync() {},
  bind(act) {
    const op = (o) => tracked(() => bezierOp(o, act));
    $('bz-elevate').addEventListener('click', () => op({ op: 'elevate', by: 1 }));
    $('bz-reduce').addEventListener('click', () => op({ op: 'reduce_exact' }));
    $('bz-approx').addEventListener('click', () => op({ op: 'reduce_approx', target: Number($('bz-target').value), ends: $('bz-ends').value }));
  },
};

async function bezierOp(op, act) {
  try {
    currentCurve('by');
    const answer = await post('/api/bezier', Object.assign({ curve: bezierObject(state.bezier.control) }, op));
    deviation = answer.deviation;
    state.bezier.control = answer.view.control;
    commit();
    act.update();
  } catch (e) { showError(e); }
}
