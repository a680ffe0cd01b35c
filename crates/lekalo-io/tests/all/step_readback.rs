//! STEP files read back with an independent ISO 10303-21 parser (`ruststep`), and the parsed
//! control points, weights and knots evaluated against our curve.

#![allow(clippy::missing_assert_message)] // test helpers: the values in the failure say enough
use lekalo::{BSplineCurve, NurbsCurve, Points};
use lekalo_io::CurveJson;
use lekalo_io::{CurveNet, Grid, Object, StepWriter, SurfaceNet};
use ruststep::ast::{EntityInstance, Name, Parameter, Record};
use std::collections::HashMap;

/// Parsed DATA section: id → records (one for a simple instance, several for a complex one).
fn parse(text: &str) -> HashMap<u64, Vec<Record>> {
    let ex = ruststep::parser::parse(text).expect("ruststep parses the file");
    assert_eq!(ex.data.len(), 1, "one DATA section");
    let header: Vec<&str> = ex.header.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(header, ["FILE_DESCRIPTION", "FILE_NAME", "FILE_SCHEMA"]);
    let mut out = HashMap::new();
    for e in &ex.data[0].entities {
        let (id, recs) = match e {
            EntityInstance::Simple { id, record } => (*id, vec![record.clone()]),
            EntityInstance::Complex { id, subsuper } => (*id, subsuper.0.clone()),
        };
        assert!(out.insert(id, recs).is_none(), "entity #{id} defined twice");
    }
    // every line of the file's DATA section was parsed (nothing silently skipped)
    let n_lines = text.lines().filter(|l| l.starts_with('#')).count();
    assert_eq!(out.len(), n_lines, "all entity instances parsed");
    out
}

fn params(r: &Record) -> &[Parameter] {
    match &r.parameter {
        Parameter::List(v) => v,
        other => panic!("record parameters {other:?}"),
    }
}

fn list(p: &Parameter) -> &[Parameter] {
    match p {
        Parameter::List(v) => v,
        other => panic!("expected a list, got {other:?}"),
    }
}

fn real(p: &Parameter) -> f64 {
    match p {
        Parameter::Real(x) => *x,
        Parameter::Integer(i) => *i as f64,
        other => panic!("expected a real, got {other:?}"),
    }
}

fn int(p: &Parameter) -> usize {
    match p {
        Parameter::Integer(i) => usize::try_from(*i).unwrap(),
        other => panic!("expected an integer, got {other:?}"),
    }
}

fn point(data: &HashMap<u64, Vec<Record>>, p: &Parameter) -> Vec<f64> {
    let Parameter::Ref(Name::Entity(id)) = p else {
        panic!("expected a reference, got {p:?}")
    };
    let rec = &data[id][0];
    assert_eq!(rec.name, "CARTESIAN_POINT");
    list(&params(rec)[1]).iter().map(real).collect()
}

fn expand(mults: &[Parameter], knots: &[Parameter]) -> Vec<f64> {
    assert_eq!(
        mults.len(),
        knots.len(),
        "one multiplicity per distinct knot"
    );
    mults
        .iter()
        .zip(knots)
        .flat_map(|(m, k)| std::iter::repeat_n(real(k), int(m)))
        .collect()
}

/// Reads the one curve of the file back as a NURBS (unit weights for a non-rational curve).
fn read_curve(text: &str) -> NurbsCurve {
    let data = parse(text);
    let (_, recs) = data
        .iter()
        .find(|(_, r)| r.iter().any(|r| r.name.starts_with("B_SPLINE_CURVE")))
        .expect("a B-spline curve entity");
    let get = |name: &str| recs.iter().find(|r| r.name == name);
    let (degree, ctrl, mults, knots, weights);
    if let Some(simple) = get("B_SPLINE_CURVE_WITH_KNOTS").filter(|_| recs.len() == 1) {
        let p = params(simple);
        assert_eq!(p.len(), 9, "B_SPLINE_CURVE_WITH_KNOTS has 9 attributes");
        degree = int(&p[1]);
        ctrl = list(&p[2]).to_vec();
        assert_eq!(p[3], Parameter::Enumeration("UNSPECIFIED".into()));
        assert_eq!(p[4], Parameter::Enumeration("F".into()));
        mults = list(&p[6]).to_vec();
        knots = list(&p[7]).to_vec();
        weights = vec![1.0; ctrl.len()];
    } else {
        let names: Vec<&str> = recs.iter().map(|r| r.name.as_str()).collect();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        assert_eq!(
            names, sorted,
            "complex instance lists its partial records in order"
        );
        let b = params(get("B_SPLINE_CURVE").unwrap());
        degree = int(&b[0]);
        ctrl = list(&b[1]).to_vec();
        let k = params(get("B_SPLINE_CURVE_WITH_KNOTS").unwrap());
        mults = list(&k[0]).to_vec();
        knots = list(&k[1]).to_vec();
        weights = list(&params(get("RATIONAL_B_SPLINE_CURVE").unwrap())[0])
            .iter()
            .map(real)
            .collect();
    }
    let rows: Vec<Vec<f64>> = ctrl.iter().map(|p| point(&data, p)).collect();
    NurbsCurve::new(
        degree,
        expand(&mults, &knots),
        Points::from_rows(&rows).unwrap(),
        weights,
    )
    .expect("the file's curve is a valid NURBS")
}

