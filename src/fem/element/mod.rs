//! The element interface. A [`ReferenceElement`] is a shape on its reference domain: its
//! dimension, nodes, shape functions and their derivatives, quadrature rule and VTK cell. An
//! [`ElementGeometry`] maps it onto one element of a mesh (`dN_a/dX` and the weights at the
//! quadrature points, computed once per mesh). A [`FiniteElement`] is what an element computes
//! on that geometry from its nodal displacements: force, energy and tangent. The finite elements
//! are registered by [`ElementKind`], the one place that chooses between them.
//!
//! With `G_a = dN_a/dX` at a quadrature point of weight `w` (reference Jacobian included):
//! `F = I + sum_a u_a (x) G_a`, `f_ai = sum_gp w P_iJ G_aJ`, `K_ai,bk = sum_gp w G_aJ A_iJkL G_bL`,
//! `E = sum_gp w W(F)`. Element unknowns are numbered by [`ELEMENT_DOFS`] (node `a`, component `i`).

use crate::error::{Error, Result};
use crate::material::Tensor2;
use crate::mesh::DofMap;

pub mod displacement;
mod hex27;
mod kind;
pub mod mixed;
mod quad9;

pub use displacement::DisplacementElement;
pub use hex27::Hex27;
pub use kind::{ElementKind, Registry, LOCKING_RATIO};
pub use mixed::{pressures, MixedElement, Penalty, PressureUpdate, Pressures, Volumetric, MAX_PRESSURES, PRESSURES};
pub use quad9::Quad9;

/// A shape on its reference domain, in `D` dimensions with `N` nodes and a quadrature rule of
/// `Q` points.
pub trait ReferenceElement<const D: usize, const N: usize, const Q: usize> {
    /// What the element is, for messages.
    const NAME: &'static str;
    /// VTK's cell type number.
    const VTK_CELL_TYPE: u8;
    /// VTK's node `k` is local node `VTK_ORDER[k]`.
    const VTK_ORDER: [usize; N];
    /// The quadrature point at the element's centre (where cell fields are evaluated).
    const CENTRE: usize;
    /// `N_a(xi)`.
    fn shape_functions(xi: [f64; D]) -> [f64; N];
    /// `dN_a/dxi_r`.
    fn shape_derivatives(xi: [f64; D]) -> [[f64; D]; N];
    /// Quadrature points and weights.
    fn quadrature() -> [([f64; D], f64); Q];
    /// Reference coordinates of local node `a`.
    fn node_coordinates(a: usize) -> [f64; D];
}

/// The element of the plane meshes.
pub type PlaneElement = Quad9;
/// Nodes per element.
pub const NODES: usize = 9;
/// Unknowns per element.
pub const DOFS: usize = ELEMENT_DOFS.count(NODES);
/// Quadrature points per element (3x3).
pub const GAUSS_POINTS: usize = 9;
/// The numbering of an element's own unknowns by its local nodes.
pub const ELEMENT_DOFS: DofMap = DofMap::PLANE;

/// An element vector (forces or displacements) of `U` unknowns, numbered by the element's
/// [`DofMap`] (node `a`, component `i` at `D a + i`).
pub type ElementVector<const U: usize = DOFS> = [f64; U];
/// An element matrix, ordered like [`ElementVector`].
pub type ElementMatrix<const U: usize = DOFS> = [[f64; U]; U];

/// Reference geometry of one element at its quadrature points, computed once per mesh.
#[derive(Clone, Debug)]
pub struct ElementGeometry<const D: usize = 2, const N: usize = NODES, const Q: usize = GAUSS_POINTS> {
    /// `dN_a/dX` at each quadrature point.
    gradients: [[[f64; D]; N]; Q],
    /// Quadrature weight times `det(dX/dxi)`.
    weights: [f64; Q],
    /// Reference position `X` of each quadrature point.
    points: [[f64; D]; Q],
}

