//! `lekalo demo`: the documents' worked examples on built-in data, with their key numbers.

use std::io::Write;

use anyhow::Result;
use lekalo::{basis::basis_function_recursive, BSplineCurve, KnotVector, Points};

/// Prints a summary table of the built-in constructions.
pub(crate) fn run(out: &mut impl Write) -> Result<()> {
    writeln!(out, "lekalo demo: worked examples of the source documents")?;
    writeln!(out)?;
    // document 002 §C.5: the lecture's B-spline example
    let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]])?;
    let knots = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0])?;
    let curve = BSplineCurve::from_knot_vector(2, knots.clone(), ctrl)?;
    writeln!(
        out,
        "doc 002 §C.5  B-spline, P = (1,1),(2,3),(4,3), knots [0,0,1,2,3,3], degree 2"
    )?;
    writeln!(
        out,
        "  {:>5}  {:>26}  {:>18}",
        "t", "(N02, N12, N22)", "P(t)"
    )?;
    for t in [0.0, 0.5, 1.0, 1.5, 2.0, 2.5] {
        let n: Vec<f64> = (0..3)
            .map(|i| basis_function_recursive(&knots, i, 2, t))
            .collect::<lekalo::Result<_>>()?;
        let p: Vec<f64> = (0..2)
            .map(|d| {
                (0..3)
                    .map(|i| n[i] * curve.control_points().point(i)[d])
                    .sum()
            })
            .collect();
        writeln!(
            out,
            "  {t:>5.2}  ({:>6.4}, {:>6.4}, {:>6.4})  ({:>7.4}, {:>7.4})",
            n[0], n[1], n[2], p[0], p[1]
        )?;
    }
    let (a, b) = curve.domain();
    writeln!(
        out,
        "  domain [{a}, {b}] (partition of unity there); P({a}) = {:?}, P({b}) = {:?}",
        curve.eval(a)?,
        curve.eval(b)?
    )?;
    writeln!(out)?;
    // document 000 eq. (3): averaged knots for P&T Example 9.1, chord length
    let t = [0.0, 5.0 / 17.0, 9.0 / 17.0, 14.0 / 17.0, 1.0];
    let kv = KnotVector::averaged(&t, 3)?;
    writeln!(
        out,
        "doc 000 eq.(3)  averaged knots, chord parameters of P&T Ex. 9.1: {:?}",
        kv.as_slice()
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn demo_prints_lecture_numbers() {
        let mut buf = Vec::new();
        super::run(&mut buf).unwrap();
        let s = String::from_utf8(buf).unwrap();
        assert!(s.contains("(0.1250, 0.7500, 0.1250)"), "{s}");
        assert!(s.contains("( 2.1250,  2.7500)"), "{s}");
    }
}
