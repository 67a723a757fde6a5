//! Data flows one way. Every `crate::<module>` path in the library's code (imports, paths in
//! expressions and doc links alike; test modules excepted) must name a module of a lower layer
//! of README's "Layout", and no two files may import from each other, directly or through
//! others (a file's own parent module, which declares it, excepted).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Every module may use these.
const BASE: &[&str] = &["numerics", "error", "format"];

/// Each top-level module and the modules it may use besides [`BASE`]. The command line and the
/// Python package sit above all of them.
const LAYERS: &[(&str, &[&str])] = &[
    ("format", &[]),
    ("error", &[]),
    ("numerics", &[]),
    ("parameters", &[]),
    ("material", &["parameters"]),
    ("homogeneous", &["material", "parameters"]),
    ("mesh", &[]),
    ("stability", &["homogeneous", "material", "parameters"]),
    ("fem", &["material", "mesh"]),
    ("protocol", &["fem", "mesh", "homogeneous", "material", "parameters"]),
    ("output", &[]),
    (
        "studies",
        &[
            "output",
            "protocol",
            "fem",
            "stability",
            "mesh",
            "homogeneous",
            "material",
            "parameters",
        ],
    ),
];

/// Whether `from` may use `to`.
fn allowed(from: &str, to: &str) -> Option<bool> {
    let (_, above) = LAYERS.iter().find(|(module, _)| *module == from)?;
    let below_base = BASE.iter().position(|m| *m == from);
    let base = match below_base {
        // Within the base, each module uses only those after it: numerics -> error -> format.
        Some(at) => BASE[at + 1..].contains(&to),
        None => BASE.contains(&to),
    };
    Some(base || above.contains(&to))
}

fn source() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The Rust files under `dir`.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}

/// The code of a file without its test modules (files of tests are skipped by the caller).
fn without_tests(text: &str) -> &str {
    let mut cut = text.len();
    for marker in [
        "#[cfg(test)]\nmod ",
        "#[cfg(test)]\npub(super) mod ",
        "#[cfg(test)]\npub(crate) mod ",
    ] {
        if let Some(at) = text.find(marker) {
            cut = cut.min(at);
        }
    }
    &text[..cut]
}

/// Whether `path` (relative to `src`) holds only tests.
fn is_test_file(path: &Path) -> bool {
    let name = path.file_stem().unwrap().to_string_lossy();
    name == "tests" || name.ends_with("_tests")
}

/// Every `crate::a::b::...` path in `code`, as its segments.
fn crate_paths(code: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = rest[..at].chars().last();
        rest = &rest[at + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let mut segments = Vec::new();
        let mut tail = rest;
        loop {
            let end = tail
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(tail.len());
            if end == 0 {
                break;
            }
            segments.push(tail[..end].to_string());
            tail = &tail[end..];
            match tail.strip_prefix("::") {
                Some(next) => tail = next,
                None => break,
            }
        }
        // `crate::x::{a, b}`: each item of the group is a path of its own.
        if tail.starts_with('{') {
            let group = &tail[1..tail.find('}').unwrap_or(tail.len())];
            for item in group.split(',') {
                let item = item.trim().split("::").next().unwrap_or("").trim();
                if !item.is_empty() && item != "self" {
                    let mut path = segments.clone();
                    path.push(item.to_string());
                    paths.push(path);
                }
            }
        }
        if !segments.is_empty() {
            paths.push(segments);
        }
    }
    paths
}

/// The top-level module a file (relative to `src`) belongs to.
fn top_module(relative: &Path) -> String {
    let first = relative.components().next().unwrap().as_os_str().to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The edges `from module -> to module` outside [`LAYERS`] in the library's files.
fn forbidden_edges(files: &[(PathBuf, String)]) -> Vec<String> {
    let mut forbidden = Vec::new();
    for (relative, code) in files {
        let from = top_module(relative);
        if allowed(&from, &from).is_none() {
            forbidden.push(format!("{}: module `{from}` is not in LAYERS", relative.display()));
            continue;
        }
        for path in crate_paths(code) {
            let target = match path[0].as_str() {
                "Error" | "Result" => "error",
                "Parameters" => "parameters",
                other => other,
            };
            if target != from && allowed(&from, target) != Some(true) {
                forbidden.push(format!("{}: {from} -> crate::{}", relative.display(), path.join("::")));
            }
        }
    }
    forbidden.sort();
    forbidden.dedup();
    forbidden
}

/// The module path of a file relative to `src` (`fem/element/mod.rs` is `fem::element`).
fn module_of(relative: &Path) -> Vec<String> {
    let mut segments: Vec<String> = relative
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .collect();
    if segments.last().is_some_and(|s| s == "mod") {
        segments.pop();
    }
    segments
}

/// The file module that the longest prefix of `path` names, if any.
fn file_of(path: &[String], modules: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| modules.contains(p))
}

