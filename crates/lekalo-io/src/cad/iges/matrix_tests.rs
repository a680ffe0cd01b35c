//! Tests of transformation matrices (entity 124): applied, chained, in the file's unit, and
//! refused with the reason where they place nothing.

use lekalo::{NurbsCurve, NurbsSurface, Points};

use super::*;
use crate::object::Object;
use crate::shape::Surface;

/// A directory entry's two records (fields right-aligned in 8 columns) at sequence `seq`.
fn entry(ty: u32, start: usize, lines: usize, matrix: u64, form: u32, seq: usize) -> String {
    let a = format!(
        "{ty:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{matrix:>8}{:>8}{:>8}D{seq:>7}\n",
        0, 0, 0, 0, 0, "00000000"
    );
    let b = format!(
        "{ty:>8}{:>8}{:>8}{lines:>8}{form:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
        0,
        0,
        "",
        "",
        "",
        "",
        seq + 1
    );
    a + &b
}

/// `text` (an `IgesWriter` file of one entity) with the entity pointing at the first of
/// `matrices` (parameters, form and the next matrix, chained in order), which are appended.
fn with_matrices(text: &str, matrices: &[([f64; 12], u32)]) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let d: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| &l[72..73] == "D")
        .collect();
    let mut p: Vec<String> = lines
        .iter()
        .filter(|l| &l[72..73] == "P")
        .map(|l| (*l).to_string())
        .collect();
    let mut de = String::new();
    let first = d.len() + 1;
    for (k, (m, form)) in matrices.iter().enumerate() {
        let seq = first + 2 * k;
        let next = if k + 1 < matrices.len() { seq + 2 } else { 0 };
        let params: Vec<String> = m.iter().map(|x| format!("{x:?}")).collect();
        let body = format!("124,{};", params.join(","));
        de += &entry(124, p.len() + 1, 1, next as u64, *form, seq);
        p.push(format!("{body:<64}{seq:>8}P{:>7}", p.len() + 1));
    }
    // the entity's own first record points at the first matrix (field 7, columns 49–56)
    let own = format!("{}{first:>8}{}", &d[0][..48], &d[0][56..]);
    let start: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| matches!(&l[72..73], "S" | "G"))
        .collect();
    format!(
        "{}\n{own}\n{}\n{de}{}\nS      1G      2D{:>7}P{:>7}{:>40}T      1\n",
        start.join("\n"),
        d[1],
        p.join("\n"),
        d.len() + 2 * matrices.len(),
        p.len(),
        ""
    )
}

