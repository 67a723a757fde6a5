//! Generated input, never a panic: thousands of random and mutated parameter files and `--set`
//! values through the library's parsers, and hundreds of command lines (random flags at and
//! beyond their ranges, extreme but valid parameters) through the binary. Every run must exit 0,
//! 2 (bad input, one-line message) or 1 (a solver failure with a message), never panic or hang,
//! write no NaN or infinity into any file, and leave no file behind on exit code 2.

mod common;

use common::{scratch, Rng};
use fiberfold::parameters::{is_boolean, parameter_names, Parameters};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Values a user might type for a number: valid, extreme, malformed.
const NASTY: &[&str] = &[
    "nan",
    "NaN",
    "inf",
    "-inf",
    "-0",
    "0",
    "1e308",
    "-1e308",
    "1e-320",
    "",
    " ",
    "1,5",
    "0x10",
    "1e",
    "--1",
    "3.14.15",
    "µ",
    "零",
    "\u{0}",
    "1_000",
    "true",
    "false",
    "[]",
    "\"1\"",
    "0.5",
    "1",
    "2",
    "10",
    "100",
    "1e6",
    "1e9",
    "-1",
    "0.9999999",
    "1.0000001",
    "6.2832",
    "1.5707963",
];

fn random_value(rng: &mut Rng) -> String {
    if rng.below(3) == 0 {
        let x = (rng.next() as f64 / u64::MAX as f64) * 10f64.powi(rng.below(12) as i32 - 4);
        format!("{}{x}", if rng.below(4) == 0 { "-" } else { "" })
    } else {
        rng.pick(NASTY).to_string()
    }
}

/// A parameter file: Table 1, mutated (values, keys, syntax).
fn random_toml(rng: &mut Rng) -> String {
    let mut text = Parameters::default().to_toml();
    for _ in 0..1 + rng.below(4) {
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        if lines.is_empty() {
            lines.push(String::new());
        }
        let i = rng.below(lines.len());
        match rng.below(6) {
            0 => {
                lines[i] = format!(
                    "{} = {}",
                    rng.pick(&parameter_names().collect::<Vec<_>>()),
                    random_value(rng)
                )
            }
            1 => {
                lines[i] = format!(
                    "{} = {}",
                    rng.pick(&["gamma", "mu", "", "beta beta", "Mu_l"]),
                    random_value(rng)
                )
            }
            2 => {
                lines.remove(i);
            }
            3 => {
                let cut = rng.below(lines[i].len() + 1);
                let cut = (0..=cut).rev().find(|&k| lines[i].is_char_boundary(k)).unwrap_or(0);
                lines[i].truncate(cut);
            }
            4 => lines.insert(
                i,
                rng.pick(&["[section]", "= 3", "beta = [1, 2]", "beta = 'x'", "#", "\u{feff}"])
                    .to_string(),
            ),
            _ => {
                let mut bytes = lines[i].clone().into_bytes();
                if !bytes.is_empty() {
                    let j = rng.below(bytes.len());
                    bytes[j] = rng.next() as u8;
                }
                lines[i] = String::from_utf8_lossy(&bytes).into_owned();
            }
        };
        text = lines.join("\n");
    }
    text
}

/// What a run may print and leave behind.
fn check_run(args: &[String], dir: &Path) -> i32 {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_fiberfold"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("binary runs");
    let status = loop {
        if let Some(status) = child.try_wait().expect("status") {
            break status;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("hang: {args:?}");
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
    let code = status.code().unwrap_or(-1);
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert!(matches!(code, 0..=2), "{args:?} exit {code}: {stderr}");
    if code != 0 {
        let message: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error: ")).collect();
        assert_eq!(message.len(), 1, "{args:?}: one error line expected: {stderr}");
        if code == 1 {
            println!("exit 1: {} <- {args:?}", message[0]);
        }
    }
    if dir.exists() {
        for file in files(dir) {
            if code == 2 {
                panic!("{args:?} exited 2 but left {}", file.display());
            }
            if let Some("csv" | "json" | "md" | "toml") = file.extension().and_then(|e| e.to_str()) {
                let text = std::fs::read_to_string(&file).unwrap();
                for bad in ["NaN", "nan,", ",nan", "inf,", ",inf", "Infinity"] {
                    assert!(!text.contains(bad), "{args:?}: `{bad}` in {}", file.display());
                }
            }
        }
        std::fs::remove_dir_all(dir).unwrap();
    }
    code
}

fn files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(files(&path));
        } else if !path.file_name().unwrap().to_string_lossy().starts_with('.') {
            out.push(path);
        }
    }
    out
}

