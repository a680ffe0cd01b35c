// End-to-end tests of the `lekalo serve` editor in headless Chromium (Debian's /usr/bin/chromium),
// driven by playwright-core. The server is started by scripts/test-browser.sh, which passes its
// address in LEKALO_URL. Each test acts as a person would (clicks, drags, typed values) and checks
// the drawn SVG paths against the API's own answer for the same construction.
//
// Environment: LEKALO_URL (required), ARTIFACTS (screenshots; default ../target/browser-artifacts),
// SCREENSHOTS_FOR_DOCS=1 also writes the README's pictures to ../docs/img/.
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const base = process.env.LEKALO_URL;
if (!base) throw new Error('set LEKALO_URL to the address printed by `lekalo serve`');
const artifacts = process.env.ARTIFACTS || path.join(here, '..', 'target', 'browser-artifacts');
const docsImg = path.join(here, '..', 'docs', 'img');
mkdirSync(artifacts, { recursive: true });

export const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

async function api(route, body) {
  const r = await fetch(new URL(route, base), { method: 'POST', body: JSON.stringify(body) });
  const data = await r.json();
  assert.ok(r.ok, `${route}: ${JSON.stringify(data)}`);
  return data;
}

// vertices of an SVG path "M x y L x y ..."
function vertices(d) {
  const nums = (d.match(/-?\d+(\.\d+)?(e-?\d+)?/g) || []).map(Number);
  const out = [];
  for (let i = 0; i + 1 < nums.length; i += 2) out.push([nums[i], nums[i + 1]]);
  return out;
}

// the drawn #curve equals the API's points, mapped to the screen by the page's own transform
async function assertCurveIs(page, points, what) {
  const d = await page.getAttribute('#curve', 'd');
  const drawn = vertices(d);
  const expected = await page.evaluate((pts) => pts.map((p) => window.lekaloEditor.toScreen(p)), points);
  assert.equal(drawn.length, expected.length, `${what}: vertex count`);
  for (let i = 0; i < drawn.length; i++) {
    const err = Math.hypot(drawn[i][0] - expected[i][0], drawn[i][1] - expected[i][1]);
    assert.ok(err < 0.02, `${what}: vertex ${i} drawn at ${drawn[i]} but the API says ${expected[i]}`);
  }
}

async function idle(page) {
  await page.evaluate(() => window.lekaloEditor.idle());
}

async function shot(page, name, forDocs) {
  await page.screenshot({ path: path.join(artifacts, `${name}.png`) });
  if (forDocs && process.env.SCREENSHOTS_FOR_DOCS === '1') {
    mkdirSync(docsImg, { recursive: true });
    await page.locator('main').screenshot({ path: path.join(docsImg, `serve-${name}.png`) });
  }
}

async function canvasToPage(page, p) {
  return page.evaluate((q) => {
    const [x, y] = window.lekaloEditor.toScreen(q);
    const r = document.getElementById('canvas').getBoundingClientRect();
    return [r.left + x * r.width / 800, r.top + y * r.height / 500];
  }, p);
}

async function setValue(page, selector, value) {
  await page.fill(selector, String(value));
  await page.dispatchEvent(selector, 'change');
  await idle(page);
}

// every message shown next to a control, joined (empty when none is shown)
async function shownErrors(page) {
  return page.evaluate(() => [...document.querySelectorAll('.err')].map((e) => e.textContent).filter((t) => t).join(' | '));
}

// what each bound label covers: curve segments it crosses, data points (circles) it overlaps,
// other labels it overlaps, and whether it leaves the canvas; all in the canvas's coordinates
async function boundLabelClashes(page) {
  return page.evaluate(() => {
    const nums = (document.getElementById('curve').getAttribute('d').match(/-?\d+(\.\d+)?(e-?\d+)?/g) || []).map(Number);
    const pts = [];
    for (let i = 0; i + 1 < nums.length; i += 2) pts.push([nums[i], nums[i + 1]]);
    // a segment meets the box [l, t, r, b] (Liang–Barsky)
    const meets = ([x1, y1], [x2, y2], [l, t, r, b]) => {
      let u0 = 0, u1 = 1;
      const dx = x2 - x1, dy = y2 - y1;
      for (const [p, q] of [[-dx, x1 - l], [dx, r - x1], [-dy, y1 - t], [dy, b - y1]]) {
        if (p === 0) { if (q < 0) return false; continue; }
        const u = q / p;
        if (p < 0) { if (u > u1) return false; u0 = Math.max(u0, u); } else { if (u < u0) return false; u1 = Math.min(u1, u); }
      }
      return true;
    };
    const boxes = [...document.querySelectorAll('#bound-labels text')].map((t) => {
      const b = t.getBBox();
      return { text: t.textContent, box: [b.x, b.y, b.x + b.width, b.y + b.height] };
    });
    return boxes.map(({ text, box }, i) => {
      const [l, t, r, b] = box;
      const segments = pts.slice(1).filter((q, k) => meets(pts[k], q, box)).length;
      const points = [...document.querySelectorAll('#points circle')].filter((c) => {
        const cx = +c.getAttribute('cx'), cy = +c.getAttribute('cy'), rad = +c.getAttribute('r');
        return Math.hypot(Math.max(l - cx, 0, cx - r), Math.max(t - cy, 0, cy - b)) < rad;
      }).length;
      const labels = boxes.filter((o, j) => j !== i && l < o.box[2] && o.box[0] < r && t < o.box[3] && o.box[1] < b).length;
      const outside = l < 0 || t < 0 || r > 800 || b > 500;
      return { text, box: box.map((v) => Math.round(v)), segments, points, labels, outside };
    });
  });
}

const tests = [];
const test = (name, fn) => tests.push({ name, fn });

test('B-spline: add points, drag one, change the degree; the drawn curve is the API\'s', async (page) => {
  await page.goto(base);
  await idle(page);
  const n0 = await page.locator('#points circle').count();
  for (const p of [[2, 1], [4, 0.6]]) {
    const [x, y] = await canvasToPage(page, p);
    await page.mouse.click(x, y);
    await idle(page);
  }
  assert.equal(await page.locator('#points circle').count(), n0 + 2, 'two control points added');
  let s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  let answer = await api('/api/bspline', { control: s.control, degree: s.degree, samples: 400 });
  await assertCurveIs(page, answer.points, 'after adding points');

  const before = await page.getAttribute('#curve', 'd');
  await page.evaluate(() => {
    window.__draws = 0;
    new MutationObserver(() => { window.__draws++; }).observe(document.getElementById('curve'), { attributes: true });
  });
  const [x, y] = await canvasToPage(page, s.control[2]);
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) {
    await page.mouse.move(x + 5 * k, y + 7.5 * k);
    await idle(page);
  }
  await page.mouse.up();
  await idle(page);
  // the curve follows the pointer during the drag, not only at its end
  assert.ok(await page.evaluate(() => window.__draws) >= 8, 'a redraw per pointer move');
  s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.notDeepEqual(s.control[2], answer.control[2], 'the dragged point moved');
  assert.notEqual(await page.getAttribute('#curve', 'd'), before, 'the curve changed');
  answer = await api('/api/bspline', { control: s.control, degree: s.degree, samples: 400 });
  await assertCurveIs(page, answer.points, 'after the drag');

  await setValue(page, '#bs-degree', 2);
  answer = await api('/api/bspline', { control: s.control, degree: 2, samples: 400 });
  assert.equal(answer.degree, 2);
  await assertCurveIs(page, answer.points, 'degree 2');
  // knot marks on the curve: one per distinct knot
  assert.equal(await page.locator('#knot-marks rect').count(), answer.knot_marks.length, 'knot marks');
  // the basis panel: one path per basis function, the active ones highlighted at the cursor
  assert.equal(await page.locator('#basis-paths path').count(), s.control.length, 'basis functions');
  const box = await page.locator('#basis').boundingBox();
  await page.mouse.move(box.x + box.width * 0.5, box.y + 80);
  await idle(page);
  assert.equal(await page.locator('#basis-paths path.active').count(), 3, 'p + 1 = 3 active functions');
  await shot(page, 'bspline', true);
});

