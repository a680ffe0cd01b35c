// Frame rate while dragging a control point of a 200-point cubic B-spline in the editor
// (headless Chromium), reported as figures, not checked against a threshold.
//
// The drag is synthetic and paced by the display: after a real press on point 100, the page
// moves the pointer once per animation frame (a PointerEvent on the document, as a mouse
// sends one per frame while it moves), for 3 s. Measured in the page:
// - frames: requestAnimationFrame timestamps (performance.now() clock): frames/s and the
//   95th-percentile gap between frames (16.7 ms at 60 frames/s);
// - redraws: how often the curve changed (each one an answer of the server drawn), and the
//   JavaScript time of each redraw (the page's draw(), without the browser's style, layout and
//   paint, which fall in the frames above);
// - long animation frames (> 50 ms, the Long Animation Frames API) with their total time.
//
// Usage: LEKALO_URL=http://127.0.0.1:PORT/ node bench/serve/fps.mjs [SECONDS]
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, '..', '..', 'web-tests', 'package.json'));
const { chromium } = require('playwright-core');
const base = process.env.LEKALO_URL;
if (!base) throw new Error('set LEKALO_URL');
const seconds = Number(process.argv[2] || 3);

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
await page.mouse.move(target[0], target[1]);
await page.mouse.down();
const r = await page.evaluate(([x0, y0, ms]) => new Promise((done) => {
  const frames = [], drawTimes = [], long = [];
  let draws = 0;
  // the page's draw(), timed (a global function of the page's script)
  const draw = window.draw;
  window.draw = (answer) => {
    const s = performance.now();
    draw(answer);
    drawTimes.push(performance.now() - s);
  };
  const curve = document.getElementById('curve');
  const observer = new MutationObserver(() => { draws++; });
  observer.observe(curve, { attributes: true, attributeFilter: ['d'] });
  const loaf = new PerformanceObserver((list) => { for (const e of list.getEntries()) long.push(e.duration); });
  try { loaf.observe({ type: 'long-animation-frame' }); } catch { /* not in this browser */ }
  let k = 0;
  const tick = (t) => {
    frames.push(t);
    if (t - frames[0] < ms) {
      k++;
      document.dispatchEvent(new PointerEvent('pointermove', { bubbles: true, pointerId: 1, isPrimary: true,
        pointerType: 'mouse', buttons: 1, clientX: x0 + 80 * Math.sin(k / 20), clientY: y0 + 60 * Math.cos(k / 15) }));
      requestAnimationFrame(tick);
    } else {
      observer.disconnect();
      loaf.disconnect();
      window.draw = draw;
      const gaps = frames.slice(1).map((g, i) => g - frames[i]).sort((a, b) => a - b);
      drawTimes.sort((a, b) => a - b);
      const secs = (frames[frames.length - 1] - frames[0]) / 1000;
      const q = (v, p) => (v.length ? v[Math.min(v.length - 1, Math.floor(p * v.length))] : NaN);
      done({ fps: gaps.length / secs, p95gap: q(gaps, 0.95), moves: k, secs, redraws: draws / secs,
        drawP50: q(drawTimes, 0.5), drawP95: q(drawTimes, 0.95), long: long.length,
        longMs: long.reduce((a, b) => a + b, 0) });
    }
  };
  requestAnimationFrame(tick);
}), [target[0], target[1], seconds * 1000]);
await page.mouse.up();
console.log(`drag with 200 control points, ${r.secs.toFixed(1)} s, a pointer move each frame (${r.moves} moves): ` +
  `${r.fps.toFixed(1)} frames/s, 95th-percentile frame gap ${r.p95gap.toFixed(1)} ms; ` +
  `${r.redraws.toFixed(1)} curve redraws/s, draw() p50 ${r.drawP50.toFixed(2)} ms, p95 ${r.drawP95.toFixed(2)} ms; ` +
  `${r.long} frames over 50 ms (${r.longMs.toFixed(0)} ms in all)`);
await browser.close();
