// The editor's modes by name, each a module with the same parts:
//   fewest, point   the fewest points it draws a curve from, and what a point is called
//   help            the line shown above its panel
//   compute(s, view, n)  the request for state `s` (view options, n editable points): a
//                   promise of the answer, `{view, …}`
//   others(answer)  what else is drawn: the control polygon, a dashed polyline or curve,
//                   the bounds of a fit
//   describe(answer, text), show(answer)  the info line (from the curve's description) and
//                   the mode's own panel figures, when it has them
//   sync(s), bind(act)   the panel's controls from the state, and their listeners
import { mode as bspline } from './bspline.js';
import { mode as interpolate } from './interpolate.js';
import { mode as bezier } from './bezier.js';
import { blend, corners, spline } from './blend.js';
import { mode as quasi } from './quasi.js';
import { mode as fit } from './fit.js';

export const MODES = { bspline, interpolate, bezier, blend, corners, spline, quasi, fit };
