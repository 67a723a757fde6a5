//! The 9-node biquadratic quadrilateral (Q2): Lagrange shape functions on `[-1, 1]^2` and the
//! 3x3 Gauss rule. Local node `a + 3 b` sits at `(xi, eta) = (a - 1, b - 1)`.

use super::ReferenceElement;

/// The 9-node quadrilateral on `[-1, 1]^2`.
#[derive(Clone, Copy, Debug)]
pub struct Quad9;

/// 1D quadratic Lagrange polynomials on the nodes `-1, 0, 1`.
pub(super) fn lagrange(t: f64) -> [f64; 3] {
    [0.5 * t * (t - 1.0), 1.0 - t * t, 0.5 * t * (t + 1.0)]
}

/// Derivatives of [`lagrange`].
pub(super) fn lagrange_derivative(t: f64) -> [f64; 3] {
    [t - 0.5, -2.0 * t, t + 0.5]
}

/// The 3-point Gauss rule on `[-1, 1]`: points and weights, exact for quintics.
pub(super) fn gauss_1d() -> [(f64, f64); 3] {
    let r = (0.6f64).sqrt();
    [(-r, 5.0 / 9.0), (0.0, 8.0 / 9.0), (r, 5.0 / 9.0)]
}

impl ReferenceElement<2, 9, 9> for Quad9 {
    const NAME: &'static str = "9-node quadrilateral";
    /// `VTK_BIQUADRATIC_QUAD`.
    const VTK_CELL_TYPE: u8 = 28;
    /// VTK's order: four corners counter-clockwise, the four edge midpoints, the centre.
    const VTK_ORDER: [usize; 9] = [0, 2, 8, 6, 1, 5, 7, 3, 4];
    /// The point `xi = eta = 0`, the middle of the 3x3 rule.
    const CENTRE: usize = 4;

    /// `N_a(xi, eta) = l_(a mod 3)(xi) l_(a div 3)(eta)`.
    fn shape_functions(xi: [f64; 2]) -> [f64; 9] {
        let (lx, ly) = (lagrange(xi[0]), lagrange(xi[1]));
        std::array::from_fn(|a| lx[a % 3] * ly[a / 3])
    }

    /// `[dN_a/dxi, dN_a/deta]`.
    fn shape_derivatives(xi: [f64; 2]) -> [[f64; 2]; 9] {
        let (lx, ly) = (lagrange(xi[0]), lagrange(xi[1]));
        let (dx, dy) = (lagrange_derivative(xi[0]), lagrange_derivative(xi[1]));
        std::array::from_fn(|a| [dx[a % 3] * ly[a / 3], lx[a % 3] * dy[a / 3]])
    }

    /// The 3x3 Gauss rule, exact for bi-quintic polynomials.
    fn quadrature() -> [([f64; 2], f64); 9] {
        let points = gauss_1d();
        std::array::from_fn(|g| {
            let ((x, wx), (y, wy)) = (points[g % 3], points[g / 3]);
            ([x, y], wx * wy)
        })
    }

    fn node_coordinates(a: usize) -> [f64; 2] {
        [(a % 3) as f64 - 1.0, (a / 3) as f64 - 1.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::ElementGeometry;

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate() {
        let xi = [0.31, -0.77];
        let n = Quad9::shape_functions(xi);
        let d = Quad9::shape_derivatives(xi);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(d.iter().map(|g| g[0]).sum::<f64>().abs() < 1e-14);
        assert!(d.iter().map(|g| g[1]).sum::<f64>().abs() < 1e-14);
        for a in 0..9 {
            assert!((Quad9::shape_functions(Quad9::node_coordinates(a))[a] - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn shape_derivatives_are_the_central_differences_of_the_shape_functions() {
        let (xi, h) = ([0.23, -0.41], 1e-6);
        let d = Quad9::shape_derivatives(xi);
        for r in 0..2 {
            let shifted = |s: f64| {
                let mut x = xi;
                x[r] += s * h;
                Quad9::shape_functions(x)
            };
            let (plus, minus) = (shifted(1.0), shifted(-1.0));
            for a in 0..9 {
                assert!(((plus[a] - minus[a]) / (2.0 * h) - d[a][r]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn gauss_rule_integrates_quintics_and_area() {
        let integral: f64 = Quad9::quadrature()
            .iter()
            .map(|(x, w)| w * x[0].powi(4) * x[1].powi(2))
            .sum();
        assert!((integral - 0.4 * 2.0 / 3.0).abs() < 1e-15);
        let square: [[f64; 2]; 9] = std::array::from_fn(|a| [(a % 3) as f64, 0.5 * (a / 3) as f64]);
        assert!((ElementGeometry::new::<Quad9>(&square).unwrap().volume() - 2.0).abs() < 1e-14);
        assert_eq!(Quad9::quadrature()[Quad9::CENTRE].0, [0.0, 0.0]);
    }
}
