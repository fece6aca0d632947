//! The documentation as a fresh clone sees it: every link in README.md, ARCHITECTURE.md and docs/*.md resolves to a
//! file (and, for `#anchor`, a heading) inside the repository; nothing points at files the repository does not ship;
//! every pointer into docs/ that the program prints, and every page of the documentation the code cites, names a
//! file and heading that exist; the README's (and the docs') commands run as written; and the scenes they show are
//! valid.

mod common;

use common::binary::{Scratch, describe};
use std::collections::HashSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root (where README.md is).
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// The files of `folder` whose names end in `extension`, sorted.
fn files_in(folder: &str, extension: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = fs::read_dir(root().join(folder))
        .unwrap_or_else(|e| panic!("cannot list {folder}: {e}"))
        .map(|entry| entry.expect("a folder entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == extension))
        .collect();
    files.sort();
    files
}

/// The repository's documentation: README.md, ARCHITECTURE.md and docs/*.md.
fn documents() -> Vec<PathBuf> {
    let mut documents = vec![root().join("README.md"), root().join("ARCHITECTURE.md")];
    documents.extend(files_in("docs", "md"));
    documents
}

/// A path as shown in messages: relative to the repository.
fn shown(path: &Path) -> String {
    path.strip_prefix(root()).unwrap_or(path).display().to_string()
}

// ---------------------------------------------------------------------------------------------------------------
// Markdown: code blocks, headings, links

/// A fenced code block: its info string (`sh`, `toml`, ...) and its lines.
struct Block {
    info: String,
    lines: Vec<String>,
}

/// Splits Markdown into the lines outside fenced code blocks (with their 1-based numbers) and the blocks.
fn split_markdown(text: &str) -> (Vec<(usize, &str)>, Vec<Block>) {
    let mut prose = Vec::new();
    let mut blocks = Vec::new();
    // The open block's fence (``` or ~~~) and its contents so far.
    let mut open: Option<(&str, Block)> = None;
    for (number, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let closes =
            matches!(&open, Some((fence, _)) if trimmed.strip_prefix(fence).is_some_and(|r| r.trim().is_empty()));
        if closes {
            blocks.push(open.take().expect("an open block").1);
        } else if let Some((_, block)) = &mut open {
            block.lines.push(line.to_string());
        } else if let Some(fence) = ["```", "~~~"].into_iter().find(|f| trimmed.starts_with(f)) {
            let info = trimmed[fence.len()..].trim().to_string();
            open = Some((fence, Block { info, lines: Vec::new() }));
        } else {
            prose.push((number + 1, line));
        }
    }
    assert!(open.is_none(), "a code block is never closed");
    (prose, blocks)
}

/// A line without its inline code spans (a link written inside backticks is not a link).
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut in_code = false;
    for c in line.chars() {
        if c == '`' {
            in_code = !in_code;
        } else if !in_code {
            out.push(c);
        }
    }
    out
}

/// The targets of the inline links and images of a prose line: `[text](target)`, `![alt](target "title")`.
fn link_targets(line: &str) -> Vec<String> {
    let text = without_code_spans(line);
    let mut targets = Vec::new();
    let mut rest = text.as_str();
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].split_whitespace().next().unwrap_or_default();
        targets.push(target.trim_start_matches('<').trim_end_matches('>').to_string());
        rest = &after[end..];
    }
    targets
}

/// GitHub's anchor for a heading: lower case, letters, digits, `-` and `_` kept, spaces turned into `-`, everything
/// else dropped (backticks, punctuation, en dashes).
fn slug(heading: &str) -> String {
    heading
        .trim()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .flat_map(char::to_lowercase)
        .collect()
}

/// The anchors of a Markdown file's headings (a repeated heading gets `-1`, `-2`, ... as on GitHub).
fn anchors(text: &str) -> HashSet<String> {
    let (prose, _) = split_markdown(text);
    let mut seen = HashSet::new();
    for (_, line) in prose {
        let level = line.chars().take_while(|c| *c == '#').count();
        if level == 0 || level > 6 || !line[level..].starts_with(' ') {
            continue;
        }
        let base = slug(&line[level..]);
        let mut anchor = base.clone();
        let mut n = 0;
        while seen.contains(&anchor) {
            n += 1;
            anchor = format!("{base}-{n}");
        }
        seen.insert(anchor);
    }
    seen
}

