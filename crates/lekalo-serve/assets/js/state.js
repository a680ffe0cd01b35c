// The editor's state: the construction of every mode (what the URL after # keeps), undo and
// redo over it, and the passing state of the page (selection, cursor, last answer).
import { r4 } from './screen.js';

export function defaultState() {
  return {
    mode: 'bspline',
    comb: false,
    bspline: { degree: 3, control: [[1, 1], [2.5, 4.5], [5, 5], [7, 1.5], [9, 4]], knots: null, weights: null },
    interpolate: { degree: 3, param: 'chord', knots: 'auto', end: 'free',
      points: [[1, 2], [3, 4.5], [5, 2.5], [7, 4], [9, 2]], d0: [2, 2], d1: [2, -2] },
    bezier: { control: [[1, 1], [3, 5], [7, 5], [9, 1]] },
    blend: { k: 2, a: [[1, 2], [3, 5.5], [7, 5.5], [9, 2]], b: [[3, 0.5], [7, 0.5]] },
    corners: { k: 2, window: 25, points: [[1, 1], [3, 5], [5, 1.5], [7, 5], [9, 1]] },
    spline: { k: 2, closed: false, points: [[1, 1], [3, 5], [5, 1.5], [7, 5], [9, 1]] },
    quasi: { expr: 'x*cos(x)', breaks: '0, 0.5, 0.9, 1.4, 2.1, 2.7, 3', order: 3, rule: 'first-knot-after', tau: '' },
    fit: { smoothing: 'lambda', lambda: -4, s: 0, points: noisyPoints(1), shape: {} },
    query: false,
    queryLength: 1,
  };
}

// 40 samples of a wave with deterministic noise (a linear congruential generator seeded by
// `seed`), so that a shared link shows the same points
export function noisyPoints(seed) {
  let r = seed >>> 0;
  const rand = () => { r = (Math.imul(r, 1664525) + 1013904223) >>> 0; return r / 4294967296 - 0.5; };
  const out = [];
  for (let i = 0; i < 40; i++) {
    const x = 0.6 + i * 8.8 / 39;
    out.push([r4(x + 0.1 * rand()), r4(3.1 + 1.8 * Math.sin(0.9 * x) + 0.7 * rand())]);
  }
  return out;
}

function loadHash() {
  if (location.hash.length < 2) return null;
  try {
    const s = JSON.parse(decodeURIComponent(location.hash.slice(1)));
    return Object.assign(defaultState(), s);
  } catch (e) {
    return null;
  }
}

// `state` is read everywhere (a live binding) and replaced only here, by undo and redo
export let state = loadHash() || defaultState();
const undoStack = [], redoStack = [];
let committed = JSON.stringify(state);
let restored = () => {};

// the page's passing state: the selected point, the parameter under the basis panel's pointer,
// the last answer drawn (for the queries, the knot drag, the exports and the tests)
export const ui = { selected: -1, cursorT: null, last: null };

// what to do after undo or redo replaced the state (set by main.js: sync the controls, compute)
export function onRestore(fn) { restored = fn; }

// records the state after a finished action (undo point, URL)
export function commit() {
  const now = JSON.stringify(state);
  if (now === committed) return;
  undoStack.push(committed);
  if (undoStack.length > 200) undoStack.shift();
  redoStack.length = 0;
  committed = now;
  history.replaceState(null, '', '#' + encodeURIComponent(now));
}

function restore(text) {
  state = JSON.parse(text);
  committed = text;
  history.replaceState(null, '', '#' + encodeURIComponent(text));
  ui.selected = -1;
  restored();
}

export function undo() { if (undoStack.length) { redoStack.push(committed); restore(undoStack.pop()); } }
export function redo() { if (redoStack.length) { undoStack.push(committed); restore(redoStack.pop()); } }

// the editable points of the current mode (blending: curve A's, then curve B's inner ones)
export function editable() {
  const s = state;
  switch (s.mode) {
    case 'bspline': return s.bspline.control;
    case 'interpolate': return s.interpolate.points;
    case 'bezier': return s.bezier.control;
    case 'blend': return s.blend.a.concat(s.blend.b);
    case 'corners': return s.corners.points;
    case 'spline': return s.spline.points;
    case 'fit': return s.fit.points;
    default: return [];
  }
}

export function setEditable(i, p) {
  const s = state;
  if (s.mode === 'blend') {
    const na = s.blend.a.length;
    if (i < na) s.blend.a[i] = p; else s.blend.b[i - na] = p;
  } else {
    editable()[i] = p;
  }
}
