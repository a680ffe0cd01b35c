// Counting the work in flight, so that a test (or a screenshot) can wait until the page is idle:
// the computation loop reports whether it runs, one-off requests (order change, knot
// operations, import, projections) count themselves with `tracked` or `begin`/`end`.
let running = false, busy = 0;
const waiters = [];

function wake() {
  if (!running && busy === 0) while (waiters.length) waiters.shift()();
}

export function setRunning(r) { running = r; wake(); }
export function begin() { busy++; }
export function end() { busy--; wake(); }

export async function tracked(fn) {
  begin();
  try { await fn(); } finally { end(); }
}

// a promise settled once nothing is in flight
export function idle() {
  return running || busy ? new Promise((r) => waiters.push(r)) : Promise.resolve();
}
