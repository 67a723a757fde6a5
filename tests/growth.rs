//! Growth, `F = Fe Fg`, in the linear theory: independent facts it must reproduce.

use fiberfold::homogeneous::HomogeneousRow;
use fiberfold::material::Bilayer;
use fiberfold::parameters::Load;
use fiberfold::stability::{discrete::DiscreteOptions, Method, Minimum, StabilityAnalysis};
use fiberfold::Parameters;

fn with_load(mut p: Parameters, load: Load) -> Parameters {
    p.load = load;
    p
}

/// Both layers grown by `g` with the ends held are the grown body compressed by `1/g`, whose
/// referential wavenumber is `k/g`: `g_c(k) = 1 / (1 - d_c(k / g_c))`, i.e. the strain
/// `1 - 1/g_c(k)` equals `d_c(k / g_c)`, by either method, with the fibres.
#[test]
fn uniform_growth_is_compression_of_the_grown_body() {
    let base = Parameters {
        beta: std::f64::consts::FRAC_PI_4,
        ..Parameters::default()
    };
    let discrete = Method::Discrete(DiscreteOptions {
        layer_elements: 8,
        substrate_elements: 80,
        depth_decay_lengths: 20.0,
    });
    for (method, tolerance) in [(Method::Exact, 1e-10), (discrete, 1e-9)] {
        let growing = StabilityAnalysis::new(&with_load(base.clone(), Load::UniformGrowth), method).unwrap();
        let compressed = StabilityAnalysis::new(&base, method).unwrap();
        for k in [0.3, 0.7, 1.6] {
            let strain = growing.critical_compression(k).unwrap();
            let g_c = 1.0 / (1.0 - strain);
            let d_c = compressed.critical_compression(k / g_c).unwrap();
            assert!(
                (strain - d_c).abs() < tolerance,
                "{method:?}, k = {k}: 1 - 1/g_c = {strain}, d_c(k/g_c) = {d_c}"
            );
        }
    }
}

/// The homogeneous state of the uniformly grown body is the compressed one: the same
/// transverse stretch and the same Cauchy stresses, since both have the same `Fe`.
#[test]
fn uniformly_grown_state_is_the_compressed_state() {
    for incompressible in [false, true] {
        let base = Parameters {
            beta: 0.6,
            incompressible,
            ..Parameters::default()
        };
        let growing = Bilayer::new(&with_load(base.clone(), Load::UniformGrowth));
        let compressed = Bilayer::new(&base);
        for d in [0.05, 0.2, 0.4] {
            let (g, c) = (
                HomogeneousRow::new(&growing, d).unwrap(),
                HomogeneousRow::new(&compressed, d).unwrap(),
            );
            assert_eq!(g.state.lambda1, 1.0);
            assert!((g.state.growth_layer - 1.0 / (1.0 - d)).abs() < 1e-14);
            assert!(
                (g.state.lambda2_layer - c.state.lambda2_layer).abs() < 1e-12,
                "{incompressible} {d}"
            );
            assert!((g.state.lambda2_substrate - c.state.lambda2_substrate).abs() < 1e-12);
            for i in 0..4 {
                assert!(
                    (g.layer_stress[i] - c.layer_stress[i]).abs() < 1e-9,
                    "{incompressible} {d} layer {i}"
                );
                assert!((g.substrate_stress[i] - c.substrate_stress[i]).abs() < 1e-10);
            }
        }
    }
}

/// A thin stiff film growing on an unstressed substrate: the classical wrinkling strain
/// `(1/4)(3 mu_s / mu_l)^(2/3)` and wavenumber `k0 H = (3 mu_s / mu_l)^(1/3)` (plane-strain
/// moduli `4 mu` of incompressible or nearly incompressible layers), within 2 %.
#[test]
fn a_thin_stiff_growing_film_wrinkles_at_the_thin_film_law() {
    let ratio: f64 = 1000.0;
    let strain = 0.25 * (3.0 / ratio).powf(2.0 / 3.0);
    let k0 = (3.0 / ratio).cbrt();
    for incompressible in [true, false] {
        let p = Parameters {
            mu_l: ratio,
            K_l: 1e4 * ratio,
            K_s: 1e4,
            phi_m: 1.0,
            phi_f: 0.0,
            incompressible,
            load: Load::Growth,
            ..Parameters::default()
        };
        let onset = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
        assert_eq!(onset.minimum, Minimum::Interior);
        assert!(
            (onset.d_c / strain - 1.0).abs() < 0.02,
            "{incompressible}: 1 - 1/g_c = {}, thin film {strain}",
            onset.d_c
        );
        assert!(
            (onset.k0 / k0 - 1.0).abs() < 0.02,
            "{incompressible}: k0 = {}, thin film {k0}",
            onset.k0
        );
    }
}

