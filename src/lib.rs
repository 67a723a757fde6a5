//! fiberfold: wrinkling, creasing and folding of a stiff layer bonded to a fibre-reinforced
//! substrate under compression.
//!
//! Data flows one way: [`parameters`] -> [`material`] -> ([`homogeneous`] state | stability |
//! finite elements) -> results -> [`output`].

pub mod error;
pub mod fem;
pub mod format;
pub mod homogeneous;
pub mod material;
pub mod mesh;
pub mod numerics;
pub mod output;
pub mod parameters;
pub mod protocol;
pub mod stability;
pub mod studies;

pub use error::{Error, Result};
pub use parameters::Parameters;
