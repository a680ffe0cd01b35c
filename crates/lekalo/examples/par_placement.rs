//! Parallel evaluation and thread placement: the speed-up of `par_eval_batch` on two threads
//! with a rayon pool left to the scheduler, with a pool whose workers are pinned to distinct
//! processors, and with two plain scoped threads, timed alternately (so that all three see the
//! same machine state) against the sequential `eval_batch`.
//!
//! Run: `cargo run --release -p lekalo --example par_placement [-- POINTS [ROUNDS]]`
//! (default 10^6 points, 60 rounds). Prints the median sequential time a point and the three
//! speed-ups (median over median), for sorted and random parameters.

#[path = "../benches/common/mod.rs"]
mod common;

use std::time::Instant;

use lekalo::{CurveEvaluator, EvalKernel};

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
        let mut times = [(); 4].map(|()| Vec::with_capacity(rounds));
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
        }
        let [seq, f, p, s] = times.map(median);
        println!(
            "{name}: sequential {seq:.2} ns/pt; rayon unpinned {:.2}x, rayon pinned {:.2}x, \
             scoped threads {:.2}x",
            seq / f,
            seq / p,
            seq / s
        );
    }
    Ok(())
}
