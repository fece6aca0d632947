//! `impact gallery`: regenerates the README's committed figures in `plots/` (and only on this explicit command).

use crate::history::Recording;
use crate::impact::simulate;
use crate::output::figures;
use crate::scene::Scene;
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct GalleryArgs {
    /// Folder for the figures.
    #[arg(long, value_name = "DIR", default_value = "plots")]
    pub out: PathBuf,
}

/// The one-impact figures of the gallery: (scene name, scene text, the figures kept). The demonstration's steel
/// balls show the Hunt–Crossley force pulse and the velocities meeting at V0; the Kelvin–Voigt rubber ball shows
/// the force jump at first contact and the tensile end, which Hertz-type laws do not have.
const SCENES: [(&str, &str, &[&str]); 2] = [
    ("demo", include_str!("../../models/demo.toml"), &["force_time", "velocities"]),
    ("kelvin_voigt", include_str!("../../models/rubber-ball-kelvin-voigt.toml"), &["force_penetration"]),
];

pub fn run(args: &GalleryArgs) -> anyhow::Result<()> {
    for (name, text, keep) in SCENES {
        let scene = Scene::parse(text, Path::new(&format!("{name}.toml")))?;
        let simulation = simulate(&scene, Recording::Uniform(super::run::FIGURE_SAMPLES))?;
        let history = simulation.history.as_ref().expect("a uniform history was asked for");
        let staging = args.out.join(format!(".{name}"));
        for written in figures::write_all(&simulation.report, history, &staging)? {
            let file = written.file_name().expect("figure files have names").to_string_lossy().into_owned();
            if file.strip_suffix(".png").is_some_and(|stem| keep.contains(&stem)) {
                let target = args.out.join(format!("{name}_{file}"));
                std::fs::rename(&written, &target)?;
                println!("wrote {}", target.display());
            } else {
                std::fs::remove_file(&written)?;
            }
        }
        std::fs::remove_dir(&staging)?;
    }
    effective_restitution(&args.out)
}

/// The comparison figure of the contact-mechanics literature: the e each published map actually gives against
/// the e it was asked for (physics.md §3), from a sweep of the hysteresis-family scene under several laws.
fn effective_restitution(folder: &Path) -> anyhow::Result<()> {
    let scratch = std::env::temp_dir().join(format!("impact-gallery-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)?;
    let scene = scratch.join("scene.toml");
    std::fs::write(&scene, include_str!("../../models/hysteresis-lankarani-nikravesh.toml"))?;
    let target = folder.join("effective_restitution.png");
    let sweep = super::sweep::SweepArgs {
        scene,
        vary: vec!["contact.restitution=0.05:1:39".into()],
        log: false,
        law: ["hunt-crossley", "lankarani-nikravesh", "gonthier", "flores", "hu-guo", "carvalho-martins"]
            .map(String::from)
            .to_vec(),
        out: scratch.join("sweep.csv"),
        plot: Some(target.clone()),
        shard: None,
        threads: None,
    };
    let result = super::sweep::run(&sweep);
    let _ = std::fs::remove_dir_all(&scratch);
    result
}
