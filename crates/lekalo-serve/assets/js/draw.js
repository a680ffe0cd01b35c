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
  $('crossing-marks').textContent = '';
  $('bounds').textContent = '';
  $('bound-labels').textContent = '';
  forgetPanels();
  drawPoints();
  hideProjection();
  $('length-mark').setAttribute('visibility', 'hidden');
  for (const id of ['fit-info', 'bz-info', 'qi-info', 'query-info', 'query-at', 'query-crossings']) $(id).textContent = '';
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
  drawBounds(others.bounds || [], v, pts);
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
  // grid lines with their coordinates: x along the bottom edge, y along the left edge, every
  // label half a font size (about 5 screen pixels) inside the canvas, so that on a phone they do
  // not touch its edge; a label whose box would leave the canvas or meet the other row is left out
  const label = (v, step) => String(Number(v.toFixed(Math.max(0, -Math.floor(Math.log10(step))))));
  const size = Number(font);
  const margin = 0.5 * size;
  // a text's box around its baseline (ascent and descent of the sans-serif fonts) and width
  const [ascent, descent] = [0.95 * size, 0.3 * size];
  const width = (text) => 0.62 * size * text.length;
  const xBaseline = H - margin - descent;
  const xRowTop = xBaseline - ascent;
  const step = niceStep((world.x1 - world.x0) / 10);
  for (let x = Math.ceil(world.x0 / step) * step; x <= world.x1; x += step) {
    el('line', { x1: sx(x), x2: sx(x), y1: 0, y2: H, class: 'gridline' }, g);
    const text = label(x, step);
    const half = width(text) / 2;
    if (sx(x) - half < margin || sx(x) + half > W - margin) continue;
    el('text', { x: sx(x), y: xBaseline, class: 'grid-label', 'font-size': font, 'text-anchor': 'middle' }, g).textContent = text;
  }
  const ystep = niceStep((world.y1 - world.y0) / 6);
  for (let y = Math.ceil(world.y0 / ystep) * ystep; y <= world.y1; y += ystep) {
    el('line', { x1: 0, x2: W, y1: sy(y), y2: sy(y), class: 'gridline' }, g);
    const baseline = sy(y) - 3;
    if (baseline - ascent < margin || baseline + descent > xRowTop - 2) continue;
    el('text', { x: margin, y: baseline, class: 'grid-label', 'font-size': font }, g).textContent = label(y, ystep);
  }
}

// the bounds `y ≥ a`, `y ≤ b` a fit is held within: a dashed line over the fit's x range
// (under the curve), each labelled where its text covers no curve, point or other label:
// `placeLabel` tries the side of the line the fit never goes to first (below y ≥ a, above
// y ≤ b), from the right end of the line leftwards, then the side the fit keeps to
function drawBounds(bounds, v, curve) {
  const g = $('bounds'), labels = $('bound-labels');
  g.textContent = '';
  labels.textContent = '';
  const [x0, x1] = v.domain;
  const segments = [];
  for (let i = 1; i < curve.length; i++) {
    segments.push([sx(curve[i - 1][0]), sy(curve[i - 1][1]), sx(curve[i][0]), sy(curve[i][1])]);
  }
  const dots = editable().map((p) => [sx(p[0]), sy(p[1])]);
  // the labels keep a readable size on screen however the drawing is scaled (as the grid's)
  const shown = $('canvas').getBoundingClientRect().width || W;
  const size = Math.min(26, 13 * W / shown);
  // the room the labels may use: the canvas without the grid's coordinates (drawGrid's font)
  const grid = Math.min(24, 11 * W / shown);
  // (three characters of y coordinates half a size from the left edge, the row of x coordinates
  // 1.75 sizes high at the bottom)
  const room = [0.5 * grid + 3 * 0.62 * grid + 3, 0, W, H - 1.75 * grid - 2];
  const placed = [];
  for (const { y, text, outside } of bounds) {
    el('line', { x1: sx(x0), x2: sx(x1), y1: sy(y), y2: sy(y), class: 'bound', 'data-bound': text }, g);
    const t = el('text', { x: 0, y: 0, class: 'bound-label', 'text-anchor': 'end', 'font-size': size.toFixed(1) }, labels);
    t.textContent = text;
    placed.push(placeLabel(t, [sx(x0), sx(x1), sy(y)], outside, size, room, segments, dots, placed));
  }
}

// the box [left, top, right, bottom] of a label of font size `size` and width `w`, its right end
// at `right`, on the side `side` (-1 above, +1 below) of the line at height `ly`
function labelBox(right, ly, side, size, w) {
  const gap = 0.4 * size, height = 1.2 * size;
  const top = side < 0 ? ly - gap - height : ly + gap;
  return [right - w - 3, top, right + 3, top + height];
}

// how many curve segments, points (radius 6) and labels the box covers; a box outside the
// room [left, top, right, bottom] the labels may use covers too much to be used
function covered(box, room, segments, dots, placed) {
  const [l, t, r, b] = box;
  if (l < room[0] || t < room[1] || r > room[2] || b > room[3]) return Infinity;
  let n = 0;
  for (const s of segments) if (segmentMeetsBox(s, box)) n++;
  for (const [x, y] of dots) if (x > l - 6 && x < r + 6 && y > t - 6 && y < b + 6) n++;
  for (const o of placed) if (l < o[2] && o[0] < r && t < o[3] && o[1] < b) n++;
  return n;
}

// a segment [x1, y1, x2, y2] meets the box (Liang–Barsky clipping)
function segmentMeetsBox([x1, y1, x2, y2], [l, t, r, b]) {
  let u0 = 0, u1 = 1;
  const dx = x2 - x1, dy = y2 - y1;
  for (const [p, q] of [[-dx, x1 - l], [dx, r - x1], [-dy, y1 - t], [dy, b - y1]]) {
    if (p === 0) { if (q < 0) return false; continue; }
    const u = q / p;
    if (p < 0) { if (u > u1) return false; if (u > u0) u0 = u; } else { if (u < u0) return false; if (u < u1) u1 = u; }
  }
  return true;
}

// places the text `t` of a bound's line [left, right, height] at the first position whose box
// covers nothing (else the one covering least) and answers that box
function placeLabel(t, [left, right, ly], outside, size, room, segments, dots, placed) {
  const w = t.getComputedTextLength();
  let best = null;
  for (const side of [outside, -outside]) {
    // from the right end of the line to its left end, then beside the y axis
    const ends = [];
    for (let r = Math.min(right, W - 4); r - w >= Math.max(left, room[0]) - 1; r -= Math.max(8, w / 3)) ends.push(r);
    ends.push(room[0] + w + 4);
    for (const r of ends) {
      const box = labelBox(r, ly, side, size, w);
      const n = covered(box, room, segments, dots, placed);
      if (!best || n < best.n) best = { n, box, r, side };
      if (n === 0) break;
    }
    if (best.n === 0) break;
  }
  t.setAttribute('x', best.r);
  t.setAttribute('y', best.box[1] + 0.95 * size);
  return best.box;
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
