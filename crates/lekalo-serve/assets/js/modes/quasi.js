// Mode "Quasi-interpolation" (POST /api/quasi, document 003): a typed f(x), breakpoints, order
// and the τ rule or explicit τ values; f dashed, q solid, f − q in the lower panel.
import { $ } from '../screen.js';
import { state } from '../state.js';
import { post } from '../api.js';
import { drawError } from '../panels.js';
import { bindNumber, numberList } from './common.js';

export const mode = {
  point: 'point',
  help: 'Type f(x); the quasi-interpolant q (solid) and f (dashed); the lower panel plots f − q.',
  compute(s) {
    const q = s.quasi;
    const breaks = numberList(q.breaks, 'breakpoints');
    const req = { expression: q.expr, breakpoints: breaks, order: q.order, intervals: 200, basis_samples: 300 };
    if (q.rule === 'explicit') req.tau = numberList(q.tau, 'tau');
    else req.rule = q.rule;
    return post('/api/quasi', req);
  },
  others() { return {}; },
  show(answer) {
    $('qi-info').textContent = `max |f − q| on 200 intervals: ${answer.max_error.toExponential(4)}`;
    drawError(answer);
  },
  sync(s) {
    $('qi-expr').value = s.quasi.expr;
    $('qi-breaks').value = s.quasi.breaks;
    $('qi-order').value = s.quasi.order;
    $('qi-rule').value = s.quasi.rule;
    $('qi-tau').value = s.quasi.tau || '';
    $('qi-tau-label').hidden = s.quasi.rule !== 'explicit';
  },
  bind(act) {
    $('qi-expr').addEventListener('input', () => { state.quasi.expr = $('qi-expr').value; act.update(); });
    $('qi-expr').addEventListener('change', act.commit);
    $('qi-breaks').addEventListener('change', () => { state.quasi.breaks = $('qi-breaks').value; act.commit(); act.update(); });
    bindNumber(act, $('qi-order'), (v) => { state.quasi.order = v; });
    $('qi-rule').addEventListener('change', () => { state.quasi.rule = $('qi-rule').value; act.commit(); act.syncControls(); act.update(); });
    $('qi-tau').addEventListener('change', () => { state.quasi.tau = $('qi-tau').value; act.commit(); act.update(); });
  },
};