/// `text` with the directory entry at sequence `seq` pointing at the matrix `at` (field 7).
fn pointing(text: &str, seq: usize, at: usize) -> String {
    let own = format!("D{seq:>7}");
    text.lines()
        .map(|l| {
            if l.ends_with(&own) {
                format!("{}{at:>8}{}", &l[..48], &l[56..])
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A quarter turn about z, then `t`.
fn turn(t: [f64; 3]) -> [f64; 12] {
    [
        0.0, -1.0, 0.0, t[0], 1.0, 0.0, 0.0, t[1], 0.0, 0.0, 1.0, t[2],
    ]
}

fn arc() -> NurbsCurve {
    NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        Points::from_3d(&[[1.0, 0.0, 0.5], [1.0, 1.0, 0.5], [0.0, 1.0, 0.5]]).unwrap(),
        vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
    )
    .unwrap()
}

#[test]
fn a_curve_is_read_in_the_coordinates_of_its_chained_matrices() {
    let mut w = IgesWriter::new();
    w.add_object(&Object::Nurbs(arc())).unwrap();
    let text = w.finish("arc", "20000101.000000");
    // turned a quarter about z and moved by (1, 2, 3), then moved by (10, 0, 0)
    let moved = with_matrices(
        &text,
        &[
            (turn([1.0, 2.0, 3.0]), 0),
            (
                [1.0, 0.0, 0.0, 10.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                0,
            ),
        ],
    );
    let r = read_iges(&moved, "moved.igs").unwrap();
    assert!(r.skipped.is_empty(), "{:?}", r.skipped);
    let Shape::Curve(c) = &r.shapes[0].1 else {
        panic!("a curve")
    };
    // (x, y, z) ↦ (−y + 1 + 10, x + 2, z + 3): exact in binary
    // (a NURBS keeps w·x: the middle point comes back through a weight of 1/√2)
    let want = [[11.0, 3.0, 3.5], [10.0, 3.0, 3.5], [10.0, 2.0, 3.5]];
    for (p, q) in c.control_points().iter().zip(want) {
        assert!(
            p.iter()
                .zip(q)
                .all(|(a, b)| (a - b).abs() <= 4.0 * f64::EPSILON * b.abs()),
            "{p:?}"
        );
    }
    assert_eq!(c.weights(), Some(arc().weights()));
    assert_eq!(c.knots().as_slice(), arc().knots().as_slice());
    // the circle's centre moved with it: every point at distance 1 from (11, 2, 3.5)
    for k in 0..=8 {
        let p = c.eval(k as f64 / 8.0).unwrap();
        assert!(((p[0] - 11.0).hypot(p[1] - 2.0) - 1.0).abs() < 1e-15);
    }
}

#[test]
fn a_surface_follows_its_matrix_and_translations_are_in_the_file_unit() {
    let net = Points::from_3d(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.25],
        [1.0, 0.0, -0.5],
        [1.0, 1.0, 1.0],
    ])
    .unwrap();
    let s = NurbsSurface::new(
        1,
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![0.0, 0.0, 1.0, 1.0],
        net,
        vec![1.0, 2.0, 0.5, 1.0],
        (2, 2),
    )
    .unwrap();
    let mut w = IgesWriter::new();
    w.add_surface(&Surface::Nurbs(s.clone())).unwrap();
    // the same file in inches: the net and the translation are both scaled to millimetres
    let text = w.finish("s", "20000101.000000");
    assert!(text.contains(",2,2HMM,"), "{text}");
    let text = text.replace(",2,2HMM,", ",1,2HIN,");
    let moved = with_matrices(&text, &[(turn([1.0, 0.0, 0.0]), 1)]);
    let r = read_iges(&moved, "patch.igs").unwrap();
    let Shape::Surface(got) = &r.shapes[0].1 else {
        panic!("a surface")
    };
    for (p, q) in got.control_points().iter().zip(s.control_points().iter()) {
        let want = [(1.0 - q[1]) * 25.4, q[0] * 25.4, q[2] * 25.4];
        assert!(
            p.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12),
            "{p:?} {want:?}"
        );
    }
    assert_eq!(got.weights(), Some(s.weights()));
}

#[test]
fn matrices_that_place_nothing_are_reasons_to_skip() {
    let mut w = IgesWriter::new();
    w.add_object(&Object::Nurbs(arc())).unwrap();
    let text = w.finish("arc", "20000101.000000");
    let reason = |moved: &str| {
        let r = read_iges(moved, "m.igs").unwrap();
        assert!(r.shapes.is_empty());
        r.skipped.listed()[0].reason.clone()
    };
    // a finite-element coordinate system
    let fem = with_matrices(&text, &[(turn([0.0; 3]), 10)]);
    assert!(reason(&fem).contains("form 10"), "{}", reason(&fem));
    // a matrix short of its twelve numbers
    let short = with_matrices(&text, &[(turn([0.0; 3]), 0)])
        .replace(",0.0,0.0,1.0,0.0;", ";                ");
    assert!(
        reason(&short).contains("12 finite numbers"),
        "{}",
        reason(&short)
    );
    // a pointer at the entity itself, not at a matrix
    let own = pointing(&with_matrices(&text, &[(turn([0.0; 3]), 0)]), 1, 1);
    assert!(
        reason(&own).contains("not an entity 124"),
        "{}",
        reason(&own)
    );
    // two matrices that point at each other
    let two = with_matrices(&text, &[(turn([0.0; 3]), 0), (turn([0.0; 3]), 0)]);
    let cycle = pointing(&two, 5, 3);
    assert!(
        reason(&cycle).contains("form a cycle, D3 → D5 → D3"),
        "{}",
        reason(&cycle)
    );
}
