//! `interpolate --grid` with the interior knots of some directions given (`--knots-u`,
//! `--knots-v`, `--knots-in K=LIST`): the knots are the written spline's, the other directions
//! keep their averaged knots, and wrong knots exit with 2 naming the option and the direction;
//! `--end` and `--knots` (placement) apply to every direction of the grid.

#![allow(clippy::missing_assert_message)] // assert_cmd's assertions print the output

use std::fs;
use std::path::Path;

use assert_cmd::Command;
use predicates::str::contains;

fn lekalo() -> Command {
    Command::cargo_bin("lekalo").unwrap()
}

/// `f(x, y, z) = x·y + z²` on the uniform grid of `[0, 1]³` with 6 × 5 × 4 nodes, one value a
/// row, the first direction slowest.
fn values(dir: &Path) -> std::path::PathBuf {
    let mut s = String::new();
    let at = |k: u32, n: u32| f64::from(k) / f64::from(n - 1);
    for i in 0..6 {
        for j in 0..5 {
            for k in 0..4 {
                let (x, y, z) = (at(i, 6), at(j, 5), at(k, 4));
                s.push_str(&format!("{:?}\n", x * y + z * z));
            }
        }
    }
    let v = dir.join("values.txt");
    fs::write(&v, s).unwrap();
    v
}

fn knots(j: &serde_json::Value, a: usize) -> Vec<f64> {
    j["knots"][a]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect()
}