/// Why `target` (a link or pointer written in `from`, a file of the repository) does not resolve, if it does not:
/// the file must exist inside the repository, and an anchor must be a heading of that (Markdown) file.
fn unresolved(from: &Path, target: &str) -> Option<String> {
    let (path, anchor) = match target.split_once('#') {
        Some((path, anchor)) => (path, Some(anchor)),
        None => (target, None),
    };
    let file = if path.is_empty() { from.to_path_buf() } else { from.parent().expect("a folder").join(path) };
    let Ok(resolved) = file.canonicalize() else { return Some(format!("`{target}`: no such file")) };
    let repository = root().canonicalize().expect("the repository's root");
    if !resolved.starts_with(&repository) {
        return Some(format!("`{target}` points outside the repository"));
    }
    let anchor = anchor?;
    if resolved.extension().is_none_or(|e| e != "md") {
        return Some(format!("`{target}`: an anchor into a file that is not Markdown"));
    }
    if !anchors(&read(&resolved)).contains(anchor) {
        return Some(format!("`{target}`: {} has no heading with the anchor `#{anchor}`", shown(&resolved)));
    }
    None
}

#[test]
fn every_link_of_the_documentation_resolves_in_the_repository() {
    let mut problems = Vec::new();
    let mut links = 0;
    for document in documents() {
        let text = read(&document);
        for (number, line) in split_markdown(&text).0 {
            for target in link_targets(line) {
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                links += 1;
                if let Some(why) = unresolved(&document, &target) {
                    problems.push(format!("{}:{number}: {why}", shown(&document)));
                }
            }
        }
    }
    assert!(links > 30, "only {links} links found: is the link parser broken?");
    assert!(problems.is_empty(), "links that do not resolve in a clone:\n  {}", problems.join("\n  "));
}

#[test]
fn headings_give_the_anchors_github_gives() {
    assert_eq!(slug("Kelvin–Voigt"), "kelvinvoigt");
    assert_eq!(slug("Laws that turn tensile, and `separation`"), "laws-that-turn-tensile-and-separation");
    assert_eq!(slug("`[[bodies]]`"), "bodies");
    assert_eq!(slug("Brilliantov (viscoelastic spheres)"), "brilliantov-viscoelastic-spheres");
    assert_eq!(slug("`instantaneous` and `instantaneous_nominal`"), "instantaneous-and-instantaneous_nominal");
    let repeated = anchors("# A\n\n## Notes\n\n```sh\n# not a heading\n```\n\n## Notes\n");
    assert_eq!(repeated, HashSet::from(["a".to_string(), "notes".into(), "notes-1".into()]));
    assert_eq!(
        link_targets("see [a](docs/a.md#b) and ![c](plots/c.png \"t\"), not `[d](e)`"),
        ["docs/a.md#b", "plots/c.png"]
    );
}

/// The words of a text that name a Markdown file (`scene.md`, `docs/laws.md#walls`), without any anchor.
fn markdown_names(text: &str) -> Vec<String> {
    text.split(|c: char| !(c.is_alphanumeric() || "_./#-".contains(c)))
        .map(|word| word.split('#').next().unwrap_or_default().trim_end_matches('.'))
        .filter(|word| word.ends_with(".md") && word.len() > 3)
        .map(str::to_string)
        .collect()
}

