//! Parallel evaluation and thread placement: the speed-up of `par_eval_batch` on two threads
//! with a rayon pool left to the scheduler, with a pool whose workers are pinned to distinct
//! processors, and with two plain scoped threads, timed alternately (so that all three see the
//! same machine state) against the sequential `eval_batch`.
//!
//! The same alternation times the memory traffic of a batch without its arithmetic: one
//! parameter read and three numbers written a point, on one thread and on the pinned pool in
//! the same chunks. How much faster two threads move those bytes than one is what the memory
//! system, shared with the host's other guests, allows any two-thread batch at that moment.
//! Likewise for arithmetic alone (a cubic's Horner steps a parameter, nothing written): how
//! much faster two vCPUs compute than one at that moment.
//!
//! Run: `cargo run --release -p lekalo --example par_placement [-- POINTS [ROUNDS]]`
//! (default 10^6 points, 60 rounds). Prints the median sequential time a point, the three
//! speed-ups (median over median) and the traffic and arithmetic times, for sorted and random
//! parameters.

#[path = "../benches/common/mod.rs"]
mod common;

use std::time::Instant;

use lekalo::{CurveEvaluator, EvalKernel};
use rayon::prelude::*;

/// The memory traffic of evaluating `ts` into `out` (3-D) without the arithmetic: each
/// parameter read, three numbers derived from it written.
fn traffic(ts: &[f64], out: &mut [f64]) {
    for (&t, o) in ts.iter().zip(out.chunks_exact_mut(3)) {
        o[0] = t;
        o[1] = t * 0.5;
        o[2] = t * 0.25;
    }
    std::hint::black_box(out);
}

/// Arithmetic alone: for each parameter four rounds of a 3-D cubic's Horner steps (about the
/// power-form kernel's work, with no table and no output), summed into three accumulators.
fn arithmetic(ts: &[f64]) -> f64 {
    const C: [[f64; 4]; 3] = [
        [0.5, -1.0, 2.0, 0.25],
        [1.5, 0.75, -0.5, 1.0],
        [-2.0, 1.0, 0.5, 0.125],
    ];
    let mut acc = [0.0; 3];
    for &t in ts {
        let mut u = t;
        for _ in 0..4 {
            for (a, c) in acc.iter_mut().zip(&C) {
                *a += ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
            }
            u = u * 0.5 + 0.25;
        }
    }
    std::hint::black_box(acc.iter().sum())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map_or(Ok(1_000_000), |s| s.parse())?;
    let rounds: usize = args.next().map_or(Ok(60), |s| s.parse())?;
    if n < 2 || rounds == 0 {
        return Err("usage: par_placement [POINTS ≥ 2 [ROUNDS ≥ 1]]".into());
    }
    let curve = common::curve(3, 1000, 3);
    let ev = CurveEvaluator::with_kernel(&curve, EvalKernel::PowerForm)?;
    let (free, pinned) = (common::rayon_pool(2, false), common::rayon_pool(2, true));
    let mut out = vec![0.0; n * 3];
    println!("{n} points, {rounds} rounds; speed-up = sequential median / parallel median");
    for (name, ts) in [
        ("sorted", common::sorted_params(n)),
        ("random", common::random_params(n)),
    ] {
        let mut times = [(); 8].map(|()| Vec::with_capacity(rounds));
        let per_point = |t0: Instant| t0.elapsed().as_secs_f64() * 1e9 / n as f64;
        for _ in 0..rounds {
            let t0 = Instant::now();
            ev.eval_batch(&ts, &mut out)?;
            times[0].push(per_point(t0));
            for (k, pool) in [(1, &free), (2, &pinned)] {
                let t0 = Instant::now();
                pool.install(|| ev.par_eval_batch(&ts, &mut out))?;
                times[k].push(per_point(t0));
            }
            let t0 = Instant::now();
            let (t1, t2) = ts.split_at(n / 2);
            let (o1, o2) = out.split_at_mut(n / 2 * 3);
            std::thread::scope(|s| {
                let other = s.spawn(|| ev.eval_batch(t2, o2));
                let mine = ev.eval_batch(t1, o1);
                other.join().map_err(|_| "worker panicked").and(Ok(mine))
            })??;
            times[3].push(per_point(t0));
            let t0 = Instant::now();
            traffic(&ts, &mut out);
            times[4].push(per_point(t0));
            // the chunks of `par_eval_batch` (8192 parameters at least, about four a thread)
            let chunk = n.div_ceil(8).max(8192);
            let t0 = Instant::now();
            pinned.install(|| {
                ts.par_chunks(chunk)
                    .zip(out.par_chunks_mut(chunk * 3))
                    .for_each(|(t, o)| traffic(t, o));
            });
            times[5].push(per_point(t0));
            let t0 = Instant::now();
            arithmetic(&ts);
            times[6].push(per_point(t0));
            let t0 = Instant::now();
            pinned.install(|| ts.par_chunks(chunk).map(arithmetic).sum::<f64>());
            times[7].push(per_point(t0));
        }
        let [seq, f, p, s, m1, m2, a1, a2] = times.map(median);
        println!(
            "{name}: sequential {seq:.2} ns/pt; rayon unpinned {:.2}x, rayon pinned {:.2}x, \
             scoped threads {:.2}x",
            seq / f,
            seq / p,
            seq / s
        );
        println!(
            "  memory traffic alone (1 number read, 3 written a point): 1 thread {m1:.2} ns/pt, \
             2 pinned {m2:.2} ({:.2}x)",
            m1 / m2
        );
        println!(
            "  arithmetic alone (Horner steps, nothing written): 1 thread {a1:.2} ns/pt, \
             2 pinned {a2:.2} ({:.2}x)",
            a1 / a2
        );
    }
    Ok(())
}
