//! History belongs in CHANGELOG.md. README.md, the user guide (`docs/guide/src/**/*.md`) and the
//! documentation comments of the library (`///` and `//!` under `src/`) must hold no commit hash
//! (a word of 7 to 40 hexadecimal digits with at least one digit and one letter a-f) and no date
//! (`YYYY-MM-DD`), which would tie a measurement to a moment of the code's history. The one
//! exception is the benchmarks page, which `bench/benchmarks.sh` writes whole, naming the date and
//! the commit it measured (and which nobody edits by hand: it must say so in its first line).

use std::path::{Path, PathBuf};

/// The files under `dir` whose names end in `extension`, recursively, sorted.
fn files(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(files(&path, extension));
        } else if path.extension().is_some_and(|e| e == extension) {
            found.push(path);
        }
    }
    found.sort();
    found
}

/// Whether `word` looks like a commit hash: 7 to 40 characters of `0-9a-f`, with at least one
/// digit and one letter (so that plain numbers and plain words pass).
fn is_hash(word: &str) -> bool {
    (7..=40).contains(&word.len())
        && word.chars().all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c))
        && word.chars().any(|c| c.is_ascii_digit())
        && word.chars().any(|c| c.is_ascii_alphabetic())
}

/// Whether `line` holds a date `YYYY-MM-DD` (not inside a longer run of digits).
fn has_date(line: &str) -> bool {
    let bytes = line.as_bytes();
    let digit = |i: usize| bytes[i].is_ascii_digit();
    (0..bytes.len().saturating_sub(9)).any(|i| {
        let shape =
            [0, 1, 2, 3, 5, 6, 8, 9].iter().all(|&j| digit(i + j)) && bytes[i + 4] == b'-' && bytes[i + 7] == b'-';
        let before = i == 0 || !digit(i - 1);
        let after = i + 10 == bytes.len() || !digit(i + 10);
        shape && before && after
    })
}

/// What is wrong with `line`, if anything.
fn offence(line: &str) -> Option<String> {
    if let Some(word) = line.split(|c: char| !c.is_ascii_alphanumeric()).find(|w| is_hash(w)) {
        return Some(format!("commit hash `{word}`"));
    }
    has_date(line).then(|| "a date".to_string())
}

#[test]
fn the_patterns_tell_hashes_and_dates_from_numbers_and_words() {
    assert!(is_hash("1e9fba1") && is_hash("76229c6"));
    assert!(!is_hash("4294967295") && !is_hash("deadbeefs") && !is_hash("faceted") && !is_hash("1e9fba"));
    assert!(has_date("measured on 2026-11-03") && has_date("2026-11-03"));
    assert!(!has_date("1e-12 and 0.2-0.3") && !has_date("12026-11-033"));
}

#[test]
fn documentation_holds_no_commit_hash_and_no_date() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut hits = Vec::new();
    let mut pages = vec![root.join("README.md")];
    pages.extend(files(&root.join("docs/guide/src"), "md"));
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap_or_else(|e| panic!("{}: {e}", page.display()));
        if text.starts_with(WRITTEN_BY_SCRIPT) {
            continue;
        }
        for (number, line) in text.lines().enumerate() {
            if let Some(what) = offence(line) {
                hits.push(format!("{}:{}: {what}: {}", page.display(), number + 1, line.trim()));
            }
        }
    }
    for file in files(&root.join("src"), "rs") {
        let text = std::fs::read_to_string(&file).unwrap();
        for (number, line) in text.lines().enumerate() {
            let trimmed = line.trim_start();
            if !(trimmed.starts_with("///") || trimmed.starts_with("//!")) {
                continue;
            }
            if let Some(what) = offence(trimmed) {
                hits.push(format!("{}:{}: {what}: {}", file.display(), number + 1, trimmed));
            }
        }
    }
    assert!(
        hits.is_empty(),
        "history belongs in CHANGELOG.md; found in the documentation:\n{}",
        hits.join("\n")
    );
}

/// The first line of the page `bench/benchmarks.sh` writes.
const WRITTEN_BY_SCRIPT: &str = "<!-- Written by bench/benchmarks.sh";

#[test]
fn the_benchmarks_page_is_the_scripts() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = std::fs::read_to_string(root.join("docs/guide/src/benchmarks.md")).unwrap();
    assert!(
        page.starts_with(WRITTEN_BY_SCRIPT),
        "the benchmarks page is written by bench/benchmarks.sh"
    );
    let script = std::fs::read_to_string(root.join("bench/benchmarks.sh")).unwrap();
    assert!(
        script.contains(&format!("echo \"{WRITTEN_BY_SCRIPT}")),
        "the script writes the marker"
    );
    // Nothing else in the guide claims to be the script's.
    for page in files(&root.join("docs/guide/src"), "md") {
        let text = std::fs::read_to_string(&page).unwrap();
        assert!(
            !text.starts_with(WRITTEN_BY_SCRIPT) || page.ends_with("benchmarks.md"),
            "{}",
            page.display()
        );
    }
}
