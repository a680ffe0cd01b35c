// The pointer and the keyboard: click to add a point, drag a point, a tangent handle or an
// interior knot, Alt+click to delete, the basis panel's cursor, the closest point under the
// pointer; Ctrl+Z and Ctrl+Y. Listeners sit on the groups drawn into (points, handles, ruler),
// so redrawing never loses them.
import { $, r4, svgPoint, sx, sy, wx, wy } from './screen.js';
import { commit, editable, redo, setEditable, state, ui, undo } from './state.js';
import { HANDLE } from './draw.js';
import { axis } from './panels.js';
import { projectTo, forgetTarget } from './queries.js';
import { syncWeight } from './modes/bspline.js';
import { update } from './schedule.js';

let drag = null;

function startDrag(e, what) {
  e.preventDefault();
  e.stopPropagation();
  if (e.altKey && what.kind === 'point') { deletePoint(what.index); return; }
  drag = what;
  if (what.kind === 'point') { ui.selected = what.index; syncWeight(); }
  drag.element = e.target;
  document.addEventListener('pointermove', onDrag);
  document.addEventListener('pointerup', endDrag, { once: true });
}

function onDrag(e) {
  if (!drag) return;
  if (drag.kind === 'knot') {
    const [px] = svgPoint(e, $('ruler'));
    const b = state.bspline;
    const knots = b.knots || ui.last.view.knots.slice();
    const i = drag.index;
    // a knot moves between its neighbours: the order is the user's, as in the CLI
    const t = drag.a + (px - 20) / 760 * (drag.b - drag.a);
    knots[i] = Math.min(Math.max(t, knots[i - 1]), knots[i + 1]);
    b.knots = knots;
    update();
    return;
  }
  const [px, py] = svgPoint(e, $('canvas'));
  const p = [r4(wx(px)), r4(wy(py))];
  if (drag.kind === 'handle') {
    const it = state.interpolate, n = it.points.length;
    const base = drag.name === 'd0' ? it.points[0] : it.points[n - 1];
    it[drag.name] = [r4((p[0] - base[0]) / HANDLE), r4((p[1] - base[1]) / HANDLE)];
  } else {
    setEditable(drag.index, p);
    // the dragged point follows the pointer at once; the curve follows the answer
    drag.element.setAttribute('cx', sx(p[0]));
    drag.element.setAttribute('cy', sy(p[1]));
  }
  update();
}

function endDrag() {
  document.removeEventListener('pointermove', onDrag);
  drag = null;
  commit();
}

function addPoint(e) {
  if (state.mode === 'quasi' || e.button !== 0) return;
  const [px, py] = svgPoint(e, $('canvas'));
  addPointAt([r4(wx(px)), r4(wy(py))]);
}

// a new point at `p` (world coordinates): curve B's in blending, else the mode's last
export function addPointAt(p) {
  if (state.mode === 'quasi') return;
  const s = state;
  if (s.mode === 'blend') s.blend.b.push(p);
  else {
    editable().push(p);
    if (s.mode === 'bspline') {
      s.bspline.knots = null;
      if (s.bspline.weights) s.bspline.weights.push(1);
    }
  }
  commit();
  update();
}

// deletes point i (blending: curve A keeps its end points, which B shares)
export function deletePoint(i) {
  const s = state;
  if (s.mode === 'blend') {
    const na = s.blend.a.length;
    if (i >= na) s.blend.b.splice(i - na, 1); else if (i > 0 && i < na - 1) s.blend.a.splice(i, 1);
  } else {
    editable().splice(i, 1);
    if (s.mode === 'bspline') {
      s.bspline.knots = null;
      if (s.bspline.weights) s.bspline.weights.splice(i, 1);
    }
  }
  ui.selected = -1;
  commit();
  update();
}

export function bindPointer() {
  $('points').addEventListener('pointerdown', (e) => {
    const i = e.target.dataset.index;
    if (i !== undefined) startDrag(e, { kind: 'point', index: Number(i) });
  });
  $('handles').addEventListener('pointerdown', (e) => {
    const name = e.target.dataset.handle;
    if (name) startDrag(e, { kind: 'handle', name });
  });
  $('ruler-knots').addEventListener('pointerdown', (e) => {
    if (!e.target.classList.contains('movable') || !ui.last || !ui.last.view) return;
    const [a, b] = ui.last.view.domain;
    startDrag(e, { kind: 'knot', index: Number(e.target.dataset.knot), rx: axis(a, b), a, b });
  });
  $('canvas').addEventListener('pointermove', (e) => {
    if (!state.query || drag || state.mode === 'quasi') return;
    const [px, py] = svgPoint(e, $('canvas'));
    projectTo([wx(px), wy(py)]);
  });
  $('canvas').addEventListener('pointerleave', forgetTarget);
  $('canvas').addEventListener('pointerdown', addPoint);
  $('canvas').addEventListener('contextmenu', (e) => e.preventDefault());
  $('basis').addEventListener('pointermove', (e) => {
    if (!ui.last || !ui.last.view) return;
    const [px] = svgPoint(e, $('basis'));
    const [a, b] = ui.last.view.domain;
    ui.cursorT = Math.min(b, Math.max(a, a + (px - 20) / 760 * (b - a)));
    $('basis-cursor').setAttribute('x1', px);
    $('basis-cursor').setAttribute('x2', px);
    update();
  });
  // Ctrl+Z undoes, Ctrl+Y and Ctrl+Shift+Z redo; in a text field they edit the text
  document.addEventListener('keydown', (e) => {
    if (!(e.ctrlKey || e.metaKey) || e.target.matches('input[type=text]')) return;
    const key = e.key.toLowerCase();
    if (key === 'z' && !e.shiftKey) { e.preventDefault(); undo(); }
    if (key === 'y' || (key === 'z' && e.shiftKey)) { e.preventDefault(); redo(); }
  });
}