/// A fixed growth of 1 is no growth: the same onset to the last bit.
#[test]
fn unit_growth_changes_nothing() {
    let mut p = Parameters {
        beta: 0.7,
        ..Parameters::default()
    };
    let plain = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    p.growth_layer = 1.0;
    p.growth_substrate = 1.0;
    p.area_growth = true;
    let grown = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    assert_eq!((plain.k0, plain.d_c), (grown.k0, grown.d_c));
}

/// The exact bifurcation of the discretised perfect bilayer under growth, on the fine mesh with
/// either element, against the linear theory's smallest `g_c(m pi / 50)`: within 1e-4, as for
/// compression (measured: 2e-6 displacement, 1.3e-6 mixed).
#[test]
fn fe_bifurcation_under_growth_meets_the_linear_theory_on_the_fine_mesh() {
    use fiberfold::fem::ElementKind;
    use fiberfold::mesh::MeshSpec;
    use fiberfold::protocol::{find_bifurcation, BifurcationSettings};
    use fiberfold::studies::bifurcation::admissible_minimum;
    let p = Parameters {
        load: Load::Growth,
        ..Parameters::default()
    };
    let theory = admissible_minimum(&StabilityAnalysis::new(&p, Method::Exact).unwrap(), 50.0).unwrap();
    let g_theory = 1.0 / (1.0 - theory.d_c);
    for element in [ElementKind::Displacement, ElementKind::Mixed] {
        let spec = MeshSpec::fine().with_element(element);
        let found = find_bifurcation(&Bilayer::new(&p), spec, &BifurcationSettings::default()).unwrap();
        let g = 1.0 / (1.0 - found.d);
        println!(
            "{element:?}: g_b = {g:.8}, theory {g_theory:.8} (m = {})",
            theory.mode_number
        );
        assert_eq!(found.mode_number, theory.mode_number);
        assert!(
            (g / g_theory - 1.0).abs() < 1e-4,
            "{element:?}: g_b = {g}, theory {g_theory}"
        );
    }
}

/// A neo-Hookean solid has no length scale: grown uniformly in its plane (`Fg = diag(g, g)`) with
/// the ends held, the block, its mesh and its fold are the compressed ones scaled by `g`, so it
/// creases at the compressed one's strain to the root's tolerance. (Grown along `X` alone, the
/// 12 H block is stretched and the converged thresholds differ by 2.5e-3 with either element:
/// a finite block's length scale, not an error.)
#[test]
fn a_uniformly_grown_half_space_creases_at_the_compressed_one_s_strain() {
    let crease = |load: &str| -> serde_json::Value {
        let dir = std::env::temp_dir().join(format!("fiberfold-growth-crease-{load}-{}", std::process::id()));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_fiberfold"))
            .args([
                "crease", "--set", "mu_l=1", "--set", "K_l=100", "--set", "K_s=100", "--set", "phi_m=1",
            ])
            .args([
                "--set",
                "phi_f=0",
                "--set",
                "area_growth=true",
                "--fold",
                "1",
                "--d-from",
                "0.3",
                "--d-to",
                "0.38",
                "--d-step",
                "0.04",
            ])
            .args(["--no-convergence", "--load", load, "--out", dir.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let report = std::fs::read_to_string(dir.join("crease.json")).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        serde_json::from_str(&report).unwrap()
    };
    let (compressed, grown) = (crease("compression"), crease("uniform_growth"));
    let d = |r: &serde_json::Value| r["d_crease"].as_f64().unwrap();
    println!("d_crease: compressed {}, grown {}", d(&compressed), d(&grown));
    assert!((d(&compressed) - d(&grown)).abs() < 1e-5);
    assert!(compressed["g_crease"].is_null());
    assert!((grown["g_crease"].as_f64().unwrap() - 1.0 / (1.0 - d(&grown))).abs() < 1e-12);
}
