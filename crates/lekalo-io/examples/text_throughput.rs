//! Reading and writing speed of the points text formats, for `bench/io/run.sh`.
//!
//! `text_throughput read FILE REPEATS`: reads the points file (CSV, whitespace or JSON) `REPEATS`
//! times and prints the best time and the speed in MB/s of text.
//! `text_throughput write FILE ROWS REPEATS`: writes a CSV table of `ROWS` rows `t,x,y,z`
//! (a helix's samples) to `FILE` `REPEATS` times, buffered, and prints the best time and MB/s.

use std::time::Instant;

use lekalo_io::SampleTable;

fn best_of<T>(repeats: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = f();
    for _ in 0..repeats {
        let t = Instant::now();
        out = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, out)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: text_throughput read FILE REPEATS | write FILE ROWS REPEATS";
    let arg = |i: usize| args.get(i).ok_or(usage);
    match arg(1)?.as_str() {
        "read" => {
            let path = std::path::Path::new(arg(2)?);
            let repeats: usize = arg(3)?.parse()?;
            let (secs, n) = best_of(repeats, || {
                // the command line's path: bytes, checked as UTF-8 part by part while parsed
                let (bytes, name) = lekalo_io::read_input_bytes(path)?;
                lekalo_io::read_points_bytes(&bytes, &name, lekalo_io::Header::Auto)
                    .map(|p| p.len())
            });
            let bytes = std::fs::metadata(path)?.len() as f64;
            println!(
                "read {} points in {secs:.4} s: {:.0} MB/s",
                n?,
                bytes / secs / 1e6
            );
        }
        "write" => {
            let path = std::path::Path::new(arg(2)?);
            let rows: u32 = arg(3)?.parse()?;
            let repeats: usize = arg(4)?.parse()?;
            let table = SampleTable {
                header: ["t", "x", "y", "z"].map(String::from).to_vec(),
                rows: (0..rows)
                    .map(|i| {
                        let t = f64::from(i) * 1e-3;
                        vec![Some(t), Some(t.cos()), Some(t.sin()), Some(t / 10.0)]
                    })
                    .collect(),
            };
            let (secs, r) = best_of(repeats, || {
                lekalo_io::write_atomic_stream(
                    path,
                    &[],
                    lekalo_io::WriteOptions { force: true },
                    |w| table.write_csv(w, true),
                )
            });
            r?;
            let bytes = std::fs::metadata(path)?.len() as f64;
            println!(
                "wrote {rows} rows in {secs:.4} s: {:.0} MB/s",
                bytes / secs / 1e6
            );
        }
        _ => return Err(usage.into()),
    }
    Ok(())
}
