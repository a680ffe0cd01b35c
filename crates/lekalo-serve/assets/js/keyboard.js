// The canvas by keyboard (Tab to the canvas, which then shows a cross):
//   arrow keys          move the cross, or the selected point with it (Shift: ten times farther)
//   Enter, Space        place a point at the cross (as a click there)
//   N, P                select the next or previous point (the cross jumps to it)
//   Escape              select no point
//   Delete, Backspace   delete the selected point (as Alt+click)
import { $, DEFAULT_WORLD, r4, sx, sy } from './screen.js';
import { commit, editable, setEditable, state, ui } from './state.js';
import { addPointAt, deletePoint } from './pointer.js';
import { drawPoints } from './draw.js';
import { syncWeight } from './modes/bspline.js';
import { update } from './schedule.js';

// one step of the arrow keys in world units (a tenth of a grid square of the default view)
const STEP = 0.1;
const cross = [(DEFAULT_WORLD.x0 + DEFAULT_WORLD.x1) / 2, (DEFAULT_WORLD.y0 + DEFAULT_WORLD.y1) / 2];

function drawCross() {
  const c = $('kbd-cross');
  const [x, y] = [sx(cross[0]), sy(cross[1])];
  c.setAttribute('d', `M${x - 9} ${y}L${x + 9} ${y}M${x} ${y - 9}L${x} ${y + 9}`);
}

function select(i) {
  ui.selected = i;
  const pts = editable();
  if (i >= 0 && i < pts.length) { cross[0] = pts[i][0]; cross[1] = pts[i][1]; }
  syncWeight();
  drawPoints();
  drawCross();
}

const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };

function onKey(e) {
  if (e.ctrlKey || e.metaKey || e.altKey || state.mode === 'quasi') return;
  const pts = editable();
  const n = pts.length;
  const key = e.key.length === 1 ? e.key.toLowerCase() : e.key;
  if (ARROWS[key]) {
    const [dx, dy] = ARROWS[key];
    const step = e.shiftKey ? 10 * STEP : STEP;
    cross[0] = r4(cross[0] + dx * step);
    cross[1] = r4(cross[1] + dy * step);
    if (ui.selected >= 0 && ui.selected < n) {
      setEditable(ui.selected, [cross[0], cross[1]]);
      drawPoints();
      commit();
      update();
    }
    drawCross();
  } else if (key === 'Enter' || key === ' ') {
    addPointAt([cross[0], cross[1]]);
    select(editable().length - 1);
  } else if ((key === 'n' || key === 'p') && n > 0) {
    const from = ui.selected >= 0 && ui.selected < n ? ui.selected : (key === 'n' ? -1 : 0);
    select(((from + (key === 'n' ? 1 : -1)) % n + n) % n);
  } else if (key === 'Escape') {
    select(-1);
  } else if ((key === 'Delete' || key === 'Backspace') && ui.selected >= 0 && ui.selected < n) {
    deletePoint(ui.selected);
  } else {
    return;
  }
  e.preventDefault();
}

export function bindKeyboard() {
  const canvas = $('canvas');
  canvas.addEventListener('keydown', onKey);
  canvas.addEventListener('focus', () => { drawCross(); $('kbd-cross').setAttribute('visibility', 'visible'); });
  canvas.addEventListener('blur', () => $('kbd-cross').setAttribute('visibility', 'hidden'));
}
