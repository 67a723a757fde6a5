//! The registration of the finite elements: the one place that chooses the element of an
//! [`ElementKind`], and when the displacement element locks.

use super::{
    DisplacementElement, ElementGeometry, FiniteElement, Hex27, MixedElement, Quad9, ReferenceElement, Volumetric,
};
use crate::error::{Error, Result};
use crate::material::Tissue;
pub use crate::mesh::ElementKind;

/// `K / mu` above which the displacement element locks noticeably (README: its coarse-mesh
/// bifurcation is 1.0e-3 off the linear theory at 100, 3.7e-3 at 1000, and fails from 1e5).
pub const LOCKING_RATIO: f64 = 100.0;

/// The finite elements on one reference element (in `D` dimensions, `N` nodes, `Q` quadrature
/// points, `U` unknowns): which kinds exist there and what each computes.
pub trait Registry<const D: usize, const N: usize, const Q: usize, const U: usize> {
    /// The reference element.
    type Reference: ReferenceElement<D, N, Q>;

    /// An error naming the element when this kind has no element on [`Registry::Reference`].
    fn check_available(kind: ElementKind) -> Result<()>;

    /// The element of `kind` on `geometry` of `tissue`; `constraint` resists the mixed
    /// element's volume change through multipliers (the displacement element has none).
    fn element(
        self,
        geometry: &ElementGeometry<D, N, Q>,
        tissue: &Tissue,
        constraint: Option<Volumetric>,
    ) -> Box<dyn FiniteElement<D, N, Q, U>>;
}

impl Registry<2, 9, 9, 18> for ElementKind {
    type Reference = Quad9;

    fn check_available(_kind: ElementKind) -> Result<()> {
        Ok(())
    }

    fn element(
        self,
        geometry: &ElementGeometry,
        tissue: &Tissue,
        constraint: Option<Volumetric>,
    ) -> Box<dyn FiniteElement> {
        match self {
            ElementKind::Displacement => Box::new(DisplacementElement::new(tissue)),
            ElementKind::Mixed => Box::new(<MixedElement>::new(geometry, tissue, constraint)),
        }
    }
}

impl Registry<3, 27, 27, 81> for ElementKind {
    type Reference = Hex27;

    fn check_available(_kind: ElementKind) -> Result<()> {
        Ok(())
    }

    fn element(
        self,
        geometry: &ElementGeometry<3, 27, 27>,
        tissue: &Tissue,
        constraint: Option<Volumetric>,
    ) -> Box<dyn FiniteElement<3, 27, 27, 81>> {
        match self {
            ElementKind::Displacement => Box::new(DisplacementElement::new(tissue)),
            ElementKind::Mixed => Box::new(MixedElement::<3, 27, 4>::new(geometry, tissue, constraint)),
        }
    }
}

impl ElementKind {
    /// Whether this element can model the tissue: exactly incompressible tissue needs the
    /// mixed element (the displacement element cannot keep `J = 1`).
    pub fn check_for(self, incompressible: bool) -> Result<()> {
        if incompressible && self != ElementKind::Mixed {
            return Err(Error::invalid(
                "element",
                self.name(),
                "mixed when incompressible = true (the displacement element cannot keep J = 1)",
            ));
        }
        Ok(())
    }

    /// A one-line note when this element locks for tissues whose largest `K / mu` is `ratio`:
    /// the displacement element above [`LOCKING_RATIO`] (compressible tissue); it points to the
    /// mixed element.
    pub fn locking_note(self, ratio: f64, incompressible: bool) -> Option<String> {
        (self == ElementKind::Displacement && !incompressible && ratio > LOCKING_RATIO).then(|| {
            format!(
                "note: K / mu = {ratio:.1e} with the displacement element, which locks above K / mu ~ {LOCKING_RATIO} \
                 (too stiff in bending; from about 1e5 its runs fail); --element mixed does not"
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_displacement_element_notes_its_locking_above_k_over_mu_100() {
        assert_eq!(ElementKind::Displacement.locking_note(3.0, false), None);
        let note = ElementKind::Displacement.locking_note(1e6, false).unwrap();
        assert!(note.contains("1.0e6") && note.contains("--element mixed"), "{note}");
        assert_eq!(ElementKind::Mixed.locking_note(1e6, false), None);
        assert!(ElementKind::Displacement.locking_note(101.0, false).is_some());
        // Refused elsewhere, with its own message.
        assert_eq!(ElementKind::Displacement.locking_note(1e6, true), None);
    }
}
