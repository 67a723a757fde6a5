//! Jobs on a real single-node SLURM (`ci/slurm.sh`, as root). The map as a job array: two array
//! tasks compute their shards into one folder; one of them is killed (`scancel --signal=KILL`)
//! while it computes a point and requeued (`scontrol requeue`), and resumes from the points it
//! had written; `--collect` assembles the shards, and the result equals the unsharded map. A
//! `simulate` job with `--resume`, killed after its first checkpoint and requeued, finishes with
//! the files of the uninterrupted run.
//! Ignored by a plain `cargo test` (it installs and starts daemons); `.ci/run` runs it with
//! `--ignored`.

mod common;

use common::resume::{assert_same_files, rows, run_args};
use common::{fiberfold, map_points, scratch, tiny_map_of};
use std::path::Path;
use std::process::Command;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Each test starts and stops the cluster: one at a time.
static CLUSTER: Mutex<()> = Mutex::new(());

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

/// Runs a SLURM client of the cluster in `state`; its standard output.
fn client(state: &Path, program: &str, args: &[&str]) -> String {
    let out = Command::new(program)
        .env("SLURM_CONF", state.join("slurm.conf"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{program} runs: {e}"));
    assert!(
        out.status.success(),
        "{program} {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// Writes `command` (its words, quoted as they should be) as the job script `dir/job.sh`, one
/// thread a task, and submits it with `flag`, its output appended to `log`: the job's id.
fn submit(state: &Path, dir: &Path, command: &[String], flag: &str, log: &Path) -> String {
    let job = dir.join("job.sh");
    let script = format!(
        "#!/bin/bash\nset -e\nexport RAYON_NUM_THREADS=1\n{}\n",
        command.join(" ")
    );
    std::fs::write(&job, script).unwrap();
    let (log, job) = (log.to_str().unwrap(), job.to_str().unwrap());
    client(
        state,
        "sbatch",
        &["--parsable", flag, "--open-mode=append", "-o", log, job],
    )
}

/// Waits (up to `seconds`) until `done` holds.
fn wait_until(seconds: u64, what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(
            start.elapsed() < Duration::from_secs(seconds),
            "waited {seconds} s for {what}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The point files of shard 0 of 2 (the even indices) in `dir`.
fn shard_zero_points(dir: &Path) -> usize {
    std::fs::read_dir(dir.join("points")).map_or(0, |entries| {
        entries
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter_map(|n| n.strip_prefix("point-")?.strip_suffix(".json")?.parse::<usize>().ok())
            .filter(|index| index % 2 == 0)
            .count()
    })
}

#[test]
#[ignore = "starts a real SLURM as root: run by .ci/run with --ignored"]
fn a_killed_and_requeued_array_task_resumes_and_the_array_computes_the_same_map() {
    let _one = CLUSTER.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let state = scratch("slurm-state");
    slurm("start", &state);
    let outcome = std::panic::catch_unwind(|| {
        let sharded = scratch("slurm-map");
        std::fs::create_dir_all(&sharded).unwrap();
        let mut shard_args = tiny_map_of(8, &sharded, &[]);
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
        // One thread a task: each takes a few seconds for its 4 points, one after the other.
        let id = submit(&state, &sharded, &command, "--array=0-1", &sharded.join("task_%a.log"));
        let task = format!("{id}_0");
        let running = |task: &str| {
            let state_of = client(&state, "squeue", &["-h", "-j", task, "-o", "%T"]);
            state_of == "RUNNING" || state_of == "COMPLETING"
        };

        // Task 0 is killed once its first point is written, while it computes the next.
        wait_until(120, "the first point of shard 0", || shard_zero_points(&sharded) >= 1);
        client(&state, "scancel", &["--signal=KILL", &task]);
        wait_until(60, "the killed task to end", || !running(&task));
        let written = shard_zero_points(&sharded);
        assert!(
            written < 4,
            "the kill came after the task's last point: a slower map is needed"
        );
        // A requeued job waits a scheduler delay before it is eligible; a user may start it now.
        client(&state, "scontrol", &["requeue", &task]);
        client(
            &state,
            "scontrol",
            &["update", &format!("JobId={task}"), "StartTime=now"],
        );
        wait_until(300, "the array job to end", || {
            client(&state, "squeue", &["-h", "-j", &id]).is_empty()
        });

        let logs: Vec<String> = (0..2)
            .map(|i| std::fs::read_to_string(sharded.join(format!("task_{i}.log"))).unwrap_or_default())
            .collect();
        assert!(
            logs[1].contains("shard 1/2: 4 points") && logs[1].contains("4 points computed, 0 reused"),
            "{}",
            logs[1]
        );
        assert_eq!(
            logs[0].matches("shard 0/2: 4 points").count(),
            2,
            "run, then rerun: {}",
            logs[0]
        );
        assert!(
            logs[0].contains(&format!("{} points computed, {written} reused", 4 - written)),
            "the requeued task resumes from the {written} points written: {}",
            logs[0]
        );
        let collected = fiberfold(&tiny_map_of(8, &sharded, &["--collect"]));
        assert!(
            collected.status.success(),
            "{}",
            String::from_utf8_lossy(&collected.stderr)
        );

        let whole = scratch("slurm-whole");
        let unsharded = fiberfold(&tiny_map_of(8, &whole, &[]));
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

#[test]
#[ignore = "starts a real SLURM as root: run by .ci/run with --ignored"]
fn a_killed_and_requeued_simulate_job_resumes_to_the_uninterrupted_path() {
    let _one = CLUSTER.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let state = scratch("slurm-simulate-state");
    slurm("start", &state);
    let outcome = std::panic::catch_unwind(|| {
        let dir = scratch("slurm-simulate");
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("run");
        // The job always passes --resume: its first start finds no checkpoint.
        let args = [run_args("mixed", &out), vec!["--resume".to_string()]].concat();
        let command: Vec<String> = std::iter::once(env!("CARGO_BIN_EXE_fiberfold").to_string())
            .chain(args.iter().map(|a| format!("'{a}'")))
            .collect();
        let log = dir.join("job.log");
        let id = submit(&state, &dir, &command, "--requeue", &log);
        let running = || {
            let state_of = client(&state, "squeue", &["-h", "-j", &id, "-o", "%T"]);
            state_of == "RUNNING" || state_of == "COMPLETING"
        };
        wait_until(120, "the job's first checkpoint", || {
            out.join("checkpoint.bin").is_file() && rows(&out).len() > 15
        });
        client(&state, "scancel", &["--signal=KILL", &id]);
        wait_until(60, "the killed job to end", || !running());
        assert!(!out.join("simulate.json").exists(), "the kill came after the job's end");
        client(&state, "scontrol", &["requeue", &id]);
        client(&state, "scontrol", &["update", &format!("JobId={id}"), "StartTime=now"]);
        wait_until(300, "the requeued job to end", || {
            client(&state, "squeue", &["-h", "-j", &id]).is_empty() && out.join("simulate.json").is_file()
        });
        let said = std::fs::read_to_string(&log).unwrap_or_default();
        assert_eq!(said.matches("no checkpoint in").count(), 1, "{said}");
        assert!(
            said.contains("resuming at d = "),
            "the requeued job did not resume: {said}"
        );

        let whole = scratch("slurm-simulate-whole");
        let uninterrupted = fiberfold(&run_args("mixed", &whole));
        assert!(uninterrupted.status.success());
        assert_same_files(&whole, &out, "killed and requeued on SLURM");
        let _ = std::fs::remove_dir_all(&dir);
        let _ = std::fs::remove_dir_all(&whole);
    });
    slurm("stop", &state);
    if let Err(panic) = outcome {
        std::panic::resume_unwind(panic);
    }
}