test('Interpolation: a refused degree shows the library\'s message next to the degree field; undo restores', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'interpolate');
  await idle(page);
  await page.selectOption('#in-end', 'natural');
  await idle(page);
  await setValue(page, '#in-degree', 2);
  const msg = await page.textContent('[data-mode="interpolate"] [data-err="degree"]');
  const s = await page.evaluate(() => window.lekaloEditor.state.interpolate);
  const direct = await fetch(new URL('/api/interpolate', base), { method: 'POST',
    body: JSON.stringify({ points: s.points, degree: 2, parametrization: s.param, knots: s.knots, end: 'natural' }) });
  assert.equal(direct.status, 400);
  const body = await direct.json();
  assert.equal(body.field, 'degree');
  assert.equal(msg, body.error, 'the page shows the API\'s message');
  await page.click('#undo');
  await idle(page);
  assert.equal(await page.textContent('[data-mode="interpolate"] [data-err="degree"]'), '', 'error cleared');
  assert.equal(await page.inputValue('#in-degree'), '3');
});

test('B-spline: a degree above what the points allow draws the highest they allow and says so', async (page) => {
  await page.goto(base);
  await idle(page);
  await setValue(page, '#bs-degree', 9);
  assert.equal(await shownErrors(page), '');
  assert.equal(await page.evaluate(() => window.lekaloEditor.last.view.degree), 4);
  assert.match(await page.textContent('#info'), /5 control points allow degree 4 at most: drawn with degree 4; place 5 more for degree 9/);
});

test('the state lives in the URL: a reload shows the same construction', async (page) => {
  await page.goto(base);
  await idle(page);
  await setValue(page, '#bs-degree', 4);
  const url = page.url();
  assert.ok(url.includes('#'), 'hash written');
  const d = await page.getAttribute('#curve', 'd');
  const other = await page.context().newPage();
  await other.goto(url);
  await idle(other);
  assert.equal(await other.getAttribute('#curve', 'd'), d);
  await other.close();
});

test('Bezier: elevate keeps the curve and the real degree; approximate reduction shows the deviation', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'bezier');
  await idle(page);
  const before = await page.evaluate(() => window.lekaloEditor.last.view);
  await page.click('#bz-elevate');
  await idle(page);
  const after = await page.evaluate(() => window.lekaloEditor.last);
  assert.equal(after.view.degree, before.degree + 1, 'degree + 1');
  assert.equal(after.real_degree, 3, 'real degree unchanged');
  const expected = await api('/api/bezier', { curve: before.curve, op: 'elevate', by: 1, samples: 400 });
  assert.deepEqual(after.view.control, expected.view.control);
  await assertCurveIs(page, expected.view.points, 'elevated');
  await setValue(page, '#bz-target', 2);
  await page.click('#bz-approx');
  await idle(page);
  const info = await page.textContent('#bz-info');
  assert.match(info, /max deviation \d\.\d+e[-+]\d+/, info);
  await shot(page, 'bezier', false);
});

test('Blending: C^k deformation drawn as the API computes it', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'blend');
  await idle(page);
  await setValue(page, '#bl-k', 3);
  const s = await page.evaluate(() => window.lekaloEditor.state.blend);
  const a = s.a;
  const expected = await api('/api/blend/deform', {
    first: { lekalo: 1, type: 'bezier_curve', control: a },
    second: { lekalo: 1, type: 'bezier_curve', control: [a[0], ...s.b, a[a.length - 1]] },
    continuity: 3, samples: 400 });
  await assertCurveIs(page, expected.points, 'blend k = 3');
  await shot(page, 'blend', true);
});

test('Polyline corners: the corners rounded over the window as `lekalo blend corners`, turning one way; the curve through the points is its own mode', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'corners');
  await idle(page);
  const pts = await page.evaluate(() => window.lekaloEditor.state.corners.points);
  for (const window of [25, 50]) {
    await setValue(page, '#co-window', window);
    const expected = await api('/api/blend/corners', { points: pts, continuity: 2, fraction: window / 100, samples: 400 });
    assert.equal(expected.degree, 5);
    await assertCurveIs(page, expected.points, `corners, window ${window}%`);
  }
  await setValue(page, '#co-window', 80);
  assert.match(await page.textContent('[data-mode="corners"] [data-err="fraction"]'), /\(0, 0\.5\]/, 'a window above 50% is refused next to its field');
  await page.selectOption('#mode', 'spline');
  await idle(page);
  const s = await page.evaluate(() => window.lekaloEditor.state.spline);
  const through = await api('/api/blend/spline', { points: s.points, continuity: 2, closed: false, samples: 400 });
  await assertCurveIs(page, through.points, 'curve through the points');
});

test('Interpolation with end tangents, then periodic; quasi-interpolation with its error', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'interpolate');
  await page.selectOption('#in-end', 'derivatives');
  await idle(page);
  assert.equal(await page.locator('#handles circle').count(), 2, 'two tangent handles');
  const s = await page.evaluate(() => window.lekaloEditor.state.interpolate);
  const expected = await api('/api/interpolate', { points: s.points, degree: 3, parametrization: 'chord',
    knots: 'auto', end: 'derivatives', start_derivative: s.d0, end_derivative: s.d1, samples: 400 });
  await assertCurveIs(page, expected.points, 'end tangents');
  await shot(page, 'interpolate', true);
  await page.selectOption('#in-end', 'periodic');
  await idle(page);
  const v = await page.evaluate(() => window.lekaloEditor.last.view);
  const p = v.points;
  assert.ok(Math.hypot(p[0][0] - p[p.length - 1][0], p[0][1] - p[p.length - 1][1]) < 1e-9, 'closed');

  await page.selectOption('#mode', 'quasi');
  await idle(page);
  const q = await page.evaluate(() => window.lekaloEditor.last);
  assert.ok(q.max_error > 0 && q.max_error < 0.5, `max error ${q.max_error}`);
  assert.ok((await page.getAttribute('#error-path', 'd')).length > 100, 'error plotted');
  await shot(page, 'quasi', true);
  await page.fill('#qi-expr', 'sin(');
  await page.dispatchEvent('#qi-expr', 'input');
  await idle(page);
  assert.match(await page.textContent('[data-err="expression"]'), /invalid expression/);
  await shot(page, 'quasi-error', false);
});