#[test]
fn parsers_never_panic_on_generated_input() {
    let mut rng = Rng(0xD1B54A32D192ED03);
    let mut accepted = 0;
    for _ in 0..3000 {
        let text = random_toml(&mut rng);
        let parsed =
            std::panic::catch_unwind(|| Parameters::from_toml_str(&text).and_then(|p| p.validate().map(|_| p)));
        match parsed.unwrap_or_else(|_| panic!("panic on {text:?}")) {
            Ok(p) => {
                accepted += 1;
                for name in parameter_names().filter(|n| !is_boolean(n)).collect::<Vec<_>>().iter() {
                    assert!(p.number(name).unwrap().is_finite(), "{name} not finite from {text:?}");
                }
            }
            Err(e) => assert!(e.is_user_input(), "{e} from {text:?}"),
        }
        let assignment = format!(
            "{}={}",
            rng.pick(&parameter_names().collect::<Vec<_>>()),
            random_value(&mut rng)
        );
        let mut p = Parameters::default();
        let result = std::panic::catch_unwind(move || p.set(&assignment).and_then(|()| p.validate()));
        if let Ok(Err(e)) = &result {
            assert!(e.is_user_input(), "{e}");
        }
        assert!(result.is_ok(), "panic on a --set");
    }
    assert!(
        accepted > 100,
        "the mutations should leave some files valid ({accepted})"
    );
}

#[test]
fn the_binary_exits_0_1_or_2_on_generated_command_lines() {
    let dir = scratch("fuzz");
    let out = dir.to_str().unwrap().to_string();
    let params_file = scratch("fuzz-params.toml");
    let mut rng = Rng(0x9E3779B97F4A7C15);
    let mut codes = [0usize; 3];
    let runs = 2000;
    for _ in 0..runs {
        let mut args: Vec<String> = Vec::new();
        let command = *rng.pick(&["params", "homogeneous", "onset", "dispersion", "sweep", "simulate"]);
        args.push(command.into());
        // Parameters: a mutated file, random --set values, or extreme but valid ones.
        match rng.below(4) {
            0 => {
                std::fs::write(&params_file, random_toml(&mut rng)).unwrap();
                args.extend(["--params".into(), params_file.display().to_string()]);
            }
            1 => {
                for _ in 0..1 + rng.below(2) {
                    args.extend([
                        "--set".into(),
                        format!(
                            "{}={}",
                            rng.pick(&parameter_names().collect::<Vec<_>>()),
                            random_value(&mut rng)
                        ),
                    ]);
                }
            }
            2 => {
                let extreme = rng.pick(&[
                    "mu_f=1e6",
                    "K_s=1e9",
                    "K_l=1e9",
                    "mu_l=1e4",
                    "mu_l=0.01",
                    "lambda_f=0.5",
                    "beta=1.5707963",
                    "phi_m=0",
                    "phi_f=1",
                ]);
                args.extend(["--set".into(), extreme.to_string()]);
            }
            _ => {}
        }
        let flag = |rng: &mut Rng, name: &str| vec![format!("--{name}"), random_value(rng)];
        match command {
            "homogeneous" => {
                if rng.below(2) == 0 {
                    args.extend(flag(&mut rng, "d-max"));
                }
                if rng.below(2) == 0 {
                    args.extend([
                        "--points".into(),
                        rng.pick(&["0", "1", "2", "50", "-3", "1e3", "x", "100000000000"])
                            .to_string(),
                    ]);
                }
            }
            "dispersion" => {
                for name in ["k-min", "k-max"] {
                    if rng.below(2) == 0 {
                        args.extend(flag(&mut rng, name));
                    }
                }
                args.extend([
                    "--points".into(),
                    rng.pick(&["0", "1", "2", "5", "-1", "x"]).to_string(),
                ]);
            }
            "sweep" => {
                args.extend([
                    "--param".into(),
                    rng.pick(&["beta", "mu_f", "gamma", "tension_only", ""]).to_string(),
                ]);
                args.extend(flag(&mut rng, "from"));
                args.extend(flag(&mut rng, "to"));
                args.extend(["--points".into(), rng.pick(&["0", "1", "3", "-2", "x"]).to_string()]);
                if rng.below(3) == 0 {
                    args.extend([
                        "--series".into(),
                        rng.pick(&["mu_f=1,10", "mu_f=", "=1", "mu_f=a,b", "beta=nan"])
                            .to_string(),
                    ]);
                }
            }
            "simulate" => {
                args.extend(["--nx".into(), rng.pick(&["20", "0", "1", "-5", "x", "18"]).to_string()]);
                args.extend([
                    "--layer-elements".into(),
                    "1".into(),
                    "--substrate-elements".into(),
                    "4".into(),
                ]);
                args.extend([
                    "--waves".into(),
                    rng.pick(&["4.5", "0", "-1", "4.3", "nan", "1e9", "2"]).to_string(),
                ]);
                args.extend([
                    "--d-max".into(),
                    rng.pick(&["0.02", "0", "1", "0.005", "nan", "-0.1", "0.03"])
                        .to_string(),
                ]);
                for name in ["max-step", "min-step", "eta", "imperfection", "vtu-every"] {
                    if rng.below(4) == 0 {
                        args.extend(flag(&mut rng, name));
                    }
                }
            }
            _ => {}
        }
        if command != "params" || rng.below(2) == 0 {
            args.extend(["--out".into(), out.clone()]);
        }
        // A command line cannot carry a NUL byte (files can, and do above).
        let args: Vec<String> = args.iter().map(|a| a.replace('\0', "\\0")).collect();
        let code = check_run(&args, &dir);
        codes[code as usize] += 1;
    }
    println!(
        "exit codes over {runs} command lines: 0: {}, 1: {}, 2: {}",
        codes[0], codes[1], codes[2]
    );
    assert!(codes[0] > 20 && codes[2] > 20, "{codes:?}");
}
