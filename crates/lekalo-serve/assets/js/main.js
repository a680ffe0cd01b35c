// lekalo editor: every computation is a request to the server's JSON API (docs/serve.md); the
// page keeps the state, draws the answers and turns pointer moves into requests. The modules,
// by job:
//   screen.js     the world-to-canvas transform and SVG helpers
//   state.js      the construction of every mode, undo/redo, the URL
//   api.js        the API client: requests, the progress bar and Stop
//   schedule.js   the computation loop (one request in flight, the rest collapsed)
//   draw.js       the canvas; panels.js the knot ruler and the basis panel
//   queries.js    closest point and arc length
//   pointer.js    the pointer, Ctrl+Z/Y; keyboard.js the canvas by keyboard
//   files.js      import and export
//   errors.js     messages next to the control at fault; idle.js work in flight (for tests)
//   modes/        one module per mode: its request, its panel, its info line
//   main.js       the header's controls, the panels' visibility, start-up
import { $ } from './screen.js';
import { commit, defaultState, editable, onRestore, redo, state, ui, undo } from './state.js';
import { MODES } from './modes/index.js';
import { syncWeight } from './modes/bspline.js';
import { drawGrid } from './draw.js';
import { hideProjection } from './queries.js';
import { bindPointer } from './pointer.js';
import { bindKeyboard } from './keyboard.js';
import { bindFiles } from './files.js';
import { update } from './schedule.js';
import { idle } from './idle.js';
import { sx, sy } from './screen.js';

// the controls of every panel from the state, and which panels are shown
function syncControls() {
  const s = state;
  $('mode').value = s.mode;
  $('comb').checked = s.comb;
  for (const m of Object.values(MODES)) m.sync(s);
  $('query').checked = s.query;
  $('query-length').value = s.queryLength;
  $('query-panel').hidden = !s.query || s.mode === 'quasi';
  if (!s.query) hideProjection();
  // quasi-interpolation plots the functions f and q over x, not a curve of the plane: the comb
  // and the closest point do not apply there, and their boxes are greyed out saying so
  const planar = s.mode !== 'quasi';
  for (const id of ['comb', 'query']) {
    const label = $(id).closest('label');
    label.dataset.title = label.dataset.title ?? label.title;
    $(id).disabled = !planar;
    label.title = planar ? label.dataset.title : 'Not in quasi-interpolation: it draws the functions f and q over x, not a curve of the plane.';
  }
  document.querySelectorAll('.panel[data-mode]').forEach((p) => { p.hidden = p.dataset.mode !== s.mode; });
  // the lower panel: the basis functions, or for quasi-interpolation its error over them; the
  // blending modes have no basis to show
  const basis = !['blend', 'corners', 'spline'].includes(s.mode);
  $('basis').toggleAttribute('hidden', !basis);
  $('basis-caption').hidden = !basis;
  $('basis-caption').innerHTML = s.mode === 'quasi'
    ? 'The error f − q (red; scaled to the panel, with its zero line) over the basis functions.'
    : 'Basis functions N<sub>i,p</sub>: move the pointer over this panel to see which are active.';
  $('help').textContent = MODES[s.mode].help;
  syncWeight();
}

const act = { commit, update, syncControls };

function bind() {
  $('mode').addEventListener('change', () => { state.mode = $('mode').value; ui.selected = -1; ui.cursorT = null; commit(); syncControls(); update(); });
  $('comb').addEventListener('change', () => { state.comb = $('comb').checked; commit(); update(); });
  $('undo').addEventListener('click', undo);
  $('redo').addEventListener('click', redo);
  // Clear empties the canvas of the current mode, keeping its settings: points are then placed
  // one by one. Blending keeps curve A (the curve to deform) and clears curve B to the chord;
  // quasi-interpolation, which has no points, returns to its example.
  $('clear').addEventListener('click', () => {
    const s = state, m = s.mode;
    if (m === 'quasi') s.quasi = defaultState().quasi;
    else if (m === 'blend') s.blend.b = [];
    else {
      editable().length = 0;
      if (m === 'bspline') { s.bspline.knots = null; s.bspline.weights = null; }
    }
    ui.selected = -1;
    ui.cursorT = null;
    commit(); syncControls(); update();
  });
  $('query').addEventListener('change', () => { state.query = $('query').checked; commit(); syncControls(); update(); });
  $('query-length').addEventListener('change', () => { state.queryLength = Number($('query-length').value); commit(); update(); });
  for (const m of Object.values(MODES)) m.bind(act);
  bindPointer();
  bindKeyboard();
  bindFiles(act);
  onRestore(() => { ui.cursorT = null; syncControls(); update(); });
}

// for the browser tests
window.lekaloEditor = {
  get state() { return state; },
  get last() { return ui.last; },
  toScreen: (p) => [sx(p[0]), sy(p[1])],
  idle,
};

bind();
syncControls();
update();
// a resized window redraws the grid's coordinates at their on-screen size
window.addEventListener('resize', () => { if (ui.last && ui.last.view) drawGrid(); });
