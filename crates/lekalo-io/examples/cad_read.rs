//! Reading speed of STEP and IGES files, for `bench/peers/cad_read.py`.
//!
//! `cad_read FILE REPEATS [faces]`: reads the file (the text from disk, then every curve and
//! surface, and with `faces` the faces as well, as `lekalo convert --faces` does) `REPEATS`
//! times and prints one line `seconds <wall> cpu <cpu> shapes <n> faces <n> result_mb <r>
//! heap_mb <h> peak_mb <p>`: the median wall time and the median CPU time (all threads, from
//! Linux's `/proc/self/task/*/schedstat`; 0 elsewhere) of a whole read, file read included; the
//! memory the result of a read holds (the bytes allocated that are still live once the file's
//! text is dropped), and the peak of the bytes allocated during the reads (text included), both
//! counted by this program's allocator (`lekalo_testkit::alloc`); and the peak resident memory of the process (`VmHWM` of
//! Linux's `/proc/self/status`, which the allocator's overhead and the program's code add to;
//! 0 elsewhere), all in MB.

use std::path::Path;
use std::time::Instant;

use lekalo_testkit::alloc::{live, peak, Counting};

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Shapes and faces read from `path`, and the bytes the result holds.
fn read(path: &Path, faces: bool) -> Result<(usize, usize, usize), Box<dyn std::error::Error>> {
    let before = live();
    let (text, name) = lekalo_io::read_input(path)?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let iges = matches!(ext.as_str(), "igs" | "iges");
    // the result held while the text is dropped: what is then live beyond `before` is the result
    let result = |text: String, counts: (usize, usize)| {
        drop(text);
        let bytes = live().saturating_sub(before);
        (counts.0, counts.1, bytes)
    };
    Ok(match (iges, faces) {
        (true, false) => {
            let r = lekalo_io::read_iges(&text, &name)?;
            result(text, (r.shapes.len(), 0))
        }
        (true, true) => {
            let r = lekalo_io::read_iges_faces(&text, &name, usize::MAX)?;
            result(text, (r.shapes.len(), r.faces.len()))
        }
        (false, false) => {
            let r = lekalo_io::read_step(&text, &name)?;
            result(text, (r.shapes.len(), 0))
        }
        (false, true) => {
            let r = lekalo_io::read_step_faces(&text, &name, usize::MAX)?;
            result(text, (r.shapes.len(), r.faces.len()))
        }
    })
}

/// The peak resident memory of the process in MB (`VmHWM`, Linux; 0 elsewhere).
fn peak_rss_mb() -> f64 {
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else {
        return 0.0;
    };
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(0.0, |kb| kb * 1024.0 / 1e6)
}

/// CPU time of the process so far, all threads, in seconds (0 where Linux's schedstat is
/// missing).
fn cpu_seconds() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0.0;
    };
    let ns: u64 = tasks
        .filter_map(|t| std::fs::read_to_string(t.ok()?.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .sum();
    ns as f64 * 1e-9
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: cad_read FILE REPEATS [faces]";
    let path = Path::new(args.get(1).ok_or(usage)?);
    let repeats: usize = args.get(2).ok_or(usage)?.parse()?;
    let faces = args.get(3).is_some_and(|a| a == "faces");
    let mut wall = Vec::with_capacity(repeats.max(1));
    let mut cpu = Vec::with_capacity(repeats.max(1));
    let mut counts = (0, 0, 0);
    for _ in 0..repeats.max(1) {
        let c = cpu_seconds();
        let t = Instant::now();
        counts = read(path, faces)?;
        wall.push(t.elapsed().as_secs_f64());
        cpu.push(cpu_seconds() - c);
    }
    wall.sort_by(f64::total_cmp);
    cpu.sort_by(f64::total_cmp);
    println!(
        "seconds {:.6} cpu {:.6} shapes {} faces {} result_mb {:.1} heap_mb {:.1} peak_mb {:.1}",
        wall[wall.len() / 2],
        cpu[cpu.len() / 2],
        counts.0,
        counts.1,
        counts.2 as f64 / 1e6,
        peak() as f64 / 1e6,
        peak_rss_mb()
    );
    Ok(())
}