// a range input moved by the user: its value, then the events the page listens to
async function slide(page, selector, value) {
  await page.evaluate(([sel, v]) => {
    const e = document.querySelector(sel);
    e.value = String(v);
    e.dispatchEvent(new Event('input'));
    e.dispatchEvent(new Event('change'));
  }, [selector, value]);
  await idle(page);
}

async function downloadText(page, button) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
  const chunks = [];
  for await (const c of await dl.createReadStream()) chunks.push(c);
  return { name: dl.suggestedFilename(), text: Buffer.concat(chunks).toString('utf8') };
}

test('Fitting: the smoothing slider changes λ and s; curve, residual and knot count are the API\'s', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'fit');
  await idle(page);
  const pts = await page.evaluate(() => window.lekaloEditor.state.fit.points);
  assert.equal(await page.locator('#points circle').count(), pts.length, 'one circle per noisy point');
  let expected = await api('/api/fit', { points: pts, smoothing: 'lambda', lambda: 1e-4, samples: 400 });
  await assertCurveIs(page, expected.view.points, 'λ = 1e-4');
  let info = await page.textContent('#fit-info');
  assert.ok(info.includes(`RMS ${expected.report.rms.toPrecision(4)}`), info);
  const rough = expected.report.rms;
  await slide(page, '#fit-slider', -1);
  expected = await api('/api/fit', { points: pts, smoothing: 'lambda', lambda: 0.1, samples: 400 });
  await assertCurveIs(page, expected.view.points, 'λ = 0.1');
  assert.ok(expected.report.rms > rough, 'more smoothing, larger residual');
  info = await page.textContent('#fit-info');
  assert.ok(info.includes(`residual max ${expected.report.max_residual.toPrecision(4)}`), info);
  await page.selectOption('#fit-mode', 's');
  await idle(page);
  await slide(page, '#fit-slider', 0);
  expected = await api('/api/fit', { points: pts, smoothing: 's', s: 1, samples: 400 });
  await assertCurveIs(page, expected.view.points, 's = 1');
  info = await page.textContent('#fit-info');
  const k = expected.report.interior_knots;
  assert.ok(info.includes(`${k} interior knot${k === 1 ? '' : 's'},`), info);
  assert.ok(expected.report.weighted_rss <= 1, 'the smoothing condition holds');
  assert.equal(await page.locator('#ruler-knots rect').count(), expected.view.knots.length, 'knots on the ruler');
  await shot(page, 'fit', true);
});

test('Fitting with a shape: ticking increasing and y ≥ 0 draws the API\'s constrained fit, which rises', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'fit');
  await idle(page);
  await page.check('#fit-increasing');
  await idle(page);
  await setValue(page, '#fit-min', 0);
  assert.equal(await shownErrors(page), '');
  const f = await page.evaluate(() => window.lekaloEditor.state.fit);
  const expected = await api('/api/fit', { points: f.points, smoothing: 'lambda', lambda: Math.pow(10, f.lambda),
    increasing: true, min: 0, samples: 400 });
  await assertCurveIs(page, expected.view.points, 'increasing fit');
  const ys = expected.view.points.map((p) => p[1]);
  assert.ok(ys.every((y, i) => i === 0 || y >= ys[i - 1] - 1e-12), 'the fit rises');
  // the unconstrained fit of the same points does not
  const free = await api('/api/fit', { points: f.points, smoothing: 'lambda', lambda: Math.pow(10, f.lambda), samples: 400 });
  const fy = free.view.points.map((p) => p[1]);
  assert.ok(fy.some((y, i) => i > 0 && y < fy[i - 1]), 'without the constraint the wave falls somewhere');
  await shot(page, 'fit-shape', false);
});

test('Fitting with bounds: y ≥ a and y ≤ b are drawn as labelled dashed lines at their heights over the fit', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'fit');
  await idle(page);
  assert.equal(await page.locator('#bounds line').count(), 0, 'no bound, no line');
  await setValue(page, '#fit-min', 1);
  await setValue(page, '#fit-max', 5);
  assert.equal(await shownErrors(page), '');
  const f = await page.evaluate(() => window.lekaloEditor.state.fit);
  const expected = await api('/api/fit', { points: f.points, smoothing: 'lambda', lambda: Math.pow(10, f.lambda),
    min: 1, max: 5, samples: 400 });
  await assertCurveIs(page, expected.view.points, 'bounded fit');
  const ys = expected.view.points.map((p) => p[1]);
  assert.ok(ys.every((y) => y >= 1 - 1e-9 && y <= 5 + 1e-9), 'the fit stays within the bounds');
  const lines = await page.evaluate(() => [...document.querySelectorAll('#bounds line')].map((l) => ({
    bound: l.dataset.bound, x1: +l.getAttribute('x1'), x2: +l.getAttribute('x2'), y: +l.getAttribute('y1'),
    dash: getComputedStyle(l).strokeDasharray, stroke: getComputedStyle(l).stroke })));
  assert.deepEqual(lines.map((l) => l.bound), ['y ≥ 1', 'y ≤ 5']);
  const [a, b] = expected.view.domain;
  for (const [l, y] of [[lines[0], 1], [lines[1], 5]]) {
    const [x0, sy] = await page.evaluate((p) => window.lekaloEditor.toScreen(p), [a, y]);
    const [x1] = await page.evaluate((p) => window.lekaloEditor.toScreen(p), [b, y]);
    assert.ok(Math.abs(l.y - sy) < 1e-6 && Math.abs(l.x1 - x0) < 1e-6 && Math.abs(l.x2 - x1) < 1e-6, `${l.bound} drawn at ${JSON.stringify(l)}`);
    assert.notEqual(l.dash, 'none', `${l.bound} dashed`);
  }
  assert.deepEqual(await page.locator('#bound-labels text').allTextContents(), ['y ≥ 1', 'y ≤ 5'], 'labelled');
  // each label is readable: on no curve, point or other label, inside the canvas (here the
  // fit touches y ≤ 5 near the right end, where a label at the line's end would sit on it)
  for (const c of await boundLabelClashes(page)) {
    assert.ok(c.segments === 0 && c.points === 0 && c.labels === 0 && !c.outside, `${c.text} label covers ${JSON.stringify(c)}`);
  }
  // the labels are drawn over the data points, not hidden under them
  assert.ok(await page.evaluate(() => document.getElementById('points')
    .compareDocumentPosition(document.getElementById('bound-labels')) & Node.DOCUMENT_POSITION_FOLLOWING), 'labels above the points');
  // the exported SVG keeps them
  const svg = await downloadText(page, '#export-svg');
  assert.match(svg.text, /class="bound"/);
  await shot(page, 'fit-bounds', false);
  // an emptied field removes its line
  await setValue(page, '#fit-max', '');
  assert.deepEqual(await page.locator('#bound-labels text').allTextContents(), ['y ≥ 1']);
});

