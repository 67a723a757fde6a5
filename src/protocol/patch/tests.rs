use super::*;
use crate::mesh::{ElementKind, MeshSpec, Sides};
use crate::parameters::Parameters;
use crate::protocol::find_bifurcation;

fn patch(sides: Sides, nz: usize) -> PatchSpec {
    PatchSpec {
        nx: 4,
        nz,
        length_x: 8.0,
        length_z: 6.0,
        layer_elements: 1,
        substrate_elements: 4,
        top_substrate_thickness: 1.0,
        depth: 10.0,
        sides,
        element: ElementKind::Displacement,
    }
}

/// The homogeneous biaxial state is exact on the hexahedra: its residual vanishes to round-off
/// on a periodic patch with fibres out of the X-Y plane (whose in-plane shear stress `sigma_13`
/// periodic sides carry) and on a symmetric one.
#[test]
fn the_homogeneous_biaxial_state_is_an_equilibrium_of_the_patch() {
    for (sides, psi) in [(Sides::Periodic, 0.0), (Sides::Periodic, 0.5), (Sides::Symmetry, 0.0)] {
        let p = Parameters {
            beta: 0.6,
            psi,
            ..Parameters::default()
        };
        let materials = Bilayer::new(&p);
        let mut path = PatchPath::new(&materials, patch(sides, 2), 0.5).unwrap();
        let (state, bc, u) = path.homogeneous(0.12).unwrap();
        assert!(state.lambda2_layer > 1.0 && state.lambda2_substrate > 1.0);
        let assembled = path.system.assemble(&u, &bc, None, true).unwrap();
        let relative = relative_residual(&assembled, &u);
        assert!(relative < 1e-13, "{sides:?} {psi}: relative residual {relative:e}");
        // Not a trivial zero: the same state a little off is far from equilibrium.
        let off: Vec<f64> = u
            .iter()
            .enumerate()
            .map(|(i, v)| v * (1.0 + 1e-3 * (i % 7) as f64))
            .collect();
        let assembled = path.system.assemble(&off, &bc, None, true).unwrap();
        assert!(relative_residual(&assembled, &off) > 1e-6, "{sides:?} {psi}");
    }
}

/// A slab one hexahedron thick with `u_Z = 0` is the plane-strain strip on the same X-Y mesh:
/// the two codes (quadrilaterals, hexahedra) find the same first bifurcation.
#[test]
fn a_slab_in_plane_strain_bifurcates_where_the_strip_does() {
    let p = Parameters {
        beta: std::f64::consts::FRAC_PI_4,
        ..Parameters::default()
    };
    let materials = Bilayer::new(&p);
    let settings = BifurcationSettings {
        scan_step: 0.02,
        tolerance: 1e-7,
        ..BifurcationSettings::default()
    };
    let slab = PatchPath::new(&materials, patch(Sides::Symmetry, 1), 0.0)
        .unwrap()
        .in_plane_strain()
        .bifurcation(&settings)
        .unwrap();
    let strip = MeshSpec::new(4, 1, 4, 1.0, 8.0, 10.0).with_element(ElementKind::Displacement);
    let plane = find_bifurcation(&materials, strip, &settings).unwrap();
    assert!((slab.d - plane.d).abs() <= 2e-7, "slab {} strip {}", slab.d, plane.d);
    assert_eq!(slab.negative_pivots, plane.negative_pivots);
}
