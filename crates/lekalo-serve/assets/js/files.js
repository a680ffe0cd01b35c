// Files: import of a curve in the CLI's JSON (POST /api/import), export of the drawn curve as
// JSON or STEP (POST /api/export/json, /api/export/step), and of the canvas as SVG or PNG.
import { $, H, SVGNS, W } from './screen.js';
import { commit, state } from './state.js';
import { JSON_BODY, request } from './api.js';
import { showError } from './errors.js';
import { tracked } from './idle.js';
import { currentCurve } from './modes/common.js';

async function importFile(act) {
  const file = $('import').files[0];
  if (!file) return;
  try {
    const r = await request('/api/import', { method: 'POST', headers: JSON_BODY, body: await file.text() });
    const v = await r.json();
    if (!r.ok) throw Object.assign(new Error(v.error), { field: v.field });
    if (v.curve.type === 'bezier_curve') {
      state.mode = 'bezier';
      state.bezier.control = v.control;
    } else {
      state.mode = 'bspline';
      state.bspline = { degree: v.degree, control: v.control, knots: v.knots, weights: v.weights };
    }
    commit(); act.syncControls(); act.update();
  } catch (e) {
    // the message names the file's field; it is shown next to the import control
    showError(Object.assign(e, { field: 'file' }));
  }
  $('import').value = '';
}

async function exportCurve(path, name) {
  try {
    const r = await request(path, { method: 'POST', headers: JSON_BODY,
      body: JSON.stringify({ curve: currentCurve('file') }) });
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

const SVG_STYLE = `.bg{fill:#fff}.gridline{stroke:#eee}.grid-label{fill:#888}.curve{fill:none;stroke:#1f4e9c;stroke-width:2.5}
.polygon{fill:none;stroke:#999;stroke-dasharray:4 3}.other{fill:none;stroke:#c77;stroke-dasharray:4 3}
.exact{fill:none;stroke:#d62728;stroke-dasharray:6 4}.comb{fill:none;stroke:#2ca02c;stroke-width:0.8}
.knot{fill:#ff7f0e}.cp{fill:#fff;stroke:#333;stroke-width:1.5}.cp.second{fill:#fdd}.data{fill:#1f4e9c}
.fit-data{fill:#888}.handle{fill:#2ca02c}.handle-line{stroke:#2ca02c}
.bound{stroke:#d62728;stroke-width:1.5;stroke-dasharray:8 4}.bound-label{fill:#d62728;font-family:sans-serif;paint-order:stroke;stroke:#fff;stroke-width:4px}`;

function exportPng() {
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

export function bindFiles(act) {
  $('import').addEventListener('change', () => tracked(() => importFile(act)));
  $('export-json').addEventListener('click', () => exportCurve('/api/export/json', 'curve.json'));
  $('export-step').addEventListener('click', () => exportCurve('/api/export/step', 'curve.step'));
  $('export-svg').addEventListener('click', () => download(new Blob([svgText()], { type: 'image/svg+xml' }), 'lekalo.svg'));
  $('export-png').addEventListener('click', exportPng);
}
