//! The fast path (src/fast) against exact references: physics.md's tables, the closed forms and quadratures of
//! `impact::reference`, momentum and energy balances, and the general Dop853 path.

mod fast_support;

use fast_support::{Case, QUANTITIES, errors, reference_cases};
use impact::fast::{Outcome, simulate_normal};

fn run(case: &Case, tolerance: f64) -> Outcome {
    simulate_normal(&case.request(tolerance)).unwrap_or_else(|e| panic!("{}: {e}", case.name()))
}

#[test]
fn survey() {
    for tol in [1e-6, 1e-10, 1e-13, 1e-16] {
        for case in reference_cases() {
            let out = run(&case, tol);
            let Some(exact) = case.exact() else {
                println!("{tol:e} {:32} not separated: {:?} steps {}", case.name(), out.ending, out.steps);
                continue;
            };
            let err = errors(&out, &exact);
            let worst = err.iter().cloned().fold(0.0, f64::max);
            let which = QUANTITIES[err.iter().position(|&e| e == worst).unwrap()];
            println!(
                "{tol:e} {:32} steps {:3} worst {worst:.1e} ({which}) all {:?}",
                case.name(),
                out.steps,
                err.map(|e| format!("{e:.0e}"))
            );
        }
    }
}
