//! The map as a SLURM job array on a real single-node SLURM (`ci/slurm.sh`, as root): two array
//! tasks compute their shards into one folder, `--collect` assembles them, and the result equals
//! the unsharded map. Ignored by a plain `cargo test` (it installs and starts daemons); `.ci/run`
//! runs it with `--ignored`.

mod common;

use common::{fiberfold, map_points, scratch, tiny_map};
use std::path::Path;
use std::process::Command;

fn slurm(action: &str, dir: &Path) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("ci/slurm.sh");
    let status = Command::new("bash")
        .arg(script)
        .arg(action)
        .arg(dir)
        .status()
        .expect("bash runs");
    assert!(status.success(), "ci/slurm.sh {action} failed");
}

#[test]
#[ignore = "starts a real SLURM as root: run by .ci/run with --ignored"]
fn a_job_array_computes_the_same_map() {
    let state = scratch("slurm-state");
    slurm("start", &state);
    let outcome = std::panic::catch_unwind(|| {
        let sharded = scratch("slurm-map");
        std::fs::create_dir_all(&sharded).unwrap();
        let mut shard_args = tiny_map(&sharded, &[]);
        shard_args.push("--shard".into());
        shard_args.push("${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}".into());
        let command: Vec<String> = std::iter::once(env!("CARGO_BIN_EXE_fiberfold").to_string())
            .chain(shard_args.into_iter().map(|a| {
                if a.starts_with("${") {
                    format!("\"{a}\"")
                } else {
                    format!("'{a}'")
                }
            }))
            .collect();
        let job = sharded.join("job.sh");
        std::fs::write(&job, format!("#!/bin/bash\nset -e\n{}\n", command.join(" "))).unwrap();
        let submitted = Command::new("sbatch")
            .env("SLURM_CONF", state.join("slurm.conf"))
            .args(["--parsable", "--wait", "--array=0-1", "-o"])
            .arg(sharded.join("task_%a.log"))
            .arg(&job)
            .output()
            .expect("sbatch runs");
        let logs: String = (0..2)
            .map(|i| std::fs::read_to_string(sharded.join(format!("task_{i}.log"))).unwrap_or_default())
            .collect();
        assert!(
            submitted.status.success(),
            "array job failed: {}\n{logs}",
            String::from_utf8_lossy(&submitted.stderr)
        );
        assert!(logs.contains("shard 0/2") && logs.contains("shard 1/2"), "{logs}");
        let collected = fiberfold(&tiny_map(&sharded, &["--collect"]));
        assert!(
            collected.status.success(),
            "{}",
            String::from_utf8_lossy(&collected.stderr)
        );

        let whole = scratch("slurm-whole");
        let unsharded = fiberfold(&tiny_map(&whole, &[]));
        assert!(unsharded.status.success());
        assert_eq!(map_points(&sharded), map_points(&whole));
        let _ = std::fs::remove_dir_all(&sharded);
        let _ = std::fs::remove_dir_all(&whole);
    });
    slurm("stop", &state);
    if let Err(panic) = outcome {
        std::panic::resume_unwind(panic);
    }
}
