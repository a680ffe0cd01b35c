//! The command line's input layer as a hostile user drives it: a file's contents read with
//! every `--header` rule and with a byte-order mark, as points, as an object and as JSON Lines,
//! then plotted with hostile plot options (view angles, sample counts, data points). Whatever
//! is accepted must be finite, and a plot must never contain NaN or infinite coordinates.
#![no_main]

use arbitrary::Arbitrary;
use lekalo_io::{
    curve_figure, read_json_lines, read_points_with, CurvePlot, Header, Object, Projection,
};
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input {
    header: u8,
    bom: bool,
    azimuth: f64,
    elevation: f64,
    samples: u16,
    contents: String,
    points: String,
}

fn check_svg(svg: &str) {
    assert!(
        !svg.contains("NaN") && !svg.contains("inf"),
        "a plot holds a non-finite coordinate"
    );
}

fuzz_target!(|input: Input| {
    let header = match input.header % 3 {
        0 => Header::Auto,
        1 => Header::Yes,
        _ => Header::No,
    };
    let text = if input.bom {
        format!("\u{feff}{}", input.contents)
    } else {
        input.contents.clone()
    };
    if let Ok(p) = read_points_with(&text, "fuzz", header) {
        assert!(p.as_slice().iter().all(|v| v.is_finite()), "{p:?}");
    }
    let data = read_points_with(&input.points, "fuzz-points", header).ok();
    let mut objects: Vec<Object> = read_json_lines(&text, "fuzz")
        .into_iter()
        .filter_map(|(_, o)| o.ok())
        .take(4)
        .collect();
    if let Ok(o) = Object::from_json_str(&text, "fuzz") {
        objects.push(o);
    }
    // the CLI refuses non-finite view angles and samples outside [2, 10^6]
    if !(input.azimuth.is_finite() && input.elevation.is_finite()) {
        return;
    }
    let samples = usize::from(input.samples).clamp(2, 2_000);
    for o in &objects {
        if o.control_points().len() > 5_000 || o.degree() > 200 {
            continue;
        }
        let plot = CurvePlot {
            samples,
            data_points: data.as_ref(),
            projection: Projection {
                azimuth: input.azimuth,
                elevation: input.elevation,
            },
            ..CurvePlot::default()
        };
        if let Ok(fig) = curve_figure(o, &plot) {
            check_svg(&fig.to_svg());
        }
    }
});
