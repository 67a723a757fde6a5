//! The loading protocol, its outputs and the onset estimators, on small meshes: the exact FE
//! bifurcation against the linear theory, step cutting and a final failure that keeps its
//! results, VTU files read back, inadmissible wavenumbers rejected, and the three onset
//! estimators on synthetic curves with a known `d_c`.

mod common;

use common::{fiberfold, scratch};
use fiberfold::material::Bilayer;
use fiberfold::mesh::{Mesh, MeshSpec};
use fiberfold::protocol::onset::{a2_fit, max_curvature, steepest};
use fiberfold::protocol::{find_bifurcation, stages, BifurcationSettings, Event, Protocol, StepControl};
use fiberfold::stability::{Method, StabilityAnalysis};
use fiberfold::studies::simulate::{self, Progress, SimulateStudy};
use fiberfold::Parameters;
use std::f64::consts::{FRAC_PI_4, PI};
use std::path::Path;

/// `beta = pi/4`, other parameters from Table 1.
fn params() -> Parameters {
    Parameters {
        beta: FRAC_PI_4,
        ..Parameters::default()
    }
}

/// A short domain `L = 10`, `D = 10`: 20 x (2 + 8) elements, 1,722 unknowns.
fn small_mesh() -> MeshSpec {
    MeshSpec::new(20, 2, 8, 0.5, 10.0, 10.0)
}

/// `m = 2` half wavelengths across `L = 10` (k = 0.628, near the onset wavenumber 0.61).
fn small_k() -> f64 {
    2.0 * PI / 10.0
}

fn quiet(_: Progress<'_>) -> fiberfold::Result<()> {
    Ok(())
}

#[test]
fn perfect_system_bifurcation_matches_the_linear_theory_on_a_small_mesh() {
    let p = params();
    let found = find_bifurcation(&Bilayer::new(&p), small_mesh(), &BifurcationSettings::default()).unwrap();
    let theory = StabilityAnalysis::new(&p, Method::Exact)
        .unwrap()
        .critical_compression(found.k_mode)
        .unwrap();
    let relative = found.d / theory - 1.0;
    println!(
        "d_b = {:.7} (m = {}, k = {:.4}), theory {theory:.7}, relative {relative:.2e}",
        found.d, found.mode_number, found.k_mode
    );
    assert_eq!(found.mode_number, 2, "the admissible k nearest the onset k0 = 0.61");
    assert!(found.bracket.1 - found.bracket.0 <= 1e-6);
    assert_eq!(found.negative_pivots, 1);
    // 1e-3: ten elements per wavelength and a depth of 10 (the mode decays like e^{0.6 Y}) cost
    // a few 1e-4 here; the preset meshes reach 4e-4 (coarse) and 2e-5 (fine).
    assert!(relative.abs() < 1e-3, "relative difference {relative:e}");
}

#[test]
fn a_huge_step_that_fails_is_cut_and_the_run_continues() {
    let mut protocol = Protocol::new(small_k(), 0.05, 0.2);
    protocol.control = StepControl {
        initial: 0.15,
        max: 0.15,
        min: 1e-4,
        ..StepControl::default()
    };
    let mut cuts = Vec::new();
    let outcome = stages::run(&Bilayer::new(&params()), small_mesh(), &protocol, &mut |event| {
        if let Event::Cut(cut) = event {
            cuts.push(cut.clone());
        }
        Ok(())
    })
    .unwrap();
    println!("cuts: {cuts:?}");
    assert!(outcome.stopped.is_none(), "{:?}", outcome.stopped);
    assert_eq!(outcome.continuation.d(), 0.2);
    assert!(!cuts.is_empty(), "the step of 0.15 across the onset should fail once");
    assert!((cuts[0].d - 0.155).abs() < 1e-12 && !cuts[0].reason.is_empty());
}

/// A study on the small mesh with fixed steps of `step`.
fn fixed_step_study(step: f64, d_max: f64) -> SimulateStudy {
    let mut protocol = Protocol::new(small_k(), 0.05, d_max);
    protocol.control = StepControl {
        initial: step,
        max: step,
        min: step,
        ..StepControl::default()
    };
    SimulateStudy {
        vtu_every: 0.05,
        ..SimulateStudy::new(small_mesh(), protocol)
    }
}

