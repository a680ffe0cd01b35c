//! Parquet batches (docs/formats.md#parquet-batches): the command's work on one group of
//! points ([`curves_of_groups`], [`samples_of_groups`]) or one curve ([`samples_of_curves`])
//! applied to every group of a batch. A batch is read a few MiB at a time, decoding, the
//! groups' work (in parallel) and encoding overlapped (`pipeline`), row groups written by
//! size, so memory is bounded by a few batches and one output row group. A bad group is
//! written with its `error`, reported on stderr with its key, and does not stop the others;
//! the exit code is then 2. Also the conversion of curves between Parquet and JSON Lines
//! ([`convert_curves`]), and of a CSV of point sets with a key column to a Parquet batch.

use lekalo_io::CurveJson;
use std::path::Path;

use anyhow::Result;
use lekalo_io::{GroupKey, IoError, Object, ParquetBatchWriter, SampleSpec};
use rayon::prelude::*;

use crate::context::Context;
use crate::exit::{bad_input, BadInput};
use crate::items::is_parquet;
use crate::output::report;

/// The output path of a batch: a `.parquet` file (batches are not written to stdout).
fn parquet_output<'a>(out: Option<&'a Path>, what: &str) -> Result<&'a Path> {
    match out {
        Some(p) if is_parquet(p) => Ok(p),
        _ => bad_input(format!(
            "a Parquet input gives {what} as Parquet: give -o FILE.parquet"
        )),
    }
}

/// Reports the failed groups on stderr; `Err(BadInput)` if there were any.
fn finish(failed: &[String], total: usize, input: &Path) -> Result<()> {
    for f in failed.iter().take(20) {
        report(f);
    }
    if failed.len() > 20 {
        report(&format!("... and {} more", failed.len() - 20));
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(BadInput(format!(
            "{}: {} of {total} groups failed (written with their error in the `error` column)",
            input.display(),
            failed.len()
        ))
        .into())
    }
}

/// The encoded size of the row groups written: a few input batches each, few enough row groups
/// for readers, and the bound of the writer's memory.
const ROW_GROUP_BYTES: usize = 4 << 20;

/// The Parquet writer of a batch, into the temporary file of an atomic write.
type Writer<'w> = ParquetBatchWriter<&'w mut (dyn std::io::Write + Send)>;

