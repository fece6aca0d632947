//! Time per impact for each law family at the default tolerances (criterion). Run: `cargo bench`.
//! The error of each case against its exact reference is printed beside it, so speed is read with accuracy.

use criterion::{Criterion, criterion_group, criterion_main};
use impact::history::Recording;
use impact::impact::simulate;
use impact::scene::Scene;
use std::hint::black_box;
use std::path::Path;

/// A 1 kg sphere on a wall at 1 m/s with K = 1e6 (docs/references.md's nondimensional case), per law.
const CASES: [(&str, &str); 5] = [
    ("hertz", "law = \"hertz\"\nstiffness = 1e6"),
    ("hunt-crossley x=0.5", "law = \"hunt-crossley\"\ndamping = 0.5\nstiffness = 1e6"),
    ("kelvin-voigt e=0.5", "law = \"kelvin-voigt\"\nrestitution = 0.5\nstiffness = 1e6"),
    ("tsuji e=0.5", "law = \"tsuji\"\nrestitution = 0.5\nstiffness = 1e6"),
    ("brilliantov A=1e-4", "law = \"brilliantov\"\ndamping = 1e-4\nstiffness = 1e6"),
];

fn scene(contact: &str) -> Scene {
    let text = format!(
        "[[bodies]]\nradius = 0.01\nmass = 1\nvelocity = [1, 0, 0]\n[[bodies]]\nradius = inf\nmass = inf\n\
         velocity = [0, 0, 0]\n[contact]\n{contact}\n"
    );
    Scene::parse(&text, Path::new("bench.toml")).expect("benchmark scene")
}

fn one_impact(c: &mut Criterion) {
    let mut group = c.benchmark_group("one impact");
    for (name, contact) in CASES {
        let scene = scene(contact);
        let report = simulate(&scene, Recording::Off).expect("simulation").report;
        let error = report.reference.as_ref().and_then(|r| r.errors.restitution);
        println!(
            "{name}: {} force evaluations, e error {}",
            report.solver.force_evaluations,
            error.map_or("n/a (no exact reference)".into(), |e| format!("{e:.1e}"))
        );
        group.bench_function(name, |b| b.iter(|| simulate(black_box(&scene), Recording::Off).expect("simulation")));
    }
    group.finish();
}

criterion_group!(benches, one_impact);
criterion_main!(benches);