#[test]
fn given_interior_knots_are_the_splines_and_it_still_interpolates() {
    let d = tempfile::tempdir().unwrap();
    let v = values(d.path());
    let t = d.path().join("tensor.json");
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "6x5x4", "--degree", "3,3,2", "--param", "uniform"])
        .args(["--knots-u", "0.3,0.55", "--knots-in", "3=0.6", "-o"])
        .arg(&t)
        .assert()
        .success();
    let j: serde_json::Value = serde_json::from_str(&fs::read_to_string(&t).unwrap()).unwrap();
    assert_eq!(
        knots(&j, 0),
        [0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 1.0, 1.0, 1.0, 1.0]
    );
    assert_eq!(knots(&j, 2), [0.0, 0.0, 0.0, 0.6, 1.0, 1.0, 1.0]);
    // direction 2 keeps its averaged knot: the mean of the parameters 1/4, 2/4, 3/4
    let k1 = knots(&j, 1);
    assert_eq!(k1.len(), 9);
    assert!((k1[4] - 0.5).abs() < 1e-15, "{k1:?}");
    // the spline space holds f, so the interpolant is f everywhere, with the new knots too
    let out = lekalo()
        .arg("eval")
        .arg(&t)
        .args(["--at", "0.35,0.7,0.45,0.9,0.1,0.65", "--json"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let e: serde_json::Value = serde_json::from_slice(&out).unwrap();
    for (row, (x, y, z)) in [(0.35, 0.7, 0.45), (0.9, 0.1, 0.65)]
        .into_iter()
        .enumerate()
    {
        let got = e["rows"][row][3].as_f64().unwrap();
        assert!((got - (x * y + z * z)).abs() < 1e-12, "{got}");
    }
    // --knots-in 1= is --knots-u
    let same = lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "6x5x4", "--degree", "3,3,2", "--param", "uniform"])
        .args(["--knots-in", "1=0.3,0.55", "--knots-in", "3=0.6"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_eq!(
        String::from_utf8(same).unwrap(),
        fs::read_to_string(&t).unwrap()
    );
}

#[test]
fn a_surface_grid_takes_knots_in_u_and_v_as_fit_does() {
    let d = tempfile::tempdir().unwrap();
    let pts = d.path().join("grid.csv");
    let mut s = String::new();
    for i in 0..5 {
        for j in 0..4 {
            s.push_str(&format!("{i},{},{}\n", j * j, f64::from(i + j * j).sqrt()));
        }
    }
    fs::write(&pts, s).unwrap();
    let out = lekalo()
        .arg("interpolate")
        .arg(&pts)
        .args(["--grid", "5x4", "--degree", "3,2", "--knots-v", "0.25"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let j: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(j["type"], "bspline_surface");
    assert_eq!(
        j["knots_v"],
        serde_json::json!([0.0, 0.0, 0.0, 0.25, 1.0, 1.0, 1.0])
    );
    // clamped in both directions: the net's corners are the grid's corners
    let corner = &j["control"][19];
    assert!(
        (corner[1].as_f64().unwrap() - 9.0).abs() < 1e-12,
        "{corner}"
    );
    assert!(
        (corner[2].as_f64().unwrap() - 13f64.sqrt()).abs() < 1e-12,
        "{corner}"
    );
    // without knots, averaging puts the v knot elsewhere
    let placed = lekalo()
        .arg("interpolate")
        .arg(&pts)
        .args(["--grid", "5x4", "--degree", "3,2"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let p: serde_json::Value = serde_json::from_slice(&placed).unwrap();
    assert_eq!(p["knots_u"], j["knots_u"]);
    assert_ne!(p["knots_v"], j["knots_v"]);
}

#[test]
fn wrong_knots_exit_2_naming_the_option_and_direction() {
    let d = tempfile::tempdir().unwrap();
    let v = values(d.path());
    let fails = |args: &[&str], needle: &str| {
        lekalo()
            .arg("interpolate")
            .arg(&v)
            .args(["--grid", "6x5x4", "--degree", "3,3,2", "--param", "uniform"])
            .args(args)
            .assert()
            .code(2)
            .stderr(contains(needle));
    };
    fails(
        &["--knots-in", "3=0.4,0.6"],
        "--knots-in 3: 2 interior knots for the 4 grid values of direction 3 at degree 2",
    );
    fails(
        &["--knots-v", "1.5"],
        "--knots-v: the knot 1.5 is not inside",
    );
    fails(
        &["--knots-u", "0.05,0.1"],
        "--knots-u (direction 1, grid parameters",
    );
    fails(&["--knots-u", "0.05,0.1"], "Schoenberg–Whitney");
    fails(
        &["--knots-in", "4=0.5"],
        "--knots-in 4: the spline has 3 directions",
    );
    fails(
        &["--knots-in", "0=0.5"],
        "is not a direction number (from 1)",
    );
    fails(
        &["--knots-v", "0.5", "--knots-in", "2=0.5"],
        "direction 2 already has knots from --knots-v",
    );
    fails(&["--knots-in", "0.5"], "is not K=LIST");
    fails(&["--knots-in", "z=0.5"], "is not a direction number");
    fails(&["--knots-u", "0.3,x"], "--knots-u");
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--knots-u", "0.5"])
        .assert()
        .code(2)
        .stderr(contains("--grid"));
}

/// `lekalo eval FILE --at …` of a tensor spline: the value column of each row.
fn eval_at(spline: &Path, at: &[[f64; 3]]) -> Vec<f64> {
    let (_, rows) = crate::common::eval_at(spline, at);
    rows.iter().map(|r| r[3]).collect()
}

#[test]
fn end_conditions_and_knot_placement_apply_to_every_direction() {
    let d = tempfile::tempdir().unwrap();
    let v = values(d.path());
    let run = |extra: &[&str], name: &str| {
        let t = d.path().join(name);
        lekalo()
            .arg("interpolate")
            .arg(&v)
            .args(["--grid", "6x5x4", "--param", "uniform"])
            .args(extra)
            .arg("-o")
            .arg(&t)
            .assert()
            .success();
        let j: serde_json::Value = serde_json::from_str(&fs::read_to_string(&t).unwrap()).unwrap();
        (t, j)
    };
    // periodic in every direction: the grid does not repeat its first line, and the spline
    // takes the same value at both ends of each direction's domain
    let (t, j) = run(&["--degree", "3,2,2", "--end", "periodic"], "periodic.json");
    let domain: Vec<(f64, f64)> = (0..3)
        .map(|a| {
            let k = knots(&j, a);
            let p = [3, 2, 2][a];
            (k[p], k[k.len() - p - 1])
        })
        .collect();
    // a point inside the box, then its direction a moved to either end of the domain
    let inside: Vec<f64> = domain
        .iter()
        .zip([0.3, 0.45, 0.7])
        .map(|(&(lo, hi), s)| lo + s * (hi - lo))
        .collect();
    for a in 0..3 {
        let at = |x: f64| [0, 1, 2].map(|b| if b == a { x } else { inside[b] });
        let v = eval_at(&t, &[at(domain[a].0), at(domain[a].1)]);
        assert!((v[0] - v[1]).abs() < 1e-12, "direction {}: {v:?}", a + 1);
    }
    // the same values as one NumPy array: rows x1, x2, x3, y
    let npy = d.path().join("values.npy");
    let at: Vec<String> = inside.iter().map(|x| format!("{x:?}")).collect();
    lekalo()
        .arg("eval")
        .arg(&t)
        .args(["--at", &at.join(","), "-o"])
        .arg(&npy)
        .assert()
        .success();
    let (shape, flat) = lekalo_io::read_npy_array(&fs::read(&npy).unwrap(), "values.npy").unwrap();
    assert_eq!(shape, [1, 4]);
    assert_eq!(
        flat[3],
        eval_at(&t, &[[inside[0], inside[1], inside[2]]])[0]
    );
    // natural ends differ from free ones; uniform knots are evenly spaced
    let (_, natural) = run(&["--end", "natural", "--degree", "3"], "natural.json");
    let (_, free) = run(&["--degree", "3"], "free.json");
    assert_ne!(natural["control"], free["control"]);
    let (_, uniform) = run(&["--degree", "3", "--knots", "uniform"], "uniform.json");
    let k0 = knots(&uniform, 0);
    assert!(
        (k0[4] - 1.0 / 3.0).abs() < 1e-15 && (k0[5] - 2.0 / 3.0).abs() < 1e-15,
        "{k0:?}"
    );
    assert!((knots(&free, 0)[4] - 0.4).abs() < 1e-15);
    // end derivatives, and periodic ends with given knots, are refused naming the options
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "6x5x4", "--end", "derivatives"])
        .args(["--start-derivative", "0", "--end-derivative", "0"])
        .assert()
        .code(2)
        .stderr(contains("--end"));
    lekalo()
        .arg("interpolate")
        .arg(&v)
        .args(["--grid", "6x5x4", "--end", "periodic", "--knots-u", "0.5"])
        .assert()
        .code(2)
        .stderr(contains("drop"));
}

/// A surface grid (two sizes) takes `--end` and `--knots` as grids in more directions do: the
/// tensor interpolation of two directions, written as a surface. Averaged knots with free ends
/// are the surface interpolation's own, bit for bit.
#[test]
fn a_surface_grid_takes_end_conditions_and_knot_placements() {
    let d = tempfile::tempdir().unwrap();
    let pts = d.path().join("grid.csv");
    let mut s = String::new();
    for i in 0..6 {
        for j in 0..5 {
            let (x, y) = (f64::from(i), f64::from(j * j) / 4.0);
            s.push_str(&format!("{x},{y},{}\n", (0.7 * x).sin() * (0.5 * y).cos()));
        }
    }
    fs::write(&pts, s).unwrap();
    let run = |extra: &[&str]| -> serde_json::Value {
        let out = lekalo()
            .arg("interpolate")
            .arg(&pts)
            .args(["--grid", "6x5", "--degree", "3"])
            .args(extra)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        serde_json::from_slice(&out).unwrap()
    };
    let plain = run(&[]);
    assert_eq!(plain, run(&["--knots", "averaged"]));
    let natural = run(&["--end", "natural"]);
    assert_eq!(natural["type"], "bspline_surface");
    assert_ne!(natural["control"], plain["control"]);
    // still through the grid's corners (clamped in both directions)
    let last = natural["control"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    assert!((last[0].as_f64().unwrap() - 5.0).abs() < 1e-12, "{last}");
    assert!((last[1].as_f64().unwrap() - 4.0).abs() < 1e-12, "{last}");
    // (uniform knots with free ends: second-derivative ends take their own knots, "auto")
    let uniform = run(&["--knots", "uniform"]);
    let ku: Vec<f64> = uniform["knots_u"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        (ku[4] - 1.0 / 3.0).abs() < 1e-15 && (ku[5] - 2.0 / 3.0).abs() < 1e-15,
        "{ku:?}"
    );
    let periodic = run(&["--end", "periodic"]);
    assert_eq!(periodic["type"], "bspline_surface");
    lekalo()
        .arg("interpolate")
        .arg(&pts)
        .args(["--grid", "6x5", "--end", "periodic", "--knots-u", "0.5"])
        .assert()
        .code(2)
        .stderr(contains("drop"));
}
