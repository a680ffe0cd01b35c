//! Faces: validation of loops and the point-in-face test on a square with a round hole.

use super::*;
use crate::{BSplineCurve, BSplineSurface, Curve, Error, NurbsCurve, Points, Surface};
use proptest::prelude::*;

pub(super) fn plane() -> Surface {
    Surface::from(
        BSplineSurface::new(
            1,
            1,
            vec![0.0, 0.0, 4.0, 4.0],
            vec![0.0, 0.0, 4.0, 4.0],
            Points::from_3d(&[
                [0.0, 0.0, 0.0],
                [0.0, 4.0, 0.0],
                [4.0, 0.0, 0.0],
                [4.0, 4.0, 0.0],
            ])
            .unwrap(),
            (2, 2),
        )
        .unwrap(),
    )
}

pub(super) fn segment(a: [f64; 2], b: [f64; 2]) -> Edge {
    let d = [b[0] - a[0], b[1] - a[1]];
    Edge::new(
        Curve::from(
            BSplineCurve::line_segment(&[a[0], a[1], 0.0], &[d[0], d[1], 0.0], 0.0, 1.0).unwrap(),
        ),
        Some(Curve::from(
            BSplineCurve::line_segment(&a, &d, 0.0, 1.0).unwrap(),
        )),
    )
    .unwrap()
}

pub(super) fn square(reverse: bool) -> Loop {
    let mut c = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
    if reverse {
        c.reverse();
    }
    Loop::new((0..4).map(|k| segment(c[k], c[(k + 1) % 4])).collect()).unwrap()
}

