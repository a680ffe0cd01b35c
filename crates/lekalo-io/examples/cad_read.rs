//! Reading speed of STEP and IGES files, for `bench/peers/cad_read.py`.
//!
//! `cad_read FILE REPEATS [faces]`: reads the file (the text from disk, then every curve and
//! surface, and with `faces` the faces as well, as `lekalo convert --faces` does) `REPEATS`
//! times and prints one line `seconds <wall> cpu <cpu> shapes <n> faces <n>`: the median wall
//! time and the median CPU time (all threads, from Linux's `/proc/self/task/*/schedstat`; 0
//! elsewhere) of a whole read, file read included.

use std::path::Path;
use std::time::Instant;

/// Shapes and faces read from `path`.
fn read(path: &Path, faces: bool) -> Result<(usize, usize), Box<dyn std::error::Error>> {
    let (text, name) = lekalo_io::read_input(path)?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let iges = matches!(ext.as_str(), "igs" | "iges");
    Ok(match (iges, faces) {
        (true, false) => {
            let r = lekalo_io::read_iges(&text, &name)?;
            (r.shapes.len(), 0)
        }
        (true, true) => {
            let r = lekalo_io::read_iges_faces(&text, &name, usize::MAX)?;
            (r.shapes.len(), r.faces.len())
        }
        (false, false) => {
            let r = lekalo_io::read_step(&text, &name)?;
            (r.shapes.len(), 0)
        }
        (false, true) => {
            let r = lekalo_io::read_step_faces(&text, &name, usize::MAX)?;
            (r.shapes.len(), r.faces.len())
        }
    })
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
    let mut counts = (0, 0);
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
        "seconds {:.6} cpu {:.6} shapes {} faces {}",
        wall[wall.len() / 2],
        cpu[cpu.len() / 2],
        counts.0,
        counts.1
    );
    Ok(())
}