/// Writes `out` atomically: `fill` reads `input` and writes row groups, `empty` writes the
/// layout of a batch that had no rows. An error of `fill` keeps its own kind (a bad input is
/// exit code 2, not a failed write).
fn write_parquet(
    cx: &Context,
    input: &Path,
    out: &Path,
    fill: impl FnOnce(&mut Writer<'_>) -> lekalo_io::IoResult<()>,
    empty: impl FnOnce(&mut Writer<'_>) -> std::io::Result<()>,
) -> Result<()> {
    let mut input_error: Option<IoError> = None;
    lekalo_io::write_atomic_send(out, &[input.to_path_buf()], cx.write_options(), |w| {
        let mut writer = ParquetBatchWriter::new(w).with_row_group_bytes(ROW_GROUP_BYTES);
        fill(&mut writer).map_err(|e| {
            let msg = e.to_string();
            input_error = Some(e);
            std::io::Error::other(msg)
        })?;
        writer.close(empty)
    })
    .map_err(|e| input_error.take().unwrap_or(e))?;
    Ok(())
}

/// A failed write of `out` as the formats crate's error.
fn write_error(out: &Path) -> impl Fn(std::io::Error) -> IoError + '_ {
    move |error| IoError::Write {
        path: out.to_path_buf(),
        error,
    }
}

/// Runs a batch as three stages on their own threads, joined by channels that hold one batch
/// each: `read` (the caller's thread) decodes the input and hands over its batches, `compute`
/// turns a batch into output rows (on the rayon pool), `write` encodes them. Decoding, the
/// groups' work and encoding then overlap, and at most a few batches are in memory at once.
/// The first error stops the others: a failed write before the read that it stopped.
fn pipeline<T: Send, U: Send>(
    read: impl FnOnce(&mut dyn FnMut(T) -> lekalo_io::IoResult<()>) -> lekalo_io::IoResult<()>,
    compute: impl Fn(T) -> U + Sync,
    mut write: impl FnMut(U) -> lekalo_io::IoResult<()> + Send,
) -> lekalo_io::IoResult<()> {
    use std::sync::mpsc::sync_channel;
    std::thread::scope(|s| {
        let (to_compute, computing) = sync_channel::<T>(1);
        let (to_write, writing) = sync_channel::<U>(1);
        let compute = &compute;
        let computer = s.spawn(move || {
            for batch in computing {
                if to_write.send(compute(batch)).is_err() {
                    break;
                }
            }
        });
        let writer = s.spawn(move || {
            for rows in writing {
                write(rows)?;
            }
            Ok(())
        });
        let read = read(&mut |batch| {
            to_compute.send(batch).map_err(|_| IoError::Write {
                path: "(the Parquet writer)".into(),
                error: std::io::Error::other("stopped"),
            })
        });
        drop(to_compute);
        let joined = |r: std::thread::Result<()>| {
            if let Err(p) = r {
                std::panic::resume_unwind(p)
            }
        };
        joined(computer.join());
        let written = writer
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        written.and(read)
    })
}

/// `make` applied to each group of a batch, in parallel: its result, or why the group has none
/// (a bad group's own error, or `make`'s with the file and the group's key).
fn each_group<T: Send>(
    groups: Vec<lekalo_io::PointGroup>,
    input: &Path,
    make: impl Fn(&lekalo::Points) -> Result<T> + Sync,
) -> Vec<(GroupKey, Result<T, String>)> {
    groups
        .into_par_iter()
        .map(|(k, pts)| {
            let r = pts.map_err(|e| e.to_string()).and_then(|p| {
                make(&p).map_err(|e| format!("{}: group {k}: {e:#}", input.display()))
            });
            (k, r)
        })
        .collect()
}

/// The curve that `make` gives of each group, sampled at `n` evenly spaced parameters over
/// its domain, in one pass (no curve file in between): the samples layout of [`samples_of_curves`]
/// at the same parameters, bit for bit (`lekalo interpolate points.parquet --samples N`).
pub(crate) fn samples_of_groups(
    cx: &Context,
    input: &Path,
    out: Option<&Path>,
    n: usize,
    make: &(dyn Fn(&lekalo::Points) -> Result<Object> + Sync),
) -> Result<()> {
    let out = parquet_output(out, "samples")?;
    let key = &cx.group_column;
    let mut failed = Vec::new();
    let mut total = 0usize;
    let mut header: Option<Vec<String>> = None;
    write_parquet(
        cx,
        input,
        out,
        |writer| {
            pipeline(
                |each| lekalo_io::read_point_groups(input, Some(key), each),
                |groups: Vec<lekalo_io::PointGroup>| {
                    each_group(groups, input, |p| -> Result<Sampled> {
                        let o = make(p)?;
                        Ok(sampled(&o, o.uniform_parameters(n))?)
                    })
                },
                |rows| {
                    total += rows.len();
                    write_points(rows, input, key, writer, &mut header, &mut failed)
                        .map_err(write_error(out))
                },
            )
        },
        empty_samples(key),
    )?;
    finish_samples(cx, &failed, total, input, out)
}

/// [`finish`] for a samples file, after the `--verbose` report of what it holds.
fn finish_samples(
    cx: &Context,
    failed: &[String],
    total: usize,
    input: &Path,
    out: &Path,
) -> Result<()> {
    if cx.is_verbose() {
        report(&format!(
            "wrote the samples of {} curves to {}",
            total - failed.len(),
            out.display()
        ));
    }
    finish(failed, total, input)
}

/// The layout of a samples file without rows (a batch that had none).
fn empty_samples(key: &str) -> impl FnOnce(&mut Writer<'_>) -> std::io::Result<()> + '_ {
    move |w| {
        let empty = lekalo_io::SampleTable {
            header: vec!["t".into()],
            rows: Vec::new(),
        };
        w.write_samples(key, &[(GroupKey::Int(0), empty)])
    }
}

/// The curve that `make` gives of each group of points, written as a batch of curves
/// (`lekalo interpolate` and `lekalo fit` of a Parquet batch).
pub(crate) fn curves_of_groups(
    cx: &Context,
    input: &Path,
    out: Option<&Path>,
    make: &(dyn Fn(&lekalo::Points) -> Result<Object> + Sync),
) -> Result<()> {
    let out = parquet_output(out, "curves")?;
    let key = &cx.group_column;
    let mut failed = Vec::new();
    let mut total = 0usize;
    write_parquet(
        cx,
        input,
        out,
        |writer| {
            pipeline(
                |each| lekalo_io::read_point_groups(input, Some(key), each),
                |groups: Vec<lekalo_io::PointGroup>| each_group(groups, input, make),
                |rows| {
                    total += rows.len();
                    failed.extend(rows.iter().filter_map(|(_, r)| r.as_ref().err().cloned()));
                    writer.write_curves(key, &rows).map_err(write_error(out))
                },
            )
        },
        |w| w.write_curves(key, &[]),
    )?;
    if cx.is_verbose() {
        report(&format!(
            "wrote {} curves to {}",
            total - failed.len(),
            out.display()
        ));
    }
    finish(&failed, total, input)
}

/// The samples of every curve of a batch at the parameters that `params` gives of it: points,
/// and the derivatives, curvature and torsion of `spec` (`lekalo eval curves.parquet`).
pub(crate) fn samples_of_curves(
    cx: &Context,
    input: &Path,
    out: Option<&Path>,
    spec: SampleSpec,
    params: &(dyn Fn(&Object) -> Result<Vec<f64>> + Sync),
) -> Result<()> {
    let out = parquet_output(out, "samples")?;
    let key = &cx.group_column;
    let mut failed = Vec::new();
    let mut total = 0usize;
    let mut header: Option<Vec<String>> = None;
    let points_only = spec.derivatives == 0 && !spec.curvature && !spec.torsion;
    write_parquet(
        cx,
        input,
        out,
        |writer| {
            pipeline(
                |each| lekalo_io::read_curve_groups(input, Some(key), each),
                |curves: Vec<(GroupKey, Result<Object, IoError>)>| {
                    if points_only {
                        Samples::Points(sample_points(curves, input, params))
                    } else {
                        Samples::Tables(sample_tables(curves, input, params, spec))
                    }
                },
                |samples| {
                    let written = match samples {
                        Samples::Points(rows) => {
                            total += rows.len();
                            write_points(rows, input, key, writer, &mut header, &mut failed)
                        }
                        Samples::Tables(tables) => {
                            total += tables.len();
                            write_tables(tables, input, key, writer, &mut header, &mut failed)
                        }
                    };
                    written.map_err(write_error(out))
                },
            )
        },
        empty_samples(key),
    )?;
    finish_samples(cx, &failed, total, input, out)
}

/// The parameters, the points (flat) and the dimension of one curve's samples.
type Sampled = (Vec<f64>, Vec<f64>, usize);

/// `o` at the parameters `ts`, by the library's batch evaluation into one flat buffer.
fn sampled(o: &Object, ts: Vec<f64>) -> lekalo::Result<Sampled> {
    let mut pts = vec![0.0; ts.len() * o.dim()];
    o.eval_batch(&ts, &mut pts)?;
    Ok((ts, pts, o.dim()))
}

/// The samples of a batch of curves, or why a curve has none.
enum Samples {
    /// Points only.
    Points(Vec<(GroupKey, Result<Sampled, String>)>),
    /// With derivatives or curvature.
    Tables(Vec<(GroupKey, Result<lekalo_io::SampleTable, String>)>),
}

/// Points only: each curve's samples by the library's batch evaluation into one flat buffer
/// (no table rows), the curves in parallel.
fn sample_points(
    curves: Vec<(GroupKey, Result<Object, IoError>)>,
    input: &Path,
    params: &(dyn Fn(&Object) -> Result<Vec<f64>> + Sync),
) -> Vec<(GroupKey, Result<Sampled, String>)> {
    curves
        .into_par_iter()
        .map(|(k, obj)| {
            let r = obj.map_err(|e| e.to_string()).and_then(|o| {
                let ts = params(&o).map_err(|e| e.to_string())?;
                sampled(&o, ts).map_err(|e| format!("{}: group {k}: {e}", input.display()))
            });
            (k, r)
        })
        .collect()
}

/// With derivatives or curvature: each curve's sample table, the curves in parallel.
fn sample_tables(
    curves: Vec<(GroupKey, Result<Object, IoError>)>,
    input: &Path,
    params: &(dyn Fn(&Object) -> Result<Vec<f64>> + Sync),
    spec: SampleSpec,
) -> Vec<(GroupKey, Result<lekalo_io::SampleTable, String>)> {
    curves
        .into_par_iter()
        .map(|(k, obj)| {
            let t = obj.map_err(|e| e.to_string()).and_then(|o| {
                let ts = params(&o).map_err(|e| e.to_string())?;
                lekalo_io::sample_table(&o, &ts, spec)
                    .map_err(|e| format!("{}: group {k}: {e}", input.display()))
            });
            (k, t)
        })
        .collect()
}

/// A curve of another dimension than the file's first.
fn other_dimension(input: &Path, k: &GroupKey, d: usize) -> String {
    format!(
        "{}: group {k}: a {d}-D curve among curves of another dimension; a samples file holds one dimension",
        input.display()
    )
}

/// Writes the sampled points of a batch as columns; the first curve's dimension is the
/// file's.
fn write_points<W: std::io::Write + Send>(
    rows: Vec<(GroupKey, Result<Sampled, String>)>,
    input: &Path,
    key: &str,
    writer: &mut ParquetBatchWriter<W>,
    header: &mut Option<Vec<String>>,
    failed: &mut Vec<String>,
) -> std::io::Result<()> {
    let mut ok = Vec::with_capacity(rows.len());
    let mut dim = None;
    for (k, r) in rows {
        match r {
            Ok((ts, pts, d)) => {
                let names = header.get_or_insert_with(|| vec![d.to_string()]);
                if *names == [d.to_string()] {
                    dim = Some(d);
                    ok.push((k, ts, pts));
                } else {
                    failed.push(other_dimension(input, &k, d));
                }
            }
            Err(e) => failed.push(e),
        }
    }
    match dim {
        Some(d) => writer.write_point_samples(key, d, &ok),
        None => Ok(()),
    }
}

/// Writes the sample tables of a batch; the first curve's columns are the file's.
fn write_tables<W: std::io::Write + Send>(
    tables: Vec<(GroupKey, Result<lekalo_io::SampleTable, String>)>,
    input: &Path,
    key: &str,
    writer: &mut ParquetBatchWriter<W>,
    header: &mut Option<Vec<String>>,
    failed: &mut Vec<String>,
) -> std::io::Result<()> {
    let mut ok = Vec::with_capacity(tables.len());
    for (k, t) in tables {
        match t {
            Ok(t) if header.get_or_insert_with(|| t.header.clone()) == &t.header => {
                ok.push((k, t));
            }
            Ok(t) => failed.push(other_dimension(input, &k, t.header.len().saturating_sub(1))),
            Err(e) => failed.push(e),
        }
    }
    writer.write_samples(key, &ok)
}

/// Curves between Parquet and JSON Lines, whichever `input` is (`lekalo convert`).
pub(crate) fn convert_curves(
    cx: &Context,
    input: &Path,
    read: Option<(String, String)>,
    out: Option<&Path>,
) -> Result<()> {
    let key = &cx.group_column;
    let inputs = [input.to_path_buf()];
    if is_parquet(input) {
        let mut lines = Vec::new();
        lekalo_io::read_curve_groups(input, Some(key), |curves| {
            for (k, o) in curves {
                // the objects alone, in the file's order (an object line has no key field)
                let line = match o {
                    Ok(o) => (true, o.to_json_line()),
                    Err(e) => (
                        false,
                        serde_json::json!({"line": lines.len() + 1, key: key_json(&k), "error": e.to_string()})
                            .to_string(),
                    ),
                };
                lines.push(line);
            }
            Ok(())
        })?;
        return super::lines::finish(cx, lines, out, &inputs);
    }
    if read.is_none() && is_point_table(input) {
        return convert_point_table(cx, input, out);
    }
    let out = parquet_output(out, "curves")?;
    // standard input is read by the caller, once
    let (text, name) = match read {
        Some(read) => read,
        None => lekalo_io::read_input(input)?,
    };
    let rows: Vec<(GroupKey, Result<Object, String>)> = lekalo_io::read_json_lines(&text, &name)
        .into_iter()
        .map(|(line, o)| {
            let line = i64::try_from(line).unwrap_or(i64::MAX);
            (GroupKey::Int(line), o.map_err(|e| e.to_string()))
        })
        .collect();
    let failed: Vec<String> = rows
        .iter()
        .filter_map(|(_, r)| r.as_ref().err().cloned())
        .collect();
    write_parquet(
        cx,
        input,
        out,
        |writer| writer.write_curves("line", &rows).map_err(write_error(out)),
        |w| w.write_curves("line", &[]),
    )?;
    finish(&failed, rows.len(), input)
}

/// A CSV or whitespace table (`.csv`, `.tsv`, `.txt`): point sets with a key column.
fn is_point_table(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
        ["csv", "tsv", "txt"]
            .iter()
            .any(|t| e.eq_ignore_ascii_case(t))
    })
}

