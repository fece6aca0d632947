//! Helpers shared by the tests that drive the real `impact` binary: a scratch folder per test, running the binary
//! in it, and reading its answer.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh folder for one test under the system temp folder; removed when the test passes, kept when it fails.
///
/// The folder is `impact-CRATE-PID-TEST`, where CRATE is the test file (each file in tests/ is its own crate) and
/// PID the test process, so that two files, two tests or two runs never share a folder as long as the tests of one
/// file give distinct names.
pub struct Scratch(PathBuf);

impl Scratch {
    pub fn new(test: &str) -> Scratch {
        let file = env!("CARGO_CRATE_NAME");
        let path = std::env::temp_dir().join(format!("impact-{file}-{}-{test}", std::process::id()));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap_or_else(|e| panic!("cannot create {}: {e}", path.display()));
        Scratch(path)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }

    /// Writes a scene file into the folder and returns its full path as an argument.
    pub fn scene(&self, name: &str, text: &str) -> String {
        let path = self.0.join(name);
        fs::write(&path, text).expect("write the scene");
        path.to_str().expect("a UTF-8 temp path").to_string()
    }

    /// Writes a file into the folder; returns its name (commands run in the folder).
    pub fn write(&self, name: &str, text: &str) -> String {
        fs::write(self.0.join(name), text).expect("write a file");
        name.to_string()
    }

    pub fn read(&self, name: &str) -> String {
        fs::read_to_string(self.0.join(name)).unwrap_or_else(|e| panic!("cannot read {name}: {e}"))
    }

    pub fn exists(&self, name: &str) -> bool {
        self.0.join(name).exists()
    }

    /// The names of the files in the folder, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(&self.0)
            .expect("list the folder")
            .map(|entry| entry.expect("an entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = fs::remove_dir_all(&self.0);
        }
    }
}

/// Runs `impact ARGS...` in `folder`, with no backtrace asked for (so that a panic shows its hint on stderr).
pub fn impact(folder: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .current_dir(folder)
        .env_remove("RUST_BACKTRACE")
        .output()
        .expect("the impact binary runs")
}

pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Status, stderr and stdout, for failure messages.
pub fn describe(output: &Output) -> String {
    format!("status {:?}\n--- stderr\n{}--- stdout\n{}", output.status.code(), stderr(output), stdout(output))
}

/// Asserts exit status 0 and no panic on stderr.
#[track_caller]
pub fn assert_success(output: &Output) {
    assert_eq!(output.status.code(), Some(0), "expected success\n{}", describe(output));
    assert!(!stderr(output).contains("panicked"), "{}", describe(output));
}
