//! Tests of the Parquet batches: round trips through files written here with the writer (and
//! with the arrow writer directly for the layouts and the malformed cases).

use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use arrow_array::types::Float64Type;
use arrow_array::{ArrayRef, RecordBatch};
use parquet::arrow::ArrowWriter;

use super::*;
use crate::error::{IoError, IoResult};
use crate::object::Object;
use lekalo::{BSplineCurve, NurbsCurve, Points};

fn tmp(name: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    (dir, p)
}

/// Writes `batches` as one row group each with the arrow writer.
fn write_batches(path: &Path, batches: &[RecordBatch]) {
    let f = File::create(path).unwrap();
    let mut w = ArrowWriter::try_new(f, batches[0].schema(), None).unwrap();
    for b in batches {
        w.write(b).unwrap();
        w.flush().unwrap();
    }
    w.close().unwrap();
}

fn batch(cols: Vec<(&str, ArrayRef)>) -> RecordBatch {
    RecordBatch::try_from_iter(cols).unwrap()
}

fn f64s(v: &[f64]) -> ArrayRef {
    Arc::new(arrow_array::Float64Array::from(v.to_vec()))
}

fn read_all(path: &Path, key: Option<&str>) -> IoResult<Vec<(GroupKey, Result<Points, String>)>> {
    let mut out = Vec::new();
    read_point_groups(path, key, |g| {
        out.extend(
            g.into_iter()
                .map(|(k, p)| (k, p.map_err(|e| e.to_string()))),
        );
        Ok(())
    })?;
    Ok(out)
}

/// The curves of a file as the reader gives them, checked against the same file read with
/// the control points always through Arrow's nested lists (the reader decodes them from their
/// levels where the layout allows): both give the same curves and the same errors.
fn read_curves_both(path: &Path, key: Option<&str>) -> Vec<(GroupKey, Result<Object, String>)> {
    let read = |levels: bool| {
        let mut got = Vec::new();
        super::read_curves::read_curves(path, key, levels, |c| {
            got.extend(
                c.into_iter()
                    .map(|(k, r)| (k, r.map_err(|e| e.to_string()))),
            );
            Ok(())
        })
        .unwrap();
        got
    };
    let from_levels = read(true);
    assert_eq!(
        from_levels,
        read(false),
        "control points from their levels and from Arrow's lists"
    );
    from_levels
}

/// Whether the reader decodes the control points of the file at `path` from their levels.
fn control_from_levels(path: &Path) -> bool {
    let rg = super::columns::RowGroups::open(path).unwrap();
    let root = rg.schema().index_of("control").unwrap();
    super::read_curves::control_leaf(&rg, root).is_some()
}

#[test]
fn points_round_trip_across_row_groups() {
    let (_d, path) = tmp("pts.parquet");
    let a = Points::from_rows(&[[0.0, 1.0], [0.5, -2.0], [1.0, 0.1 + 0.2]]).unwrap();
    let b = Points::from_rows(&[[3.0, 4.0], [5.0, 6.0]]).unwrap();
    let c = Points::from_rows(&[[7.0, 8.0]]).unwrap();
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    // group 2 runs on from the first row group into the second
    w.write_points(
        "group",
        &["x", "y"],
        &[(GroupKey::Int(1), a.clone()), (GroupKey::Int(2), b.clone())],
    )
    .unwrap();
    w.write_points("group", &["x", "y"], &[(GroupKey::Int(2), c.clone())])
        .unwrap();
    w.close(|_| Ok(())).unwrap();
    let got = read_all(&path, None).unwrap();
    let mut bc = b.as_slice().to_vec();
    bc.extend_from_slice(c.as_slice());
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(got[0], (GroupKey::Int(1), Ok(a)), "bit for bit");
    assert_eq!(
        got[1],
        (GroupKey::Int(2), Ok(Points::from_flat(2, bc).unwrap())),
        "joined across row groups"
    );
}

#[test]
fn lists_layout_and_string_keys() {
    let (_d, path) = tmp("lists.parquet");
    let list = |rows: Vec<Option<Vec<Option<f64>>>>| -> ArrayRef {
        Arc::new(arrow_array::ListArray::from_iter_primitive::<
            Float64Type,
            _,
            _,
        >(rows))
    };
    write_batches(
        &path,
        &[batch(vec![
            (
                "id",
                Arc::new(arrow_array::StringArray::from(vec!["a", "b", "c"])),
            ),
            (
                "x",
                list(vec![
                    Some(vec![Some(0.0), Some(1.0)]),
                    Some(vec![Some(2.0)]),
                    Some(vec![Some(1.0), None]),
                ]),
            ),
            (
                "y",
                list(vec![
                    Some(vec![Some(5.0), Some(6.0)]),
                    Some(vec![Some(2.0), Some(3.0)]),
                    Some(vec![Some(1.0), Some(1.0)]),
                ]),
            ),
        ])],
    );
    let got = read_all(&path, Some("id")).unwrap();
    assert_eq!(
        got[0],
        (
            GroupKey::Str("a".into()),
            Ok(Points::from_rows(&[[0.0, 5.0], [1.0, 6.0]]).unwrap())
        ),
        "rows of the lists"
    );
    let e = got[1].1.as_ref().unwrap_err();
    assert!(
        e.contains("group \"b\": field `y`: 2 values, but `x` has 1"),
        "{e}"
    );
    let e = got[2].1.as_ref().unwrap_err();
    assert!(e.contains("group \"c\": field `x`: value 1 is null"), "{e}");
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(
        e.contains("no key column `group` (columns: id, x, y)"),
        "{e}"
    );
}