impl<const D: usize, const N: usize, const Q: usize> ElementGeometry<D, N, Q> {
    /// The geometry of the reference element `R` on the reference nodes `nodes`;
    /// `det(dX/dxi) <= 0` is an error.
    pub fn new<R: ReferenceElement<D, N, Q>>(nodes: &[[f64; D]; N]) -> Result<Self> {
        let mut gradients = [[[0.0; D]; N]; Q];
        let mut weights = [0.0; Q];
        let mut points = [[0.0; D]; Q];
        for (g, (xi, w)) in R::quadrature().into_iter().enumerate() {
            for (x, n) in nodes.iter().zip(R::shape_functions(xi)) {
                for (p, x_i) in points[g].iter_mut().zip(x) {
                    *p += n * x_i;
                }
            }
            let dn = R::shape_derivatives(xi);
            // j[I][r] = dX_I / dxi_r.
            let mut j = [[0.0; D]; D];
            for (x, d) in nodes.iter().zip(&dn) {
                for (row, &x_i) in j.iter_mut().zip(x) {
                    for (entry, d_r) in row.iter_mut().zip(d) {
                        *entry += x_i * d_r;
                    }
                }
            }
            let det = determinant(&j);
            if !(det > 0.0 && det.is_finite()) {
                return Err(Error::invalid(
                    "mesh",
                    format!("an element with det(dX/dxi) = {det:e} at a Gauss point"),
                    "elements with det(dX/dxi) > 0 (reduce the imperfection)",
                ));
            }
            for (grad, d) in gradients[g].iter_mut().zip(&dn) {
                *grad = physical_gradient(d, &j, det);
            }
            weights[g] = w * det;
        }
        Ok(ElementGeometry {
            gradients,
            weights,
            points,
        })
    }

    /// Reference volume of the element (its area in two dimensions).
    pub fn volume(&self) -> f64 {
        self.weights.iter().sum()
    }

    /// Quadrature weights (quadrature weight times reference Jacobian).
    pub fn weights(&self) -> &[f64; Q] {
        &self.weights
    }

    /// Reference positions of the quadrature points.
    pub fn points(&self) -> &[[f64; D]; Q] {
        &self.points
    }

    /// `dN_a/dX` at quadrature point `g`.
    pub fn gradients(&self, g: usize) -> &[[f64; D]; N] {
        &self.gradients[g]
    }
}

impl<const D: usize, const N: usize, const Q: usize> ElementGeometry<D, N, Q> {
    /// `F = I + Grad u` at quadrature point `g` (`F[i][J]`), of the element's nodal
    /// displacements `u` (`U = D N` unknowns).
    pub fn gradient_at<const U: usize>(&self, g: usize, u: &ElementVector<U>) -> [[f64; D]; D] {
        let dofs = DofMap::of_dimension(D);
        let mut f: [[f64; D]; D] = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
        for (a, grad) in self.gradients[g].iter().enumerate() {
            for (i, row) in f.iter_mut().enumerate() {
                let u_ai = u[dofs.dof(a, i)];
                for (entry, g_j) in row.iter_mut().zip(grad) {
                    *entry += u_ai * g_j;
                }
            }
        }
        f
    }
}

impl ElementGeometry {
    /// `F = I + Grad u` at quadrature point `g`, row-major `[F11, F12, F21, F22]`.
    pub fn deformation_gradient(&self, g: usize, u: &ElementVector) -> Tensor2 {
        crate::material::flat(&self.gradient_at(g, u))
    }
}

/// `det F` of a 2x2 or 3x3 matrix.
pub fn determinant<const D: usize>(j: &[[f64; D]; D]) -> f64 {
    match D {
        2 => j[0][0] * j[1][1] - j[0][1] * j[1][0],
        3 => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
        _ => unreachable!("elements are two- or three-dimensional"),
    }
}

