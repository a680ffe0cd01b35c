// Drawing an answer on the canvas: the grid with its coordinates, the curve, its control
// polygon, the other curves of a mode (dashed), the curvature comb, the knots, the editable
// points and handles, and the bounds a fit is held within. Every number drawn is the API's.
import { $, DEFAULT_WORLD, H, W, el, fitWorld, niceStep, pathOf, plural, setWorld, sx, sy, world } from './screen.js';
import { editable, state, ui } from './state.js';
import { drawBasis, drawRuler, forgetPanels } from './panels.js';
import { drawQuery, hideProjection } from './queries.js';

// an end derivative d is drawn as a handle of length HANDLE·|d|
export const HANDLE = 0.25;

// What the grid was last drawn from: while it is unchanged it is left as it is.
let gridFrom = null;

// the curve of mode `m`, as drawn: quasi-interpolation plots q(x) over x
function curvePoints(m, v) { return m === 'quasi' ? v.points.map((p, i) => [v.t[i], p[0]]) : v.points; }

// nothing to draw yet: the points placed so far and a note
export function drawEmpty(answer) {
  ui.last = answer;
  setWorld(DEFAULT_WORLD);
  drawGrid();
  for (const id of ['curve', 'polygon', 'exact', 'other', 'other2', 'comb-path']) $(id).setAttribute('d', '');
  $('knot-marks').textContent = '';
  $('bounds').textContent = '';
  $('bound-labels').textContent = '';
  forgetPanels();
  drawPoints();
  hideProjection();
  $('length-mark').setAttribute('visibility', 'hidden');
  for (const id of ['fit-info', 'bz-info', 'qi-info', 'query-info', 'query-at']) $(id).textContent = '';
  $('info').textContent = answer.note;
}

// `others`: the dashed curves of the mode besides the answer's control polygon
export function draw(answer, others) {
  ui.last = answer;
  const m = state.mode;
  const v = answer.view;
  if (m === 'quasi') {
    fitWorld(answer.t.map((t, i) => [t, answer.exact[i]]).concat(curvePoints(m, v)));
  } else {
    setWorld(DEFAULT_WORLD);
  }
  drawGrid();
  const pts = curvePoints(m, v);
  $('curve').setAttribute('d', pathOf(pts));
  drawQuery(answer);
  $('polygon').setAttribute('d', others.polygon ? pathOf(others.polygon) : '');
  $('exact').setAttribute('d', m === 'quasi' ? pathOf(answer.t.map((t, i) => [t, answer.exact[i]])) : '');
  $('other').setAttribute('d', others.dashed ? pathOf(others.dashed, others.closed) : '');
  $('other2').setAttribute('d', '');
  drawBounds(others.bounds || [], v);
  drawComb(v, pts);
  drawKnots(v, m === 'quasi' ? (p, t) => [t, p[0]] : (p) => p);
  drawPoints();
  drawRuler(v);
  drawBasis(v.basis, v.domain, v);
}

export function drawGrid() {
  // the coordinates keep a readable size on screen however the drawing is scaled
  const shown = $('canvas').getBoundingClientRect().width || W;
  const font = Math.min(24, 11 * W / shown).toFixed(1);
  const key = [world.x0, world.x1, world.y0, world.y1, font].join(',');
  if (gridFrom === key) return;
  gridFrom = key;
  const g = $('grid');
  g.textContent = '';
  // grid lines with their coordinates: x along the bottom edge, y along the left edge
  const label = (v, step) => String(Number(v.toFixed(Math.max(0, -Math.floor(Math.log10(step))))));
  const step = niceStep((world.x1 - world.x0) / 10);
  for (let x = Math.ceil(world.x0 / step) * step; x <= world.x1; x += step) {
    el('line', { x1: sx(x), x2: sx(x), y1: 0, y2: H, class: 'gridline' }, g);
    if (sx(x) > 24) el('text', { x: sx(x), y: H - 4, class: 'grid-label', 'font-size': font, 'text-anchor': 'middle' }, g).textContent = label(x, step);
  }
  const ystep = niceStep((world.y1 - world.y0) / 6);
  for (let y = Math.ceil(world.y0 / ystep) * ystep; y <= world.y1; y += ystep) {
    el('line', { x1: 0, x2: W, y1: sy(y), y2: sy(y), class: 'gridline' }, g);
    if (sy(y) < H - 2 * font) el('text', { x: 4, y: sy(y) - 3, class: 'grid-label', 'font-size': font }, g).textContent = label(y, ystep);
  }
}

