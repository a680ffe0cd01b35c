// A bounded load on loopback: C concurrent clients send R requests each (a fifth of them
// hostile: malformed JSON, NaN, huge sizes), then the server must still answer a health check.
// Prints the status counts, throughput and p99; exits 1 if a request got an unexpected status.
//
// Usage: LEKALO_URL=http://127.0.0.1:PORT/ node bench/serve/load.mjs [C] [R]
const base = process.env.LEKALO_URL;
if (!base) throw new Error('set LEKALO_URL');
const clients = Number(process.argv[2] || 16), rounds = Number(process.argv[3] || 200);
const points = Array.from({ length: 100 }, (_, i) => [i / 10, Math.sin(i / 10)]);
const good = JSON.stringify({ points, samples: 1000, basis_samples: 300, at: 0.5 });
const hostile = ['{"points": [[0, NaN]]}', '{"points": ', JSON.stringify({ points, samples: 1e9 }),
  JSON.stringify({ points: Array(20000).fill([0.5, 0.5]) })];
const counts = {}, times = [];
let unexpected = 0;
const t0 = performance.now();
await Promise.all(Array.from({ length: clients }, async (_, c) => {
  for (let i = 0; i < rounds; i++) {
    const bad = (c + i) % 5 === 0;
    const body = bad ? hostile[(c + i) % hostile.length] : good;
    const s = performance.now();
    const r = await fetch(new URL('/api/interpolate', base), { method: 'POST', body });
    await r.arrayBuffer();
    times.push(performance.now() - s);
    counts[r.status] = (counts[r.status] || 0) + 1;
    if (r.status !== (bad ? 400 : 200)) unexpected++;
  }
}));
const secs = (performance.now() - t0) / 1000;
times.sort((a, b) => a - b);
const health = await fetch(new URL('/api/health', base));
console.log(`load: ${clients} clients x ${rounds} requests in ${secs.toFixed(2)} s (${(clients * rounds / secs).toFixed(0)} req/s), statuses ${JSON.stringify(counts)}, p99 ${times[Math.floor(0.99 * times.length)].toFixed(2)} ms, health ${health.status}`);
process.exit(unexpected || health.status !== 200 ? 1 : 0);