/// The `use` declarations of `code`, each as the paths it imports (groups expanded), relative
/// to the file's module `module`.
fn imports(code: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut offset = 0;
    for line in code.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let trimmed = line.trim_start();
        let Some(after) = ["use ", "pub use ", "pub(crate) use ", "pub(super) use "]
            .iter()
            .find_map(|keyword| trimmed.strip_prefix(keyword))
        else {
            continue;
        };
        let from = start + (line.len() - after.len());
        let rest = &code[from..];
        let declaration: String = rest[..rest.find(';').unwrap_or(rest.len())]
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect();
        expand(&declaration, Vec::new(), &mut paths);
    }
    paths
        .into_iter()
        .filter_map(|path| {
            let (head, tail) = path.split_first()?;
            let mut absolute = match head.as_str() {
                "crate" => Vec::new(),
                "self" => module.to_vec(),
                "super" => module[..module.len().saturating_sub(1)].to_vec(),
                _ => return None,
            };
            let mut tail = tail;
            while tail.first().is_some_and(|s| s == "super") {
                absolute.pop();
                tail = &tail[1..];
            }
            absolute.extend(tail.iter().cloned());
            Some(absolute)
        })
        .collect()
}

/// The paths of one `use` tree `tree` (no spaces) under `prefix`, into `paths`.
fn expand(tree: &str, prefix: Vec<String>, paths: &mut Vec<Vec<String>>) {
    match tree.find('{') {
        None => {
            let mut path = prefix;
            path.extend(
                tree.split("::")
                    .filter(|s| !s.is_empty() && *s != "self")
                    .map(|s| s.split(" as ").next().unwrap_or(s).to_string()),
            );
            paths.push(path);
        }
        Some(open) => {
            let mut path = prefix;
            path.extend(tree[..open].split("::").filter(|s| !s.is_empty()).map(str::to_string));
            let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
            // Split the group at its top-level commas.
            let (mut depth, mut start) = (0, 0);
            for (i, c) in inner.char_indices().chain([(inner.len(), ',')]) {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        let item = &inner[start..i];
                        if !item.is_empty() {
                            expand(item, path.clone(), paths);
                        }
                        start = i + 1;
                    }
                    _ => {}
                }
            }
        }
    }
}

/// Cycles of `use` between two files of the library, neither the other's ancestor: each as
/// `a <-> b`.
fn file_cycles(files: &[(PathBuf, String)]) -> Vec<String> {
    let modules: BTreeSet<Vec<String>> = files.iter().map(|(relative, _)| module_of(relative)).collect();
    let mut edges: BTreeSet<(Vec<String>, Vec<String>)> = BTreeSet::new();
    for (relative, code) in files {
        let from = module_of(relative);
        for path in imports(code, &from) {
            if let Some(to) = file_of(&path, &modules) {
                let related = to.starts_with(&from) || from.starts_with(&to);
                if !related {
                    edges.insert((from.clone(), to));
                }
            }
        }
    }
    // Strongly connected: a path each way.
    let reaches = |start: &Vec<String>, goal: &Vec<String>| {
        let mut seen = BTreeSet::from([start.clone()]);
        let mut frontier = vec![start.clone()];
        while let Some(node) = frontier.pop() {
            for (a, b) in &edges {
                if a == &node && seen.insert(b.clone()) {
                    if b == goal {
                        return true;
                    }
                    frontier.push(b.clone());
                }
            }
        }
        false
    };
    let mut cycles = Vec::new();
    for (a, b) in &edges {
        if a < b && reaches(b, a) {
            cycles.push(format!("{} <-> {}", a.join("::"), b.join("::")));
        }
    }
    cycles
}

fn library_files() -> Vec<(PathBuf, String)> {
    let src = source();
    rust_files(&src)
        .into_iter()
        .map(|path| path.strip_prefix(&src).unwrap().to_path_buf())
        .filter(|relative| {
            let top = top_module(relative);
            !["cli", "main", "lib"].contains(&top.as_str()) && !is_test_file(relative)
        })
        .map(|relative| {
            let text = std::fs::read_to_string(source().join(&relative)).unwrap();
            let code = without_tests(&text).to_string();
            (relative, code)
        })
        .collect()
}

#[test]
fn every_module_uses_only_the_layers_below_it() {
    let forbidden = forbidden_edges(&library_files());
    assert!(
        forbidden.is_empty(),
        "edges against the layers:\n{}",
        forbidden.join("\n")
    );
}

#[test]
fn no_two_files_use_each_other() {
    let cycles = file_cycles(&library_files());
    assert!(cycles.is_empty(), "file cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_checks_catch_a_forbidden_edge_and_a_cycle() {
    let file = |path: &str, code: &str| (PathBuf::from(path), code.to_string());
    let upward = [file(
        "fem/assembly.rs",
        "use crate::mesh::Mesh;\nuse crate::protocol::{Loading, stages};\n/// [`crate::parameters::Load`]\n",
    )];
    assert_eq!(
        forbidden_edges(&upward),
        [
            "fem/assembly.rs: fem -> crate::parameters::Load",
            "fem/assembly.rs: fem -> crate::protocol",
            "fem/assembly.rs: fem -> crate::protocol::Loading",
            "fem/assembly.rs: fem -> crate::protocol::stages",
        ]
    );
    let in_test = "use crate::mesh::Mesh;\n#[cfg(test)]\nmod tests {\n    use crate::parameters::Parameters;\n}\n";
    assert!(forbidden_edges(&[file("fem/boundary.rs", without_tests(in_test))]).is_empty());
    let pair = [
        file("studies/crease/mod.rs", "mod released;\nmod threshold;\n"),
        file("studies/crease/released.rs", "use super::threshold::FoldThreshold;\n"),
        file(
            "studies/crease/threshold.rs",
            "use super::{released::released_threshold, Scan};\n",
        ),
    ];
    assert_eq!(
        file_cycles(&pair),
        ["studies::crease::released <-> studies::crease::threshold"]
    );
}
