// Frame rate while dragging a control point of a 200-point B-spline in the editor (headless
// Chromium): the page counts requestAnimationFrame callbacks with performance.now() while the
// pointer moves for 3 s, and the curve updates (answers drawn) in the same time.
//
// Usage: LEKALO_URL=http://127.0.0.1:PORT/ node bench/serve/fps.mjs
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '..', '..', 'web-tests', 'package.json'));
const { chromium } = require('playwright-core');
const base = process.env.LEKALO_URL;
if (!base) throw new Error('set LEKALO_URL');

const control = Array.from({ length: 200 }, (_, i) => [0.5 + 9 * i / 199, 3 + 2 * Math.sin(i / 7)]);
const state = { mode: 'bspline', comb: false, bspline: { degree: 3, control, knots: null, weights: null } };
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'] });
const page = await browser.newPage({ viewport: { width: 1200, height: 820 } });
await page.goto(base + '#' + encodeURIComponent(JSON.stringify(state)));
await page.evaluate(() => window.lekaloEditor.idle());
const target = await page.evaluate(() => {
  const c = document.querySelector('#points circle[data-index="100"]').getBoundingClientRect();
  return [c.x + c.width / 2, c.y + c.height / 2];
});
await page.evaluate(() => {
  window.__frames = [];
  window.__draws = 0;
  const curve = document.getElementById('curve');
  new MutationObserver(() => { window.__draws++; }).observe(curve, { attributes: true });
  const tick = (t) => { window.__frames.push(t); if (!window.__stop) requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
});
await page.mouse.move(target[0], target[1]);
await page.mouse.down();
const start = Date.now();
let i = 0;
while (Date.now() - start < 3000) {
  i++;
  await page.mouse.move(target[0] + 80 * Math.sin(i / 20), target[1] + 60 * Math.cos(i / 15));
}
await page.mouse.up();
const r = await page.evaluate(() => {
  window.__stop = true;
  const f = window.__frames;
  const gaps = f.slice(1).map((t, k) => t - f[k]).sort((a, b) => a - b);
  return { fps: (f.length - 1) / ((f[f.length - 1] - f[0]) / 1000), p95gap: gaps[Math.floor(0.95 * gaps.length)],
    draws: window.__draws, secs: (f[f.length - 1] - f[0]) / 1000 };
});
console.log(`drag with 200 control points: ${r.fps.toFixed(1)} frames/s (95th percentile frame gap ${r.p95gap.toFixed(1)} ms), ${i} pointer moves, ${(r.draws / r.secs).toFixed(1)} curve redraws/s`);
await browser.close();
