//! What every bench binary times with (included by `mod common;`).
#![allow(dead_code)]

use std::time::Instant;

/// The median of `v` (sorted in place; the upper one of an even count).
pub fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// µs per call of `f`, median of 7 rounds of `calls` calls.
pub fn time(calls: usize, mut f: impl FnMut()) -> f64 {
    let mut rounds = Vec::new();
    for _ in 0..7 {
        let t0 = Instant::now();
        for _ in 0..calls {
            f();
        }
        rounds.push(t0.elapsed().as_secs_f64() / calls as f64 * 1e6);
    }
    median(&mut rounds)
}