#[test]
fn bad_groups_are_reported_and_the_others_read() {
    let (_d, path) = tmp("bad.parquet");
    let keys: ArrayRef = Arc::new(arrow_array::Int64Array::from(vec![1, 1, 2, 2, 1, 3]));
    let x: ArrayRef = Arc::new(arrow_array::Float64Array::from(vec![
        Some(0.0),
        Some(1.0),
        Some(f64::NAN),
        Some(2.0),
        Some(4.0),
        Some(9.0),
    ]));
    let y: ArrayRef = Arc::new(arrow_array::Float32Array::from(vec![
        Some(0.5f32),
        None,
        Some(1.0),
        Some(1.0),
        Some(1.0),
        Some(2.0),
    ]));
    write_batches(&path, &[batch(vec![("group", keys), ("x", x), ("y", y)])]);
    let got = read_all(&path, None).unwrap();
    assert_eq!(got.len(), 4, "{got:?}");
    let e = got[0].1.as_ref().unwrap_err();
    assert!(
        e.ends_with("group 1: field `y`: row 2: null; every coordinate must be a finite number"),
        "{e}"
    );
    let e = got[1].1.as_ref().unwrap_err();
    assert!(e.contains("group 2: field `x`: row 3: NaN"), "{e}");
    let e = got[2].1.as_ref().unwrap_err();
    assert!(e.contains("group 1: appears again at row 5"), "{e}");
    assert_eq!(
        got[3],
        (
            GroupKey::Int(3),
            Ok(Points::from_rows(&[[9.0, 2.0]]).unwrap())
        ),
        "the good group"
    );
}

#[test]
fn malformed_files_give_named_errors() {
    let (_d, path) = tmp("m.parquet");
    std::fs::write(&path, b"PAR1 not really").unwrap();
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(e.contains("m.parquet: not a readable Parquet file"), "{e}");
    let e = read_all(&path.with_extension("missing"), None).unwrap_err();
    assert!(matches!(e, IoError::Read { .. }), "{e}");
    // a text column among the coordinates
    write_batches(
        &path,
        &[batch(vec![
            ("group", Arc::new(arrow_array::Int32Array::from(vec![1]))),
            ("x", f64s(&[1.0])),
            ("label", Arc::new(arrow_array::StringArray::from(vec!["a"]))),
        ])],
    );
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(
        e.contains("field `label`: the column is Utf8, not numbers"),
        "{e}"
    );
    // a key that is neither an integer nor a string
    write_batches(
        &path,
        &[batch(vec![("group", f64s(&[1.0])), ("x", f64s(&[1.0]))])],
    );
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(
        e.contains("field `group`: the key column is Float64"),
        "{e}"
    );
    // no coordinates
    write_batches(
        &path,
        &[batch(vec![(
            "group",
            Arc::new(arrow_array::Int64Array::from(vec![1])) as ArrayRef,
        )])],
    );
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(
        e.contains("no coordinate columns besides the key `group`"),
        "{e}"
    );
    // a null key
    write_batches(
        &path,
        &[batch(vec![
            (
                "group",
                Arc::new(arrow_array::Int64Array::from(vec![Some(1), None])),
            ),
            ("x", f64s(&[1.0, 2.0])),
        ])],
    );
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(e.contains("row 2: the key is null"), "{e}");
    // empty row groups and an empty file: no groups, no error
    let empty = batch(vec![
        (
            "group",
            Arc::new(arrow_array::Int64Array::from(Vec::<i64>::new())),
        ),
        ("x", f64s(&[])),
    ]);
    write_batches(&path, &[empty.clone(), empty]);
    assert!(read_all(&path, None).unwrap().is_empty(), "no groups");
}