test('Blending: the info line names the result as the library does, its pieces and the continuity the API reports', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'blend');
  await idle(page);
  await setValue(page, '#bl-k', 3);
  const deform = await page.evaluate(() => window.lekaloEditor.last.view);
  assert.equal(deform.continuity, 3, 'the API reports the library\'s continuity');
  let info = await page.textContent('#info');
  assert.doesNotMatch(info, /knot/, `a Bezier curve has no knots: ${info}`);
  assert.match(info, new RegExp(`^Bezier curve of degree ${deform.degree} \\(one polynomial piece, ${deform.control.length} control points\\)`), info);
  assert.match(info, /C\^3 contact with A at the start and with B at the end/, info);

  await page.selectOption('#mode', 'corners');
  await idle(page);
  await setValue(page, '#co-k', 3);
  const pts = await page.evaluate(() => window.lekaloEditor.state.corners.points);
  const corners = await api('/api/blend/corners', { points: pts, continuity: 3, fraction: 0.25, samples: 400 });
  assert.equal(corners.continuity, 3);
  info = await page.textContent('#info');
  assert.match(info, new RegExp(`^B-spline curve of degree 7 in ${corners.knot_marks.length - 1} polynomial pieces .*C\\^3 at every join`), info);

  await page.selectOption('#mode', 'spline');
  await idle(page);
  const sp = await page.evaluate(() => window.lekaloEditor.last.view);
  info = await page.textContent('#info');
  assert.match(info, new RegExp(`^NURBS curve of degree ${sp.degree} in ${sp.knot_marks.length - 1} polynomial pieces .*C\\^${sp.continuity} at every join`), info);

  // the Bezier mode's curve has no knots either
  await page.selectOption('#mode', 'bezier');
  await idle(page);
  info = await page.textContent('#info');
  assert.match(info, /^Bezier curve of degree 3, 4 control points; real degree 3$/, info);
});

test('Queries: the closest point follows the pointer, the arc length and the parameter at a length are the API\'s', async (page) => {
  await page.goto(base);
  await idle(page);
  await page.check('#query');
  await idle(page);
  const curve = await page.evaluate(() => window.lekaloEditor.last.view.curve);
  const m = await api('/api/measure', { curve, at_length: [1] });
  assert.match(await page.textContent('#query-info'), new RegExp(`arc length ${m.length.toPrecision(8)}`));
  assert.match(await page.textContent('#query-at'), new RegExp(`t = ${m.at_length[0].t.toPrecision(8)}`));
  for (const q of [[5, 1], [2, 5.5]]) {
    const [x, y] = await canvasToPage(page, q);
    await page.mouse.move(x, y);
    await idle(page);
    const shown = JSON.parse(await page.getAttribute('#query-info', 'data-projection'));
    const p = await api('/api/project', { curve, point: shown.from });
    assert.deepEqual([shown.t, shown.distance], [p.t, p.distance], 'the projection is the API\'s');
    const [fx, fy] = await page.evaluate((pt) => window.lekaloEditor.toScreen(pt), p.point);
    assert.ok(Math.abs(Number(await page.getAttribute('#proj-line', 'x2')) - fx) < 1e-6, 'line ends at the foot point');
    assert.ok(Math.abs(Number(await page.getAttribute('#proj-line', 'y2')) - fy) < 1e-6, 'line ends at the foot point');
    assert.equal(await page.getAttribute('#proj-line', 'visibility'), 'visible');
  }
  await shot(page, 'query', true);
  await setValue(page, '#query-length', 1e6);
  assert.match(await page.textContent('[data-err="at_length"]'), /invalid arc length/);
});

test('Queries: a Bezier curve with a loop has its self-intersection circled with the kind and parameters the API gives', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'bezier');
  await idle(page);
  await page.click('#clear');
  await idle(page);
  await page.check('#query');
  await idle(page);
  for (const q of [[2, 1], [9, 5], [1, 5], [8, 1]]) {
    const [x, y] = await canvasToPage(page, q);
    await page.mouse.click(x, y);
    await idle(page);
  }
  assert.equal(await shownErrors(page), '');
  const curve = await page.evaluate(() => window.lekaloEditor.last.view.curve);
  const r = await api('/api/intersect', { curve });
  assert.equal(r.intersections.length, 1, JSON.stringify(r));
  const h = r.intersections[0];
  assert.equal(h.kind, 'crossing');
  const marks = page.locator('#crossing-marks circle');
  assert.equal(await marks.count(), 1);
  assert.equal(await marks.first().getAttribute('data-kind'), 'crossing');
  const [fx, fy] = await page.evaluate((pt) => window.lekaloEditor.toScreen(pt), h.point);
  assert.ok(Math.abs(Number(await marks.first().getAttribute('cx')) - fx) < 1e-6, 'circled at the API\'s point');
  assert.ok(Math.abs(Number(await marks.first().getAttribute('cy')) - fy) < 1e-6, 'circled at the API\'s point');
  const text = await page.textContent('#query-crossings');
  assert.match(text, new RegExp(`crossing at t = ${h.t_a.toPrecision(6)} and ${h.t_b.toPrecision(6)}`), text);
  // the queries off: no marks
  await page.uncheck('#query');
  await idle(page);
  assert.equal(await page.locator('#crossing-marks circle').count(), 0);
});

test('Fitting with a shape from an empty canvas: a shape is kept with the penalty and with a residual target s', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'fit');
  await idle(page);
  await page.click('#clear');
  await idle(page);
  const pts = [[1, 1], [2, 2.2], [3, 1.8], [4, 3.5], [5, 3], [6, 4.6], [7, 4.1]];
  for (const q of pts) {
    const [x, y] = await canvasToPage(page, q);
    await page.mouse.click(x, y);
    await idle(page);
  }
  await page.check('#fit-increasing');
  await idle(page);
  assert.equal(await shownErrors(page), '');
  await page.selectOption('#fit-mode', 's');
  await idle(page);
  assert.equal(await shownErrors(page), '', 'a shape with s is no error');
  assert.ok(await page.locator('#fit-increasing').isChecked(), 'the shape stays ticked');
  // the drawn fit is the library's constrained fit whose residual is s
  const state = await page.evaluate(() => window.lekaloEditor.state.fit);
  const drawn = await page.evaluate(() => window.lekaloEditor.last.view.curve);
  const points = await page.evaluate(() => window.lekaloEditor.state.fit.points);
  const s = Math.pow(10, state.s);
  const ref = await api('/api/fit', { points, smoothing: 's', s, increasing: true });
  assert.deepEqual(drawn, ref.view.curve);
  assert.ok(ref.report.weighted_rss <= s * (1 + 1e-3), `rss ${ref.report.weighted_rss}, s ${s}`);
});

