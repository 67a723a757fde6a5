//! `reproduce`: every figure of the paper available so far, into one folder, with a report.
//!
//! Each piece writes into its own sub-folder and copies its figures to the top folder. A piece
//! whose `done.json` records the same parameters is skipped, so an interrupted run resumes.

use super::stability_figures::Resolution;
use super::Tick;
use crate::error::{Error, Result};
use crate::output::{ensure_dir, write_json};
use crate::parameters::Parameters;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of a reproduction run.
#[derive(Clone, Copy, Debug, Default)]
pub struct ReproduceOptions {
    /// Coarser meshes and fewer points.
    pub quick: bool,
}

/// One independent part of the reproduction.
pub struct Piece {
    pub name: &'static str,
    /// Figures (stems) this piece produces.
    pub figures: &'static [&'static str],
    /// Rows for the report's table of claims.
    pub run: fn(&Parameters, &ReproduceOptions, &Path, Tick) -> Result<Vec<Claim>>,
}

/// One claim of the paper set beside ours.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Claim {
    pub what: String,
    pub paper: String,
    pub ours: String,
    pub note: String,
    pub command: String,
}

#[derive(Serialize, Deserialize)]
struct Done {
    parameters: Parameters,
    quick: bool,
    claims: Vec<Claim>,
    seconds: f64,
}

/// What one piece reported when it finished (or was found finished).
pub struct PieceOutcome {
    pub name: &'static str,
    pub seconds: f64,
    pub skipped: bool,
    pub claims: Vec<Claim>,
}

/// The pieces, in report order.
pub fn pieces() -> Vec<Piece> {
    vec![
        Piece {
            name: "homogeneous",
            figures: &["fig2"],
            run: run_homogeneous,
        },
        Piece {
            name: "fig4b",
            figures: &["fig4b"],
            run: run_fig4b,
        },
        Piece {
            name: "fig5",
            figures: &["fig5"],
            run: run_fig5,
        },
        Piece {
            name: "fig6",
            figures: &["fig6"],
            run: run_fig6,
        },
    ]
}

fn claim(what: &str, paper: f64, ours: f64, command: &str) -> Claim {
    let relative = ours / paper - 1.0;
    let note = if relative.abs() < 0.01 {
        "agrees within 1 %".to_string()
    } else {
        format!("differs by {:+.1} %", 100.0 * relative)
    };
    Claim {
        what: what.into(),
        paper: format!("{paper}"),
        ours: format!("{ours:.4}"),
        note,
        command: command.into(),
    }
}

fn run_fig4b(params: &Parameters, options: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    let facts = super::stability_figures::fig4b(params, &Resolution::new(options.quick), dir, tick)?;
    write_json(&dir.join("fig4b.json"), &facts)?;
    let sweep_20 = "fiberfold sweep --param beta --from 0 --to 1.5707963 --set mu_f=20";
    let mut claims = vec![
        claim(
            "k0 with unloaded fibres (mu_f = 0, phi_m = 0.9)",
            0.5515,
            facts.k0_unloaded_fibres,
            "fiberfold onset --set mu_f=0",
        ),
        claim(
            "max change of k0 from the fibre-free value, mu_f = 20",
            0.134,
            facts.max_relative_change_mu_f_20,
            sweep_20,
        ),
        claim(
            "angle of the largest k0, mu_f = 20",
            1.18,
            facts.angle_of_k_max_mu_f_20,
            sweep_20,
        ),
        claim(
            "max/min wavelength over beta, mu_f = 20",
            1.15,
            facts.wavelength_ratio_mu_f_20,
            sweep_20,
        ),
    ];
    if let (Some(beta), Some(k)) = (facts.crossing_angle, facts.crossing_k0) {
        let sweep = "fiberfold sweep --param beta --from 0 --to 1.5707963 --series mu_f=1,50";
        claims.push(claim(
            "angle beta_c where the k0(beta) curves cross",
            0.3846,
            beta,
            sweep,
        ));
        claims.push(claim("k0 at the crossing", 0.5516, k, sweep));
    }
    Ok(claims)
}

