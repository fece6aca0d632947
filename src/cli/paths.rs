//! The paths of one command, checked before any work (README.md#exit-status-and-output-files): an output never
//! replaces an input of the same run (the scene file, a shard being merged) nor another output of it, and at most one
//! output goes to standard output. A clash is bad input (exit status 2) naming both paths; an output path that cannot
//! be examined (its parent is a file, it is a folder) is an I/O error (status 1) from [`Destination::resolve`].

use super::BadInput;
use crate::files::{Destination, Identity};
use crate::scene::SceneError;
use std::path::{Path, PathBuf};

/// Where a path was given: on the command line, or by a key of the scene file (then errors name the key and line).
#[derive(Debug, Clone)]
pub enum Origin {
    CommandLine,
    Scene { file: PathBuf, key: &'static str, line: Option<usize> },
}

impl Origin {
    /// Bad input about a path given here: exit status 2, located in the scene file when it came from there.
    pub fn bad(&self, message: String) -> anyhow::Error {
        match self {
            Origin::CommandLine => BadInput(message).into(),
            Origin::Scene { file, key, line } => SceneError {
                file: file.display().to_string(),
                key: Some(key.to_string()),
                line: *line,
                message,
                form: false,
            }
            .into(),
        }
    }
}

struct Output {
    /// How messages name it, e.g. `--csv out.csv` or `--plot figs (figs/force_time.png)`.
    label: String,
    origin: Origin,
    identity: Identity,
}

/// The inputs and outputs of one command, each output checked against everything added before it.
#[derive(Default)]
pub struct Paths {
    /// Each input's description (e.g. `the scene file demo.toml being read`) and identity.
    inputs: Vec<(String, Identity)>,
    outputs: Vec<Output>,
}

impl Paths {
    /// Adds an input; `description` names it in messages, e.g. `the shard s1.csv being merged`.
    pub fn input(&mut self, description: String, path: &Path) {
        self.inputs.push((description, Identity::of(path)));
    }

    /// Resolves and adds an output file, or refuses it (see the module's comment).
    pub fn output(&mut self, label: String, origin: Origin, path: &Path) -> anyhow::Result<Destination> {
        let destination = Destination::resolve(path)?;
        self.add(Output { label, origin, identity: destination.identity().clone() })?;
        Ok(destination)
    }

    /// Adds a text that goes to standard output (the JSON report), or refuses it when an output already goes there.
    pub fn standard_output(&mut self, label: String) -> anyhow::Result<()> {
        self.add(Output { label, origin: Origin::CommandLine, identity: Identity::StandardOutput })
    }

    fn add(&mut self, output: Output) -> anyhow::Result<()> {
        let label = &output.label;
        if let Some((input, _)) = self.inputs.iter().find(|(_, identity)| output.identity.same_as(identity)) {
            return Err(output.origin.bad(format!("{label} is {input}: an output never replaces an input of the run")));
        }
        for other in &self.outputs {
            let message = if output.identity.same_as(&other.identity) {
                if output.identity == Identity::StandardOutput {
                    format!("{label} and {} both write to standard output: give one of them a file", other.label)
                } else {
                    format!(
                        "{label} and {} are the same file: the outputs of a run never overwrite each other",
                        other.label
                    )
                }
            } else if output.identity.is_inside(&other.identity) || other.identity.is_inside(&output.identity) {
                format!("{label} and {} collide: one path would have to be both a file and a folder", other.label)
            } else {
                continue;
            };
            // Where either was written in the scene file, the error points there.
            let origin = if matches!(output.origin, Origin::Scene { .. }) { &output.origin } else { &other.origin };
            return Err(origin.bad(message));
        }
        self.outputs.push(output);
        Ok(())
    }
}