#[test]
fn failure_at_the_minimum_step_keeps_the_curve_and_names_d() {
    let dir = scratch("failure");
    // Steps of 0.1 converge to d = 0.205 when Newton may grind (12 tangents, no stall or
    // divergence cut); the one to 0.3 cannot, and may not be cut.
    let mut study = fixed_step_study(0.1, 0.3);
    study.protocol.newton.max_iterations = 12;
    study.protocol.newton.stall = None;
    study.protocol.newton.diverging_after = None;
    let error = simulate::run(&params(), &study, &dir, &quiet).unwrap_err();
    let message = error.to_string();
    println!("{message}");
    assert!(!error.is_user_input());
    assert!(
        message.contains("d = 0.300000") && message.contains("last converged d = 0.205000"),
        "{message}"
    );
    let csv = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "d,A,strain_energy,newton_iterations,residual,min_J,step_seconds,in_contact,contact_length,penetration,\
         stabilisation_energy_fraction,snap,minimised,ellipticity_layer,ellipticity_substrate,growth_layer"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let d: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(d.len(), 3, "{csv}");
    assert!((d[2] - 0.205).abs() < 1e-12);
    assert!(rows.iter().all(|r| r.len() == 16 && r.iter().all(|x| x.is_finite())));
    for file in [
        "surface.csv",
        "onset_estimates.json",
        "simulate.json",
        "simulate.pvd",
        "fig3.png",
    ] {
        assert!(dir.join(file).exists(), "{file} missing after the failure");
    }
}

#[test]
fn the_binary_exits_non_zero_with_the_message_after_a_final_failure() {
    let dir = scratch("cli-failure");
    let args = [
        "simulate",
        "--waves",
        "4.5",
        "--nx",
        "20",
        "--layer-elements",
        "2",
        "--substrate-elements",
        "8",
        "--h0",
        "0.5",
        "--max-step",
        "0.1",
        "--min-step",
        "0.1",
        "--d-max",
        "0.3",
        "--out",
    ];
    let out = fiberfold(&[&args[..], &[dir.to_str().unwrap()]].concat());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("stopped at d = "), "{stderr}");
    assert!(stderr.contains("stabilisation = snap crosses"), "{stderr}");
    // The message names the last converged d, which is the last row of amplitude.csv.
    let last_converged: f64 = stderr.split("last converged d = ").nth(1).expect("names the last d")[..8]
        .parse()
        .unwrap();
    let csv = std::fs::read_to_string(dir.join("amplitude.csv")).unwrap();
    let last_row: f64 = csv.lines().last().unwrap().split(',').next().unwrap().parse().unwrap();
    assert!((last_row - last_converged).abs() < 1e-6, "{stderr}\n{csv}");
}

#[test]
fn inadmissible_wavenumbers_are_rejected_with_exit_code_2() {
    for (flag, value, words) in [
        ("--k", "0.6", ["`k`", "half wavelengths"]),
        ("--waves", "4.3", ["`waves`", "2N a positive integer"]),
        (
            "--imperfection2-waves",
            "0.3",
            ["`imperfection2-waves`", "2 N2 a positive integer"],
        ),
    ] {
        let dir = scratch("bad-k");
        let seeded = if flag == "--imperfection2-waves" {
            &["--waves", "5"][..]
        } else {
            &[]
        };
        let out = fiberfold(
            &[
                &["simulate"][..],
                seeded,
                &[flag, value, "--out", dir.to_str().unwrap()],
            ]
            .concat(),
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(words.iter().all(|w| stderr.contains(w)), "{stderr}");
        assert!(!dir.exists(), "nothing may be written for bad input");
    }
}

/// A data array read back: name, components, values.
type NamedArray = (String, usize, Vec<f64>);

/// Reads a `.vtu` file with vtkio (an independent reader): point and cell counts, the
/// connectivity, and every named array with its number of components.
fn read_vtu(path: &Path) -> (usize, usize, Vec<u64>, Vec<NamedArray>) {
    use vtkio::model::{Attribute, DataSet, ElementType, Piece, VertexNumbers};
    let vtk = vtkio::Vtk::import(path).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid")
    };
    let Piece::Inline(piece) = pieces.into_iter().next().expect("one piece") else {
        panic!("not inline")
    };
    let points = piece.num_points();
    let connectivity = match piece.cells.cell_verts {
        VertexNumbers::XML { connectivity, .. } => connectivity,
        VertexNumbers::Legacy { .. } => panic!("legacy cells in a .vtu"),
    };
    let cells = piece.cells.types.len();
    let mut arrays = vec![("Points".to_string(), 3, piece.points.cast_into::<f64>().unwrap())];
    for attribute in piece.data.point.into_iter().chain(piece.data.cell) {
        let Attribute::DataArray(array) = attribute else {
            panic!("field data")
        };
        let components = match array.elem {
            ElementType::Scalars { num_comp, .. } => num_comp as usize,
            ElementType::Vectors => 3,
            ElementType::Tensors => 9,
            ElementType::Generic(n) => n as usize,
            other => panic!("{other:?}"),
        };
        arrays.push((array.name, components, array.data.cast_into::<f64>().unwrap()));
    }
    (points, cells, connectivity, arrays)
}

