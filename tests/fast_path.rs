//! The fast path (src/fast) against exact references: physics.md's tables, the closed forms and quadratures of
//! `impact::reference`, momentum and energy balances, and the general Dop853 path.

use impact::dynamics::Scales;
use impact::fast::{Outcome, Request, simulate_normal};
use impact::law::{ContactLaw, LawKind, Separation};

/// A contact with m* = 1, K = 1, v0 = 1, so that SI values are the scaled ones.
fn request(kind: LawKind, exponent: f64, damping: f64, separation: Separation, tolerance: f64) -> Request {
    Request {
        law: ContactLaw { kind, stiffness: 1.0, exponent, damping, tsuji_scale: 1.0 },
        scales: Scales::new(1.0, 1.0, exponent, 1.0),
        separation,
        tolerance,
    }
}

fn run(request: &Request) -> Outcome {
    simulate_normal(request).expect("fast path")
}

fn rel(got: f64, exact: f64) -> f64 {
    ((got - exact) / exact).abs()
}

/// physics.md §3 table: x, n, e, dmax/L, t0/T, tc/T, Fmax/F0.
const HUNT_CROSSLEY_TABLE: [[f64; 7]; 5] = [
    [0.5, 1.5, 0.7484349315974, 0.9777703257171, 1.505190262472, 3.338252755937, 1.03820817965],
    [2.0, 1.5, 0.410719686061, 0.7949076199716, 1.33112133457, 3.78025803753, 1.10425499427],
    [0.5, 1.0, 0.7484349315974, 0.8696431079096, 1.437445184309, 3.166389384992, 0.945050174739],
    [1.0, 2.2, 0.59362426004, 0.9943173787563, 1.468630256523, 3.613729878934, 1.18053806176],
    [10.0, 1.5, 0.09998162475294, 0.5146945181523, 1.026446744025, 6.458113911715, 1.63632476647],
];

#[test]
fn hunt_crossley_table() {
    for [x, n, e, dmax, t0, tc, fmax] in HUNT_CROSSLEY_TABLE {
        let out = run(&request(LawKind::HuntCrossley, n, x, Separation::Penetration, 1e-10));
        let errors = [
            rel(-out.end.rate, e),
            rel(out.max_compression.penetration, dmax),
            rel(out.max_compression.time, t0),
            rel(out.end.time, tc),
            rel(out.peak_force, fmax),
        ];
        println!("x {x} n {n}: steps {} errors {:?}", out.steps, errors.map(|e| format!("{e:.1e}")));
    }
}

#[test]
fn debug_case() {
    let r = impact::reference::hysteresis_contact(0.5, 1.5);
    for tol in [1e-6, 1e-8, 1e-10, 1e-12, 1e-14] {
        let out = run(&request(LawKind::HuntCrossley, 1.5, 0.5, Separation::Penetration, tol));
        println!(
            "tol {tol:e} steps {} order {} e {:.1e} t0 {:.1e} tc {:.1e} dmax {:.1e} F {:.1e}",
            out.steps,
            out.order,
            rel(-out.end.rate, r.restitution),
            rel(out.max_compression.time, r.max_compression_time),
            rel(out.end.time, r.duration),
            rel(out.max_compression.penetration, r.max_penetration),
            rel(out.peak_force, r.max_force)
        );
    }
}
