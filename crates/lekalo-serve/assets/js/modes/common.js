// What the modes share: the note on a degree the placed points do not allow yet, the current
// curve of a one-off operation, and numbers typed in a text field.
import { plural } from '../screen.js';
import { ui } from '../state.js';
import { showError } from '../errors.js';

// While a curve is being placed point by point, the degree asked for may need more points than
// there are: the curve is drawn with the highest degree the points allow, and the note says so.
export function degreeNote(n, asked, used, word) {
  return used < asked
    ? `${plural(n, word)} allow${n === 1 ? 's' : ''} degree ${used} at most: drawn with degree ${used}; place ${asked + 1 - n} more for degree ${asked}.`
    : '';
}

// the current curve, or an error shown at `field` when there is none yet
export function currentCurve(field) {
  if (ui.last && ui.last.view) return ui.last.view.curve;
  throw Object.assign(new Error('There is no curve yet: place points on the canvas first.'), { field });
}

// numbers typed in a text field, separated by commas, spaces or semicolons
export function numberList(text, field) {
  const v = text.split(/[\s,;]+/).filter((x) => x !== '').map(Number);
  if (v.some((x) => !Number.isFinite(x))) {
    throw Object.assign(new Error(`${field}: give numbers separated by commas`), { field });
  }
  return v;
}

// a number input: on change, `set(value)`, an undo point and a new computation; an emptied
// field is not read as 0 but named, next to itself
export function bindNumber(act, input, set) {
  input.addEventListener('change', () => {
    if (input.value.trim() === '') {
      showError({ message: 'Type a number here (the field is empty).', field: input.dataset.field });
      return;
    }
    set(Number(input.value));
    act.commit();
    act.update();
  });
}
