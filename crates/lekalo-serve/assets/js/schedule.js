// The computation loop: at most one computation in flight; changes made during it (a point
// dragged, a slider moved) collapse into the next one. Each computation asks the mode's route,
// with the queries' measure and self-intersections when they are on, then draws the answer or
// shows the error.
import { $, plural } from './screen.js';
import { editable, state, ui } from './state.js';
import { MODES } from './modes/index.js';
import { draw, drawEmpty, describeCurve } from './draw.js';
import { measure, selfIntersections } from './queries.js';
import { clearErrors, showError } from './errors.js';
import { setRunning } from './idle.js';

let pending = false, running = false;

export function update() {
  pending = true;
  if (!running) pump();
}

async function pump() {
  running = true;
  setRunning(true);
  while (pending) {
    pending = false;
    try {
      const answer = await compute();
      if (state.query && state.mode !== 'quasi' && answer.view) {
        answer.measure = await measure(answer.view);
        answer.crossings = await selfIntersections(answer.view);
      }
      clearErrors();
      show(answer);
    } catch (e) {
      showError(e);
    }
  }
  running = false;
  setRunning(false);
}

function compute() {
  const s = state, m = MODES[s.mode];
  const view = { samples: 400, comb: s.comb, basis_samples: 300 };
  if (ui.cursorT !== null) view.at = ui.cursorT;
  const n = editable().length;
  // below the fewest points the mode draws a curve from: the points alone and a note
  if (m.fewest !== undefined && n < m.fewest) {
    const note = n === 0
      ? 'Click on the canvas to place the first point.'
      : `Place ${plural(m.fewest - n, 'more point')} to draw a curve (${plural(n, m.point)} so far).`;
    return Promise.resolve({ empty: true, note });
  }
  return m.compute(s, view, n);
}

function show(answer) {
  if (answer.empty) { drawEmpty(answer); return; }
  const m = MODES[state.mode];
  draw(answer, m.others(answer));
  if (m.show) m.show(answer);
  const curve = describeCurve(answer.view);
  const text = m.describe ? m.describe(answer, curve) : curve;
  $('info').textContent = answer.note ? `${text}. ${answer.note}` : text;
}