#[test]
fn curves_round_trip_bit_for_bit() {
    let (_d, path) = tmp("curves.parquet");
    let ctrl = Points::from_rows(&[
        [0.0, 0.0, 1.0],
        [1.0, 2.0, 0.3],
        [2.0, 0.0, 1.0 / 3.0],
        [3.0, 1.0, 0.0],
    ])
    .unwrap();
    let knots = vec![0.0, 0.0, 0.0, 0.1 + 0.2, 1.0, 1.0, 1.0];
    let bs = Object::BSpline(BSplineCurve::new(2, knots.clone(), ctrl.clone()).unwrap());
    let nu =
        Object::Nurbs(NurbsCurve::new(2, knots, ctrl.clone(), vec![1.0, 0.5, 2.0, 1e-3]).unwrap());
    let bz = Object::Bezier(lekalo::BezierCurve::new(ctrl).unwrap());
    let rows = [
        (GroupKey::Str("b".into()), Ok(bs.clone())),
        (
            GroupKey::Str("bad".into()),
            Err("degree 9 is too high".to_string()),
        ),
        (GroupKey::Str("n".into()), Ok(nu.clone())),
        (GroupKey::Str("z".into()), Ok(bz.clone())),
    ];
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    w.write_curves("name", &rows[..2]).unwrap();
    w.write_curves("name", &rows[2..]).unwrap();
    w.close(|_| Ok(())).unwrap();
    let mut got = Vec::new();
    read_curve_groups(&path, Some("name"), |c| {
        got.extend(c);
        Ok(())
    })
    .unwrap();
    assert_eq!(got.len(), 4, "every row");
    assert_eq!(got[0].1.as_ref().unwrap(), &bs, "B-spline bit for bit");
    let e = got[1].1.as_ref().unwrap_err().to_string();
    assert!(
        e.ends_with("group \"bad\": no curve: degree 9 is too high"),
        "{e}"
    );
    assert_eq!(got[2].1.as_ref().unwrap(), &nu, "NURBS bit for bit");
    assert_eq!(got[3].1.as_ref().unwrap(), &bz, "Bezier");
    let e = read_curve_groups(&path, None, |_| Ok(()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no column `group`"), "{e}");
}

#[test]
fn an_empty_batch_still_has_the_layout() {
    let (_d, path) = tmp("e.parquet");
    let w = ParquetBatchWriter::new(File::create(&path).unwrap());
    w.close(|w| w.write_curves("group", &[])).unwrap();
    let mut n = 0;
    read_curve_groups(&path, None, |c| {
        n += c.len();
        Ok(())
    })
    .unwrap();
    assert_eq!(n, 0, "no curves");
}

/// A row group in which every curve lacks knots (Bezier), weights or everything (errors), after
/// one with all of them: the list columns are written empty, never null (parquet 57 panics on a
/// list column that is null in every row of a later row group), and read back as before.
#[test]
fn row_groups_without_knots_or_curves_after_full_ones() {
    let ctrl = Points::from_rows(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0], [3.0, 1.0]]).unwrap();
    let knots = vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let nu = Object::Nurbs(
        NurbsCurve::new(2, knots.clone(), ctrl.clone(), vec![1.0, 2.0, 0.5, 1.0]).unwrap(),
    );
    let bs = Object::BSpline(BSplineCurve::new(2, knots, ctrl.clone()).unwrap());
    let bz = Object::Bezier(lekalo::BezierCurve::new(ctrl).unwrap());
    let failed = || Err("too few points".to_string());
    let groups = [
        vec![(GroupKey::Int(1), Ok(nu.clone()))],
        vec![(GroupKey::Int(2), Ok(bz.clone()))],
        vec![(GroupKey::Int(3), failed())],
        vec![(GroupKey::Int(4), Ok(bs.clone()))],
    ];
    let (_d, path) = tmp("later.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    for g in &groups {
        w.write_curves("g", g).unwrap();
    }
    w.close(|_| Ok(())).unwrap();
    let mut got = Vec::new();
    read_curve_groups(&path, Some("g"), |c| {
        got.extend(c);
        Ok(())
    })
    .unwrap();
    assert_eq!(got.len(), 4, "every row");
    assert_eq!(got[0].1.as_ref().unwrap(), &nu, "NURBS");
    assert_eq!(got[1].1.as_ref().unwrap(), &bz, "Bezier");
    let e = got[2].1.as_ref().unwrap_err().to_string();
    assert!(e.ends_with("no curve: too few points"), "{e}");
    assert_eq!(got[3].1.as_ref().unwrap(), &bs, "B-spline");
}

