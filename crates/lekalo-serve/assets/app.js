// lekalo editor: every computation is a request to the server's JSON API (docs/serve.md);
// this page only keeps the state, draws the answers and turns pointer moves into requests.
'use strict';

const W = 800, H = 500, PAD = 20;
const SVGNS = 'http://www.w3.org/2000/svg';
const $ = (id) => document.getElementById(id);

// ---------- state, undo/redo, URL ----------

function defaultState() {
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
function noisyPoints(seed) {
  let r = seed >>> 0;
  const rand = () => { r = (Math.imul(r, 1664525) + 1013904223) >>> 0; return r / 4294967296 - 0.5; };
  const out = [];
  for (let i = 0; i < 40; i++) {
    const x = 0.6 + i * 8.8 / 39;
    out.push([r4(x + 0.1 * rand()), r4(3.1 + 1.8 * Math.sin(0.9 * x) + 0.7 * rand())]);
  }
  return out;
}

let state = loadHash() || defaultState();
const undoStack = [], redoStack = [];
let committed = JSON.stringify(state);

function loadHash() {
  if (location.hash.length < 2) return null;
  try {
    const s = JSON.parse(decodeURIComponent(location.hash.slice(1)));
    return Object.assign(defaultState(), s);
  } catch (e) {
    return null;
  }
}

// records the state after a finished action (undo point, URL)
function commit() {
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
  syncControls();
  update();
}

function undo() { if (undoStack.length) { redoStack.push(committed); restore(undoStack.pop()); } }
function redo() { if (redoStack.length) { undoStack.push(committed); restore(redoStack.pop()); } }

// ---------- view transform (world → screen) ----------

let world = { x0: 0, x1: 10, y0: 0, y1: 6.25 };
function sx(x) { return PAD + (x - world.x0) / (world.x1 - world.x0) * (W - 2 * PAD); }
function sy(y) { return H - PAD - (y - world.y0) / (world.y1 - world.y0) * (H - 2 * PAD); }
function wx(px) { return world.x0 + (px - PAD) / (W - 2 * PAD) * (world.x1 - world.x0); }
function wy(py) { return world.y0 + (H - PAD - py) / (H - 2 * PAD) * (world.y1 - world.y0); }
function r4(v) { return Math.round(v * 1e4) / 1e4; }

function pathOf(points, close) {
  if (!points || points.length === 0) return '';
  let d = 'M' + sx(points[0][0]).toFixed(2) + ' ' + sy(points[0][1]).toFixed(2);
  for (let i = 1; i < points.length; i++) {
    d += 'L' + sx(points[i][0]).toFixed(2) + ' ' + sy(points[i][1]).toFixed(2);
  }
  return close ? d + 'Z' : d;
}

// ---------- requests ----------

let inFlight = 0, pending = null, running = false, seq = 0;
const idleWaiters = [];

// ---------- long requests: a progress bar with the time left, and Stop ----------
// Every computing request carries a job id (header x-lekalo-job). One still unanswered after
// SHOW_AFTER_MS shows the bar under the canvas, fed by GET /api/progress?job=ID every POLL_MS:
// the share done of the computation's current stage and the server's estimate of the time left
// (before the computation reports, the bar moves without a share). Stop aborts the request; the
// server stops a computation whose request is dropped.
const SHOW_AFTER_MS = 500, POLL_MS = 250;
const DOING = { '/api/fit': 'Fitting', '/api/import': 'Reading the file', '/api/export/step': 'Writing STEP',
  '/api/export/json': 'Writing JSON', '/api/measure': 'Measuring', '/api/project': 'Projecting' };
let jobSeq = 0;
let shownJob = null;

function stoppedError() {
  return Object.assign(new Error('Stopped: the computation was cancelled. The drawing is the last one computed; change a point or a setting to compute again.'), { stopped: true });
}

function secondsText(s) { return s < 10 ? `${s.toFixed(1)} s` : `${Math.round(s)} s`; }

function showProgress(job, path, ctl, started) {
  shownJob = job;
  $('progress-what').textContent = `${DOING[path] || 'Computing'}…`;
  const bar = $('progress-bar');
  bar.removeAttribute('value');
  $('progress-text').textContent = '';
  $('progress-stop').onclick = () => ctl.abort();
  $('progress').hidden = false;
  return setInterval(async () => {
    try {
      const r = await fetch(`/api/progress?job=${job}`);
      const p = await r.json();
      if (shownJob !== job) return;
      const elapsed = (performance.now() - started) / 1000;
      if (p.running && p.total > 0) {
        bar.max = p.total;
        bar.value = p.done;
        const share = Math.floor(100 * p.done / p.total);
        $('progress-text').textContent = p.remaining_s === null
          ? `${share} % · ${secondsText(elapsed)}`
          : `${share} % · about ${secondsText(p.remaining_s)} left`;
      } else {
        bar.removeAttribute('value');
        $('progress-text').textContent = secondsText(elapsed);
      }
    } catch (e) { /* the next poll tries again; the request itself reports its errors */ }
  }, POLL_MS);
}

// fetch with a job id, the progress bar after SHOW_AFTER_MS, and Stop
async function request(path, init) {
  const job = `${Date.now().toString(36)}-${++jobSeq}`;
  const ctl = new AbortController();
  const started = performance.now();
  let poll = null;
  const timer = setTimeout(() => { poll = showProgress(job, path, ctl, started); }, SHOW_AFTER_MS);
  try {
    return await fetch(path, Object.assign({}, init, {
      headers: Object.assign({ 'x-lekalo-job': job }, init.headers || {}), signal: ctl.signal }));
  } catch (e) {
    throw e.name === 'AbortError' ? stoppedError() : e;
  } finally {
    clearTimeout(timer);
    if (poll !== null) clearInterval(poll);
    if (shownJob === job) { shownJob = null; $('progress').hidden = true; }
  }
}

async function post(path, body) {
  const r = await request(path, { method: 'POST', headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body) });
  let data;
  try {
    const ct = r.headers.get('content-type') || '';
    data = ct.includes('json') ? await r.json() : await r.text();
  } catch (e) {
    throw e.name === 'AbortError' ? stoppedError() : e;
  }
  if (!r.ok) throw Object.assign(new Error(data.error || String(data)), { field: data.field, status: r.status });
  return data;
}

