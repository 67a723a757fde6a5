//! `bifurcation`: the exact first bifurcation of the discretised perfect system
//! ([`crate::protocol::bifurcation`]) against the linear theory's `min_m d_c(m pi / L)`.
//! Writes `bifurcation.json`, `inertia.csv` (negative pivots along the homogeneous path),
//! `mode_surface.csv` and `mode.png/.svg` (the mode's top-surface `u_y`), and `mode.vtu`.

use super::simulate::{nodal_array, write_state, MeshSummary};
use crate::error::{Error, Result};
use crate::fem::System;
use crate::homogeneous::homogeneous_state;
use crate::material::Bilayer;
use crate::mesh::{Mesh, MeshSpec, Y};
use crate::output::{write_json, CsvWriter, Figure, LineStyle, Series};
use crate::parameters::{Load, Parameters};
use crate::protocol::basic_state::homogeneous_unknowns;
use crate::protocol::Loading;
use crate::protocol::{find_bifurcation, Bifurcation, BifurcationSettings};
use crate::stability::{Method, StabilityAnalysis};
use serde::Serialize;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Largest wavenumber in the theory's minimum over admissible `k = m pi / L`.
const K_SEARCHED: f64 = 3.0;

/// The mesh and the search settings.
#[derive(Clone, Copy, Debug)]
pub struct BifurcationStudy {
    pub mesh: MeshSpec,
    pub settings: BifurcationSettings,
}

impl BifurcationStudy {
    /// The search with default settings on the mesh preset called `mesh`, with the element
    /// called `element` (the preset's when `None`).
    pub fn on_preset(mesh: &str, element: Option<&str>) -> Result<Self> {
        let preset = MeshSpec::preset(mesh)?;
        Ok(BifurcationStudy {
            mesh: match element {
                Some(name) => preset.with_element(crate::mesh::ElementKind::from_name(name)?),
                None => preset,
            },
            settings: BifurcationSettings::default(),
        })
    }
}

/// The linear theory's smallest `d_c(m pi / L)` over the admissible wavenumbers.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct AdmissibleMinimum {
    pub d_c: f64,
    pub mode_number: usize,
    pub k: f64,
}

/// `min_m d_c(m pi / L)` for `k = m pi / L <= 3` (wavenumbers without a root are skipped).
pub fn admissible_minimum(analysis: &StabilityAnalysis, length: f64) -> Result<AdmissibleMinimum> {
    let modes = 1..=(K_SEARCHED * length / PI).floor() as usize;
    let mut best: Option<AdmissibleMinimum> = None;
    for m in modes {
        let k = m as f64 * PI / length;
        let d_c = match analysis.critical_compression(k) {
            Err(Error::NoRoot { .. }) => continue,
            other => other?,
        };
        if best.is_none_or(|b| d_c < b.d_c) {
            best = Some(AdmissibleMinimum { d_c, mode_number: m, k });
        }
    }
    best.ok_or_else(|| Error::NoRoot {
        what: format!("a bifurcation of the linear theory for k = m pi / {length} <= {K_SEARCHED}"),
        lower: 0.0,
        upper: 1.0,
    })
}

/// `bifurcation.json`.
#[derive(Debug, Serialize)]
pub struct BifurcationReport {
    pub command: &'static str,
    pub parameters: Parameters,
    pub mesh: MeshSummary,
    /// What loads the bilayer; under growth `d` is the strain `1 - 1/g`.
    pub load: Load,
    pub d_bifurcation: f64,
    /// The growth at the bifurcation (null under compression).
    pub g_bifurcation: Option<f64>,
    pub bracket: (f64, f64),
    pub k_mode: f64,
    pub waves: f64,
    pub mode_number: usize,
    pub negative_pivots_past_bifurcation: usize,
    pub smallest_eigenvalue_before: f64,
    pub d_linear_theory_min: f64,
    pub k_linear_theory_min: f64,
    /// The theory's smallest critical growth (null under compression).
    pub g_linear_theory_min: Option<f64>,
    /// The FE bifurcation over the theory's minimum, minus 1, in the load's parameter (`d`,
    /// or `g` under growth).
    pub relative_difference: f64,
    pub d_linear_theory_at_k_mode: f64,
    pub relative_difference_at_k_mode: f64,
    /// Points of the homogeneous path whose inertia was computed (scan and bisection).
    pub inertia_evaluations: usize,
    pub wall_seconds: f64,
    pub files: Vec<String>,
}

