//! The project stands alone: a clone must hold everything its documents and comments refer to.
//! No tracked text file may point at files outside the repository (the folder the paper and its
//! reading notes came from, or notes kept elsewhere), README.md must link the model document,
//! and every relative link of a tracked Markdown file must resolve in the checkout.
//!
//! The tracked files are listed by `git ls-files`: without `git` or outside a git checkout the
//! test fails with a message rather than pass unchecked (CI runs on a clone).

use std::path::Path;
use std::process::Command;

/// References to files outside the repository, spelled in pieces so that this file holds none.
const OUTSIDE: [&str; 3] = [
    concat!("..", "/shared"),
    concat!("NOTES", ".md"),
    concat!("notes/rust-", "ecosystem.md"),
];

/// The files `git ls-files` lists in the crate root.
fn tracked_files() -> Vec<String> {
    let root = env!("CARGO_MANIFEST_DIR");
    let output = Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(root)
        .output()
        .unwrap_or_else(|e| panic!("cannot run `git ls-files` in {root}: {e} (this test needs git)"));
    assert!(
        output.status.success(),
        "`git ls-files` failed in {root} (this test needs a git checkout): {}",
        String::from_utf8_lossy(&output.stderr).trim()
    );
    let files: Vec<String> = String::from_utf8(output.stdout)
        .expect("file names in UTF-8")
        .split('\0')
        .filter(|name| !name.is_empty())
        .map(String::from)
        .collect();
    assert!(
        files.iter().any(|f| f == "README.md"),
        "`git ls-files` in {root} does not list README.md: {files:?}"
    );
    files
}

/// The text of a tracked file, `None` for a file that is not UTF-8 (e.g. a PNG) or is absent
/// from the work tree.
fn read_text(file: &str) -> Option<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    match std::fs::read(&path) {
        Ok(bytes) => String::from_utf8(bytes).ok(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => panic!("{}: {e}", path.display()),
    }
}

#[test]
fn no_tracked_file_refers_to_files_outside_the_repository() {
    let mut hits = Vec::new();
    for file in tracked_files() {
        let Some(text) = read_text(&file) else { continue };
        for (number, line) in text.lines().enumerate() {
            if OUTSIDE.iter().any(|outside| line.contains(outside)) {
                hits.push(format!("{file}:{}: {}", number + 1, line.trim()));
            }
        }
    }
    assert!(
        hits.is_empty(),
        "references to files outside the repository ({OUTSIDE:?}):\n{}",
        hits.join("\n")
    );
}

#[test]
fn readme_links_the_model_document_and_every_relative_link_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    assert!(root.join("docs/model.md").is_file(), "docs/model.md is missing");
    let readme = read_text("README.md").expect("README.md is UTF-8");
    assert!(
        readme.contains("](docs/model.md)"),
        "README.md does not link docs/model.md"
    );
    let mut broken = Vec::new();
    for file in tracked_files().into_iter().filter(|f| f.ends_with(".md")) {
        let Some(text) = read_text(&file) else { continue };
        let folder = root.join(&file).parent().expect("a file has a folder").to_path_buf();
        for (number, line) in text.lines().enumerate() {
            for link in line.split("](").skip(1) {
                let target = link.split([')', ' ']).next().unwrap_or_default();
                let path = target.split('#').next().unwrap_or_default();
                let external = target.contains("://") || target.starts_with("mailto:");
                if !external && !path.is_empty() && !folder.join(path).exists() {
                    broken.push(format!("{file}:{}: {target}", number + 1));
                }
            }
        }
    }
    assert!(
        broken.is_empty(),
        "links to files the checkout lacks:\n{}",
        broken.join("\n")
    );
}
