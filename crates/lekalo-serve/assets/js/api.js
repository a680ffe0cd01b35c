// The API client: every computation is a request to the server's JSON API (docs/serve.md).
//
// Long requests: every computing request carries a job id (header x-lekalo-job). One still
// unanswered after SHOW_AFTER_MS shows the bar under the canvas, fed by GET
// /api/progress?job=ID every POLL_MS: the share done of the computation's current stage and the
// server's estimate of the time left (before the computation reports, the bar moves without a
// share). Stop aborts the request; the server stops a computation whose request is dropped.
import { $ } from './screen.js';

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
export async function request(path, init) {
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

// the header of every body the editor posts: JSON (the server refuses forms and uploads)
export const JSON_BODY = { 'content-type': 'application/json' };

// POST a JSON body; the answer's JSON, or an Error carrying the API's message, field and status
export async function post(path, body) {
  const r = await request(path, { method: 'POST', headers: JSON_BODY,
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
