// The panels under the canvas: the knot ruler (interior knots of a B-spline dragged there) and
// the basis functions N_{i,p} of the curve's knots, those non-zero at the pointer drawn bold;
// for quasi-interpolation the error f − q over them.
import { $, el, r4 } from './screen.js';
import { state } from './state.js';

// What the ruler and the basis panel were last drawn from: while it is unchanged (a control
// point dragged moves neither the knots nor the view) they are left as they are.
const drawnFrom = { ruler: null, basis: null };

// the ruler's and the basis panel's parameter axis: the domain [a, b] on x = 20 … 780
export function axis(a, b) { return (t) => 20 + (t - a) / (b - a || 1) * 760; }

// nothing drawn: the ruler and the basis panel empty
export function forgetPanels() {
  $('ruler-knots').textContent = '';
  $('basis-paths').textContent = '';
  drawnFrom.ruler = null;
  drawnFrom.basis = null;
}

// the knots, stacked by multiplicity; the interior ones of a B-spline are movable (data-knot)
export function drawRuler(v) {
  const editableKnots = state.mode === 'bspline';
  const key = [editableKnots, v.degree, v.domain.join(','), v.knots.join(',')].join('|');
  if (drawnFrom.ruler === key) return;
  drawnFrom.ruler = key;
  const g = $('ruler-knots');
  g.textContent = '';
  const [a, b] = v.domain;
  const rx = axis(a, b);
  let mult = 0; // copies of this knot before it (the knots are sorted)
  v.knots.forEach((t, i) => {
    const interior = i > v.degree && i < v.knots.length - v.degree - 1;
    mult = i > 0 && v.knots[i - 1] === t ? mult + 1 : 0;
    el('rect', { x: rx(t) - 4, y: 14 - mult * 7, width: 8, height: 6,
      class: 'ruler-knot' + (interior && editableKnots ? ' movable' : ''), 'data-knot': i }, g);
  });
  el('text', { x: 20, y: 40, class: 'ruler-label' }, g).textContent = r4(a);
  el('text', { x: 780, y: 40, class: 'ruler-label', 'text-anchor': 'end' }, g).textContent = r4(b);
}

const BASIS_COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf'];

export function drawBasis(basis, domain, v) {
  // the functions depend on the knots, the degree and the sampling; their colours on `active`
  const key = basis ? [v.degree, domain.join(','), v.knots.join(','), basis.t.length, basis.active.join(',')].join('|') : '';
  if (drawnFrom.basis === key) return;
  drawnFrom.basis = key;
  const g = $('basis-paths');
  g.textContent = '';
  if (!basis) return;
  const bx = axis(domain[0], domain[1]);
  const by = (y) => 150 - y * 135;
  const active = new Set(basis.active);
  for (const f of basis.functions) {
    let d = '';
    f.values.forEach((y, j) => {
      const t = basis.t[f.from + j];
      d += (j === 0 ? 'M' : 'L') + bx(t).toFixed(2) + ' ' + by(y).toFixed(2);
    });
    el('path', { d, class: 'basis-fn' + (active.has(f.i) ? ' active' : ''), stroke: BASIS_COLORS[f.i % BASIS_COLORS.length],
      'data-i': f.i }, g);
  }
}

// quasi-interpolation: the error f − q in the basis panel's place, over the basis functions
export function drawError(answer) {
  const g = $('basis-paths');
  const [a, b] = answer.view.domain;
  const emax = Math.max(1e-300, ...answer.error.map(Math.abs));
  const bx = axis(a, b);
  let d = '';
  answer.error.forEach((e, i) => { d += (i ? 'L' : 'M') + bx(answer.t[i]).toFixed(2) + ' ' + (80 - e / emax * 70).toFixed(2); });
  el('line', { x1: 20, x2: 780, y1: 80, y2: 80, class: 'axis zero-line' }, g);
  el('text', { x: 784, y: 84, class: 'ruler-label' }, g).textContent = '0';
  el('path', { d, class: 'error-plot', id: 'error-path' }, g);
  el('text', { x: 24, y: 14, class: 'ruler-label' }, g).textContent = `f − q (scaled to ±${emax.toExponential(2)})`;
  drawnFrom.basis = null; // the panel now holds more than the basis: drawn anew next time
}