test('Fitting from an empty canvas: the info line counts in words, "1 interior knot", not "1 interior knots"', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'fit');
  await idle(page);
  await page.click('#clear');
  await idle(page);
  for (const q of [[1, 1], [2, 2.2], [3, 1.8]]) {
    const [x, y] = await canvasToPage(page, q);
    await page.mouse.click(x, y);
    await idle(page);
  }
  const answer = await page.evaluate(() => window.lekaloEditor.last);
  assert.equal(answer.report.interior_knots, 1, 'three points smoothed: one interior knot');
  const info = await page.textContent('#fit-info');
  assert.match(info, /; 1 interior knot, \d+ control points/);
});

test('Queries from an empty canvas: one point is measured without an error, two give a point at a length', async (page) => {
  await page.goto(base);
  await idle(page);
  await page.click('#clear');
  await idle(page);
  await page.check('#query');
  await idle(page);
  const spots = [[2, 2], [4, 4], [6, 1]];
  let [x, y] = await canvasToPage(page, spots[0]);
  await page.mouse.click(x, y);
  await idle(page);
  assert.equal(await shownErrors(page), '', 'a single point (length 0) is no error');
  assert.match(await page.textContent('#query-info'), /arc length 0/);
  assert.match(await page.textContent('#query-at'), /Place a second point/);
  for (const q of spots.slice(1)) {
    [x, y] = await canvasToPage(page, q);
    await page.mouse.click(x, y);
    await idle(page);
  }
  assert.equal(await shownErrors(page), '');
  const curve = await page.evaluate(() => window.lekaloEditor.last.view.curve);
  const m = await api('/api/measure', { curve, at_length: [1] });
  assert.match(await page.textContent('#query-at'), new RegExp(`t = ${m.at_length[0].t.toPrecision(8)}`));
});

test('The curvature comb in every blending mode is the API\'s; quasi-interpolation greys out the comb and the queries', async (page) => {
  for (const mode of ['blend', 'corners', 'spline']) {
    await page.goto(base);
    await page.selectOption('#mode', mode);
    await idle(page);
    assert.equal(await page.getAttribute('#comb-path', 'd'), '', `${mode}: no comb before the box is ticked`);
    await page.check('#comb');
    await idle(page);
    const v = await page.evaluate(() => window.lekaloEditor.last.view);
    assert.ok(v.comb && v.comb.curvature.length === v.points.length, `${mode}: the answer carries the comb`);
    // one tooth every fourth sample, then the polyline of the tips
    const teeth = ((await page.getAttribute('#comb-path', 'd')).match(/M/g) || []).length;
    assert.equal(teeth, Math.ceil(v.points.length / 4) + 1, `${mode}: the comb is drawn`);
  }
  await page.selectOption('#mode', 'quasi');
  await idle(page);
  for (const id of ['#comb', '#query']) {
    assert.ok(await page.isDisabled(id), `${id} greyed out in quasi-interpolation`);
    assert.match(await page.evaluate((s) => document.querySelector(s).closest('label').title, id), /Not in quasi-interpolation/);
  }
  await page.selectOption('#mode', 'bspline');
  await idle(page);
  assert.ok(!(await page.isDisabled('#comb')) && !(await page.isDisabled('#query')), 'enabled again in the other modes');
});

test('Blending two curves: the help names the colours A and B are drawn in', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'blend');
  await idle(page);
  const help = await page.textContent('#help');
  const fills = await page.evaluate(() => [...document.querySelectorAll('#points circle')]
    .map((c) => getComputedStyle(c).fill));
  const na = await page.evaluate(() => window.lekaloEditor.state.blend.a.length);
  // A's points are drawn white, B's pink: the help says so
  assert.ok(fills.slice(0, na).every((f) => f === 'rgb(255, 255, 255)'), `A: ${fills}`);
  assert.ok(fills.slice(na).every((f) => f === 'rgb(255, 221, 221)'), `B: ${fills}`);
  assert.match(help, /Curve A \(white points/);
  assert.match(help, /curve B \(pink points/);
});

test('Knots dragged on the ruler and a weight edited (NURBS): the curve is the API\'s', async (page) => {
  await page.goto(base);
  await idle(page);
  const knot = page.locator('#ruler-knots rect[data-knot="4"]');
  const box = await knot.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  for (let k = 1; k <= 4; k++) { await page.mouse.move(box.x + box.width / 2 + 30 * k, box.y + 3); await idle(page); }
  await page.mouse.up();
  await idle(page);
  let s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.ok(s.knots[4] > 0.6 && s.knots[4] < 1, `knot moved right: ${s.knots[4]}`);
  let expected = await api('/api/bspline', { control: s.control, degree: s.degree, knots: s.knots, samples: 400 });
  await assertCurveIs(page, expected.points, 'knot dragged');
  const [x, y] = await canvasToPage(page, s.control[2]);
  await page.mouse.click(x, y);
  await idle(page);
  await setValue(page, '#bs-weight', 4);
  s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.deepEqual(s.weights, [1, 1, 4, 1, 1]);
  expected = await api('/api/bspline', { control: s.control, degree: s.degree, knots: s.knots, weights: s.weights, samples: 400 });
  assert.equal(expected.curve.type, 'nurbs_curve');
  await assertCurveIs(page, expected.points, 'weight 4');
  await setValue(page, '#bs-weight', -1);
  assert.match(await page.textContent('[data-mode="bspline"] [data-err="weights"]'), /weight/);
});

test('JSON export, reload, import: the same curve; STEP download; undo and redo', async (page) => {
  await page.goto(base);
  await idle(page);
  await assertHeaderComplete(page, 'at 1200 px');
  await setValue(page, '#bs-degree', 2);
  const d = await page.getAttribute('#curve', 'd');
  const json = await downloadText(page, '#export-json');
  assert.equal(json.name, 'curve.json');
  assert.equal(JSON.parse(json.text).type, 'bspline_curve');
  const step = await downloadText(page, '#export-step');
  assert.ok(step.text.startsWith('ISO-10303-21;'), step.text.slice(0, 40));
  assert.match(step.text, /B_SPLINE_CURVE_WITH_KNOTS/);

  await page.goto(base + '#');
  await page.reload();
  await idle(page);
  assert.notEqual(await page.getAttribute('#curve', 'd'), d, 'a fresh page shows the default curve');
  await page.setInputFiles('#import', { name: 'curve.json', mimeType: 'application/json', buffer: Buffer.from(json.text) });
  await idle(page);
  assert.equal(await page.getAttribute('#curve', 'd'), d, 'the imported curve is drawn as before the export');
  await page.setInputFiles('#import', { name: 'bad.json', mimeType: 'application/json', buffer: Buffer.from('{"lekalo": 1, "type": "bspline_curve"}') });
  await idle(page);
  assert.match(await page.textContent('header [data-err="file"]'), /field/);

  const n = await page.locator('#points circle').count();
  const [x, y] = await canvasToPage(page, [5, 0.5]);
  await page.mouse.click(x, y);
  await idle(page);
  const added = await page.getAttribute('#curve', 'd');
  assert.equal(await page.locator('#points circle').count(), n + 1);
  await page.keyboard.press('Control+z');
  await idle(page);
  assert.equal(await page.locator('#points circle').count(), n, 'undo removes the point');
  assert.equal(await page.getAttribute('#curve', 'd'), d, 'undo restores the curve');
  await page.click('#redo');
  await idle(page);
  assert.equal(await page.locator('#points circle').count(), n + 1, 'redo adds it again');
  assert.equal(await page.getAttribute('#curve', 'd'), added);
  assert.ok(decodeURIComponent(page.url()).includes('"control":'), 'the state is in the URL');
});