/// Finds the bifurcation, compares it with the theory and writes the files (module docs).
pub fn run(params: &Parameters, study: &BifurcationStudy, out: &Path) -> Result<BifurcationReport> {
    params.validate()?;
    study.mesh.validate()?;
    study.mesh.element.check_for(params.incompressible)?;
    crate::output::ensure_dir(out)?;
    let start = Instant::now();
    let materials = Bilayer::new(params);
    let found = find_bifurcation(&materials, study.mesh, &study.settings)?;
    let analysis = StabilityAnalysis::new(params, Method::Exact)?;
    let theory = admissible_minimum(&analysis, study.mesh.length)?;
    let at_k_mode = analysis.critical_compression(found.k_mode)?;
    let mut files = write_inertia(out, &found.path)?;
    files.extend(write_mode(out, &materials, study.mesh, &found)?);
    let json = out.join("bifurcation.json");
    files.push(json.clone());
    let load = params.load;
    let growth = |d: f64| load.is_growth().then(|| load.parameter(d));
    let report = BifurcationReport {
        command: "bifurcation",
        parameters: params.clone(),
        mesh: MeshSummary::from(&study.mesh),
        load,
        d_bifurcation: found.d,
        g_bifurcation: growth(found.d),
        bracket: found.bracket,
        k_mode: found.k_mode,
        waves: found.mode_number as f64 / 2.0,
        mode_number: found.mode_number,
        negative_pivots_past_bifurcation: found.negative_pivots,
        smallest_eigenvalue_before: found.eigenvalue,
        d_linear_theory_min: theory.d_c,
        k_linear_theory_min: theory.k,
        g_linear_theory_min: growth(theory.d_c),
        relative_difference: load.parameter(found.d) / load.parameter(theory.d_c) - 1.0,
        d_linear_theory_at_k_mode: at_k_mode,
        relative_difference_at_k_mode: found.d / at_k_mode - 1.0,
        inertia_evaluations: found.path.len(),
        wall_seconds: start.elapsed().as_secs_f64(),
        files: files.iter().map(|f| f.display().to_string()).collect(),
    };
    write_json(&json, &report)?;
    Ok(report)
}

/// `inertia.csv`: every `(d, negative pivots)` of a homogeneous path evaluated, sorted by `d`.
pub(crate) fn write_inertia(out: &Path, evaluated: &[(f64, usize)]) -> Result<Vec<PathBuf>> {
    let path = out.join("inertia.csv");
    let mut table = CsvWriter::create(&path, &["d", "negative_pivots"])?;
    let mut points = evaluated.to_vec();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (d, negative) in points {
        table.append(&[d, negative as f64])?;
    }
    Ok(vec![path])
}

/// `mode.vtu` (homogeneous state at the bifurcation plus the mode), `mode_surface.csv`, `mode.png/.svg`.
fn write_mode(out: &Path, materials: &Bilayer, spec: MeshSpec, found: &Bifurcation) -> Result<Vec<PathBuf>> {
    let mesh = Mesh::new(spec)?;
    let surface: Vec<(f64, f64)> = mesh
        .top()
        .into_iter()
        .map(|n| (mesh.coordinates()[n][0], found.mode[mesh.dofs().dof(n, Y)]))
        .collect();
    let csv = out.join("mode_surface.csv");
    let mut table = CsvWriter::create(&csv, &["X", "mode_uy"])?;
    for &(x, uy) in &surface {
        table.append(&[x, uy])?;
    }
    let mut system = System::new(mesh, materials)?;
    system.load_to(found.d)?;
    let u = homogeneous_unknowns(&system, materials, &homogeneous_state(materials, found.d)?)?;
    let vtu = out.join("mode.vtu");
    let mode = nodal_array("mode", system.mesh(), &found.mode);
    write_state(&vtu, &system, materials, &u, vec![mode])?;
    let figure = Figure::new(
        format!(
            "Bifurcation mode at d = {:.6}: {} half waves, k = {:.4}",
            found.d, found.mode_number, found.k_mode
        ),
        "reference X / H",
        "u_y of the mode on the top surface (max 1)",
    )
    .with(Series::new("mode", surface, LineStyle::Solid, 0));
    let mut files = vec![csv, vtu];
    files.extend(figure.save(out, "mode")?);
    Ok(files)
}
