//! What a run leaves on disk after a fault (a kill, a full disk): every visible file complete.

use std::path::Path;

/// Every visible file under `dir` is complete for its format; returns how many were checked.
pub fn check_complete(dir: &Path) -> usize {
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name.starts_with('.') {
            continue; // the lock and the temporaries of interrupted writes
        }
        if path.is_dir() {
            checked += check_complete(&path);
            continue;
        }
        let bytes = std::fs::read(&path).unwrap();
        let text = || String::from_utf8(bytes.clone()).unwrap();
        match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
            "json" => {
                serde_json::from_slice::<serde_json::Value>(&bytes)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            }
            "csv" => {
                let text = text();
                assert!(text.ends_with('\n'), "{}: a partial last row", path.display());
                let fields = text.lines().next().unwrap().split(',').count();
                for line in text.lines() {
                    assert_eq!(line.split(',').count(), fields, "{}: row `{line}`", path.display());
                }
            }
            "vtu" => {
                vtkio::Vtk::import(&path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
            }
            "pvd" => {
                let text = text();
                assert!(text.trim_end().ends_with("</VTKFile>"), "{}", path.display());
                for file in text.split("file=\"").skip(1).map(|s| &s[..s.find('"').unwrap()]) {
                    assert!(dir.join(file).is_file(), "{} lists a missing {file}", path.display());
                }
            }
            "png" => {
                assert!(bytes.starts_with(b"\x89PNG"), "{}", path.display());
                assert!(bytes.ends_with(b"IEND\xaeB`\x82"), "{}: truncated", path.display());
            }
            "svg" => assert!(text().trim_end().ends_with("</svg>"), "{}: truncated", path.display()),
            "html" => assert!(text().trim_end().ends_with("</html>"), "{}: truncated", path.display()),
            "md" => assert!(!bytes.is_empty(), "{}", path.display()),
            // A checkpoint ends with the CRC-32 of everything before it.
            "bin" => {
                let (content, checksum) = bytes.split_last_chunk::<4>().expect("a checkpoint");
                assert!(content.starts_with(b"FFCHKPT\n"), "{}", path.display());
                assert_eq!(
                    crc32fast::hash(content).to_le_bytes(),
                    *checksum,
                    "{}: damaged",
                    path.display()
                );
            }
            other => panic!("unexpected file type {other}: {}", path.display()),
        }
        checked += 1;
    }
    checked
}
