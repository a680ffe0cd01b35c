// The drawing's coordinates: the world (the construction's plane) mapped to the 800 × 500
// canvas, and the small SVG helpers every drawing module uses. No state of the construction.

export const W = 800, H = 500, PAD = 20;
export const SVGNS = 'http://www.w3.org/2000/svg';
export const $ = (id) => document.getElementById(id);

// the world rectangle shown on the canvas (the quasi-interpolation mode fits it to f)
export const DEFAULT_WORLD = Object.freeze({ x0: 0, x1: 10, y0: 0, y1: 6.25 });
export const world = { ...DEFAULT_WORLD };
export function setWorld(w) { Object.assign(world, w); }

export function sx(x) { return PAD + (x - world.x0) / (world.x1 - world.x0) * (W - 2 * PAD); }
export function sy(y) { return H - PAD - (y - world.y0) / (world.y1 - world.y0) * (H - 2 * PAD); }
export function wx(px) { return world.x0 + (px - PAD) / (W - 2 * PAD) * (world.x1 - world.x0); }
export function wy(py) { return world.y0 + (H - PAD - py) / (H - 2 * PAD) * (world.y1 - world.y0); }
// coordinates placed by the pointer are kept to four decimals (short URLs, readable files)
export function r4(v) { return Math.round(v * 1e4) / 1e4; }

export function pathOf(points, close) {
  if (!points || points.length === 0) return '';
  let d = 'M' + sx(points[0][0]).toFixed(2) + ' ' + sy(points[0][1]).toFixed(2);
  for (let i = 1; i < points.length; i++) {
    d += 'L' + sx(points[i][0]).toFixed(2) + ' ' + sy(points[i][1]).toFixed(2);
  }
  return close ? d + 'Z' : d;
}

export function el(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

// the world rectangle around `points`, with a margin above and below
export function fitWorld(points) {
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (const p of points) { x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]); }
  if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
  if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
  const py = (y1 - y0) * 0.08;
  setWorld({ x0, x1, y0: y0 - py, y1: y1 + py });
}

// a grid step of 1, 2 or 5 times a power of ten near `raw`
export function niceStep(raw) {
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

// the pointer's position in the SVG's own coordinates, however the page scales it
export function svgPoint(e, svg) {
  const r = svg.getBoundingClientRect();
  return [(e.clientX - r.left) * (svg.viewBox.baseVal.width / r.width), (e.clientY - r.top) * (svg.viewBox.baseVal.height / r.height)];
}

export function plural(n, word) { return `${n} ${word}${n === 1 ? '' : 's'}`; }
