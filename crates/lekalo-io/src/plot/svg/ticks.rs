//! Axis ticks at round numbers and the numbers of ticks and legends.

/// Tick values at 1, 2 or 5 × 10^k covering `[lo, hi]` (about five ticks).
pub(crate) fn nice_ticks(lo: f64, hi: f64) -> Vec<f64> {
    // the span from halves, so that [-1e308, 1e308] does not overflow
    let half = hi / 2.0 - lo / 2.0;
    if half.is_nan() || half <= 0.0 || !half.is_finite() {
        return Vec::new();
    }
    let raw = half / 2.5;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    if !(step > 0.0 && step.is_finite()) {
        return Vec::new();
    }
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let mut out = Vec::new();
    let mut k = first;
    while k <= last && out.len() < 50 {
        let v = k * step;
        if v.is_finite() {
            out.push(v);
        }
        k += 1.0;
    }
    out
}

pub(crate) fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-4..1e6).contains(&a) {
        // exponent notation with up to four significant digits: `1.5e300`, `2e-320`, never
        // `inf` or a row of zeros
        let s = format!("{v:.3e}");
        return match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            None => s,
        };
    }
    let r = (v * 1e9).round() / 1e9;
    let s = format!("{r}");
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A figure in a legend: four significant digits (`0.1189`, `3.957e-7`), exponent notation
/// outside `[1e-4, 1e6)` as on the ticks.
pub(super) fn fmt_legend(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 || !(1e-4..1e6).contains(&a) {
        return fmt_tick(v);
    }
    // a is in [1e-4, 1e6): three decimals from 1 on, one more for each power of ten below
    let (mut decimals, mut bound) = (0, 1000.0);
    while a < bound && decimals < 7 {
        decimals += 1;
        bound /= 10.0;
    }
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}