test('Dragging a point of a 200-point B-spline: frame rate by the Performance API (reported, not asserted)', async (page) => {
  const control = Array.from({ length: 200 }, (_, i) => [0.5 + 9 * i / 199, 3 + 2 * Math.sin(i / 7)]);
  const state = { mode: 'bspline', comb: false, bspline: { degree: 3, control, knots: null, weights: null } };
  await page.goto(base + '#' + encodeURIComponent(JSON.stringify(state)));
  await idle(page);
  assert.equal(await page.locator('#points circle').count(), 200);
  const [x, y] = await canvasToPage(page, control[100]);
  await page.evaluate(() => {
    window.__frames = [];
    window.__draws = 0;
    new MutationObserver(() => { window.__draws++; }).observe(document.getElementById('curve'), { attributes: true });
    const tick = (t) => { window.__frames.push(t); if (!window.__stop) requestAnimationFrame(tick); };
    requestAnimationFrame(tick);
  });
  await page.mouse.move(x, y);
  await page.mouse.down();
  const start = Date.now();
  let moves = 0;
  while (Date.now() - start < 1500) {
    moves++;
    await page.mouse.move(x + 80 * Math.sin(moves / 20), y + 60 * Math.cos(moves / 15));
  }
  await page.mouse.up();
  await idle(page);
  const r = await page.evaluate(() => {
    window.__stop = true;
    const f = window.__frames;
    const gaps = f.slice(1).map((t, k) => t - f[k]).sort((a, b) => a - b);
    const secs = (f[f.length - 1] - f[0]) / 1000;
    return { fps: (f.length - 1) / secs, p95: gaps[Math.floor(0.95 * gaps.length)], draws: window.__draws, secs };
  });
  console.log(`     drag with 200 control points: ${r.fps.toFixed(1)} frames/s (95th-percentile frame gap ${r.p95.toFixed(1)} ms), ` +
    `${moves} pointer moves, ${(r.draws / r.secs).toFixed(1)} curve redraws/s`);
  assert.ok(r.draws > 0, 'the curve followed the drag');
  const s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  const expected = await api('/api/bspline', { control: s.control, degree: 3, samples: 400 });
  await assertCurveIs(page, expected.points, 'after the drag');
});

test('From an empty canvas in every mode: Clear, then each placed point is drawn with the best curve it allows', async (page) => {
  const spots = [[1, 1], [3, 4.5], [5, 2], [7, 5], [9, 1.5]];
  for (const mode of ['bspline', 'interpolate', 'bezier', 'corners', 'spline', 'fit', 'blend', 'quasi']) {
    await page.goto(base);
    await page.selectOption('#mode', mode);
    await idle(page);
    const before = await page.evaluate(() => window.lekaloEditor.state);
    await page.click('#clear');
    await idle(page);
    assert.equal(await shownErrors(page), '', `${mode}: no error after Clear`);
    if (mode === 'quasi') {
      assert.deepEqual(await page.evaluate(() => window.lekaloEditor.state.quasi), before.quasi, 'quasi: Clear returns to the example');
      assert.ok((await page.getAttribute('#curve', 'd')).length > 0, 'quasi: the example is drawn');
      assert.equal(await page.locator('#basis-paths line.zero-line').count(), 1, 'quasi: the error panel has its zero line');
      continue;
    }
    const fixed = mode === 'blend' ? before.blend.a.length : 0;
    if (mode === 'blend') {
      // curve B is the chord of A: the deformation is drawn at once, and there is no basis panel
      assert.ok((await page.getAttribute('#curve', 'd')).length > 0, 'blend: drawn after Clear');
      assert.ok(!(await page.isVisible('#basis')) && !(await page.isVisible('#basis-caption')), 'blend: no empty basis panel');
    } else {
      assert.equal(await page.getAttribute('#curve', 'd'), '', `${mode}: the old curve is gone`);
      assert.match(await page.textContent('#info'), /place the first point/, `${mode}: says what to do`);
    }
    for (let k = 1; k <= spots.length; k++) {
      const [x, y] = await canvasToPage(page, spots[k - 1]);
      await page.mouse.click(x, y);
      await idle(page);
      const what = `${mode}, ${k} point(s)`;
      assert.equal(await page.locator('#points circle').count(), fixed + k, `${what}: every placed point is drawn`);
      assert.equal(await shownErrors(page), '', `${what}: no error`);
      const d = await page.getAttribute('#curve', 'd');
      const fewest = { bspline: 1, interpolate: 2, bezier: 1, corners: 3, spline: 2, fit: 3, blend: 0 }[mode];
      if (k < fewest) {
        assert.equal(d, '', `${what}: nothing drawn yet`);
        assert.match(await page.textContent('#info'), /Place \d more point/, `${what}: says how many more`);
      } else {
        assert.ok(d.length > 0, `${what}: a curve is drawn`);
      }
      if (mode === 'bspline') {
        const s = await page.evaluate(() => window.lekaloEditor.state.bspline);
        const degree = Math.min(s.degree, k - 1);
        const answer = await api('/api/bspline', { control: s.control, degree, samples: 400 });
        await assertCurveIs(page, answer.points, what);
        const info = await page.textContent('#info');
        if (degree < s.degree) assert.match(info, new RegExp(`drawn with degree ${degree}`), `${what}: ${info}`);
        else assert.doesNotMatch(info, /drawn with degree/, `${what}: ${info}`);
        assert.match(info, new RegExp(`${k} control point${k === 1 ? '' : 's'},`), `${what}: ${info}`);
      }
    }
    // the settings survive Clear: the last curve has the degree asked for
    if (mode === 'bspline' || mode === 'interpolate') {
      assert.equal(await page.evaluate(() => window.lekaloEditor.last.view.degree), 3, `${mode}: degree 3 with 5 points`);
    }
  }
  await shot(page, 'from-empty', false);
});