// At most one computation in flight; pointer moves during it collapse into the next one.
function update() {
  pending = ++seq;
  if (!running) pump();
}

async function pump() {
  running = true;
  while (pending !== null) {
    pending = null;
    inFlight++;
    try {
      const answer = await compute();
      if (state.query && state.mode !== 'quasi' && answer.view) {
        // a curve of one control point is a point: its length only, no point at a length along it
        const along = (answer.view.curve.control || []).length > 1 ? [state.queryLength] : [];
        answer.measure = await post('/api/measure', { curve: answer.view.curve, at_length: along })
          .catch((e) => ({ error: e }));
      }
      clearErrors();
      draw(answer);
    } catch (e) {
      showError(e);
    } finally {
      inFlight--;
    }
  }
  running = false;
  wakeIdle();
}

// one-off requests (order change, knot operations, import) counted for idle()
let busy = 0;
async function tracked(fn) {
  busy++;
  try { await fn(); } finally { busy--; wakeIdle(); }
}

function wakeIdle() {
  if (!running && busy === 0) while (idleWaiters.length) idleWaiters.shift()();
}

function basisAt() { return cursorT; }

// Fewest points each mode draws a curve from; with fewer, the points alone and a note.
const FEWEST = { bspline: 1, interpolate: 2, bezier: 1, corners: 3, spline: 2, fit: 3 };
const WHAT = { bspline: 'control point', interpolate: 'data point', bezier: 'control point', corners: 'point',
  spline: 'point', fit: 'data point' };

function plural(n, word) { return `${n} ${word}${n === 1 ? '' : 's'}`; }

// While a curve is being placed point by point, the degree asked for may need more points than
// there are: the curve is drawn with the highest degree the points allow, and the note says so.
function degreeNote(n, asked, used) {
  return used < asked
    ? `${plural(n, WHAT[state.mode])} allow${n === 1 ? 's' : ''} degree ${used} at most: drawn with degree ${used}; place ${asked + 1 - n} more for degree ${asked}.`
    : '';
}

function compute() {
  const s = state, m = s.mode;
  const view = { samples: 400, comb: s.comb, basis_samples: 300 };
  if (cursorT !== null) view.at = cursorT;
  const n = editable().length;
  if (FEWEST[m] !== undefined && n < FEWEST[m]) {
    const more = FEWEST[m] - n;
    const note = n === 0
      ? 'Click on the canvas to place the first point.'
      : `Place ${plural(more, 'more point')} to draw a curve (${plural(n, WHAT[m])} so far).`;
    return Promise.resolve({ empty: true, note });
  }
  if (m === 'bspline') {
    const b = s.bspline;
    const degree = Math.min(b.degree, n - 1);
    const req = Object.assign({ control: b.control, degree }, view);
    if (b.knots && degree === b.degree) req.knots = b.knots;
    if (b.weights) req.weights = b.weights;
    return post('/api/bspline', req).then((v) => ({ view: v, note: degreeNote(n, b.degree, degree) }));
  }
  if (m === 'interpolate') {
    const it = s.interpolate;
    const degree = Math.min(it.degree, n - 1);
    // natural and end-tangent conditions are for cubics: a lower degree is drawn with free ends
    const end = degree < it.degree && (it.end === 'natural' || it.end === 'derivatives') ? 'free' : it.end;
    const req = Object.assign({ points: it.points, degree, parametrization: it.param,
      knots: it.knots, end }, view);
    if (end === 'derivatives') { req.start_derivative = it.d0; req.end_derivative = it.d1; }
    const note = degreeNote(n, it.degree, degree) +
      (end !== it.end ? ` The ${it.end} end condition applies from degree ${it.degree}.` : '');
    return post('/api/interpolate', req).then((v) => ({ view: v, note }));
  }
  if (m === 'bezier') {
    return post('/api/bezier/build', Object.assign({ control: s.bezier.control }, view));
  }
  if (m === 'blend') {
    const [first, second] = blendCurves();
    return post('/api/blend/deform', { first, second, continuity: s.blend.k, samples: 400 })
      .then((v) => ({ view: v }));
  }
  if (m === 'corners') {
    const c = s.corners;
    return post('/api/blend/corners', { points: c.points, continuity: c.k, fraction: c.window / 100, samples: 400 })
      .then((v) => ({ view: v }));
  }
  if (m === 'spline') {
    const c = s.spline;
    return post('/api/blend/spline', { points: c.points, continuity: c.k, closed: c.closed, samples: 400 })
      .then((v) => ({ view: v }));
  }
  if (m === 'fit') {
    const f = s.fit;
    const req = Object.assign({ points: f.points, smoothing: f.smoothing }, view);
    if (f.smoothing === 'lambda') req.lambda = Math.pow(10, f.lambda);
    if (f.smoothing === 's') req.s = Math.pow(10, f.s);
    // shape constraints: the points are samples y(x) of a function (the server says so)
    const shape = f.shape || {};
    for (const k of ['increasing', 'decreasing', 'convex', 'concave']) if (shape[k]) req[k] = true;
    for (const k of ['min', 'max']) if (shape[k] !== undefined && shape[k] !== '') req[k] = Number(shape[k]);
    return post('/api/fit', req);
  }
  const q = s.quasi;
  const breaks = numberList(q.breaks, 'breakpoints');
  const req = { expression: q.expr, breakpoints: breaks, order: q.order, intervals: 200, basis_samples: 300 };
  if (q.rule === 'explicit') req.tau = numberList(q.tau, 'tau');
  else req.rule = q.rule;
  return post('/api/quasi', req);
}