/// Under growth every snapshot's fields are those of its own state: each element's growth in
/// `simulate_*.vtu` is `g = 1 / (1 - d)` of the `d` the collection gives it. A state whose
/// inertia is counted in the background is written after the next attempt has moved the
/// system on; it used to be written with that attempt's tissues (5 of these 31 snapshots).
#[test]
fn growth_snapshots_carry_their_own_state_s_growth() {
    let dir = scratch("growth-snapshots");
    let output = fiberfold(&[
        "simulate",
        "--waves",
        "5",
        "--load",
        "growth",
        "--mesh",
        "coarse",
        "--d-max",
        "0.3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let pvd = std::fs::read_to_string(dir.join("simulate.pvd")).unwrap();
    let snapshots: Vec<(f64, &str)> = pvd
        .split("timestep=\"")
        .skip(1)
        .map(|s| {
            let d = s[..s.find('"').unwrap()].parse().unwrap();
            let file = s.split("file=\"").nth(1).unwrap();
            (d, &file[..file.find('"').unwrap()])
        })
        .collect();
    assert!(snapshots.len() >= 30, "{pvd}");
    for (d, file) in snapshots {
        let (_, _, _, arrays) = read_vtu(&dir.join(file));
        let (_, _, growth) = arrays.iter().find(|(name, _, _)| name == "growth").unwrap();
        let largest = growth.iter().fold(0.0f64, |m, g| m.max(*g));
        assert!(
            (largest - 1.0 / (1.0 - d)).abs() < 1e-9,
            "{file} at d = {d}: growth {largest}, its own {}",
            1.0 / (1.0 - d)
        );
    }
}

#[test]
fn vtu_snapshots_read_back_with_the_mesh_sizes_and_finite_fields() {
    let dir = scratch("vtu");
    simulate::run(&params(), &fixed_step_study(0.025, 0.1), &dir, &quiet).unwrap();
    let mesh = Mesh::new(small_mesh()).unwrap();
    let pvd = std::fs::read_to_string(dir.join("simulate.pvd")).unwrap();
    let files: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    // d = 0.005 (first), 0.055 and 0.1 (marks every 0.05; the last is the final state).
    assert_eq!(files.len(), 3, "{pvd}");
    for file in files {
        let (points, cells, connectivity, arrays) = read_vtu(&dir.join(file));
        assert_eq!((points, cells), (mesh.num_nodes(), mesh.elements().len()));
        let array = |name: &str| {
            let (_, components, values) = arrays
                .iter()
                .find(|(n, _, _)| n == name)
                .unwrap_or_else(|| panic!("no array {name}"));
            (*components, values.clone())
        };
        for (name, count) in [("Points", points), ("displacement", points)] {
            let (components, values) = array(name);
            assert_eq!(values.len(), components * count, "{name}");
            assert!(values.iter().all(|v| v.is_finite()), "{name}");
        }
        for name in [
            "J",
            "cauchy_stress",
            "von_mises",
            "fibre_stretch_1",
            "fibre_stretch_2",
            "layer",
        ] {
            let (components, values) = array(name);
            assert_eq!(values.len(), components * cells, "{name}");
            assert!(values.iter().all(|v| v.is_finite()), "{name}");
        }
        assert!(array("J").1.iter().all(|&j| j > 0.0 && j < 1.0));
        assert_eq!(connectivity.len(), 9 * cells);
        assert!(connectivity.iter().all(|&n| (n as usize) < points));
        // The points are the reference coordinates (the seeded geometry: X unchanged, Y near the mesh's).
        let written = array("Points").1;
        for (p, xy) in written.chunks(3).zip(mesh.coordinates()) {
            assert!(
                p[0] == xy[0] && (p[1] - xy[1]).abs() < 0.1 && p[2] == 0.0,
                "{p:?} vs {xy:?}"
            );
        }
    }
}

/// Samples of `a(d)` at `d = 0.005, 0.007, ..., 0.3`.
fn sample(a: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    (0..=147).map(|i| 0.005 + 0.002 * i as f64).map(|d| (d, a(d))).unzip()
}

#[test]
fn onset_estimators_recover_d_c_of_a_perfect_pitchfork() {
    // A^2 = A0^2 + c max(d - dc, 0): a kink at dc, A^2 linear beyond it, crossing zero at dc - A0^2/c.
    let (dc, a0, c) = (0.151, 0.01, 20.0);
    let (d, a) = sample(|d| (a0 * a0 + c * (d - dc).max(0.0)).sqrt());
    let (kappa, steep, fit) = (
        max_curvature(&d, &a).unwrap(),
        steepest(&d, &a).unwrap(),
        a2_fit(&d, &a).unwrap(),
    );
    println!("max curvature {kappa}, steepest {steep}, A^2 fit {fit}");
    assert!((kappa - dc).abs() <= 0.002 && (steep - dc).abs() <= 0.002);
    assert!((fit - (dc - a0 * a0 / c)).abs() < 1e-9);
}

#[test]
fn an_a2_fit_that_crosses_zero_outside_the_curve_is_no_onset() {
    // A curve that steepens at a kink (d = 0.08) and then grows slowly: its A^2 line crosses
    // zero at d = 0.08 - 1/5 = -0.12, before the curve starts.
    let (d, a) = sample(|d| (1.0 + 5.0 * (d - 0.08).max(0.0)).sqrt());
    assert!((steepest(&d, &a).unwrap() - 0.08).abs() < 0.005);
    assert_eq!(a2_fit(&d, &a), None);
    // The same kink where the curve starts from A = 0.1 has its zero inside: an estimate.
    let (d, a) = sample(|d| (0.01 + 5.0 * (d - 0.08).max(0.0)).sqrt());
    assert!((a2_fit(&d, &a).unwrap() - 0.078).abs() < 1e-9);
}

/// The positive root of the imperfect pitchfork `A^3 - c (d - dc) A - c e d = 0` (bisection).
fn imperfect_pitchfork(d: f64, dc: f64, c: f64, e: f64) -> f64 {
    let f = |a: f64| a * a * a - c * (d - dc) * a - c * e * d;
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

#[test]
fn onset_estimators_approach_d_c_as_the_imperfection_vanishes() {
    let (dc, c) = (0.145, 10.0);
    let mut errors = Vec::new();
    for e in [1e-3, 1e-5] {
        let (d, a) = sample(|d| imperfect_pitchfork(d, dc, c, e));
        let estimates = [max_curvature(&d, &a), steepest(&d, &a), a2_fit(&d, &a)].map(|x| x.unwrap() - dc);
        println!("e = {e:e}: errors (max curvature, steepest, A^2 fit) {estimates:?}");
        errors.push(estimates.map(f64::abs));
    }
    assert!(errors[1].iter().all(|&x| x < 0.004), "{errors:?}");
    assert!((0..3).all(|i| errors[1][i] <= errors[0][i] + 1e-3), "{errors:?}");
}

#[test]
fn bifurcation_command_writes_its_json_mode_and_inertia() {
    let dir = scratch("bifurcation-cli");
    let args = [
        "bifurcation",
        "--nx",
        "40",
        "--layer-elements",
        "1",
        "--substrate-elements",
        "8",
        "--out",
    ];
    let out = fiberfold(&[&args[..], &[dir.to_str().unwrap()]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("bifurcation.json")).unwrap()).unwrap();
    for key in [
        "d_bifurcation",
        "k_mode",
        "waves",
        "d_linear_theory_min",
        "relative_difference",
    ] {
        assert!(json[key].as_f64().is_some_and(f64::is_finite), "{key}: {json}");
    }
    // Table 1 with horizontal fibres: k0 = 0.505, so m = 8 (k = 0.503) is the admissible minimum.
    assert_eq!(json["k_mode"].as_f64(), Some(8.0 * PI / 50.0));
    assert!(json["relative_difference"].as_f64().unwrap().abs() < 0.01);
    for file in ["mode.vtu", "mode.png", "mode_surface.csv", "inertia.csv"] {
        assert!(dir.join(file).exists(), "{file} missing");
    }
}
