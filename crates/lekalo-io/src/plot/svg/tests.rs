//! Tests of the figures and the standard plots.

use super::plots::{deviation_stretch, PLOT_MAX_MARKERS};
use super::ticks::fmt_legend;
use super::*;
use crate::object::Object;
use crate::CurveJson;
use lekalo::{KnotVector, Points};

#[test]
fn legend_figures_have_four_significant_digits() {
    for (v, want) in [
        (0.118_924_521, "0.1189"),
        (0.039_569_3, "0.03957"),
        (1234.56, "1235"),
        (2.0, "2"),
        (0.0, "0"),
        (3.956_931_7e-7, "3.957e-7"),
        (1.5e300, "1.5e300"),
    ] {
        assert_eq!(fmt_legend(v), want, "{v}");
    }
}

#[test]
fn residual_segments_join_points_to_their_feet() {
    let data = Points::from_2d(&[[0.0, 1.0], [1.0, -2.0], [2.0, 0.5]]).expect("points");
    let feet = Points::from_2d(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]).expect("points");
    let s = residual_series(&data, &feet, &crate::Projection::default()).expect("series");
    assert_eq!(s.paths.len(), 3, "one segment a point");
    assert_eq!(s.paths[1], vec![[1.0, -2.0], [1.0, 0.0]], "point to foot");
    // max 2, RMS sqrt((1 + 4 + 0.25) / 3)
    assert_eq!(
        s.label.as_deref(),
        Some("deviations: max 2, RMS 1.323"),
        "legend"
    );
    let short = Points::from_2d(&[[0.0, 0.0]]).expect("points");
    assert!(
        residual_series(&data, &short, &crate::Projection::default()).is_err(),
        "counts differ"
    );
}

#[test]
fn deviations_below_a_pixel_are_drawn_stretched_and_say_so() {
    // a fit within 1e-3 of points spread over 10 units: the segments are stretched by 500 (the
    // largest becomes 0.5, 5 % of the extent), from the foot towards the point
    let data =
        Points::from_2d(&[[0.0, 0.0], [5.0, 1e-3], [10.0, -5e-4], [10.0, 0.0]]).expect("points");
    let feet =
        Points::from_2d(&[[0.0, 0.0], [5.0, 0.0], [10.0, 0.0], [10.0, 0.0]]).expect("points");
    let s = residual_series(&data, &feet, &crate::Projection::default()).expect("series");
    assert_eq!(
        s.paths[1],
        vec![[5.0, 0.5], [5.0, 0.0]],
        "stretched from the foot"
    );
    assert_eq!(
        s.paths[2],
        vec![[10.0, -0.25], [10.0, 0.0]],
        "the same factor for all"
    );
    assert!(
        s.label
            .as_deref()
            .is_some_and(|l| l.starts_with("deviations (drawn ×500): max 0.001,")),
        "{:?}",
        s.label
    );
    assert_eq!(
        deviation_stretch(2.0, 3.0),
        1.0,
        "visible deviations are drawn as they are"
    );
    assert_eq!(deviation_stretch(0.0, 3.0), 1.0, "no deviation");
}

#[test]
fn the_largest_residual_is_drawn_among_decimated_ones() {
    let n = 10_001;
    let data =
        Points::from_flat(2, (0..n).flat_map(|i| [i as f64, 1.0]).collect()).expect("points");
    let mut feet = data.as_slice().to_vec();
    for i in 0..n {
        feet[2 * i + 1] = if i == 4_567 { -9.0 } else { 0.0 };
    }
    let feet = Points::from_flat(2, feet).expect("points");
    let s = residual_series(&data, &feet, &crate::Projection::default()).expect("series");
    assert!(
        s.paths.len() <= PLOT_MAX_MARKERS + 1,
        "decimated: {}",
        s.paths.len()
    );
    assert!(
        s.paths.iter().any(|p| p[1] == [4_567.0, -9.0]),
        "the largest deviation is drawn"
    );
    assert_eq!(
        s.label
            .as_deref()
            .map(|l| l.starts_with("deviations (drawn ×50): max 10,")),
        Some(true),
        "{:?}",
        s.label
    );
}

#[test]
fn ticks_are_nice() {
    assert_eq!(
        nice_ticks(0.0, 1.0),
        vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
    );
    assert_eq!(nice_ticks(-3.0, 3.0), vec![-2.0, 0.0, 2.0]);
    assert!(nice_ticks(1.0, 1.0).is_empty());
    assert_eq!(fmt_tick(0.6000000000000001), "0.6");
}

#[test]
fn knot_and_curve_figures() {
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]).unwrap();
    let fig = knots_figure("k", &kv);
    // one marker per knot, stacked by multiplicity: 0 three times, 0.5 twice
    let marks = &fig.series[1].paths[0];
    assert_eq!(marks.len(), 8);
    assert_eq!(marks[4], [0.5, 2.0]);
    let obj = Object::from_json_str(
        r#"{"lekalo":1,"type":"nurbs_curve","degree":2,"knots":[0,0,0,0.5,0.5,1,1,1],
           "control":[[1,0,0],[1,1,0],[0,1,0],[-1,1,0],[-1,0,0]],"weights":[1,0.5,1,0.5,1]}"#,
        "t",
    )
    .unwrap();
    let data = Points::from_3d(&[[1.0, 0.0, 0.0]]).unwrap();
    let fig = curve_figure(
        &obj,
        &CurvePlot {
            data_points: Some(&data),
            samples: 11,
            ..CurvePlot::default()
        },
    )
    .unwrap();
    assert!(!fig.axes, "no axes in a projected 3-D view");
    let labels: Vec<_> = fig.series.iter().filter_map(|s| s.label.clone()).collect();
    assert_eq!(
        labels,
        ["control polygon", "data points", "curve", "points at knots"],
        "the data under the curve"
    );
    // knot marks at the distinct knots 0, 0.5, 1 of the domain
    assert_eq!(fig.series[4].paths[0].len(), 3);
    assert_eq!(fig.series[3].paths[0].len(), 11);
    assert!(fig.to_svg().contains("NURBS curve of degree 2"));
}

/// The figure check of a figure without a caption.
fn lekalo_io_check(svg: &str) -> Vec<String> {
    crate::check_svg(svg, None)
}

#[test]
fn basis_plot_of_the_lecture() {
    let kv = KnotVector::new(vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]).unwrap();
    let fig = basis_figure(&kv, 2, 31).unwrap();
    // three basis functions, the zero line, the knot ticks, the shaded domain [1, 2]
    assert_eq!(fig.series.len(), 5);
    assert_eq!(fig.band.as_ref().map(|b| (b.0, b.1)), Some((1.0, 2.0)));
    // N_{1,2}(1.5) = 3/4 (document 002, B-splines): sample 15 is t = 1.5
    assert_eq!(fig.series[1].paths[0][15], [1.5, 0.75]);
    let svg = fig.to_svg();
    assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    assert_eq!(svg.matches("<polyline").count(), 4);
    // N_{0,2} is drawn over its support [0, 2] only, back to the axis
    assert_eq!(fig.series[0].paths[0].last(), Some(&[2.0, 0.0]));
    assert_eq!(lekalo_io_check(&svg), Vec::<String>::new());
    assert!(basis_figure(&kv, 5, 10).is_err());
    assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
}