/// `dN/dX = dN/dxi j^-1` (by cofactors over `det`).
fn physical_gradient<const D: usize>(d: &[f64; D], j: &[[f64; D]; D], det: f64) -> [f64; D] {
    match D {
        2 => std::array::from_fn(|c| match c {
            0 => (d[0] * j[1][1] - d[1] * j[1][0]) / det,
            _ => (-d[0] * j[0][1] + d[1] * j[0][0]) / det,
        }),
        3 => {
            // (j^-1)_rc = cof(j)_cr / det, with cof_cr = j[c+1][r+1] j[c+2][r+2] - j[c+1][r+2] j[c+2][r+1].
            let cofactor = |c: usize, r: usize| {
                let (c1, c2, r1, r2) = ((c + 1) % 3, (c + 2) % 3, (r + 1) % 3, (r + 2) % 3);
                j[c1][r1] * j[c2][r2] - j[c1][r2] * j[c2][r1]
            };
            std::array::from_fn(|c| (0..3).map(|r| d[r] * cofactor(c, r)).sum::<f64>() / det)
        }
        _ => unreachable!("elements are two- or three-dimensional"),
    }
}

/// What an element of `U` unknowns contributes besides its tangent.
#[derive(Clone, Copy, Debug)]
pub struct ElementState<const U: usize = DOFS> {
    /// Internal force `f_ai = int P_iJ dN_a/dX_J dV`.
    pub force: ElementVector<U>,
    /// Strain energy `int W(F) dV`.
    pub energy: f64,
    /// The potential whose gradient `force` is: `energy`, except for the mixed element's
    /// volumetric term at fixed multipliers ([`mixed`]).
    pub potential: f64,
    /// Smallest `J = det F` over the quadrature points.
    pub min_jacobian: f64,
}

/// What one element of a mesh computes from its nodal displacements `u` (and, where it has
/// them, its pressure multipliers `lambda`, [`pressures`]`(D)` per element): an element on the
/// geometry of a reference element in `D` dimensions with `N` nodes, `Q` quadrature points and
/// `U = D N` unknowns (by default the plane meshes' [`PlaneElement`]).
pub trait FiniteElement<
    const D: usize = 2,
    const N: usize = NODES,
    const Q: usize = GAUSS_POINTS,
    const U: usize = DOFS,
>: Send + Sync + std::fmt::Debug
{
    /// Force, energy and smallest `J`, and the tangent into `stiffness` when given
    /// (overwritten, symmetric); a constraint is penalised as `penalty` says.
    /// `J <= 0` at a quadrature point is an error.
    fn evaluate(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        u: &ElementVector<U>,
        lambda: &Pressures,
        penalty: Penalty,
        stiffness: Option<&mut ElementMatrix<U>>,
    ) -> Result<ElementState<U>>;

    /// The tangent at `u = 0` of the energy whose stiffness scales each unknown (the viscous
    /// damper's, the minimiser's shift) into `stiffness`.
    fn reference_stiffness(&self, geometry: &ElementGeometry<D, N, Q>, stiffness: &mut ElementMatrix<U>) -> Result<()> {
        self.evaluate(
            geometry,
            &[0.0; U],
            &[0.0; MAX_PRESSURES],
            Penalty::Augmentation(1.0),
            Some(stiffness),
        )
        .map(|_| ())
    }

    /// The Cauchy stress at quadrature point `g` (a full symmetric 3x3 tensor; in plane strain
    /// with `sigma_33` and no out-of-plane shear).
    fn cauchy(
        &self,
        geometry: &ElementGeometry<D, N, Q>,
        g: usize,
        u: &ElementVector<U>,
        lambda: &Pressures,
    ) -> Result<[[f64; 3]; 3]>;

    /// Whether the element carries pressure multipliers in the unknowns' vector.
    fn has_multipliers(&self) -> bool {
        false
    }

    /// One step of the method of multipliers at `u`: the largest violation of the constraint
    /// and the change of each multiplier (zero for elements without multipliers).
    fn multiplier_step(
        &self,
        _geometry: &ElementGeometry<D, N, Q>,
        _u: &ElementVector<U>,
        _lambda: &Pressures,
        _penalty_scale: f64,
    ) -> Result<(f64, Pressures)> {
        Ok((0.0, [0.0; MAX_PRESSURES]))
    }
}
