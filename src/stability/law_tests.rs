//! The stability analysis with the laws besides the paper's, against classical results
//! written here independently of the Stroh code.

use super::*;
use crate::numerics::roots::brent;
use crate::parameters::Parameters;

/// An exactly incompressible, fibre-free bilayer whose layer and substrate both have the law
/// given by `settings` (`--set` assignments with `{}` for `layer` and `substrate`).
fn incompressible_pair(mu_l: f64, settings: &[&str]) -> Parameters {
    let mut p = Parameters {
        mu_l,
        mu_s: 1.0,
        phi_m: 1.0,
        phi_f: 0.0,
        mu_f: 0.0,
        incompressible: true,
        ..Parameters::default()
    };
    for table in ["layer", "substrate"] {
        for s in settings {
            p.set(&s.replace("{}", table)).unwrap();
        }
    }
    p.validate().unwrap();
    p
}

/// Dowaikh and Ogden (1990): an incompressible isotropic half-space in plane strain with a
/// free surface, at `diag(lambda, 1/lambda, 1)`, is unstable where
/// `alpha - gamma + 2 (beta + gamma) sqrt(alpha / gamma) = 0`, with `alpha = A0_1212`,
/// `gamma = A0_2121`, `2 beta = A0_1111 + A0_2222 - 2 A0_1122 - 2 A0_1221`. For the Ogden
/// energy `W = 2 mu / a^2 (l1^a + l2^a + l3^a - 3)` the moduli follow from `l_i W_i = 2 mu/a l_i^a`
/// and `l_i^2 W_ii = 2 mu (a - 1)/a l_i^a` (`W_ij = 0`, i != j):
/// `A0_iiii = l_i^2 W_ii`, `A0_ijij = (l_i W_i - l_j W_j) l_i^2 / (l_i^2 - l_j^2)`,
/// `A0_ijji = A0_ijij - l_i W_i`.
fn ogden_half_space_compression(a: f64) -> f64 {
    let condition = |lambda: f64| {
        let (l1, l2) = (lambda, 1.0 / lambda);
        let (s1, s2) = (2.0 / a * l1.powf(a), 2.0 / a * l2.powf(a));
        let alpha = (s1 - s2) * l1 * l1 / (l1 * l1 - l2 * l2);
        let gamma = (s2 - s1) * l2 * l2 / (l2 * l2 - l1 * l1);
        let a1111 = (a - 1.0) * s1;
        let a2222 = (a - 1.0) * s2;
        let a1221 = alpha - s1;
        let beta = 0.5 * (a1111 + a2222 - 2.0 * a1221);
        Ok(alpha - gamma + 2.0 * (beta + gamma) * (alpha / gamma).sqrt())
    };
    1.0 - brent("Dowaikh-Ogden condition", condition, 0.05, 0.999, 1e-14).unwrap()
}

#[test]
fn ogden_half_space_wrinkles_where_dowaikh_and_ogden_say() {
    // For alpha = 2 the condition is Biot's cubic.
    assert!((ogden_half_space_compression(2.0) - biot_compression()).abs() < 1e-10);
    let half_space = |alpha: f64| incompressible_pair(1.0, &["{}.law=ogden", &format!("{{}}.alpha={alpha}")]);
    for alpha in [-5.0, 2.0, 5.0] {
        let expected = ogden_half_space_compression(alpha);
        let analysis = StabilityAnalysis::new(&half_space(alpha), Method::Exact).unwrap();
        for k in [0.5, 2.0] {
            let d = analysis.critical_compression(k).unwrap();
            assert!(
                (d - expected).abs() < 1e-10,
                "alpha = {alpha}, k = {k}: {d} vs {expected}"
            );
        }
    }
    // alpha = -25 is unstable only at d = 0.804 (lambda_2 / lambda_1 = 26), where the Stroh
    // roots of the layer differ by a factor 26 and its transfer matrix exp(k N) grows as
    // exp(26 k): the exact solver anchors each exponential at the face where it is largest and
    // keeps the root. The discrete solver comes within 1e-3.
    let expected = ogden_half_space_compression(-25.0);
    let exact = StabilityAnalysis::new(&half_space(-25.0), Method::Exact).unwrap();
    for k in [0.5, 2.0] {
        let d = exact.critical_compression(k).unwrap();
        assert!((d - expected).abs() < 1e-10, "alpha = -25, k = {k}: {d} vs {expected}");
    }
    let discrete = StabilityAnalysis::new(&half_space(-25.0), Method::Discrete(Default::default())).unwrap();
    let d = discrete.critical_compression(0.5).unwrap();
    assert!((d - expected).abs() < 1e-3, "alpha = -25: {d} vs {expected}");
}

/// In plane strain `I1 = I2` at `J = 1`, so an incompressible Mooney-Rivlin solid is the
/// neo-Hookean one of shear modulus `2 (c1 + c2)`: its half-space is Biot's at every `c1, c2`,
/// and its bilayer's onset is the neo-Hookean bilayer's.
#[test]
fn incompressible_mooney_rivlin_is_neo_hookean_of_twice_c1_plus_c2() {
    for (c1, c2) in [(0.5, 0.0), (0.1, 0.4), (0.0, 0.5), (2.0, 3.0)] {
        let settings = [
            "{}.law=mooney_rivlin",
            &format!("{{}}.c1={c1}"),
            &format!("{{}}.c2={c2}"),
        ];
        let mut half_space = incompressible_pair(1.0, &settings);
        half_space.mu_l = half_space.mu_s;
        let analysis = StabilityAnalysis::new(&half_space, Method::Exact).unwrap();
        let d = analysis.critical_compression(1.0).unwrap();
        assert!((d - biot_compression()).abs() < 1e-7, "c1 = {c1}, c2 = {c2}: {d}");
    }
    let mooney = incompressible_pair(1.0, &["{}.law=mooney_rivlin", "{}.c1=0.1", "{}.c2=0.4"]);
    let mut mooney = mooney;
    mooney.set("layer.c1=3").unwrap();
    mooney.set("layer.c2=2").unwrap();
    let neo = incompressible_pair(10.0, &[]);
    let (a, b) = (
        StabilityAnalysis::new(&mooney, Method::Exact).unwrap().onset().unwrap(),
        StabilityAnalysis::new(&neo, Method::Exact).unwrap().onset().unwrap(),
    );
    assert!(
        (a.d_c - b.d_c).abs() < 1e-9 && (a.k0 - b.k0).abs() < 1e-6,
        "{a:?} vs {b:?}"
    );
}

/// A Gent law with a small limiting extensibility: the search ends where the homogeneous
/// state reaches it, the onset before it is found, and the state just short of it exists.
#[test]
fn a_gent_limit_ends_the_search_without_an_error() {
    let mut p = Parameters::default();
    for s in [
        "layer.law=gent",
        "layer.jm=0.3",
        "substrate.law=gent",
        "substrate.jm=0.3",
    ] {
        p.set(s).unwrap();
    }
    let onset = StabilityAnalysis::new(&p, Method::Exact).unwrap().onset().unwrap();
    let end = onset.d_domain_end.expect("the limit lies before d = 0.95");
    assert!(onset.d_c < end, "{onset:?}");
    let materials = crate::material::Bilayer::new(&p);
    assert!(crate::homogeneous::homogeneous_state(&materials, end * (1.0 - 1e-6)).is_ok());
    assert!(crate::homogeneous::homogeneous_state(&materials, end * (1.0 + 1e-6)).is_err());
    println!("Gent jm = 0.3: onset d_c = {:.6}, limit at d = {end:.6}", onset.d_c);
}