// the bounds `y ≥ a`, `y ≤ b` a fit is held within: a dashed line over the fit's x range
// (under the curve), labelled at its right end above the points (on the side of the line the
// fit keeps to, with a white halo)
function drawBounds(bounds, v) {
  const g = $('bounds'), labels = $('bound-labels');
  g.textContent = '';
  labels.textContent = '';
  const [x0, x1] = v.domain;
  for (const { y, text, below } of bounds) {
    el('line', { x1: sx(x0), x2: sx(x1), y1: sy(y), y2: sy(y), class: 'bound', 'data-bound': text }, g);
    el('text', { x: sx(x1), y: sy(y) + (below ? 16 : -7), class: 'bound-label', 'text-anchor': 'end' }, labels).textContent = text;
  }
}

function drawComb(v, pts) {
  if (!state.comb || !v.comb) { $('comb-path').setAttribute('d', ''); return; }
  const kmax = Math.max(1e-12, ...v.comb.curvature.filter((k) => k !== null));
  const scale = 1.2 / kmax; // longest tooth 1.2 world units
  let d = '';
  const tips = [];
  v.comb.curvature.forEach((k, i) => {
    const n = v.comb.normal[i];
    const p = pts[i];
    const tip = n && k !== null ? [p[0] - n[0] * k * scale, p[1] - n[1] * k * scale] : p;
    tips.push(tip);
    if (i % 4 === 0) d += 'M' + sx(p[0]) + ' ' + sy(p[1]) + 'L' + sx(tip[0]) + ' ' + sy(tip[1]);
  });
  $('comb-path').setAttribute('d', d + pathOf(tips));
}

function drawKnots(v, map) {
  const g = $('knot-marks');
  // the marks are moved, and only added or removed when their number changes
  while (g.children.length > v.knot_marks.length) g.lastChild.remove();
  while (g.children.length < v.knot_marks.length) el('rect', { width: 6, height: 6, class: 'knot' }, g);
  v.knot_marks.forEach((k, i) => {
    const p = map(k.point, k.t);
    g.children[i].setAttribute('x', sx(p[0]) - 3);
    g.children[i].setAttribute('y', sy(p[1]) - 3);
  });
}

// the editable points (circles with data-index) and the end-tangent handles (data-handle);
// pointer.js listens on their groups
export function drawPoints() {
  const g = $('points');
  const pts = editable();
  const cls = { interpolate: 'data', corners: 'data', spline: 'data', fit: 'data fit-data' }[state.mode] || 'cp';
  const na = state.blend.a.length;
  // the circles are kept while their number is unchanged: the one being dragged keeps its
  // pointer capture across redraws
  if (g.children.length !== pts.length) {
    g.textContent = '';
    pts.forEach((_, i) => el('circle', { r: 6, 'data-index': i }, g));
  }
  pts.forEach((p, i) => {
    const c = g.children[i];
    c.setAttribute('cx', sx(p[0]));
    c.setAttribute('cy', sy(p[1]));
    c.setAttribute('class', cls + (i === ui.selected ? ' selected' : '') +
      (state.mode === 'blend' && i >= na ? ' second' : ''));
  });
  const h = $('handles');
  h.textContent = '';
  if (state.mode === 'interpolate' && state.interpolate.end === 'derivatives') {
    const it = state.interpolate, n = it.points.length;
    [[it.points[0], it.d0, 'd0'], [it.points[n - 1], it.d1, 'd1']].forEach(([p, d, name]) => {
      const tip = [p[0] + d[0] * HANDLE, p[1] + d[1] * HANDLE];
      el('line', { x1: sx(p[0]), y1: sy(p[1]), x2: sx(tip[0]), y2: sy(tip[1]), class: 'handle-line' }, h);
      el('circle', { cx: sx(tip[0]), cy: sy(tip[1]), r: 5, class: 'handle', 'data-handle': name }, h);
    });
  }
}

// the name the library gives a curve's kind (lekalo::Curve::display_name)
export function curveKind(v) {
  return { bezier_curve: 'Bezier curve', bspline_curve: 'B-spline curve', nurbs_curve: 'NURBS curve' }[v.curve.type] || v.curve.type;
}

// the info line of a curve: its kind, degree, control points and, for a B-spline or NURBS
// curve, its knots (a Bezier curve is one polynomial piece and has none)
export function describeCurve(v) {
  const text = `${curveKind(v)} of degree ${v.degree}, ${plural(v.control.length, 'control point')}`;
  return v.curve.type === 'bezier_curve' ? text : `${text}, ${plural(v.knots.length, 'knot')}`;
}
