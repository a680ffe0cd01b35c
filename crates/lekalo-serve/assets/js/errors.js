// Errors next to the control that caused them: the API names the request field at fault, and
// the page shows the message at the element marked data-err="field" in the current mode's
// panel (else in the query panel, the header or beside the drawing; else at the bottom).
import { $ } from './screen.js';
import { state } from './state.js';

export function clearErrors() {
  document.querySelectorAll('.err').forEach((e) => { e.textContent = ''; });
}

export function showError(e) {
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