fn run_fig5(params: &Parameters, options: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    let facts = super::stability_figures::fig5(params, &Resolution::new(options.quick), dir, tick)?;
    write_json(&dir.join("fig5.json"), &facts)?;
    Ok(vec![claim(
        "growth of d_c from beta = 0 to pi/2 at mu_f = 10",
        0.5,
        facts.growth_mu_f_10,
        "fiberfold onset --set beta=0; fiberfold onset --set beta=1.5707963",
    )])
}

fn run_fig6(params: &Parameters, options: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    super::stability_figures::fig6(params, &Resolution::new(options.quick), dir, tick)?;
    Ok(vec![])
}

fn run_homogeneous(params: &Parameters, _: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    let p = Parameters {
        beta: 0.0,
        ..params.clone()
    };
    super::homogeneous::run(&p, &super::homogeneous::HomogeneousStudy::default(), dir, tick)?;
    Ok(vec![])
}

/// Runs (or resumes) one piece inside `out/<name>` and copies its figures to `out`.
pub fn run_piece(
    piece: &Piece,
    params: &Parameters,
    options: &ReproduceOptions,
    out: &Path,
    tick: Tick,
) -> Result<PieceOutcome> {
    let dir = out.join(piece.name);
    let done_path = dir.join("done.json");
    if let Some(done) = read_done(&done_path) {
        if done.parameters == *params && done.quick == options.quick {
            return Ok(PieceOutcome {
                name: piece.name,
                seconds: done.seconds,
                skipped: true,
                claims: done.claims,
            });
        }
    }
    ensure_dir(&dir)?;
    let start = Instant::now();
    let claims = (piece.run)(params, options, &dir, tick)?;
    for stem in piece.figures {
        for ext in ["png", "svg"] {
            let from = dir.join(format!("{stem}.{ext}"));
            let to = out.join(format!("{stem}.{ext}"));
            std::fs::copy(&from, &to).map_err(|e| Error::io(&from, e))?;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let done = Done {
        parameters: params.clone(),
        quick: options.quick,
        claims: claims.clone(),
        seconds,
    };
    write_json(&done_path, &done)?;
    Ok(PieceOutcome {
        name: piece.name,
        seconds,
        skipped: false,
        claims,
    })
}

fn read_done(path: &Path) -> Option<Done> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

/// Writes `report.md`: the figures and the paper's claims beside ours.
pub fn write_report(out: &Path, outcomes: &[PieceOutcome]) -> Result<PathBuf> {
    let mut md = String::from("# fiberfold reproduction report\n\n");
    md.push_str("Regenerated by `cargo run --release -- reproduce`. Units: lengths by H, moduli by mu_s.\n\n");
    md.push_str("## Claims of the paper beside ours\n\n");
    md.push_str("| claim | paper | fiberfold | note | command |\n|---|---|---|---|---|\n");
    for c in outcomes.iter().flat_map(|o| &o.claims) {
        md.push_str(&format!(
            "| {} | {} | {} | {} | `{}` |\n",
            c.what, c.paper, c.ours, c.note, c.command
        ));
    }
    md.push_str("\n## Figures\n\n");
    for piece in pieces() {
        for stem in piece.figures {
            md.push_str(&format!("### {stem}\n\n![{stem}]({stem}.png)\n\n"));
        }
    }
    md.push_str("## Wall time\n\n| piece | seconds | |\n|---|---|---|\n");
    for o in outcomes {
        md.push_str(&format!(
            "| {} | {:.2} | {} |\n",
            o.name,
            o.seconds,
            if o.skipped { "reused" } else { "computed" }
        ));
    }
    let path = out.join("report.md");
    std::fs::write(&path, md).map_err(|e| Error::io(&path, e))?;
    Ok(path)
}