test('An emptied number field is named next to itself, not read as 0; a k too high for the server names k and the degree', async (page) => {
  await page.goto(base);
  await page.selectOption('#mode', 'corners');
  await idle(page);
  await setValue(page, '#co-window', '');
  assert.equal(await page.textContent('[data-mode="corners"] [data-err="fraction"]'), 'Type a number here (the field is empty).');
  assert.equal(await page.evaluate(() => window.lekaloEditor.state.corners.window), 25, 'the window is kept');
  await setValue(page, '#co-window', 30);
  assert.equal(await shownErrors(page), '');
  await setValue(page, '#co-k', 40);
  assert.match(await page.textContent('[data-mode="corners"] [data-err="continuity"]'),
    /^continuity k = 40 makes a curve of degree 81, above the server's limit 64/);
});

test('Keyboard only: Tab to the drawing, Enter places points, N and the arrows move one, Delete deletes it; the curve is the API\'s', async (page) => {
  await page.goto(base);
  await idle(page);
  await page.focus('#clear');
  await page.keyboard.press('Enter');
  await idle(page);
  assert.equal(await page.locator('#points circle').count(), 0, 'cleared by keyboard');
  // the next Tab stops from Clear reach the drawing
  let reached = false;
  for (let i = 0; i < 40 && !reached; i++) {
    await page.keyboard.press('Tab');
    reached = await page.evaluate(() => document.activeElement === document.getElementById('canvas'));
  }
  assert.ok(reached, 'the drawing is reachable by Tab');
  assert.equal(await page.getAttribute('#kbd-cross', 'visibility'), 'visible', 'the cross shows where Enter places a point');
  const press = async (key, times = 1) => { for (let i = 0; i < times; i++) await page.keyboard.press(key); await idle(page); };
  // three points: at the cross (5, 3.125), then 2 to the right, then 1 up and 1 further right
  await press('Enter');
  await press('Shift+ArrowRight', 2);
  // moving the cross moves the point just placed (it is selected): Escape first
  assert.deepEqual(await page.evaluate(() => window.lekaloEditor.state.bspline.control), [[7, 3.125]], 'the selected point follows the arrows');
  await press('Escape');
  await press('Shift+ArrowLeft', 4);
  await press('Enter');
  await press('Escape');
  await press('ArrowUp', 10);
  await press('Enter');
  let s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.deepEqual(s.control, [[7, 3.125], [3, 3.125], [3, 4.125]]);
  assert.equal(await shownErrors(page), '');
  let answer = await api('/api/bspline', { control: s.control, degree: 2, samples: 400 });
  await assertCurveIs(page, answer.points, 'three points placed by keyboard');
  // N selects the first point; the arrows move it; Delete removes it
  await press('Escape');
  await press('n');
  assert.equal(await page.evaluate(() => document.querySelector('#points circle.selected').dataset.index), '0');
  await press('ArrowDown', 5);
  s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.deepEqual(s.control[0], [7, 2.625]);
  answer = await api('/api/bspline', { control: s.control, degree: 2, samples: 400 });
  await assertCurveIs(page, answer.points, 'a point moved by keyboard');
  await press('Delete');
  s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  assert.deepEqual(s.control, [[3, 3.125], [3, 4.125]]);
  // Ctrl+Z brings it back
  await press('Control+z');
  assert.equal(await page.locator('#points circle').count(), 3, 'undo restores the deleted point');
  await shot(page, 'keyboard', false);
});

// every control of the header is shown whole: inside the window, its text not cut, and a file
// input drawn by the browser (whose "No file chosen" it truncates itself) at least as wide as it
// needs, or not drawn at all; the import control is visible and says what it does
async function assertHeaderComplete(page, what) {
  const controls = await page.evaluate(() => [...document.querySelectorAll('header button, header label, header select, header input')].map((e) => {
    const r = e.getBoundingClientRect();
    const style = getComputedStyle(e);
    let natural = 0;
    if (e.type === 'file') {
      const probe = e.cloneNode();
      probe.style.cssText = 'position:absolute;visibility:hidden;width:auto;opacity:1';
      document.body.appendChild(probe);
      natural = probe.getBoundingClientRect().width;
      probe.remove();
    }
    return { id: e.id || e.textContent.trim().slice(0, 20), type: e.type || e.tagName, left: r.left, right: r.right, width: r.width, height: r.height,
      drawn: r.width > 2 && r.height > 2 && style.opacity !== '0' && style.visibility !== 'hidden',
      cut: e.tagName !== 'INPUT' && e.tagName !== 'SELECT' && e.scrollWidth > e.clientWidth + 1, natural, inner: window.innerWidth };
  }));
  for (const c of controls) {
    if (!c.drawn) continue;
    assert.ok(c.left >= -0.5 && c.right <= c.inner + 0.5, `${what}: ${c.id} inside the window (${c.left}..${c.right})`);
    assert.ok(!c.cut, `${what}: ${c.id} shows its whole text`);
    if (c.type === 'file') assert.ok(c.width >= c.natural - 0.5, `${what}: the file input is drawn ${c.width} px wide of the ${c.natural} px its text needs`);
  }
  const label = controls.find((c) => c.id.startsWith('Import JSON'));
  assert.ok(label && label.drawn, `${what}: the import control is visible`);
}

// the grid's coordinates as drawn on screen: each inside the canvas with a margin of at least
// MARGIN screen pixels, and no two of them touching (boxes of the rendered glyphs)
async function assertGridLabelsReadable(page, what) {
  const MARGIN = 3;
  const { canvas, boxes } = await page.evaluate(() => {
    const c = document.getElementById('canvas').getBoundingClientRect();
    const boxes = [...document.querySelectorAll('#grid text.grid-label')].map((t) => {
      const r = t.getBoundingClientRect();
      return { text: t.textContent, left: r.left, right: r.right, top: r.top, bottom: r.bottom };
    });
    return { canvas: { left: c.left, right: c.right, top: c.top, bottom: c.bottom }, boxes };
  });
  for (const b of boxes) {
    assert.ok(b.left >= canvas.left + MARGIN && b.right <= canvas.right - MARGIN
      && b.top >= canvas.top + MARGIN && b.bottom <= canvas.bottom - MARGIN,
    `${what}: coordinate ${b.text} at ${b.left.toFixed(1)}..${b.right.toFixed(1)} × ${b.top.toFixed(1)}..${b.bottom.toFixed(1)} `
      + `is not ${MARGIN} px inside the canvas ${canvas.left.toFixed(1)}..${canvas.right.toFixed(1)} × ${canvas.top.toFixed(1)}..${canvas.bottom.toFixed(1)}`);
  }
  for (let i = 0; i < boxes.length; i++) {
    for (let j = i + 1; j < boxes.length; j++) {
      const [a, b] = [boxes[i], boxes[j]];
      const apart = a.right + 1 <= b.left || b.right + 1 <= a.left || a.bottom <= b.top || b.bottom <= a.top;
      assert.ok(apart, `${what}: coordinates ${a.text} and ${b.text} overlap`);
    }
  }
}

test('Narrow windows: at 1200 px, 800 px and on a phone every mode fits, the canvas keeps its shape and shows coordinates inside it, apart', async (page) => {
  for (const viewport of [{ width: 1200, height: 820 }, { width: 800, height: 900 }, { width: 390, height: 844 }]) {
    await page.setViewportSize(viewport);
    for (const mode of ['bspline', 'interpolate', 'bezier', 'blend', 'corners', 'spline', 'quasi', 'fit']) {
      await page.goto(base);
      await page.selectOption('#mode', mode);
      await idle(page);
      const what = `${mode} at ${viewport.width} px`;
      const box = await page.evaluate(() => {
        const r = (id) => document.getElementById(id).getBoundingClientRect();
        const panel = document.querySelector(`.panel[data-mode="${window.lekaloEditor.state.mode}"]`).getBoundingClientRect();
        return { canvas: r('canvas'), aside: document.querySelector('aside').getBoundingClientRect(), panel,
          scroll: document.documentElement.scrollWidth, inner: window.innerWidth };
      });
      assert.ok(box.scroll <= box.inner, `${what}: no horizontal scrolling (${box.scroll} > ${box.inner})`);
      assert.ok(box.aside.right <= box.inner + 0.5 && box.panel.right <= box.inner + 0.5, `${what}: the side panel is not cut off`);
      assert.ok(box.panel.width >= 200, `${what}: the side panel is readable (${box.panel.width} px)`);
      assert.ok(Math.abs(box.canvas.width / box.canvas.height - 800 / 500) < 0.01, `${what}: canvas aspect ${box.canvas.width}×${box.canvas.height}`);
      const labels = await page.locator('#grid text.grid-label').allTextContents();
      assert.ok(labels.length >= 8 && (mode === 'quasi' || labels.includes('5')), `${what}: grid coordinates ${labels}`);
      await assertGridLabelsReadable(page, what);
      await assertHeaderComplete(page, what);
    }
    // a click lands where the pointer is, whatever the drawing's scale
    await page.goto(base);
    await idle(page);
    await page.click('#clear');
    await idle(page);
    const [x, y] = await canvasToPage(page, [4, 3]);
    await page.mouse.click(x, y);
    await idle(page);
    const p = await page.evaluate(() => window.lekaloEditor.state.bspline.control[0]);
    const tol = 10 / viewport.width * 10; // about one screen pixel in world units, with margin
    assert.ok(Math.abs(p[0] - 4) < tol && Math.abs(p[1] - 3) < tol, `${viewport.width} px: point placed at ${p}`);
    await shot(page, `narrow-${viewport.width}`, false);
  }
});

test('A long request shows a progress bar with the time left, Stop cancels it, and the editor goes on', async (page) => {
  await page.goto(base);
  await idle(page);
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  // the API's answer is held back, as on a slow machine or a large construction
  await page.route('**/api/bspline', async (route) => {
    await sleep(1500);
    await route.continue().catch(() => {}); // a stopped request is already gone
  });
  const click = async (p) => { const [x, y] = await canvasToPage(page, p); await page.mouse.click(x, y); };
  await click([3, 2]);
  // after half a second: the bar, what is computed, the time so far from the server's
  // progress route (the held request has not reached the server: no share yet)
  await page.waitForSelector('#progress', { state: 'visible', timeout: 3000 });
  assert.equal(await page.textContent('#progress-what'), 'Computing…');
  await page.waitForFunction(() => /^\d+\.\d s$/.test(document.getElementById('progress-text').textContent));
  assert.equal(await page.getAttribute('#progress-bar', 'value'), null, 'no share before a report');
  await page.waitForSelector('#progress', { state: 'hidden', timeout: 5000 });
  await idle(page);
  let s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  const answer = await api('/api/bspline', { control: s.control, degree: s.degree, samples: 400 });
  await assertCurveIs(page, answer.points, 'the held answer, drawn when it came');
  assert.equal(await shownErrors(page), '');

  // the server's report: a share and the time left
  await page.route('**/api/progress?*', (route) => route.fulfill({ contentType: 'application/json',
    body: JSON.stringify({ job: 'j', running: true, done: 30, total: 100, elapsed_s: 0.6, remaining_s: 1.4 }) }));
  const drawn = await page.getAttribute('#curve', 'd');
  await click([5, 4]);
  await page.waitForSelector('#progress', { state: 'visible', timeout: 3000 });
  await page.waitForFunction(() => document.getElementById('progress-text').textContent === '30 % · about 1.4 s left');
  assert.equal(await page.getAttribute('#progress-bar', 'max'), '100');
  assert.equal(await page.evaluate(() => document.getElementById('progress-bar').value), 30);
  await shot(page, 'progress', false);
  await page.click('#progress-stop');
  await page.waitForSelector('#progress', { state: 'hidden', timeout: 3000 });
  await idle(page);
  assert.match(await shownErrors(page), /^Stopped: the computation was cancelled/);
  assert.equal(await page.getAttribute('#curve', 'd'), drawn, 'the last computed curve stays drawn');

  // the editor goes on: the next change computes and clears the note
  await page.unroute('**/api/bspline');
  await page.unroute('**/api/progress?*');
  await click([6, 1]);
  await idle(page);
  s = await page.evaluate(() => window.lekaloEditor.state.bspline);
  const after = await api('/api/bspline', { control: s.control, degree: s.degree, samples: 400 });
  await assertCurveIs(page, after.points, 'after Stop');
  assert.equal(await shownErrors(page), '');
});

let failed = 0;
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: CHROMIUM_ARGS, headless: true });
try {
  // ONLY=text runs the tests whose name contains it (scripts/test-browser.sh runs them all)
  for (const t of tests.filter((t) => !process.env.ONLY || t.name.includes(process.env.ONLY))) {
    const context = await browser.newContext({ viewport: { width: 1200, height: 820 } });
    const page = await context.newPage();
    const problems = [];
    page.on('console', (m) => { if (m.type() === 'error') problems.push(m.text()); });
    page.on('pageerror', (e) => problems.push(String(e)));
    const started = Date.now();
    try {
      await t.fn(page);
      // a 400 answer is a shown error, not a console error; the console must stay clean otherwise
      const real = problems.filter((p) => !p.includes('400 (Bad Request)'));
      assert.deepEqual(real, [], 'console errors');
      console.log(`ok   ${t.name} (${Date.now() - started} ms)`);
    } catch (e) {
      failed++;
      console.log(`FAIL ${t.name}\n     ${e.stack}`);
      await page.screenshot({ path: path.join(artifacts, `failed-${tests.indexOf(t)}.png`) }).catch(() => {});
    }
    await context.close();
  }
} finally {
  await browser.close();
}
console.log(`${tests.filter((t) => !process.env.ONLY || t.name.includes(process.env.ONLY)).length - failed} passed, ${failed} failed; screenshots in ${artifacts}`);
process.exit(failed ? 1 : 0);
