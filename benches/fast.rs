//! Work–precision of the fast path (src/fast): time per impact for every reference impact at tolerances 1e-6,
//! 1e-10 and 1e-13 (and the rounding floor, 1e-16), with each case's largest error against its exact values
//! printed beside it. Run: `cargo bench --bench fast` (the table first, then criterion's measurements; filter
//! criterion with e.g. `cargo bench --bench fast -- 1e-10`).

#[path = "../tests/fast_support/mod.rs"]
mod fast_support;

use criterion::{Criterion, criterion_group};
use fast_support::{QUANTITIES, errors, reference_cases};
use impact::fast::{Request, simulate_normal};
use std::hint::black_box;
use std::time::{Duration, Instant};

const TOLERANCES: [f64; 3] = [1e-6, 1e-10, 1e-13];

/// Median and least, over batches, of the mean time of one impact, in µs. (On a shared machine the least is the
/// closer to the time on a quiet core: other processes only ever add time.)
fn batch_times(request: &Request) -> (f64, f64) {
    let once = || simulate_normal(black_box(request)).expect("fast path");
    // Batches of about 2 ms, after a warm-up.
    let start = Instant::now();
    let mut calls = 0u32;
    while start.elapsed() < Duration::from_millis(20) {
        black_box(once());
        calls += 1;
    }
    let per_batch = (calls / 10).max(1);
    let mut means: Vec<f64> = (0..31)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..per_batch {
                black_box(once());
            }
            t.elapsed().as_secs_f64() * 1e6 / f64::from(per_batch)
        })
        .collect();
    means.sort_by(f64::total_cmp);
    (means[means.len() / 2], means[0])
}

fn table() {
    println!(
        "\nfast path, one impact: median (least) time over batches in µs, Taylor steps, order, largest error over \
         every measured quantity"
    );
    println!("quantities: {}", QUANTITIES.join(", "));
    for tolerance in TOLERANCES.into_iter().chain([1e-16]) {
        let (mut worst_time, mut worst_least, mut worst_error): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for case in reference_cases() {
            let request = case.request(tolerance);
            let out = simulate_normal(&request).expect("fast path");
            let (time, least) = batch_times(&request);
            worst_time = worst_time.max(time);
            worst_least = worst_least.max(least);
            let error = match case.exact() {
                Some(exact) => {
                    let err = errors(&out, &exact);
                    let (i, &e) = err.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).expect("13 quantities");
                    worst_error = worst_error.max(e);
                    format!("{e:8.1e} ({})", QUANTITIES[i])
                }
                None => format!("not separated ({:?})", out.ending),
            };
            println!(
                "tol {tolerance:5.0e}  {:30} {time:6.2} ({least:5.2}) µs  {:4} steps  order {:2}  error {error}",
                case.name(),
                out.steps,
                out.order
            );
        }
        println!(
            "tol {tolerance:5.0e}  largest median time {worst_time:.2} µs (least {worst_least:.2}), largest error \
             {worst_error:.1e}\n"
        );
    }
}

fn fast_path(c: &mut Criterion) {
    for tolerance in TOLERANCES {
        let mut group = c.benchmark_group(format!("fast {tolerance:e}"));
        group.warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1)).sample_size(20);
        for case in reference_cases() {
            let request = case.request(tolerance);
            group.bench_function(case.name(), |b| b.iter(|| simulate_normal(black_box(&request))));
        }
        group.finish();
    }
}

criterion_group!(benches, fast_path);

fn main() {
    // `--list` (cargo's bench discovery) only lists.
    if !std::env::args().any(|a| a == "--list") {
        table();
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
