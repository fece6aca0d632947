#[path = "/work/wt/fast/tests/fast_support/mod.rs"]
mod fast_support;
use std::hint::black_box;
fn main() {
    let tol: f64 = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(1e-10);
    let which: usize = std::env::args().nth(2).map(|s| s.parse().unwrap()).unwrap_or(4);
    let reps: usize = std::env::args().nth(3).map(|s| s.parse().unwrap()).unwrap_or(100000);
    let cases = fast_support::reference_cases();
    let req = cases[which].request(tol);
    eprintln!("{}", cases[which].name());
    for _ in 0..reps { black_box(impact::fast::simulate_normal(black_box(&req)).unwrap()); }
}
