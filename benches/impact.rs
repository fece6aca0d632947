//! Time per impact for every contact law at its default settings (`[solver] method = "auto"`: the fast path where it
//! covers the law, Dop853 for Brilliantov), three ways: `simulate` (the whole run of `impact run`: setup,
//! integration, the report with its exact reference, whose quadratures dominate for Hunt–Crossley and Tsuji), the
//! same without the exact reference, and the outcome alone (the integration and its events: what `impact bench`
//! times); and a sweep of 1000 Hunt–Crossley impacts through the library's `Sweep` on one thread. Each case's error
//! against its exact reference is printed beside it, so speed is read with accuracy.
//! Run: `cargo bench --bench impact` (filter with e.g. `cargo bench --bench impact -- tsuji`).

use criterion::{Criterion, criterion_group, criterion_main};
use impact::history::Recording;
use impact::impact::{Options, outcome, simulate, simulate_with};
use impact::law::LawKind;
use impact::report::Report;
use impact::report::accuracy::ReferenceDetail;
use impact::scene::Scene;
use impact::setup::Setup;
use impact::sweep::Sweep;
use impact::sweep::grid::{Axis, Grid, Spacing};
use impact::sweep::table::Cell;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// A 1 kg sphere on a wall at 1 m/s with K = 1e6 (docs/references.md's nondimensional case), under `contact`.
fn scene(contact: &str) -> String {
    format!(
        "[[bodies]]\nradius = 0.01\nmass = 1\nvelocity = [1, 0, 0]\n[[bodies]]\nradius = inf\nmass = inf\n\
         velocity = [0, 0, 0]\n[contact]\n{contact}\nstiffness = 1e6\n"
    )
}

/// Each law at its defaults: nominal e = 0.5 through the law's own map (Hertz is elastic; Brilliantov's A = 1e-4
/// s, its damping given directly).
fn cases() -> Vec<(String, String)> {
    LawKind::names()
        .into_iter()
        .map(|name| {
            let damping = match name {
                "hertz" => String::new(),
                "brilliantov" => "damping = 1e-4".into(),
                _ => "restitution = 0.5".into(),
            };
            (name.to_string(), scene(&format!("law = \"{name}\"\n{damping}")))
        })
        .collect()
}

/// The largest relative error of the report against its exact reference (e, dmax, t0, tc, Fmax), if it has one.
fn largest_error(report: &Report) -> Option<f64> {
    let errors = &report.reference.as_ref()?.errors;
    let all =
        [errors.restitution, errors.max_penetration, errors.max_compression_time, errors.duration, errors.max_force];
    all.into_iter().flatten().reduce(f64::max)
}

fn per_law(c: &mut Criterion) {
    let cases: Vec<(String, Scene)> = cases()
        .into_iter()
        .map(|(name, text)| (name, Scene::parse(&text, Path::new("bench.toml")).expect("benchmark scene")))
        .collect();
    for (name, scene) in &cases {
        let report = simulate(scene, Recording::Off).expect("simulation").report;
        println!(
            "{name}: {} path, {} force evaluations, largest error against the exact reference {}",
            report.solver.method,
            report.solver.force_evaluations,
            largest_error(&report).map_or("n/a (no exact reference)".into(), |e| format!("{e:.1e}"))
        );
    }
    let no_reference = Options { recording: Recording::Off, reference: ReferenceDetail::Off, ..Options::default() };
    for group_name in ["one impact", "one impact, no exact reference", "one impact, outcome alone"] {
        let mut group = c.benchmark_group(group_name);
        group.warm_up_time(Duration::from_millis(200)).measurement_time(Duration::from_millis(700)).sample_size(20);
        for (name, scene) in &cases {
            let setup = Setup::new(scene).expect("a valid scene");
            match group_name {
                "one impact" => group.bench_function(name, |b| {
                    b.iter(|| simulate(black_box(scene), Recording::Off).expect("simulation"))
                }),
                "one impact, no exact reference" => group.bench_function(name, |b| {
                    b.iter(|| simulate_with(black_box(scene), no_reference).expect("simulation"))
                }),
                _ => group.bench_function(name, |b| b.iter(|| outcome(black_box(scene), &setup).expect("simulation"))),
            };
        }
        group.finish();
    }
}

/// The sweep of the peers: Hunt–Crossley, n = 3/2, x = alpha v0 from 0.01 to 2.
const SWEEP_POINTS: usize = 1000;

fn sweep(c: &mut Criterion) {
    let text = scene("law = \"hunt-crossley\"\ndamping = 0.5");
    let grid = Grid::new(vec![
        Axis::parse(&format!("contact.damping=0.01:2:{SWEEP_POINTS}"), Spacing::Linear).expect("an axis"),
    ])
    .expect("a grid");
    let sweep = Sweep::new(Path::new("bench.toml"), text, grid, Vec::new()).expect("a sweep");
    let indices: Vec<usize> = (0..sweep.rows()).collect();
    let rows = sweep.run(&indices, Some(1), |_| {}).expect("the sweep runs");
    let column = |name: &str| impact::sweep::table::RESULT_COLUMNS.iter().position(|c| *c == name).expect("a column");
    let (e, exact) = (column("restitution_velocity_ratio"), column("reference_restitution"));
    let worst = rows
        .iter()
        .map(|row| match (row.results[e], row.results[exact]) {
            (Cell::Number(e), Cell::Number(exact)) => ((e - exact) / exact).abs(),
            _ => f64::INFINITY,
        })
        .fold(0.0, f64::max);
    println!("sweep of {SWEEP_POINTS} Hunt–Crossley impacts, x = 0.01 to 2: largest e error {worst:.1e}");
    let mut group = c.benchmark_group("sweep");
    group.sample_size(10).measurement_time(Duration::from_secs(3));
    group.bench_function(format!("{SWEEP_POINTS} points, one thread"), |b| {
        b.iter(|| sweep.run(black_box(&indices), Some(1), |_| {}).expect("the sweep runs"))
    });
    group.finish();
}

criterion_group!(benches, per_law, sweep);
criterion_main!(benches);