/// The circle of radius 1 about (2, 2), clockwise with `reverse`.
pub(super) fn hole(reverse: bool) -> Loop {
    let c3 = NurbsCurve::circle(&[2.0, 2.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 1.0).unwrap();
    let c2 = NurbsCurve::circle(&[2.0, 2.0], &[1.0, 0.0], &[0.0, 1.0], 1.0).unwrap();
    let (mut a, mut b) = (Curve::from(c3), Curve::from(c2));
    if reverse {
        a = a.reverse().unwrap();
        b = b.reverse().unwrap();
    }
    Loop::new(vec![Edge::new(a, Some(b)).unwrap()]).unwrap()
}

#[test]
fn square_with_a_hole_contains_the_ring_only() {
    for (ro, ri) in [(false, true), (true, false), (false, false)] {
        let f = Face::new(plane(), square(ro), vec![hole(ri)], true, LOOP_CLOSURE_RTOL).unwrap();
        assert_eq!(f.edge_count(), 5);
        let r = f.trim_region().unwrap();
        assert_eq!(r.polygons().len(), 2);
        assert!(r.contains(0.5, 0.5), "corner of the ring");
        assert!(r.contains(3.5, 2.0), "right of the hole");
        assert!(!r.contains(2.0, 2.0), "centre of the hole");
        assert!(!r.contains(2.9, 2.0), "inside the hole near its edge");
        assert!(r.contains(3.1, 2.0), "outside the hole near its edge");
        assert!(
            !r.contains(-0.1, 2.0) && !r.contains(2.0, 4.1),
            "outside the square"
        );
    }
}

#[test]
fn a_loop_that_does_not_close_is_refused_with_the_edge() {
    let mut edges = square(false).edges().to_vec();
    edges[2] = segment([4.0, 4.0], [0.0, 3.0]);
    let e = Face::new(
        plane(),
        Loop::new(edges).unwrap(),
        vec![],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap_err();
    let Error::InvalidArgument { what, reason } = e else {
        panic!("{e:?}")
    };
    assert_eq!(what.words(), "face loop");
    assert!(
        reason.contains("outer loop") && reason.contains("edge 2"),
        "{reason}"
    );
    // within a looser tolerance the same loop is accepted: 1 of a model of size 4√2
    let mut edges = square(false).edges().to_vec();
    edges[2] = segment([4.0, 4.0], [0.0, 3.0]);
    assert!(Face::new(plane(), Loop::new(edges).unwrap(), vec![], true, 0.2).is_ok());
}

#[test]
fn sizes_and_dimensions_are_checked() {
    assert!(matches!(
        Loop::new(vec![]),
        Err(Error::TooFew { min: 1, got: 0, .. })
    ));
    let c3 = square(false).edges()[0].curve().clone();
    assert!(matches!(
        Edge::new(c3.clone(), Some(c3)),
        Err(Error::Dimension {
            expected: 2,
            got: 3,
            ..
        })
    ));
    let flat = Edge::new(
        Curve::from(BSplineCurve::line_segment(&[0.0, 0.0], &[1.0, 0.0], 0.0, 1.0).unwrap()),
        None,
    )
    .unwrap();
    let e = Face::new(plane(), Loop::new(vec![flat]).unwrap(), vec![], true, 1.0).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Dimension {
                expected: 3,
                got: 2,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(Face::new(plane(), square(false), vec![], true, f64::NAN).is_err());
    assert!(Face::new(plane(), square(false), vec![], true, -1.0).is_err());
}

#[test]
fn the_test_needs_pcurves() {
    let edges: Vec<Edge> = square(false)
        .edges()
        .iter()
        .map(|e| Edge::new(e.curve().clone(), None).unwrap())
        .collect();
    let f = Face::new(
        plane(),
        Loop::new(edges).unwrap(),
        vec![],
        false,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    assert!(!f.outer().has_pcurves() && !f.same_sense());
    let e = f.trim_region().unwrap_err().to_string();
    assert!(e.contains("edge 0 of loop 0 has no curve"), "{e}");
}

proptest! {
    /// A point's winding number about a convex polygon is ±1 inside and 0 outside, and its
    /// sign follows the direction of the polygon.
    #[test]
    fn winding_of_a_regular_polygon(n in 3usize..40, x in -2.0f64..2.0, y in -2.0f64..2.0) {
        let mut xy = Vec::new();
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            xy.extend([a.cos(), a.sin()]);
        }
        let inner = (std::f64::consts::PI / n as f64).cos(); // inscribed circle
        let r = x.hypot(y);
        prop_assume!((r - inner).abs() > 1e-9 && (r - 1.0).abs() > 1e-9);
        let w = winding_number(&xy, x, y);
        if r < inner {
            prop_assert_eq!(w, 1);
        } else if r > 1.0 {
            prop_assert_eq!(w, 0);
        }
        let back: Vec<f64> = xy.chunks(2).rev().flatten().copied().collect();
        prop_assert_eq!(winding_number(&back, x, y), -w);
    }
}

#[test]
fn shell_shares_edges_run_both_ways_and_closed_edges_keep_one_vertex() {
    // the same square twice, once each way round: every edge shared, used once each way
    let a = Face::new(
        plane(),
        square(false),
        vec![hole(false)],
        true,
        LOOP_CLOSURE_RTOL,
    )
    .unwrap();
    let b = Face::new(plane(), square(true), vec![], false, LOOP_CLOSURE_RTOL).unwrap();
    let shell = Shell::new(&[&a, &b]).unwrap();
    // 4 sides shared by both faces, and the hole's circle used by the first only
    assert_eq!(shell.edges().len(), 5);
    assert_eq!(
        shell.vertices().len(),
        5,
        "4 corners and the circle's one vertex"
    );
    let circle = &shell.edges()[4];
    assert_eq!(circle.vertices[0], circle.vertices[1]);
    for e in &shell.edges()[..4] {
        assert_eq!(e.uses.len(), 2);
        assert_eq!((e.uses[0].1, e.uses[1].1), (true, false));
        assert_eq!(e.uses[1].0.face, 1);
    }
    let first = EdgeUse {
        face: 0,
        lp: 0,
        edge: 0,
    };
    assert_eq!(shell.edge_of(first), Some((0, true)));
    // the circle is used once: not closed; without it, every edge is used once each way
    assert!(!shell.is_closed());
    let a = Face::new(plane(), square(false), vec![], true, LOOP_CLOSURE_RTOL).unwrap();
    assert!(Shell::new(&[&a, &b]).unwrap().is_closed());
    // one face alone is open, and a third use of an edge starts a new edge
    assert!(!Shell::new(&[&a]).unwrap().is_closed());
    let shell = Shell::new(&[&a, &b, &a]).unwrap();
    assert_eq!(shell.edges().len(), 8);
}