/// Curves written by another writer (nullable lists built point by point, with or without the
/// `dim` column): read as the same curves, and a point of another dimension named.
/// A footer whose list length overflows when the Parquet crate reserves room for it (found by
/// the `parquet_batches` fuzz target: parquet 57 panicked with "capacity overflow", and 60
/// checks the length): a named error from both readers, not a panic.
#[test]
fn a_footer_with_an_absurd_list_length_is_an_error() {
    let bytes =
        include_bytes!("../../../../fuzz/seeds/parquet_batches/footer-list-size-overflow.parquet");
    let (_d, path) = tmp("footer.parquet");
    std::fs::write(&path, bytes).unwrap();
    let e = read_all(&path, None).unwrap_err().to_string();
    assert!(e.contains("not a readable Parquet file"), "{e}");
    let e = read_curve_groups(&path, None, |_| Ok(()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a readable Parquet file"), "{e}");
}

/// Control points written by other writers: Arrow's default nested lists (nullable at every
/// level, read through Arrow) and lists declared never null (the writer's layout, decoded from
/// their levels). Both give the same curves, and the same error for a point with fewer
/// coordinates than the first, for a row without points and for a point without coordinates.
#[test]
fn control_lists_of_other_writers_are_read() {
    use arrow_array::builder::{Float64Builder, ListBuilder};
    use arrow_schema::{DataType, Field};
    let ctrl =
        Points::from_rows(&[[0.0, 0.5, 1.0], [1.0, 2.0, 0.3], [2.0, 0.0, 1.0 / 3.0]]).unwrap();
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let want = Object::BSpline(BSplineCurve::new(2, knots.to_vec(), ctrl.clone()).unwrap());
    let rows = 4;
    let control = |never_null: bool| -> ArrayRef {
        let inner = Field::new_list_field(DataType::Float64, !never_null);
        let outer = Field::new_list_field(DataType::List(Arc::new(inner.clone())), !never_null);
        let mut control =
            ListBuilder::new(ListBuilder::new(Float64Builder::new()).with_field(inner))
                .with_field(outer);
        for p in ctrl.iter() {
            control.values().values().append_slice(p);
            control.values().append(true);
        }
        control.append(true);
        // a point with two coordinates between points with three
        control.values().values().append_slice(&[0.0, 1.0, 2.0]);
        control.values().append(true);
        control.values().values().append_slice(&[0.0, 1.0]);
        control.values().append(true);
        control.values().values().append_slice(&[3.0, 4.0, 5.0]);
        control.values().append(true);
        control.append(true);
        // a row without points
        control.append(true);
        // a point without coordinates after one with three
        control.values().values().append_slice(&[0.0, 1.0, 2.0]);
        control.values().append(true);
        control.values().append(true);
        control.append(true);
        Arc::new(control.finish())
    };
    let mut kn = ListBuilder::new(Float64Builder::new());
    let mut weights = ListBuilder::new(Float64Builder::new());
    for _ in 0..rows {
        kn.values().append_slice(&knots);
        kn.append(true);
        weights.append(true);
    }
    let (kn, weights): (ArrayRef, ArrayRef) = (Arc::new(kn.finish()), Arc::new(weights.finish()));
    for (with_dim, never_null) in [(true, false), (false, false), (true, true)] {
        let mut cols: Vec<(&str, ArrayRef, bool)> = vec![
            (
                "group",
                Arc::new(arrow_array::Int64Array::from(vec![7, 8, 9, 10])),
                false,
            ),
            (
                "type",
                Arc::new(arrow_array::StringArray::from(vec!["bspline_curve"; rows])),
                true,
            ),
            (
                "degree",
                Arc::new(arrow_array::Int32Array::from(vec![2; rows])),
                true,
            ),
        ];
        if with_dim {
            cols.push((
                "dim",
                Arc::new(arrow_array::Int32Array::from(vec![3; rows])),
                true,
            ));
        }
        cols.extend([
            ("knots", kn.clone(), true),
            ("control", control(never_null), !never_null),
            ("weights", weights.clone(), true),
        ]);
        let (_d, path) = tmp("nested.parquet");
        write_batches(
            &path,
            &[RecordBatch::try_from_iter_with_nullable(cols).unwrap()],
        );
        assert_eq!(
            control_from_levels(&path),
            never_null,
            "the way the control points are read"
        );
        let got = read_curves_both(&path, None);
        assert_eq!(got[0].1.as_ref().unwrap(), &want, "bit for bit");
        let e = got[1].1.as_ref().unwrap_err();
        assert!(
            e.ends_with("group 8: field `control`: point 1 has 2 coordinates, point 0 has 3"),
            "{e}"
        );
        assert!(got[2].1.is_err() && got[3].1.is_err(), "{got:?}");
        let e = got[3].1.as_ref().unwrap_err();
        assert!(
            e.contains("point 1 has 0 coordinates, point 0 has 3"),
            "{e}"
        );
    }
}

/// Columns of doubles without nulls are read a group at a time: a NaN or an infinity there is
/// still named with its row and column, and the groups around it are read.
#[test]
fn non_finite_doubles_are_named_with_their_row() {
    let (_d, path) = tmp("nan.parquet");
    let keys: ArrayRef = Arc::new(arrow_array::Int64Array::from(vec![1, 1, 2, 2, 2, 3]));
    let x = f64s(&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    let y = f64s(&[0.0, 1.0, 2.0, f64::INFINITY, 4.0, 5.0]);
    let z = f64s(&[0.0, 1.0, 2.0, 3.0, f64::NAN, 5.0]);
    write_batches(
        &path,
        &[batch(vec![("group", keys), ("x", x), ("y", y), ("z", z)])],
    );
    let got = read_all(&path, None).unwrap();
    assert_eq!(got.len(), 3, "{got:?}");
    assert_eq!(
        got[0].1,
        Ok(Points::from_rows(&[[0.0; 3], [1.0; 3]]).unwrap()),
        "the group before"
    );
    let e = got[1].1.as_ref().unwrap_err();
    assert!(
        e.ends_with("group 2: field `y`: row 4: inf; every coordinate must be a finite number"),
        "{e}"
    );
    assert_eq!(
        got[2].1,
        Ok(Points::from_rows(&[[5.0; 3]]).unwrap()),
        "the group after"
    );
}

/// The written file's settings: no dictionary but on a string key, a delta-encoded integer
/// key with statistics, no statistics on the doubles, and the control points as lists of
/// points, each a list of doubles.
#[test]
fn written_columns_have_the_documented_encodings() {
    use parquet::basic::Encoding;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let ctrl = Points::from_rows(&[[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]]).unwrap();
    let bz = Object::Bezier(lekalo::BezierCurve::new(ctrl.clone()).unwrap());
    let (_d, path) = tmp("enc.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    w.write_curves("group", &[(GroupKey::Int(4), Ok(bz))])
        .unwrap();
    w.close(|_| Ok(())).unwrap();
    let r = SerializedFileReader::new(File::open(&path).unwrap()).unwrap();
    let rg = r.metadata().row_group(0);
    let col = |name: &str| {
        (0..rg.num_columns())
            .map(|i| rg.column(i))
            .find(|c| c.column_path().string() == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    };
    let key = col("group");
    assert!(
        key.encodings().any(|e| e == Encoding::DELTA_BINARY_PACKED),
        "delta key"
    );
    assert!(key.statistics().is_some(), "the key has statistics");
    let control = col("control.list.item.list.item");
    assert!(
        control.statistics().is_none(),
        "no statistics on the doubles"
    );
    assert!(
        control
            .encodings()
            .all(|e| e != Encoding::PLAIN_DICTIONARY && e != Encoding::RLE_DICTIONARY),
        "no dictionary"
    );
    let schema = r.metadata().file_metadata().schema_descr();
    assert_eq!(
        schema.column(5).path().string(),
        "control.list.item.list.item",
        "a list of lists"
    );
    let e = ParquetBatchWriter::new(Vec::new())
        .write_curves(
            "group",
            &[
                (GroupKey::Int(1), Err("x".into())),
                (GroupKey::Str("a".into()), Err("y".into())),
            ],
        )
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("group \"a\": a string key among integer keys"),
        "{e}"
    );
}

/// Random curves of every kind, dimension and degree, in random row groups: read back bit for
/// bit, in order, with the failed rows where they were.
mod round_trip {
    use super::*;
    use proptest::prelude::*;

    fn curve() -> impl Strategy<Value = Result<Object, String>> {
        (1usize..5, 1usize..5, 0usize..6, 0u8..4).prop_flat_map(|(dim, degree, extra, kind)| {
            let n = degree + 1 + extra;
            (
                proptest::collection::vec(-1e3f64..1e3, n * dim),
                proptest::collection::vec(0.01f64..1.0, extra + 1),
                proptest::collection::vec(0.1f64..10.0, n),
            )
                .prop_map(move |(c, gaps, w)| {
                    let ctrl = Points::from_flat(dim, c).unwrap();
                    let mut knots = vec![0.0; degree + 1];
                    let mut t = 0.0;
                    for g in &gaps[..extra] {
                        t += g;
                        knots.push(t);
                    }
                    knots.extend(vec![t + gaps[extra]; degree + 1]);
                    match kind {
                        0 => Ok(Object::BSpline(
                            BSplineCurve::new(degree, knots, ctrl).unwrap(),
                        )),
                        1 => Ok(Object::Nurbs(
                            NurbsCurve::new(degree, knots, ctrl, w).unwrap(),
                        )),
                        2 => Ok(Object::Bezier(lekalo::BezierCurve::new(ctrl).unwrap())),
                        _ => Err(format!("failed with {dim} {degree}")),
                    }
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn curves_come_back_bit_for_bit(
            curves in proptest::collection::vec(curve(), 1..12),
            cuts in proptest::collection::vec(0usize..12, 0..3),
        ) {
            let rows: Vec<(GroupKey, Result<Object, String>)> = curves
                .into_iter()
                .enumerate()
                .map(|(i, c)| (GroupKey::Int(i as i64 * 3 - 5), c))
                .collect();
            let mut cuts: Vec<usize> = cuts.into_iter().map(|c| c.min(rows.len())).collect();
            cuts.extend([0, rows.len()]);
            cuts.sort_unstable();
            let (_d, path) = tmp("rt.parquet");
            let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
            for part in cuts.windows(2) {
                w.write_curves("group", &rows[part[0]..part[1]]).unwrap();
            }
            w.close(|w| w.write_curves("group", &[])).unwrap();
            prop_assert!(control_from_levels(&path), "the writer's layout is read from its levels");
            let got = read_curves_both(&path, None);
            prop_assert_eq!(got.len(), rows.len());
            for ((k, want), (gk, g)) in rows.iter().zip(&got) {
                prop_assert_eq!(k, gk);
                match (want, g) {
                    (Ok(w), Ok(g)) => prop_assert_eq!(w, g),
                    (Err(w), Err(g)) => prop_assert!(g.ends_with(w.as_str()), "{}", g),
                    _ => prop_assert!(false, "{:?} read as {:?}", want, g),
                }
            }
        }

        /// Point sets of random sizes in the long layout, cut into row groups anywhere (a
        /// group may run on into the next): the same points, in order.
        #[test]
        fn point_groups_come_back_across_row_groups(
            sizes in proptest::collection::vec(1usize..9, 1..8),
            dim in 1usize..5,
            cut in proptest::collection::vec(0usize..40, 0..3),
        ) {
            let names = ["a", "b", "c", "d"];
            let groups: Vec<(GroupKey, Points)> = sizes
                .iter()
                .enumerate()
                .map(|(g, &n)| {
                    let data = (0..n * dim).map(|i| (g * 100 + i) as f64 * 0.1).collect();
                    (GroupKey::Int(g as i64), Points::from_flat(dim, data).unwrap())
                })
                .collect();
            // the same points as rows, cut at the row numbers `cut` into row groups
            let rows: Vec<(GroupKey, Vec<f64>)> = groups
                .iter()
                .flat_map(|(k, p)| p.iter().map(move |r| (k.clone(), r.to_vec())))
                .collect();
            let mut cuts: Vec<usize> = cut.into_iter().map(|c| c.min(rows.len())).collect();
            cuts.extend([0, rows.len()]);
            cuts.sort_unstable();
            let (_d, path) = tmp("pts.parquet");
            let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
            for part in cuts.windows(2).filter(|p| p[0] < p[1]) {
                let chunk: Vec<(GroupKey, Points)> = rows[part[0]..part[1]]
                    .iter()
                    .map(|(k, r)| (k.clone(), Points::from_flat(dim, r.clone()).unwrap()))
                    .collect();
                w.write_points("group", &names[..dim], &chunk).unwrap();
            }
            w.close(|_| Ok(())).unwrap();
            let got = read_all(&path, None).unwrap();
            let want: Vec<(GroupKey, Result<Points, String>)> =
                groups.into_iter().map(|(k, p)| (k, Ok(p))).collect();
            prop_assert_eq!(got, want);
        }
    }
}

/// A row group larger than one batch of the reader: the groups that cross from batch to batch
/// come back whole and in order, and `each` is called more than once within the row group.
/// Written with row groups of a size in bytes, the calls of the writer share row groups.
#[test]
fn groups_cross_the_batches_of_a_row_group() {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let (_d, path) = tmp("big.parquet");
    // 3 groups of 30,000 points: the first batch (BATCH_ROWS rows) ends inside group 2
    let n = 30_000;
    let groups: Vec<(GroupKey, Points)> = (0..3)
        .map(|g| {
            let data = (0..n * 2)
                .map(|i| (g * 1_000_000 + i) as f64 * 0.5)
                .collect();
            (GroupKey::Int(g as i64), Points::from_flat(2, data).unwrap())
        })
        .collect();
    assert!(3 * n > super::columns::BATCH_ROWS, "more rows than a batch");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap()).with_row_group_bytes(8 << 20);
    w.write_points("group", &["x", "y"], &groups[..1]).unwrap();
    w.write_points("group", &["x", "y"], &groups[1..]).unwrap();
    w.close(|_| Ok(())).unwrap();
    let r = SerializedFileReader::new(File::open(&path).unwrap()).unwrap();
    assert_eq!(
        r.metadata().num_row_groups(),
        1,
        "both calls in one row group"
    );
    let mut calls = 0;
    let mut got = Vec::new();
    read_point_groups(&path, None, |g| {
        calls += 1;
        got.extend(g.into_iter().map(|(k, p)| (k, p.unwrap())));
        Ok(())
    })
    .unwrap();
    assert!(calls > 1, "one call per batch, {calls}");
    assert_eq!(got, groups, "bit for bit, in order");
}

/// Row groups of a size in bytes: a new row group starts once the open one's pages reach it.
#[test]
fn row_groups_of_a_size_in_bytes() {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let (_d, path) = tmp("sized.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap()).with_row_group_bytes(1 << 16);
    let mut want = Vec::new();
    for g in 0..8 {
        // 2,000 points of 2 doubles: 32 KB of pages a call
        let data = (0..4_000).map(|i| f64::from(g * 4_000 + i)).collect();
        let p = Points::from_flat(2, data).unwrap();
        w.write_points(
            "group",
            &["x", "y"],
            &[(GroupKey::Int(g.into()), p.clone())],
        )
        .unwrap();
        want.push((GroupKey::Int(g.into()), Ok(p)));
    }
    w.close(|_| Ok(())).unwrap();
    let r = SerializedFileReader::new(File::open(&path).unwrap()).unwrap();
    let rgs = r.metadata().num_row_groups();
    assert!((2..8).contains(&rgs), "{rgs} row groups for 8 calls");
    assert_eq!(read_all(&path, None).unwrap(), want, "the same points");
}

/// The point samples of `path` as (key, t, coordinates) rows, keys as text, numbers as bits.
fn read_point_samples(path: &Path) -> (arrow_schema::SchemaRef, Vec<(String, Vec<u64>)>) {
    use arrow_array::cast::AsArray;
    use arrow_array::Array;
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
    let b = ParquetRecordBatchReaderBuilder::try_new(File::open(path).unwrap()).unwrap();
    let schema = b.schema().clone();
    let mut rows = Vec::new();
    for batch in b.build().unwrap() {
        let batch = batch.unwrap();
        for r in 0..batch.num_rows() {
            let key = batch.column(0);
            let k = match key.as_primitive_opt::<arrow_array::types::Int64Type>() {
                Some(a) => a.value(r).to_string(),
                None => key.as_string::<i32>().value(r).to_string(),
            };
            let bits = (1..batch.num_columns())
                .map(|c| {
                    let col = batch.column(c).as_primitive::<Float64Type>();
                    assert!(col.is_valid(r), "never null");
                    col.value(r).to_bits()
                })
                .collect();
            rows.push((k, bits));
        }
    }
    (schema, rows)
}

/// Samples of 3-D curves: per group, parameters and point-major points.
fn samples_of(groups: &[(i64, usize)]) -> Vec<(GroupKey, Vec<f64>, Vec<f64>)> {
    groups
        .iter()
        .map(|&(k, n)| {
            let ts: Vec<f64> = (0..n).map(|i| i as f64 / 7.0 + k as f64).collect();
            let pts = ts
                .iter()
                .flat_map(|t| [t.sin(), -t.cos() * 1e300, 0.1 + t])
                .collect();
            (GroupKey::Int(k), ts, pts)
        })
        .collect()
}

/// Point samples go through Parquet's column writers: across calls and row groups of a size,
/// they come back bit for bit, in order, in never-null columns of the documented names, with
/// the Arrow schema in the file's metadata (so that pandas and the Arrow readers see it).
#[test]
fn point_samples_round_trip_bit_for_bit() {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let (_d, path) = tmp("samples.parquet");
    let calls = [
        samples_of(&[(3, 5), (4, 1000)]),
        samples_of(&[(5, 0)]),
        samples_of(&[(6, 2500), (7, 3)]),
        samples_of(&[(8, 4000)]),
    ];
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap()).with_row_group_bytes(1 << 17);
    for rows in &calls {
        w.write_point_samples("scan", 3, rows).unwrap();
    }
    w.close(|_| panic!("rows were written")).unwrap();
    let r = SerializedFileReader::new(File::open(&path).unwrap()).unwrap();
    let meta = r.metadata();
    // 1,005 + 0 + 2,503 rows, then 4,000 would pass the 4,096 rows of 128 KiB
    assert_eq!(meta.num_row_groups(), 2, "row groups of 128 KiB");
    for g in meta.row_groups() {
        assert!(
            g.num_rows() * 32 <= 1 << 17,
            "a row group within its size: {} rows",
            g.num_rows()
        );
    }
    let kv = meta.file_metadata().key_value_metadata().unwrap();
    assert!(
        kv.iter().any(|k| k.key == "ARROW:schema"),
        "the Arrow schema is stored"
    );
    let (schema, got) = read_point_samples(&path);
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    assert_eq!(names, ["scan", "t", "x", "y", "z"], "the columns");
    assert!(
        schema.fields().iter().all(|f| !f.is_nullable()),
        "{schema:?}"
    );
    let want: Vec<(String, Vec<u64>)> = calls
        .iter()
        .flatten()
        .flat_map(|(k, ts, pts)| {
            ts.iter().zip(pts.chunks_exact(3)).map(move |(t, p)| {
                let mut bits = vec![t.to_bits()];
                bits.extend(p.iter().map(|v| v.to_bits()));
                (k.to_string(), bits)
            })
        })
        .collect();
    assert_eq!(got.len(), 7508, "every sample");
    assert!(got == want, "bit for bit, in order");
}

/// String keys (and integer keys among them, as their text), 4-D samples (`x1 … x4`), and a
/// row group per call without a size.
#[test]
fn point_samples_with_string_keys() {
    let (_d, path) = tmp("s.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    let rows = vec![
        (
            GroupKey::Str("a".into()),
            vec![0.0, 1.0],
            (0..8).map(f64::from).collect(),
        ),
        (GroupKey::Int(12), vec![0.5], vec![-1.0, -2.0, -3.0, -4.0]),
    ];
    w.write_point_samples("name", 4, &rows).unwrap();
    w.write_point_samples("name", 4, &rows[..1]).unwrap();
    w.close(|_| Ok(())).unwrap();
    let (schema, got) = read_point_samples(&path);
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    assert_eq!(names, ["name", "t", "x1", "x2", "x3", "x4"], "the columns");
    let keys: Vec<&str> = got.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(keys, ["a", "a", "12", "a", "a"], "the keys, in order");
    assert_eq!(
        got[2].1,
        [0.5, -1.0, -2.0, -3.0, -4.0].map(f64::to_bits),
        "row 2"
    );
    assert_eq!(
        got[1].1,
        [1.0, 4.0, 5.0, 6.0, 7.0].map(f64::to_bits),
        "row 1"
    );
}

/// Calls without samples write nothing; a file that never had any is the empty layout that
/// `close` is given.
#[test]
fn point_samples_of_an_empty_batch() {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let (_d, path) = tmp("e.parquet");
    let mut w = ParquetBatchWriter::new(File::create(&path).unwrap());
    w.write_point_samples("group", 3, &[]).unwrap();
    w.write_point_samples("group", 3, &samples_of(&[(1, 0)]))
        .unwrap();
    w.close(|w| w.write_point_samples("group", 2, &[])).unwrap();
    let r = SerializedFileReader::new(File::open(&path).unwrap()).unwrap();
    assert_eq!(r.metadata().num_row_groups(), 0, "no rows");
    let (schema, got) = read_point_samples(&path);
    assert!(got.is_empty(), "no samples");
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    assert_eq!(names, ["group", "t", "x", "y"], "the layout");
}

/// A call that does not fit the file's layout is refused, saying why.
#[test]
fn point_samples_refuse_another_layout() {
    let err = |calls: &dyn Fn(&mut ParquetBatchWriter<Vec<u8>>) -> std::io::Result<()>| {
        let mut w = ParquetBatchWriter::new(Vec::new());
        calls(&mut w).unwrap_err().to_string()
    };
    let e = err(&|w| {
        let mut rows = samples_of(&[(1, 2)]);
        rows.push((GroupKey::Str("b".into()), vec![0.0], vec![0.0; 3]));
        w.write_point_samples("group", 3, &rows)
    });
    assert!(
        e.contains("group \"b\": a string key among integer keys"),
        "{e}"
    );
    let e = err(&|w| {
        w.write_point_samples("group", 3, &samples_of(&[(1, 2)]))?;
        w.write_point_samples("group", 2, &[(GroupKey::Int(2), vec![0.0], vec![0.0; 2])])
    });
    assert!(
        e.contains("samples of 2-D curves keyed by `group` after samples of 3-D curves"),
        "{e}"
    );
    let e =
        err(&|w| w.write_point_samples("group", 3, &[(GroupKey::Int(2), vec![0.0], vec![0.0; 2])]));
    assert!(
        e.contains("group 2: 2 coordinates for 1 parameters of a 3-D curve"),
        "{e}"
    );
    let e = err(&|w| {
        w.write_curves("group", &[(GroupKey::Int(1), Err("x".into()))])?;
        w.write_point_samples("group", 3, &samples_of(&[(1, 2)]))
    });
    assert!(
        e.contains("point samples and other layouts in one Parquet file"),
        "{e}"
    );
}

/// A table without a key: written and read back bit for bit (negative zero, subnormals, the
/// largest double), row groups joined in order, integer and float columns read as doubles;
/// a null, a text column and too many rows refused by name.
#[test]
fn a_table_of_points_round_trips_and_names_what_it_refuses() {
    let (_d, path) = tmp("t.parquet");
    let flat = [0.0, -0.0, 5e-324, f64::MAX, -1.5, 0.1 + 0.2];
    let names = ["a".to_string(), "b".to_string(), "c".to_string()];
    std::fs::write(&path, table_to_parquet(&names, &flat).unwrap()).unwrap();
    let (pts, cols, _) = read_parquet_points(&path, 2).unwrap();
    assert_eq!(cols, names);
    assert_eq!(pts.dim(), 3);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(pts.as_slice()), bits(&flat));
    assert!(matches!(
        read_parquet_points(&path, 1),
        Err(IoError::OverLimit {
            raise_to: Some(2),
            ..
        })
    ));
    assert!(matches!(
        table_to_parquet(&names, &flat[..5]),
        Err(IoError::Render(_))
    ));

    // two row groups, an integer and a float column
    let first = batch(vec![
        (
            "i",
            Arc::new(arrow_array::Int32Array::from(vec![1, 2])) as ArrayRef,
        ),
        (
            "f",
            Arc::new(arrow_array::Float32Array::from(vec![0.5f32, 0.25])),
        ),
    ]);
    let second = batch(vec![
        (
            "i",
            Arc::new(arrow_array::Int32Array::from(vec![3])) as ArrayRef,
        ),
        ("f", Arc::new(arrow_array::Float32Array::from(vec![2.0f32]))),
    ]);
    write_batches(&path, &[first, second]);
    let (pts, _, _) = read_parquet_points(&path, 10).unwrap();
    assert_eq!(pts.as_slice(), &[1.0, 0.5, 2.0, 0.25, 3.0, 2.0]);

    // a null in the second row group names the file's row
    let nullable = |v: Vec<Option<i64>>| {
        RecordBatch::try_from_iter_with_nullable(vec![(
            "x",
            Arc::new(arrow_array::Int64Array::from(v)) as ArrayRef,
            true,
        )])
        .unwrap()
    };
    write_batches(
        &path,
        &[nullable(vec![Some(7)]), nullable(vec![Some(1), None])],
    );
    let e = read_parquet_points(&path, 10).unwrap_err().to_string();
    assert!(e.contains("field `x`") && e.contains("row 3: null"), "{e}");

    // text is not a coordinate
    let text = batch(vec![(
        "name",
        Arc::new(arrow_array::StringArray::from(vec!["a"])) as ArrayRef,
    )]);
    write_batches(&path, &[text]);
    let e = read_parquet_points(&path, 10).unwrap_err().to_string();
    assert!(
        e.contains("field `name`") && e.contains("not numbers"),
        "{e}"
    );
}
