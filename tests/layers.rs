//! The layers of ARCHITECTURE.md#layers: the top-level modules of src/ (a file `src/x.rs` or a folder `src/x/`; lib.rs
//! and main.rs are the crate roots, not modules) name one another without cycles, so each module names only modules
//! below it. A module names another by a path in its code (comments, strings and characters left out): `crate::x`,
//! `crate::{x, y::z}`, or `super::...::x` climbing to the crate root from a file or an inline `mod` block. The same
//! check as `python3 scripts/layers.py`, which also prints the layers.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::fs;
use std::path::Path;

/// A token of code: an identifier, `::` or a bracket (`{}()[]`, `,`, `;`), with its line.
struct Token<'a> {
    text: &'a str,
    line: usize,
}

/// The tokens of Rust source, without comments (nested blocks, doc comments), strings (raw, byte, C strings, escaped
/// quotes) and character literals; a lifetime `'a` is not a character: its quote is dropped, its name kept.
fn tokens(text: &str) -> Vec<Token<'_>> {
    let bytes = text.as_bytes();
    let starts = |i: usize, s: &str| bytes[i..].starts_with(s.as_bytes());
    let (mut out, mut i, mut line) = (Vec::new(), 0, 1);
    while i < bytes.len() {
        let start = i;
        let c = bytes[i];
        if starts(i, "//") {
            i = text[i..].find('\n').map_or(bytes.len(), |n| i + n);
        } else if starts(i, "/*") {
            let mut depth = 0;
            while i < bytes.len() {
                if starts(i, "/*") {
                    (depth, i) = (depth + 1, i + 2);
                } else if starts(i, "*/") {
                    (depth, i) = (depth - 1, i + 2);
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == b'"' {
            i = string_end(bytes, i + 1);
        } else if c == b'\'' {
            i = quote_end(text, i);
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let end = word_end(bytes, i);
            match literal_end(text, &text[i..end], end) {
                Some(after) => i = after,
                None => {
                    out.push(Token { text: &text[i..end], line });
                    i = end;
                }
            }
        } else if c.is_ascii_digit() {
            i = word_end(bytes, i);
        } else if starts(i, "::") {
            out.push(Token { text: "::", line });
            i += 2;
        } else if b"{}()[],;".contains(&c) {
            out.push(Token { text: &text[i..i + 1], line });
            i += 1;
        } else {
            i += 1;
        }
        line += bytes[start..i].iter().filter(|&&b| b == b'\n').count();
    }
    out
}

/// The end of the identifier (or number) starting at `i`.
fn word_end(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
        i += 1;
    }
    i
}

/// The end of a string whose body starts at `i` (after its opening quote), escaped characters skipped.
fn string_end(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() {
        match bytes[i] {
            b'\\' => i += 2,
            b'"' => return i + 1,
            _ => i += 1,
        }
    }
    bytes.len()
}

/// The end of the character literal at `i` (a quote), or `i + 1` for the quote of a lifetime or label: `'x'`,
/// `'\''`, `'\u{7b}'` and `'é'` are characters; in `'a>` or `'outer:` only the quote is skipped.
fn quote_end(text: &str, i: usize) -> usize {
    let bytes = text.as_bytes();
    if bytes.get(i + 1) == Some(&b'\\') {
        return text.get(i + 3..).and_then(|rest| rest.find('\'')).map_or(bytes.len(), |n| i + 3 + n + 1);
    }
    match text[i + 1..].chars().next() {
        Some(c) if bytes.get(i + 1 + c.len_utf8()) == Some(&b'\'') => i + 1 + c.len_utf8() + 1,
        _ => i + 1,
    }
}

/// If the identifier `word` (ending at `end`) is the prefix of a literal — `b'x'`, `b".."`, `c".."`, `r".."`,
/// `r#".."#`, `br".."`, `cr".."` — the end of that literal.
fn literal_end(text: &str, word: &str, end: usize) -> Option<usize> {
    let bytes = text.as_bytes();
    match (word, bytes.get(end)) {
        ("b", Some(b'\'')) => Some(quote_end(text, end)),
        ("b" | "c", Some(b'"')) => Some(string_end(bytes, end + 1)),
        ("r" | "br" | "cr", Some(b'"' | b'#')) => {
            let hashes = bytes[end..].iter().take_while(|&&b| b == b'#').count();
            if bytes.get(end + hashes) != Some(&b'"') {
                return None; // a raw identifier, `r#type`
            }
            let body = end + hashes + 1;
            let close = format!("\"{}", "#".repeat(hashes));
            Some(text[body..].find(&close).map_or(bytes.len(), |n| body + n + close.len()))
        }
        _ => None,
    }
}

/// The first names of the items of the `{ ... }` group whose `{` is `tokens[i]`: `{a, b::c, d::{e, f}}` gives `a`,
/// `b` and `d`.
fn group_heads(tokens: &[Token], mut i: usize) -> Vec<usize> {
    let (mut heads, mut depth, mut expect) = (Vec::new(), 0, true);
    while let Some(token) = tokens.get(i) {
        match token.text {
            "{" => {
                depth += 1;
                expect = depth == 1;
            }
            "}" => {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            "," if depth == 1 => expect = true,
            "::" => {}
            _ if depth == 1 && expect => {
                heads.push(i);
                expect = false;
            }
            _ => {}
        }
        i += 1;
    }
    heads
}

/// The names a file's code reaches at the crate root, each with its line: the segment after `crate::`, or after the
/// `super::` chain that climbs to the root (each head of a `{ ... }` group there). `module` is the file's module path:
/// `src/a/b.rs` and `src/a/b/mod.rs` are `["a", "b"]`. Names of any kind: the caller keeps the top-level modules.
fn references(module: &[&str], text: &str) -> Result<Vec<(String, usize)>, String> {
    let tokens = tokens(text);
    let at = |k: usize| tokens.get(k).map_or("", |t| t.text);
    let mut found = Vec::new();
    // Inline modules (`mod name {`): each with the brace depth it opened at, popped when its brace closes.
    let (mut inline, mut depth) = (Vec::new(), 0usize);
    let mut i = 0;
    while i < tokens.len() {
        let t = at(i);
        if t == "mod" && at(i + 2) == "{" {
            inline.push(depth);
            depth += 1;
            i += 3;
            continue;
        }
        if t == "{" {
            depth += 1;
        } else if t == "}" {
            depth = depth.saturating_sub(1);
            if inline.last() == Some(&depth) {
                inline.pop();
            }
        }
        if (t == "crate" || t == "super") && at(i + 1) == "::" && (i == 0 || at(i - 1) != "::") {
            // How far below the root the path's next segment is: `super` from `a::b` reaches `a`, one level down.
            let mut level = if t == "crate" { 0 } else { module.len() + inline.len() - 1 };
            let mut j = i + 2;
            while t == "super" && at(j) == "super" && at(j + 1) == "::" {
                level = level
                    .checked_sub(1)
                    .ok_or_else(|| format!("line {}: super:: climbs above the crate root", tokens[i].line))?;
                j += 2;
            }
            if level == 0 {
                let heads = if at(j) == "{" { group_heads(&tokens, j) } else { vec![j] };
                found.extend(heads.into_iter().filter_map(|k| tokens.get(k)).map(|t| (t.text.to_string(), t.line)));
            }
        }
        i += 1;
    }
    Ok(found)
}

/// Where a module names another: a file (`src/...`) and a line.
type Place = (String, usize);

/// Each top-level module and the modules it names, with one place for each.
type Graph = BTreeMap<String, BTreeMap<String, Place>>;

/// The module path of a file under src/: `a/b.rs` and `a/b/mod.rs` are `["a", "b"]`.
fn module_path(path: &str) -> Vec<&str> {
    let mut parts: Vec<&str> = path.strip_suffix(".rs").unwrap_or(path).split('/').collect();
    if parts.len() > 1 && parts.last() == Some(&"mod") {
        parts.pop();
    }
    parts
}

/// The graph of the crate whose src/ holds `files`: (path under src/ with `/`, text), sorted by path.
fn graph(files: &[(String, String)]) -> Result<Graph, String> {
    let top = |path: &str| module_path(path)[0].to_string();
    let mut graph: Graph = files.iter().map(|(path, _)| (top(path), BTreeMap::new())).collect();
    graph.remove("lib");
    graph.remove("main");
    for (path, text) in files {
        let module = module_path(path);
        if !graph.contains_key(module[0]) {
            continue; // lib.rs, main.rs
        }
        for (name, line) in references(&module, text).map_err(|e| format!("src/{path}: {e}"))? {
            if name != module[0] && graph.contains_key(&name) {
                let edges = graph.get_mut(module[0]).expect("a top-level module");
                edges.entry(name).or_insert_with(|| (format!("src/{path}"), line));
            }
        }
    }
    Ok(graph)
}

/// A shortest path from `start` back to itself, if `start` is on a cycle: `[start, ..., start]`.
fn cycle_through<'g>(graph: &'g Graph, start: &'g str) -> Option<Vec<&'g str>> {
    let mut parent: BTreeMap<&str, &str> = BTreeMap::new();
    let mut queue = VecDeque::from([start]);
    while let Some(module) = queue.pop_front() {
        for next in graph[module].keys() {
            if next == start {
                let mut path = vec![module];
                while let Some(&p) = parent.get(path[path.len() - 1]) {
                    path.push(p);
                }
                path.reverse();
                path.push(start);
                return Some(path);
            }
            if !parent.contains_key(next.as_str()) {
                parent.insert(next, module);
                queue.push_back(next);
            }
        }
    }
    None
}

/// The cycles of the graph, shortest first: the shortest cycle through each module on one, unless a shorter cycle
/// already given passes through it. No cycle: each module names only modules below it.
fn cycles(graph: &Graph) -> Vec<Vec<&str>> {
    let mut all: Vec<Vec<&str>> = graph.keys().filter_map(|module| cycle_through(graph, module)).collect();
    all.sort_by_key(Vec::len);
    let mut out: Vec<Vec<&str>> = Vec::new();
    for cycle in all {
        if !out.iter().any(|given| given.contains(&cycle[0])) {
            out.push(cycle);
        }
    }
    out
}

/// The cycles, each as `a -> b -> a` followed by one place of each of its edges, then the edges on the most of them
/// (a single edge upward puts every module between its ends on a cycle).
fn describe(graph: &Graph, cycles: &[Vec<&str>]) -> String {
    let mut out = String::new();
    let mut count: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    for cycle in cycles {
        out += &format!("{}\n", cycle.join(" -> "));
        for edge in cycle.windows(2) {
            let (file, line) = &graph[edge[0]][edge[1]];
            out += &format!("    {} -> {}: {file}:{line}\n", edge[0], edge[1]);
            *count.entry((edge[0], edge[1])).or_default() += 1;
        }
    }
    let most = count.values().copied().max().unwrap_or(0);
    let edges: Vec<String> =
        count.iter().filter(|&(_, &n)| n == most).map(|((a, b), _)| format!("{a} -> {b}")).collect();
    if cycles.len() > 1 {
        out += &format!("on {most} of these {} cycles: {}\n", cycles.len(), edges.join(", "));
    }
    out
}

/// The .rs files under `folder`, as (path under `root` with `/`, text).
fn rust_files(root: &Path, folder: &Path, out: &mut Vec<(String, String)>) {
    for entry in fs::read_dir(folder).unwrap_or_else(|e| panic!("cannot list {}: {e}", folder.display())) {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            rust_files(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
            let relative = path.strip_prefix(root).expect("a file under src/").to_string_lossy().replace('\\', "/");
            out.push((relative, text));
        }
    }
}

/// The graph of this crate's src/.
fn crate_graph() -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &src, &mut files);
    files.sort();
    graph(&files).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_modules_form_layers_without_cycles() {
    let graph = crate_graph();
    let cycles = cycles(&graph);
    assert!(
        cycles.is_empty(),
        "the top-level modules of src/ name one another in a cycle (ARCHITECTURE.md#layers: each module names only \
         modules below it); move what one edge of each cycle names, or what needs it, down a layer:\n{}",
        describe(&graph, &cycles)
    );
}

#[test]
fn the_scanner_finds_the_paths_of_the_code_and_nothing_else() {
    // A file at depth 2, src/a/b.rs, with an inline module.
    let text = r##"use crate::{c, d::e};
use crate::{f::{g, h}, i};
fn run() { crate::a::b(); }
use super::super::x;
use super::sibling; // in a, not at the root
// crate::no1
/// [`crate::no2`]
//! crate::no3
/* crate::no4 /* nested crate::no5 */ crate::no6 */
const S: &str = "crate::no7 \" crate::no8 \\";
const R: &str = r#"crate::no9 " crate::no10"#;
const B: &[u8] = br"crate::no11";
const Y: &[u8] = b"crate::no12";
const Q: char = '"'; const P: u8 = b'\''; const E: char = 'é';
fn lend<'a>(s: crate::j::Kind<'a>) -> &'a str { 'outer: loop { break 'outer s.name() } }
mod tests {
    const OPEN: char = '{';
    const ALSO: char = '\u{7b}';
    use super::super::super::m;
    use super::super::inside_a;
}
use super::super::{n, o::p};
"##;
    let found = references(&["a", "b"], text).expect("no climb above the root");
    let names: BTreeSet<&str> = found.iter().map(|(name, _)| name.as_str()).collect();
    assert_eq!(names, BTreeSet::from(["a", "c", "d", "f", "i", "j", "m", "n", "o", "x"]), "{found:?}");
    let line = |name: &str| found.iter().find(|(n, _)| n == name).map(|&(_, line)| line);
    assert_eq!(
        (line("c"), line("a"), line("x"), line("j"), line("m"), line("n")),
        (Some(1), Some(3), Some(4), Some(15), Some(19), Some(22))
    );
    // From src/a.rs, `super` is the root; one more climbs above it.
    assert_eq!(references(&["a"], "use super::q;").unwrap(), [("q".to_string(), 1)]);
    assert!(references(&["a"], "\n\nuse super::super::q;").is_err_and(|e| e.contains("line 3")));
}

#[test]
fn a_cycle_is_reported_with_a_place_for_each_edge() {
    let file = |path: &str, text: &str| (path.to_string(), text.to_string());
    let files = [
        file("a.rs", "use crate::b::Thing;\n"),
        file("b/c.rs", "// crate::d\n\nfn f() { super::super::a::run() }\n"),
        file("b/mod.rs", "mod c;\n"),
        file("d.rs", "use crate::a;\n"),
        file("lib.rs", "pub mod a;\n pub mod b;\n pub mod d;\nuse crate::d;\n"),
        file("main.rs", "use crate::b;\n"),
    ];
    let found = graph(&files).unwrap();
    assert_eq!(found.keys().collect::<Vec<_>>(), ["a", "b", "d"]);
    assert_eq!(cycles(&found), [["a", "b", "a"]]);
    assert_eq!(describe(&found, &cycles(&found)), "a -> b -> a\n    a -> b: src/a.rs:1\n    b -> a: src/b/c.rs:3\n");
    let without = graph(&files[1..]).unwrap();
    assert!(cycles(&without).is_empty());
}

#[test]
fn the_crate_graph_has_the_references_the_layers_rest_on() {
    let graph = crate_graph();
    let edges: usize = graph.values().map(BTreeMap::len).sum();
    assert!(edges >= 80, "only {edges} references between the top-level modules found: is the scanner blind?");
    for (from, to) in [
        ("cli", "impact"),
        ("cli", "world_run"),
        ("law", "reference"),
        ("impact", "dynamics"),
        ("world_run", "world"),
        ("scene", "body"),
        ("sweep", "output"),
        ("setup", "scales"),
    ] {
        let named = graph.get(from).is_some_and(|edges| edges.contains_key(to));
        assert!(named, "{from} should name {to}: {:?}", graph.get(from).map(|e| e.keys().collect::<Vec<_>>()));
    }
    assert!(!graph.contains_key("lib") && !graph.contains_key("main"), "the crate roots are not modules");
}