// numbers typed in a text field, separated by commas, spaces or semicolons
function numberList(text, field) {
  const v = text.split(/[\s,;]+/).filter((x) => x !== '').map(Number);
  if (v.some((x) => !Number.isFinite(x))) {
    throw Object.assign(new Error(`${field}: give numbers separated by commas`), { field });
  }
  return v;
}

function bezierObject(control) { return { lekalo: 1, type: 'bezier_curve', control }; }

// curve B shares the end points of curve A
function blendCurves() {
  const a = state.blend.a, b = state.blend.b;
  return [bezierObject(a), bezierObject([a[0], ...b, a[a.length - 1]])];
}

// ---------- drawing ----------

let last = null; // last answer, for tests and exports

function el(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

function fitWorld(points) {
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (const p of points) { x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]); }
  if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
  if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
  const py = (y1 - y0) * 0.08;
  world = { x0, x1, y0: y0 - py, y1: y1 + py };
}

// nothing to draw yet: the points placed so far and a note
function drawEmpty(answer) {
  last = answer;
  world = { x0: 0, x1: 10, y0: 0, y1: 6.25 };
  drawGrid();
  for (const id of ['curve', 'polygon', 'exact', 'other', 'other2', 'comb-path']) $(id).setAttribute('d', '');
  $('knot-marks').textContent = '';
  $('ruler-knots').textContent = '';
  $('basis-paths').textContent = '';
  drawnFrom.ruler = null;
  drawnFrom.basis = null;
  drawPoints();
  hideProjection();
  $('length-mark').setAttribute('visibility', 'hidden');
  for (const id of ['fit-info', 'bz-info', 'qi-info', 'query-info', 'query-at']) $(id).textContent = '';
  $('info').textContent = answer.note;
}

function draw(answer) {
  if (answer.empty) { drawEmpty(answer); return; }
  last = answer;
  const m = state.mode;
  const v = answer.view;
  if (m === 'quasi') {
    fitWorld(answer.t.map((t, i) => [t, answer.exact[i]]).concat(v.points.map((p, i) => [v.t[i], p[0]])));
  } else {
    world = { x0: 0, x1: 10, y0: 0, y1: 6.25 };
  }
  drawGrid();
  const curvePts = m === 'quasi' ? v.points.map((p, i) => [v.t[i], p[0]]) : v.points;
  $('curve').setAttribute('d', pathOf(curvePts));
  const showPolygon = m === 'bspline' || m === 'bezier' || m === 'blend';
  drawQuery(answer);
  $('polygon').setAttribute('d', showPolygon ? pathOf(m === 'blend' ? state.blend.a : v.control) : '');
  $('exact').setAttribute('d', m === 'quasi' ? pathOf(answer.t.map((t, i) => [t, answer.exact[i]])) : '');
  if (m === 'blend') {
    const [a, b] = blendCurves();
    $('other').setAttribute('d', pathOf(b.control));
    $('other2').setAttribute('d', '');
  } else if (m === 'corners' || m === 'spline') {
    // the polyline, dashed
    $('other').setAttribute('d', pathOf(state[m].points, m === 'spline' && state.spline.closed));
    $('other2').setAttribute('d', '');
  } else {
    $('other').setAttribute('d', '');
    $('other2').setAttribute('d', '');
  }
  drawComb(v, curvePts);
  drawKnots(v, m === 'quasi' ? (p, t) => [t, p[0]] : (p) => p);
  drawPoints();
  drawRuler(v);
  drawBasis(v.basis, v.domain, v);
  drawInfo(answer);
}

// What the grid, the ruler and the basis panel were last drawn from: while it is unchanged
// (a control point dragged moves neither the knots nor the view) they are left as they are.
const drawnFrom = { grid: null, ruler: null, basis: null };

