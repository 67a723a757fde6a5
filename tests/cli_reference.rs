//! The guide's command reference shows every flag as the command line itself documents it: each
//! page's `<!-- cli-help: COMMAND -->` block is `fiberfold COMMAND --help`, so the reference
//! cannot drift from the code. With `BLESS_CLI_REFERENCE=1` the test writes the blocks instead
//! of checking them.

mod common;

use common::fiberfold;
use std::path::Path;

const START: &str = "<!-- cli-help: ";
const END: &str = "<!-- /cli-help -->";

/// The page `text` with every help block replaced by the command's current `--help`.
fn with_current_help(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        out.push_str(line);
        out.push('\n');
        let Some(command) = line.strip_prefix(START).and_then(|l| l.strip_suffix(" -->")) else {
            continue;
        };
        // Skip the old block, if any, up to its end marker.
        let rest: Vec<&str> = lines.clone().collect();
        if let Some(end) = rest.iter().position(|l| *l == END) {
            for _ in 0..=end {
                lines.next();
            }
        }
        let help = fiberfold(&[command, "--help"]);
        assert!(help.status.success(), "{command} --help");
        let help = String::from_utf8(help.stdout).unwrap();
        out.push_str(&format!("```text\n{}\n```\n{END}\n", help.trim_end()));
    }
    out
}

#[test]
fn every_reference_page_shows_its_commands_current_help() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/src/reference");
    let bless = std::env::var_os("BLESS_CLI_REFERENCE").is_some();
    let mut blocks = 0;
    let mut stale = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        blocks += text.lines().filter(|l| l.starts_with(START)).count();
        let current = with_current_help(&text);
        if current != text {
            match bless {
                true => std::fs::write(&path, current).unwrap(),
                false => stale.push(path.display().to_string()),
            }
        }
    }
    assert!(blocks >= 12, "the reference lost its commands' help ({blocks} blocks)");
    assert!(
        stale.is_empty(),
        "stale --help in {stale:?}: run `BLESS_CLI_REFERENCE=1 cargo test --release --test cli_reference`"
    );
}
