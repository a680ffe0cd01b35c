// Mode "B-spline / NURBS" (POST /api/bspline): control points, degree, knots dragged on the
// ruler, knot insertion and removal (POST /api/knot/insert, /api/knot/remove), the weight of
// the selected point (any weight ≠ 1 makes the curve NURBS).
import { $ } from '../screen.js';
import { commit, state, ui } from '../state.js';
import { post } from '../api.js';
import { showError } from '../errors.js';
import { tracked } from '../idle.js';
import { bindNumber, currentCurve, degreeNote } from './common.js';

export const mode = {
  fewest: 1,
  point: 'control point',
  help: 'Click to add a control point, drag to move, Alt+click to delete. Drag the interior knots on the ruler. Select a point to edit its weight (NURBS).',
  compute(s, view, n) {
    const b = s.bspline;
    const degree = Math.min(b.degree, n - 1);
    const req = Object.assign({ control: b.control, degree }, view);
    if (b.knots && degree === b.degree) req.knots = b.knots;
    if (b.weights) req.weights = b.weights;
    return post('/api/bspline', req).then((v) => ({ view: v, note: degreeNote(n, b.degree, degree, this.point) }));
  },
  others(answer) { return { polygon: answer.view.control }; },
  sync(s) { $('bs-degree').value = s.bspline.degree; syncWeight(); },
  bind(act) {
    bindNumber(act, $('bs-degree'), (v) => { state.bspline.degree = v; state.bspline.knots = null; });
    $('bs-weight').addEventListener('change', () => {
      if (ui.selected < 0) return;
      const b = state.bspline;
      if (!b.weights) b.weights = b.control.map(() => 1);
      b.weights[ui.selected] = Number($('bs-weight').value);
      act.commit(); act.update();
    });
    $('knot-insert').addEventListener('click', () => tracked(() => knotOp('/api/knot/insert', act)));
    $('knot-remove').addEventListener('click', () => tracked(() => knotOp('/api/knot/remove', act)));
  },
};

// the weight field shows the selected point's weight
export function syncWeight() {
  const w = state.bspline.weights;
  $('bs-weight').value = ui.selected >= 0 && w ? w[ui.selected] : 1;
}

async function knotOp(path, act) {
  try {
    const answer = await post(path, { curve: currentCurve('t'), t: Number($('knot-t').value) });
    const v = answer.view || answer;
    const b = state.bspline;
    b.control = v.control;
    b.knots = v.knots;
    b.weights = v.weights;
    commit();
    act.update();
  } catch (e) { showError(e); }
}