fn same_points(obj: &Object, back: &NurbsCurve) {
    assert_eq!(back.domain(), obj.domain());
    for t in obj.uniform_parameters(41) {
        let a = obj.eval(t).unwrap();
        let b = back.eval(t).unwrap();
        for k in 0..3 {
            let ak = a.get(k).copied().unwrap_or(0.0);
            assert!(
                (ak - b[k]).abs() < 1e-14,
                "coordinate {k} at t = {t}: {ak} vs {}",
                b[k]
            );
        }
    }
}

#[test]
fn lecture_bspline_reads_back() {
    let ctrl = Points::from_2d(&[[1.0, 1.0], [2.0, 3.0], [4.0, 3.0]]).unwrap();
    let obj =
        Object::BSpline(BSplineCurve::new(2, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0], ctrl).unwrap());
    let mut w = StepWriter::new("lecture");
    w.add_object(&obj).unwrap();
    let text = w.finish("2026-01-01T00:00:00");
    assert!(text.contains("(2,1,1,2),(0.,1.,2.,3.)"), "{text}");
    same_points(&obj, &read_curve(&text));
}

#[test]
fn nurbs_circle_reads_back_as_rational() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let ctrl = Points::from_3d(&[
        [1.0, 0.0, 0.5],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.5],
        [-1.0, 1.0, 0.5],
        [-1.0, 0.0, 0.5],
    ])
    .unwrap();
    let c = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        ctrl,
        vec![1.0, s, 1.0, s, 1.0],
    )
    .unwrap();
    let obj = Object::Nurbs(c);
    let mut w = StepWriter::new("half circle");
    w.add_object(&obj).unwrap();
    let text = w.finish("2026-01-01T00:00:00");
    let back = read_curve(&text);
    assert_eq!(back.weights(), obj.weights().unwrap());
    same_points(&obj, &back);
}

#[test]
fn bezier_and_surface_structure() {
    let obj = Object::from_json_str(
        r#"{"lekalo":1,"type":"bezier_curve","control":[[0,0,0],[1,2,3],[2,0,1],[3,1,0]]}"#,
        "t",
    )
    .unwrap();
    let mut w = StepWriter::new("b");
    w.add_object(&obj).unwrap();
    same_points(&obj, &read_curve(&w.clone().finish("x")));

    // a bilinear patch as a rational surface with unit weights, plus the curve
    let net = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let grid = Grid::new(2, 2, 3, &net).unwrap();
    let knots = [0.0, 0.0, 1.0, 1.0];
    w.add_surface(&SurfaceNet {
        degrees: (1, 1),
        knots: (&knots, &knots),
        net: grid,
        weights: None,
    })
    .unwrap();
    w.add_surface(&SurfaceNet {
        degrees: (1, 1),
        knots: (&knots, &knots),
        net: grid,
        weights: Some(&[1.0, 2.0, 1.0, 1.0]),
    })
    .unwrap();
    let text = w.finish("x");
    let data = parse(&text);
    let find = |name: &str| {
        data.values()
            .filter(|r| r.iter().any(|r| r.name == name))
            .count()
    };
    assert_eq!(find("B_SPLINE_SURFACE_WITH_KNOTS"), 2);
    assert_eq!(find("RATIONAL_B_SPLINE_SURFACE"), 1);
    assert_eq!(
        find("GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION"),
        1
    );
    assert_eq!(find("GEOMETRIC_SET"), 1);
    let simple = data
        .values()
        .find(|r| r.len() == 1 && r[0].name == "B_SPLINE_SURFACE_WITH_KNOTS")
        .unwrap();
    let p = params(&simple[0]);
    assert_eq!(p.len(), 13, "B_SPLINE_SURFACE_WITH_KNOTS has 13 attributes");
    let net_rows = list(&p[3]);
    assert_eq!(net_rows.len(), 2);
    assert_eq!(point(&data, &list(&net_rows[1])[1]), vec![1.0, 1.0, 1.0]);
    // every reference points at a defined entity
    for recs in data.values() {
        for r in recs {
            check_refs(&r.parameter, &data);
        }
    }
    let _ = CurveNet {
        degree: 0,
        knots: &[],
        points: Points::from_flat(1, vec![]).unwrap().as_view(),
        weights: None,
    };
}

fn check_refs(p: &Parameter, data: &HashMap<u64, Vec<Record>>) {
    match p {
        Parameter::Ref(Name::Entity(id)) => assert!(data.contains_key(id), "dangling #{id}"),
        Parameter::List(v) => v.iter().for_each(|q| check_refs(q, data)),
        Parameter::Typed { parameter, .. } => check_refs(parameter, data),
        _ => {}
    }
}