function drawGrid() {
  // the coordinates keep a readable size on screen however the drawing is scaled
  const shown = $('canvas').getBoundingClientRect().width || W;
  const font = Math.min(24, 11 * W / shown).toFixed(1);
  const key = [world.x0, world.x1, world.y0, world.y1, font].join(',');
  if (drawnFrom.grid === key) return;
  drawnFrom.grid = key;
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

function niceStep(raw) {
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
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

// the editable points of the current mode
function editable() {
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

function setEditable(i, p) {
  const s = state;
  switch (s.mode) {
    case 'blend': {
      const na = s.blend.a.length;
      if (i < na) s.blend.a[i] = p; else s.blend.b[i - na] = p;
      break;
    }
    default: editable()[i] = p;
  }
}

let selected = -1;

function drawPoints() {
  const g = $('points');
  const pts = editable();
  const cls = { interpolate: 'data', corners: 'data', spline: 'data', fit: 'data fit-data' }[state.mode] || 'cp';
  const na = state.blend.a.length;
  // the circles are kept while their number is unchanged: the one being dragged keeps its
  // pointer capture across redraws
  if (g.children.length !== pts.length) {
    g.textContent = '';
    pts.forEach((_, i) => {
      const c = el('circle', { r: 6, 'data-index': i }, g);
      c.addEventListener('pointerdown', (e) => startDrag(e, { kind: 'point', index: i }));
    });
  }
  pts.forEach((p, i) => {
    const c = g.children[i];
    c.setAttribute('cx', sx(p[0]));
    c.setAttribute('cy', sy(p[1]));
    c.setAttribute('class', cls + (i === selected ? ' selected' : '') +
      (state.mode === 'blend' && i >= na ? ' second' : ''));
  });
  const h = $('handles');
  h.textContent = '';
  if (state.mode === 'interpolate' && state.interpolate.end === 'derivatives') {
    const it = state.interpolate, n = it.points.length;
    [[it.points[0], it.d0, 'd0'], [it.points[n - 1], it.d1, 'd1']].forEach(([p, d, name]) => {
      const tip = [p[0] + d[0] * HANDLE, p[1] + d[1] * HANDLE];
      el('line', { x1: sx(p[0]), y1: sy(p[1]), x2: sx(tip[0]), y2: sy(tip[1]), class: 'handle-line' }, h);
      const c = el('circle', { cx: sx(tip[0]), cy: sy(tip[1]), r: 5, class: 'handle', 'data-handle': name }, h);
      c.addEventListener('pointerdown', (e) => startDrag(e, { kind: 'handle', name }));
    });
  }
}

// an end derivative d is drawn as a handle of length HANDLE·|d|
const HANDLE = 0.25;

function drawRuler(v) {
  const editableKnots = state.mode === 'bspline';
  const key = [editableKnots, v.degree, v.domain.join(','), v.knots.join(',')].join('|');
  if (drawnFrom.ruler === key) return;
  drawnFrom.ruler = key;
  const g = $('ruler-knots');
  g.textContent = '';
  const [a, b] = v.domain;
  const rx = (t) => 20 + (t - a) / (b - a || 1) * 760;
  let index = 0;
  let mult = 0; // copies of this knot before it (the knots are sorted)
  v.knots.forEach((t, i) => {
    const interior = i > v.degree && i < v.knots.length - v.degree - 1;
    mult = i > 0 && v.knots[i - 1] === t ? mult + 1 : 0;
    const m = el('rect', { x: rx(t) - 4, y: 14 - mult * 7, width: 8, height: 6,
      class: 'ruler-knot' + (interior && editableKnots ? ' movable' : ''), 'data-knot': i }, g);
    if (interior && editableKnots) m.addEventListener('pointerdown', (e) => startDrag(e, { kind: 'knot', index: i, rx, a, b }));
    index++;
  });
  el('text', { x: 20, y: 40, class: 'ruler-label' }, g).textContent = r4(a);
  el('text', { x: 780, y: 40, class: 'ruler-label', 'text-anchor': 'end' }, g).textContent = r4(b);
}

const BASIS_COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf'];

function drawBasis(basis, domain, v) {
  // the functions depend on the knots, the degree and the sampling; their colours on `active`
  const key = basis ? [v.degree, domain.join(','), v.knots.join(','), basis.t.length, basis.active.join(',')].join('|') : '';
  if (drawnFrom.basis === key) return;
  drawnFrom.basis = key;
  const g = $('basis-paths');
  g.textContent = '';
  if (!basis) return;
  const [a, b] = domain;
  const bx = (t) => 20 + (t - a) / (b - a || 1) * 760;
  const by = (v) => 150 - v * 135;
  const active = new Set(basis.active);
  for (const f of basis.functions) {
    let d = '';
    f.values.forEach((v, j) => {
      const t = basis.t[f.from + j];
      d += (j === 0 ? 'M' : 'L') + bx(t).toFixed(2) + ' ' + by(v).toFixed(2);
    });
    el('path', { d, class: 'basis-fn' + (active.has(f.i) ? ' active' : ''), stroke: BASIS_COLORS[f.i % BASIS_COLORS.length],
      'data-i': f.i }, g);
  }
}

function drawInfo(answer) {
  const v = answer.view;
  const kind = { bezier_curve: 'Bezier', bspline_curve: 'B-spline', nurbs_curve: 'NURBS' }[v.curve.type] || v.curve.type;
  let text = `${kind} curve of degree ${v.degree}, ${plural(v.control.length, 'control point')}, ${plural(v.knots.length, 'knot')}`;
  if (answer.real_degree !== undefined) {
    text += `; real degree ${answer.real_degree}`;
    $('bz-info').textContent = `degree ${answer.degree}, real degree ${answer.real_degree}` +
      (bezierDeviation ? `; last approximate reduction: max deviation ${bezierDeviation.sampled.toExponential(3)} (bound ${bezierDeviation.bound.toExponential(3)})` : '');
  }
  if (answer.report) {
    const r = answer.report;
    $('fit-info').textContent = `residual max ${r.max_residual.toPrecision(4)} (point ${r.max_index}), RMS ${r.rms.toPrecision(4)}; ` +
      `${r.interior_knots} interior knots, ${r.control_points} control points` +
      (r.lambda !== null ? `; λ = ${r.lambda.toPrecision(4)}` : '');
  }
  if (answer.max_error !== undefined) {
    $('qi-info').textContent = `max |f − q| on 200 intervals: ${answer.max_error.toExponential(4)}`;
    drawError(answer);
  }
  $('info').textContent = answer.note ? `${text}. ${answer.note}` : text;
}

// quasi-interpolation: the error f − q in the basis panel's place, over the basis functions
function drawError(answer) {
  const g = $('basis-paths');
  const [a, b] = answer.view.domain;
  const emax = Math.max(1e-300, ...answer.error.map(Math.abs));
  const bx = (t) => 20 + (t - a) / (b - a || 1) * 760;
  let d = '';
  answer.error.forEach((e, i) => { d += (i ? 'L' : 'M') + bx(answer.t[i]).toFixed(2) + ' ' + (80 - e / emax * 70).toFixed(2); });
  el('line', { x1: 20, x2: 780, y1: 80, y2: 80, class: 'axis zero-line' }, g);
  el('text', { x: 784, y: 84, class: 'ruler-label' }, g).textContent = '0';
  el('path', { d, class: 'error-plot', id: 'error-path' }, g);
  el('text', { x: 24, y: 14, class: 'ruler-label' }, g).textContent = `f − q (scaled to ±${emax.toExponential(2)})`;
  drawnFrom.basis = null; // the panel now holds more than the basis: drawn anew next time
}

// ---------- errors next to controls ----------

function clearErrors() {
  document.querySelectorAll('.err').forEach((e) => { e.textContent = ''; });
}

function showError(e) {
  clearErrors();
  const field = e.field || '';
  const candidates = [field, field.replace(/^(curve|first|second|file)\./, ''), field.split(/[.[]/)[0]];
  const panel = document.querySelector(`.panel[data-mode="${state.mode}"]`);
  for (const f of candidates) {
    if (!f) continue;
    const target = (panel && panel.querySelector(`[data-err="${f}"]`)) || document.querySelector(`aside > [data-err="${f}"], #query-panel [data-err="${f}"], header [data-err="${f}"], .views [data-err="${f}"]`);
    if (target) { target.textContent = e.message; return; }
  }
  $('error-other').textContent = e.message;
}

// ---------- pointer interaction ----------

let drag = null;
let cursorT = null;

function svgPoint(e, svg) {
  const r = svg.getBoundingClientRect();
  return [(e.clientX - r.left) * (svg.viewBox.baseVal.width / r.width), (e.clientY - r.top) * (svg.viewBox.baseVal.height / r.height)];
}

function startDrag(e, what) {
  e.preventDefault();
  e.stopPropagation();
  if (e.altKey && what.kind === 'point') { deletePoint(what.index); return; }
  drag = what;
  if (what.kind === 'point') { selected = what.index; syncWeight(); }
  drag.element = e.target;
  document.addEventListener('pointermove', onDrag);
  document.addEventListener('pointerup', endDrag, { once: true });
}

function onDrag(e) {
  if (!drag) return;
  if (drag.kind === 'knot') {
    const [px] = svgPoint(e, $('ruler'));
    const b = state.bspline;
    const knots = b.knots || last.view.knots.slice();
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
  const p = [r4(wx(px)), r4(wy(py))];
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

function deletePoint(i) {
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
  selected = -1;
  commit();
  update();
}

// ---------- controls ----------

function syncControls() {
  const s = state;
  $('mode').value = s.mode;
  $('comb').checked = s.comb;
  $('bs-degree').value = s.bspline.degree;
  $('in-degree').value = s.interpolate.degree;
  $('in-param').value = s.interpolate.param;
  $('in-knots').value = s.interpolate.knots;
  $('in-end').value = s.interpolate.end;
  $('bl-k').value = s.blend.k;
  $('co-k').value = s.corners.k;
  $('co-window').value = s.corners.window;
  $('sp-k').value = s.spline.k;
  $('sp-closed').checked = s.spline.closed;
  $('qi-expr').value = s.quasi.expr;
  $('qi-breaks').value = s.quasi.breaks;
  $('qi-order').value = s.quasi.order;
  $('qi-rule').value = s.quasi.rule;
  $('qi-tau').value = s.quasi.tau || '';
  $('qi-tau-label').hidden = s.quasi.rule !== 'explicit';
  $('fit-mode').value = s.fit.smoothing;
  $('fit-slider-label').hidden = s.fit.smoothing === 'gcv';
  $('fit-name').textContent = s.fit.smoothing === 's' ? 's' : 'λ';
  // log10 λ from -9 to 1 (λ weighs ∫|f''|² against the squared residuals), log10 s from -2 to 2
  $('fit-slider').min = s.fit.smoothing === 's' ? -2 : -9;
  $('fit-slider').max = s.fit.smoothing === 's' ? 2 : 1;
  $('fit-slider').value = s.fit.smoothing === 's' ? s.fit.s : s.fit.lambda;
  $('fit-value').textContent = '= ' + Math.pow(10, Number($('fit-slider').value)).toPrecision(3);
  const shape = s.fit.shape || {};
  for (const k of ['increasing', 'decreasing', 'convex', 'concave']) $(`fit-${k}`).checked = !!shape[k];
  for (const k of ['min', 'max']) $(`fit-${k}`).value = shape[k] === undefined ? '' : shape[k];
  $('query').checked = s.query;
  $('query-length').value = s.queryLength;
  $('query-panel').hidden = !s.query || s.mode === 'quasi';
  if (!s.query) hideProjection();
  document.querySelectorAll('.panel[data-mode]').forEach((p) => { p.hidden = p.dataset.mode !== s.mode; });
  // the lower panel: the basis functions, or for quasi-interpolation its error over them; the
  // blending modes have no basis to show
  const basis = !['blend', 'corners', 'spline'].includes(s.mode);
  $('basis').toggleAttribute('hidden', !basis);
  $('basis-caption').hidden = !basis;
  $('basis-caption').innerHTML = s.mode === 'quasi'
    ? 'The error f − q (red; scaled to the panel, with its zero line) over the basis functions.'
    : 'Basis functions N<sub>i,p</sub>: move the pointer over this panel to see which are active.';
  $('help').textContent = HELP[s.mode];
  syncWeight();
}

function syncWeight() {
  const w = state.bspline.weights;
  $('bs-weight').value = selected >= 0 && w ? w[selected] : 1;
}

const HELP = {
  bspline: 'Click to add a control point, drag to move, Alt+click to delete. Drag the interior knots on the ruler. Select a point to edit its weight (NURBS).',
  interpolate: 'Click to add a data point, drag to move, Alt+click to delete. With end tangents, drag the two handles.',
  bezier: 'Click to add a control point, drag to move, Alt+click to delete; then change the order.',
  blend: 'Curve A (white points, grey dashed polygon) and curve B (pink points, red dashed polygon) share their end points; the solid curve is the C^k deformation of A into B. Click to add a point to B.',
  corners: 'Click to add a point of the polyline (dashed), drag to move, Alt+click to delete; each corner is rounded over a window with C^k, turning one way.',
  spline: 'Click to add a point, drag to move, Alt+click to delete; the curve through the points blends local parabolas with C^k.',
  quasi: 'Type f(x); the quasi-interpolant q (solid) and f (dashed); the lower panel plots f − q.',
  fit: 'Noisy points (click to add, drag, Alt+click to delete) smoothed by the library: move the slider to trade the residual against smoothness; tick a shape to make the fit of y(x) keep it everywhere.',
};

function bindNumber(id, get, set) {
  $(id).addEventListener('change', () => {
    const v = Number($(id).value);
    set(v);
    commit();
    update();
  });
}

function bind() {
  $('mode').addEventListener('change', () => { state.mode = $('mode').value; selected = -1; cursorT = null; commit(); syncControls(); update(); });
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
    selected = -1;
    cursorT = null;
    commit(); syncControls(); update();
  });
  document.addEventListener('keydown', (e) => {
    if ((e.ctrlKey || e.metaKey) && e.key === 'z') { e.preventDefault(); undo(); }
    if ((e.ctrlKey || e.metaKey) && e.key === 'y') { e.preventDefault(); redo(); }
  });
  bindNumber('bs-degree', null, (v) => { state.bspline.degree = v; state.bspline.knots = null; });
  $('bs-weight').addEventListener('change', () => {
    if (selected < 0) return;
    const b = state.bspline;
    if (!b.weights) b.weights = b.control.map(() => 1);
    b.weights[selected] = Number($('bs-weight').value);
    commit(); update();
  });
  $('knot-insert').addEventListener('click', () => knotOp('/api/knot/insert'));
  $('knot-remove').addEventListener('click', () => knotOp('/api/knot/remove'));
  bindNumber('in-degree', null, (v) => { state.interpolate.degree = v; });
  for (const [id, key] of [['in-param', 'param'], ['in-knots', 'knots'], ['in-end', 'end']]) {
    $(id).addEventListener('change', () => { state.interpolate[key] = $(id).value; commit(); update(); });
  }
  $('bz-elevate').addEventListener('click', () => bezierOp({ op: 'elevate', by: 1 }));
  $('bz-reduce').addEventListener('click', () => bezierOp({ op: 'reduce_exact' }));
  $('bz-approx').addEventListener('click', () => bezierOp({ op: 'reduce_approx', target: Number($('bz-target').value), ends: $('bz-ends').value }));
  bindNumber('bl-k', null, (v) => { state.blend.k = v; });
  bindNumber('co-k', null, (v) => { state.corners.k = v; });
  bindNumber('co-window', null, (v) => { state.corners.window = v; });
  bindNumber('sp-k', null, (v) => { state.spline.k = v; });
  $('sp-closed').addEventListener('change', () => { state.spline.closed = $('sp-closed').checked; commit(); update(); });
  $('qi-expr').addEventListener('input', () => { state.quasi.expr = $('qi-expr').value; update(); });
  $('qi-expr').addEventListener('change', commit);
  $('qi-breaks').addEventListener('change', () => { state.quasi.breaks = $('qi-breaks').value; commit(); update(); });
  bindNumber('qi-order', null, (v) => { state.quasi.order = v; });
  $('qi-rule').addEventListener('change', () => { state.quasi.rule = $('qi-rule').value; commit(); syncControls(); update(); });
  $('qi-tau').addEventListener('change', () => { state.quasi.tau = $('qi-tau').value; commit(); update(); });
  $('fit-mode').addEventListener('change', () => { state.fit.smoothing = $('fit-mode').value; commit(); syncControls(); update(); });
  $('fit-slider').addEventListener('input', () => {
    state.fit[state.fit.smoothing === 's' ? 's' : 'lambda'] = Number($('fit-slider').value);
    $('fit-value').textContent = '= ' + Math.pow(10, Number($('fit-slider').value)).toPrecision(3);
    update();
  });
  $('fit-slider').addEventListener('change', commit);
  for (const k of ['increasing', 'decreasing', 'convex', 'concave']) {
    $(`fit-${k}`).addEventListener('change', () => {
      state.fit.shape = Object.assign({}, state.fit.shape, { [k]: $(`fit-${k}`).checked });
      commit(); syncControls(); update();
    });
  }
  for (const k of ['min', 'max']) {
    $(`fit-${k}`).addEventListener('change', () => {
      state.fit.shape = Object.assign({}, state.fit.shape, { [k]: $(`fit-${k}`).value });
      commit(); syncControls(); update();
    });
  }
  $('fit-noise').addEventListener('click', () => {
    state.fit.points = noisyPoints(1 + Math.floor(Math.random() * 1e9));
    commit(); update();
  });
  $('query').addEventListener('change', () => { state.query = $('query').checked; commit(); syncControls(); update(); });
  $('query-length').addEventListener('change', () => { state.queryLength = Number($('query-length').value); commit(); update(); });
  $('canvas').addEventListener('pointermove', (e) => {
    if (!state.query || drag || state.mode === 'quasi') return;
    const [px, py] = svgPoint(e, $('canvas'));
    projectTo([wx(px), wy(py)]);
  });
  $('canvas').addEventListener('pointerleave', () => { projTarget = null; hideProjection(); });
  $('canvas').addEventListener('pointerdown', addPoint);
  $('canvas').addEventListener('contextmenu', (e) => e.preventDefault());
  $('basis').addEventListener('pointermove', (e) => {
    if (!last || !last.view) return;
    const [px] = svgPoint(e, $('basis'));
    const [a, b] = last.view.domain;
    cursorT = Math.min(b, Math.max(a, a + (px - 20) / 760 * (b - a)));
    $('basis-cursor').setAttribute('x1', px);
    $('basis-cursor').setAttribute('x2', px);
    update();
  });
  $('import').addEventListener('change', () => tracked(importFile));
  $('export-json').addEventListener('click', () => exportCurve('/api/export/json', 'curve.json'));
  $('export-step').addEventListener('click', () => exportCurve('/api/export/step', 'curve.step'));
  $('export-svg').addEventListener('click', () => download(new Blob([svgText()], { type: 'image/svg+xml' }), 'lekalo.svg'));
  $('export-png').addEventListener('click', exportPng);
}

let bezierDeviation = null;

// ---------- queries: closest point to the pointer, arc length ----------

// at most one projection in flight; pointer moves during it collapse into the next one
let projTarget = null, projRunning = false, projection = null;

function projectTo(p) {
  projTarget = p;
  if (projRunning) return;
  projRunning = true;
  busy++;
  (async () => {
    try {
      while (projTarget) {
        const q = projTarget;
        projTarget = null;
        if (!last || !last.view) break;
        try {
          const r = await post('/api/project', { curve: last.view.curve, point: q });
          projection = { from: q, ...r };
          drawProjection();
        } catch (e) { showError(e); }
      }
    } finally { projRunning = false; busy--; wakeIdle(); }
  })();
}

function hideProjection() {
  projection = null;
  for (const id of ['proj-line', 'proj-foot']) $(id).setAttribute('visibility', 'hidden');
}

function drawProjection() {
  if (!projection || !state.query) { hideProjection(); return; }
  const { from, point } = projection;
  const line = $('proj-line');
  line.setAttribute('x1', sx(from[0])); line.setAttribute('y1', sy(from[1]));
  line.setAttribute('x2', sx(point[0])); line.setAttribute('y2', sy(point[1]));
  line.setAttribute('visibility', 'visible');
  const foot = $('proj-foot');
  foot.setAttribute('cx', sx(point[0])); foot.setAttribute('cy', sy(point[1]));
  foot.setAttribute('visibility', 'visible');
  $('query-info').dataset.projection = JSON.stringify(projection);
  drawQueryText();
}

// the measure answer of the last drawing and the closest point, as text
function drawQueryText() {
  const m = last && last.measure;
  let text = '';
  if (m && !m.error) text = `arc length ${m.length.toPrecision(8)} (error estimate ${m.error_estimate.toExponential(1)})`;
  if (projection) {
    text += `${text ? '; ' : ''}closest point t = ${projection.t.toPrecision(6)} at (${projection.point.map((x) => x.toFixed(4)).join(', ')}), distance ${projection.distance.toPrecision(4)}`;
  }
  $('query-info').textContent = text;
}

function drawQuery(answer) {
  const mark = $('length-mark');
  const m = answer.measure;
  if (!m || state.mode === 'quasi') { mark.setAttribute('visibility', 'hidden'); hideProjection(); $('query-at').textContent = ''; return; }
  if (m.error) {
    mark.setAttribute('visibility', 'hidden');
    $('query-at').textContent = '';
    showError(m.error);
  } else if (!m.at_length.length) {
    mark.setAttribute('visibility', 'hidden');
    $('query-at').textContent = 'Place a second point to find a length along the curve.';
  } else {
    const a = m.at_length[0];
    mark.setAttribute('cx', sx(a.point[0])); mark.setAttribute('cy', sy(a.point[1]));
    mark.setAttribute('visibility', 'visible');
    $('query-at').textContent = `length ${a.length} from the start at t = ${a.t.toPrecision(8)}`;
  }
  // the curve changed: the closest point is stale until the pointer moves again
  hideProjection();
  drawQueryText();
}

function bezierOp(op) { return tracked(() => bezierOpNow(op)); }

async function bezierOpNow(op) {
  try {
    currentCurve('by');
    const answer = await post('/api/bezier', Object.assign({ curve: bezierObject(state.bezier.control) }, op));
    bezierDeviation = answer.deviation;
    state.bezier.control = answer.view.control;
    commit();
    update();
  } catch (e) { showError(e); }
}

function knotOp(path) { return tracked(() => knotOpNow(path)); }

// the current curve, or an error shown at `field` when there is none yet
function currentCurve(field) {
  if (last && last.view) return last.view.curve;
  throw Object.assign(new Error('There is no curve yet: place points on the canvas first.'), { field });
}

async function knotOpNow(path) {
  try {
    const answer = await post(path, { curve: currentCurve('t'), t: Number($('knot-t').value) });
    const v = answer.view || answer;
    const b = state.bspline;
    b.control = v.control;
    b.knots = v.knots;
    b.weights = v.weights;
    commit();
    update();
  } catch (e) { showError(e); }
}

async function importFile() {
  const file = $('import').files[0];
  if (!file) return;
  try {
    const r = await request('/api/import', { method: 'POST', body: await file.text() });
    const v = await r.json();
    if (!r.ok) throw Object.assign(new Error(v.error), { field: v.field });
    if (v.curve.type === 'bezier_curve') {
      state.mode = 'bezier';
      state.bezier.control = v.control;
    } else {
      state.mode = 'bspline';
      state.bspline = { degree: v.degree, control: v.control, knots: v.knots, weights: v.weights };
    }
    commit(); syncControls(); update();
  } catch (e) {
    // the message names the file's field; it is shown next to the import control
    showError(Object.assign(e, { field: 'file' }));
  }
  $('import').value = '';
}

async function exportCurve(path, name) {
  try {
    const r = await request(path, { method: 'POST', body: JSON.stringify({ curve: currentCurve('file') }) });
    if (!r.ok) throw Object.assign(new Error((await r.json()).error), { field: 'file' });
    download(await r.blob(), name);
  } catch (e) { showError(e); }
}

function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

// the canvas as a stand-alone SVG file, with the page's drawing styles inlined
function svgText() {
  const clone = $('canvas').cloneNode(true);
  const style = document.createElementNS(SVGNS, 'style');
  style.textContent = SVG_STYLE;
  clone.insertBefore(style, clone.firstChild);
  return new XMLSerializer().serializeToString(clone);
}

const SVG_STYLE = `.bg{fill:#fff}.gridline{stroke:#eee}.curve{fill:none;stroke:#1f4e9c;stroke-width:2.5}
.polygon{fill:none;stroke:#999;stroke-dasharray:4 3}.other{fill:none;stroke:#c77;stroke-dasharray:4 3}
.exact{fill:none;stroke:#d62728;stroke-dasharray:6 4}.comb{fill:none;stroke:#2ca02c;stroke-width:0.8}
.knot{fill:#ff7f0e}.cp{fill:#fff;stroke:#333;stroke-width:1.5}.cp.second{fill:#fdd}.data{fill:#1f4e9c}
.handle{fill:#2ca02c}.handle-line{stroke:#2ca02c}`;

async function exportPng() {
  const url = URL.createObjectURL(new Blob([svgText()], { type: 'image/svg+xml' }));
  const img = new Image();
  img.onload = () => {
    const c = document.createElement('canvas');
    c.width = W * 2; c.height = H * 2;
    const ctx = c.getContext('2d');
    ctx.scale(2, 2);
    ctx.drawImage(img, 0, 0);
    URL.revokeObjectURL(url);
    c.toBlob((b) => download(b, 'lekalo.png'), 'image/png');
  };
  img.src = url;
}

// ---------- test hooks ----------

window.lekaloEditor = {
  get state() { return state; },
  get last() { return last; },
  toScreen: (p) => [sx(p[0]), sy(p[1])],
  idle: () => (running || busy ? new Promise((r) => idleWaiters.push(r)) : Promise.resolve()),
};

bind();
syncControls();
update();
// a resized window redraws the grid's coordinates at their on-screen size
window.addEventListener('resize', () => { if (last && last.view) drawGrid(); });
