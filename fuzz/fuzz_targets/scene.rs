//! Fuzz target: the scene parser and validator (`Scene::parse`), then — for a scene it accepts — the setup of its
//! contact. Any bytes must give a scene or a located error, never a panic; an accepted scene's error messages and
//! setup must not panic either. Run with `RUSTC_BOOTSTRAP=1 cargo fuzz run scene` from the repository root.
#![no_main]

use impact::scene::Scene;
use impact::setup::Setup;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match Scene::parse(text, Path::new("fuzz.toml")) {
        Ok(scene) => {
            // Validation ran the setup already: it must succeed again, identically.
            let setup = Setup::new(&scene).expect("a validated scene sets up");
            assert!(setup.approach_speed > 0.0 && setup.approach_speed.is_finite());
            assert!(setup.effective_mass > 0.0);
        }
        Err(error) => {
            // The message names the file; a line, when given, lies inside the text.
            let message = error.to_string();
            assert!(message.starts_with("fuzz.toml"), "{message}");
            if let Some(line) = error.line {
                assert!(line >= 1 && line <= text.lines().count().max(1) + 1, "line {line} of {message}");
            }
        }
    }
});