#[test]
fn the_documentation_names_only_files_the_repository_ships() {
    // The project grew from documents outside the repository (a physics reference, an interface contract, a
    // lecture); a clone has none of them, so the documentation must not send readers there.
    let mut files = documents();
    files.extend(files_in("models", "toml"));
    let mut problems = Vec::new();
    for file in files {
        let text = read(&file);
        for (number, line) in text.lines().enumerate() {
            let at = format!("{}:{}", shown(&file), number + 1);
            for outside in ["../shared", "shared/docs", "shared/seed", "shared/tools", "../seed"] {
                if line.contains(outside) {
                    problems.push(format!("{at}: points outside the repository ({outside})"));
                }
            }
            // (A file a run writes into its output folder is named under it: `OUT_DIR/summary.md`, `out/...`.)
            for name in
                markdown_names(line).into_iter().filter(|n| !n.starts_with("OUT_DIR/") && !n.starts_with("out/"))
            {
                let here = file.parent().expect("a folder").join(&name);
                if !here.exists() && !root().join(&name).exists() && !root().join("docs").join(&name).exists() {
                    problems.push(format!("{at}: names `{name}`, which the repository does not have"));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

// ---------------------------------------------------------------------------------------------------------------
// Pointers the program prints

/// The string literals of Rust source text, as written (escapes not decoded): ordinary, byte and raw strings.
/// Comments (doc comments included) and character literals are skipped.
fn string_literals(source: &str) -> Vec<String> {
    let chars: Vec<char> = source.chars().collect();
    let at = |i: usize| chars.get(i).copied().unwrap_or('\0');
    let identifier = |c: char| c.is_alphanumeric() || c == '_';
    let mut literals = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '/' && at(i + 1) == '/' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            loop {
                if at(i) == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if at(i) == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else if i >= chars.len() {
                    break;
                } else {
                    i += 1;
                }
            }
        } else if c == 'r'
            && (at(i + 1) == '"' || at(i + 1) == '#')
            && (i == 0 || !identifier(chars[i - 1]) || chars[i - 1] == 'b')
        {
            let hashes = chars[i + 1..].iter().take_while(|c| **c == '#').count();
            if at(i + 1 + hashes) != '"' {
                i += 1;
                continue;
            }
            let start = i + 2 + hashes;
            let mut end = start;
            while end < chars.len() && !(chars[end] == '"' && (0..hashes).all(|k| at(end + 1 + k) == '#')) {
                end += 1;
            }
            literals.push(chars[start..end.min(chars.len())].iter().collect());
            i = end + 1 + hashes;
        } else if c == '"' {
            let mut end = i + 1;
            while end < chars.len() && chars[end] != '"' {
                end += if chars[end] == '\\' { 2 } else { 1 };
            }
            literals.push(chars[i + 1..end.min(chars.len())].iter().collect());
            i = end + 1;
        } else if c == '\'' {
            // A character literal ('x', '\n', '\'', '\u{..}') or a lifetime ('a).
            if at(i + 1) == '\\' {
                let mut end = i + 3;
                while end < chars.len() && chars[end] != '\'' {
                    end += 1;
                }
                i = end + 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    literals
}

/// Every Rust file under `folder`.
fn rust_files(folder: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in fs::read_dir(folder).expect("a source folder") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}

/// Names of the documents the project grew from, which live outside the repository: the physics reference, the
/// interface contract, the architecture and style notes (also with `_md` for `.md`, as test names spelt them), and
/// the folders beside the repository. Put together here so that a search of the repository for them finds only real
/// citations, never this list.
fn outside_documents() -> Vec<String> {
    let mut names = Vec::new();
    for stem in ["physics", "interface", "architecture", "style"] {
        names.push(format!("{stem}.md"));
        names.push(format!("{stem}_md"));
    }
    names.extend(["shared", "seed"].map(|folder| format!("../{folder}")));
    names
}

/// The repository's documents a line of code cites, with their anchors: `docs/laws.md#tsuji`, `README.md`,
/// `ARCHITECTURE.md`.
fn cited_documents(line: &str) -> Vec<String> {
    line.split(|c: char| !(c.is_alphanumeric() || "_./#-".contains(c)))
        .map(|word| word.trim_end_matches('.'))
        .filter(|word| {
            let path = word.split('#').next().unwrap_or_default();
            path.ends_with(".md") && (path.starts_with("docs/") || path == "README.md" || path == "ARCHITECTURE.md")
        })
        .map(str::to_string)
        .collect()
}

#[test]
fn cited_documents_keep_their_anchors() {
    assert_eq!(
        cited_documents("// see docs/laws.md#tsuji, README.md#stress-run and docs/report.md. Not scene.md or a.md"),
        ["docs/laws.md#tsuji", "README.md#stress-run", "docs/report.md"]
    );
}

#[test]
fn the_code_cites_only_documents_the_repository_ships() {
    // Comments, test names and messages once cited the documents outside the repository; each citation now names a
    // page of docs/ (or the README), and an anchor must be a heading of that page. This file is left out: its
    // tests hold made-up pointers on purpose.
    let this = root().join("tests").join("docs.rs");
    let mut files = Vec::new();
    for folder in ["src", "tests", "benches", "fuzz/fuzz_targets"] {
        files.extend(rust_files(&root().join(folder)));
    }
    files.extend(files_in("models", "toml"));
    files.extend(files_in("scripts", "sh"));
    files.extend(files_in("scripts", "toml"));
    files.retain(|file| *file != this);
    let mut problems = Vec::new();
    let mut citations = 0;
    for file in files {
        for (number, line) in read(&file).lines().enumerate() {
            let at = format!("{}:{}", shown(&file), number + 1);
            for outside in outside_documents() {
                if line.contains(&outside) {
                    problems.push(format!("{at}: cites {outside}, which a clone does not have"));
                }
            }
            for citation in cited_documents(line) {
                citations += 1;
                if let Some(why) = unresolved(&root().join("README.md"), &citation) {
                    problems.push(format!("{at}: {why}"));
                }
            }
        }
    }
    assert!(citations >= 100, "only {citations} citations of the documentation found in the code");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn string_literals_are_found_as_written() {
    let source = "let a = \"see docs/a.md\"; // \"not this\"\n/* \"nor this\" */ let b = r#\"raw \"q\" docs/b.md\"#;\n\
                  let c = '\"'; let d = \"esc \\\" docs/c.md\"; fn f<'a>(x: &'a str) {} let e = b\"bytes\";";
    assert_eq!(string_literals(source), ["see docs/a.md", "raw \"q\" docs/b.md", "esc \\\" docs/c.md", "bytes"]);
}

#[test]
fn every_pointer_the_program_prints_names_a_file_of_the_repository() {
    let mut problems = Vec::new();
    let mut pointers = 0;
    for file in rust_files(&root().join("src")) {
        for literal in string_literals(&read(&file)) {
            for outside in outside_documents() {
                if literal.contains(&outside) {
                    problems
                        .push(format!("{}: \"{literal}\" names {outside}, which a clone does not have", shown(&file)));
                }
            }
            let mut rest = literal.as_str();
            while let Some(at) = rest.find("docs/") {
                let pointer: String =
                    rest[at..].chars().take_while(|c| c.is_alphanumeric() || "_./#-".contains(*c)).collect();
                rest = &rest[at + 5..];
                let pointer = pointer.trim_end_matches('.');
                pointers += 1;
                if let Some(why) = unresolved(&root().join("README.md"), pointer) {
                    problems.push(format!("{}: {why}", shown(&file)));
                }
            }
        }
    }
    assert!(pointers >= 5, "only {pointers} pointers into docs/ found in src/");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

// ---------------------------------------------------------------------------------------------------------------
// Commands and scenes shown in the documentation

/// The command lines of the documents' `sh` blocks, with `\` continuations joined, each with where it was written.
fn shell_commands() -> Vec<(String, String)> {
    let mut commands = Vec::new();
    for document in documents() {
        let (_, blocks) = split_markdown(&read(&document));
        for block in blocks.iter().filter(|b| b.info == "sh") {
            let mut pending = String::new();
            for line in &block.lines {
                if let Some(start) = line.strip_suffix('\\') {
                    pending += start;
                    continue;
                }
                let command = pending.clone() + line;
                pending.clear();
                let command = command.trim();
                if !command.is_empty() && !command.starts_with('#') {
                    commands.push((shown(&document), command.to_string()));
                }
            }
        }
    }
    commands
}

/// The command as a shell runs it with the built `impact` first on the PATH: `cargo run --release [-- ARGS]` is
/// `impact [ARGS]`; the other cargo commands (`test`, `install`, `bench`), pip's and the virtual environment's
/// (`python3 -m venv ... && pip install ./python`) are not the program's and are left out.
fn as_program(command: &str) -> Option<String> {
    if let Some(args) = command.strip_prefix("cargo run --release --") {
        return Some(format!("impact{args}"));
    }
    if let Some(rest) = command.strip_prefix("cargo run --release") {
        assert!(rest.is_empty() || rest.trim_start().starts_with('#'), "unexpected cargo options: {command}");
        return Some(format!("impact{rest}"));
    }
    // (`pip install ./python` builds the Python package: .ci/run runs it, and python/tests its examples.)
    if command.starts_with("cargo ") || command.starts_with("pip ") || command.starts_with("python3 -m venv ") {
        return None;
    }
    // (The scripts, run by hand with their environment first — `VAR=value scripts/NAME` — measure against other
    // programs; they are not the program's commands.)
    let program = command.split_whitespace().find(|word| !word.contains('=')).unwrap_or_default();
    if program.starts_with("scripts/") {
        return None;
    }
    assert!(
        command == "impact" || command.starts_with("impact "),
        "a documented command that neither calls `impact` nor cargo: `{command}` — call the program one way"
    );
    Some(command.to_string())
}

/// Copies the repository's models into `folder`/models, so that commands run as from a clone's root.
fn copy_models(folder: &Path) {
    let models = folder.join("models");
    fs::create_dir_all(&models).expect("a models folder");
    for scene in files_in("models", "toml") {
        fs::copy(&scene, models.join(scene.file_name().expect("a name"))).expect("copy a model");
    }
}

#[test]
fn the_documented_commands_run_as_written() {
    // Every command of the README's (and the docs') `sh` blocks runs, in order, in one scratch folder holding a copy
    // of models/, through the debug build of `impact` placed first on the PATH. None is long enough to need
    // shortening: the largest is the 234-row restitution sweep (a few seconds in a debug build); `impact gallery`,
    // which redraws the committed figures, is mentioned in prose and not run here.
    let scratch = Scratch::new("commands");
    copy_models(scratch.path());
    let binary = Path::new(env!("CARGO_BIN_EXE_impact"));
    let folder = binary.parent().expect("the binary's folder");
    let path = std::env::join_paths(
        std::iter::once(folder.to_path_buf())
            .chain(std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())),
    )
    .expect("a PATH");
    let commands = shell_commands();
    assert!(commands.iter().filter(|(doc, _)| doc == "README.md").count() >= 15, "README commands: {commands:?}");
    let mut ran = 0;
    for (document, command) in &commands {
        let Some(program) = as_program(command) else { continue };
        let output = Command::new("sh")
            .arg("-c")
            .arg(&program)
            .current_dir(scratch.path())
            .env("PATH", &path)
            .env_remove("RUST_BACKTRACE")
            .output()
            .expect("sh runs");
        assert_eq!(output.status.code(), Some(0), "{document}: `{command}` failed\n{}", describe(&output));
        ran += 1;
    }
    assert!(ran >= 15, "only {ran} commands ran");
    // What the README claims of its shard example: the merged shards are the unsharded file, byte for byte.
    assert_eq!(scratch.read("out/damping-merged.csv"), scratch.read("out/damping.csv"));
}

#[test]
fn every_scene_shown_in_the_documentation_is_valid() {
    let mut scenes = 0;
    for document in documents() {
        let (_, blocks) = split_markdown(&read(&document));
        for block in blocks.iter().filter(|b| b.info == "toml") {
            let text = block.lines.join("\n") + "\n";
            // A two-body scene or a world (docs/world.md shows a rod on a floor), each with every rule checked.
            if let Err(error) = impact::scene::read_any(&text, Path::new("shown.toml")) {
                panic!("{}: a scene that is not valid: {error}\n{text}", shown(&document));
            }
            scenes += 1;
        }
    }
    assert!(scenes >= 2, "only {scenes} scenes found");
}