/// The point sets of a table with a key column (`group,x,y`, the key column named by
/// `--group-column`), written as a batch in the long layout (`lekalo convert scans.csv -o
/// scans.parquet`), the input of `interpolate`, `fit` on a Parquet file.
fn convert_point_table(cx: &Context, input: &Path, out: Option<&Path>) -> Result<()> {
    let out = parquet_output(out, "point sets")?;
    let key = &cx.group_column;
    let (text, name) = lekalo_io::read_input(input)?;
    let (names, groups) = lekalo_io::read_text_point_groups(&text, &name, key)?;
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    write_parquet(
        cx,
        input,
        out,
        |writer| {
            writer
                .write_points(key, &names, &groups)
                .map_err(write_error(out))
        },
        |w| w.write_points(key, &names, &[]),
    )
}

fn key_json(k: &GroupKey) -> serde_json::Value {
    match k {
        GroupKey::Int(i) => serde_json::Value::from(*i),
        GroupKey::Str(s) => serde_json::Value::from(s.as_str()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stop(what: &str) -> IoError {
        IoError::Write {
            path: what.into(),
            error: std::io::Error::other(what.to_string()),
        }
    }

    /// Every batch goes through in order; a failed read after some batches is the result,
    /// once the batches before it are written.
    #[test]
    fn the_pipeline_keeps_order_and_reports_a_failed_read() {
        let mut written = Vec::new();
        let r = pipeline(
            |each| {
                for i in 0..50 {
                    each(i)?;
                }
                Err(stop("read"))
            },
            |i: i32| i * 2,
            |x| {
                written.push(x);
                Ok(())
            },
        );
        assert!(
            r.unwrap_err().to_string().contains("read"),
            "the read's error"
        );
        assert_eq!(
            written,
            (0..50).map(|i| i * 2).collect::<Vec<_>>(),
            "in order"
        );
    }

    /// A failed write stops the read, and is the error reported.
    #[test]
    fn a_failed_write_stops_the_read() {
        let mut read = 0;
        let r = pipeline(
            |each| {
                for i in 0..1000 {
                    read += 1;
                    each(i)?;
                }
                Ok(())
            },
            |i: i32| i,
            |x| if x == 3 { Err(stop("write")) } else { Ok(()) },
        );
        assert!(
            r.unwrap_err().to_string().contains("write"),
            "the write's error"
        );
        assert!(read < 1000, "the read stopped after {read} batches");
    }
}
