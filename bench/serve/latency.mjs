// Round-trip latency of the editor's heaviest frequent request on loopback: interpolate 100
// points, answer 1,000 samples of the curve and the basis panel (300 samples per function, the
// active functions at a parameter). Prints p50/p90/p99/max over N requests on one keep-alive
// connection, after a warm-up. Target: p99 <= 5 ms with a release build.
//
// Usage: LEKALO_URL=http://127.0.0.1:PORT/ node bench/serve/latency.mjs [N]
const base = process.env.LEKALO_URL;
if (!base) throw new Error('set LEKALO_URL');
const n = Number(process.argv[2] || 2000);
const points = Array.from({ length: 100 }, (_, i) => [i / 10, Math.sin(i / 10) + 0.1 * Math.cos(i)]);
const url = new URL('/api/interpolate', base);

async function once(i) {
  const body = JSON.stringify({ points, degree: 3, parametrization: 'centripetal', samples: 1000,
    basis_samples: 300, at: (i % 97) / 97 });
  const t0 = performance.now();
  const r = await fetch(url, { method: 'POST', body });
  const data = await r.json();
  const dt = performance.now() - t0;
  if (!r.ok || data.points.length !== 1000) throw new Error(JSON.stringify(data).slice(0, 200));
  return dt;
}

for (let i = 0; i < 200; i++) await once(i);
const times = [];
for (let i = 0; i < n; i++) times.push(await once(i));
times.sort((a, b) => a - b);
const q = (p) => times[Math.min(times.length - 1, Math.floor(p * times.length))].toFixed(3);
console.log(`interpolate 100 points + 1000 samples + basis: n=${n} p50=${q(0.5)} ms p90=${q(0.9)} ms p99=${q(0.99)} ms max=${times[times.length - 1].toFixed(3)} ms`);
