//! The pieces of the reproduction and the paper's claims each one checks.

use super::{Claim, Piece, ReproduceOptions};
use crate::error::Result;
use crate::output::write_json;
use crate::parameters::Parameters;
use crate::studies::stability_figures::Resolution;
use crate::studies::Tick;
use std::path::Path;

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
    let facts = crate::studies::stability_figures::fig4b(params, &Resolution::new(options.quick), dir, tick)?;
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
    let facts = crate::studies::stability_figures::fig5(params, &Resolution::new(options.quick), dir, tick)?;
    write_json(&dir.join("fig5.json"), &facts)?;
    Ok(vec![claim(
        "growth of d_c from beta = 0 to pi/2 at mu_f = 10",
        0.5,
        facts.growth_mu_f_10,
        "fiberfold onset --set beta=0; fiberfold onset --set beta=1.5707963",
    )])
}

fn run_fig6(params: &Parameters, options: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    crate::studies::stability_figures::fig6(params, &Resolution::new(options.quick), dir, tick)?;
    Ok(vec![])
}

fn run_homogeneous(params: &Parameters, _: &ReproduceOptions, dir: &Path, tick: Tick) -> Result<Vec<Claim>> {
    let p = Parameters {
        beta: 0.0,
        ..params.clone()
    };
    crate::studies::homogeneous::run(&p, &crate::studies::homogeneous::HomogeneousStudy::default(), dir, tick)?;
    Ok(vec![])
}
