//! Small numerical utilities that no dependency provides in the form needed here.

pub mod banded;
pub mod density;
pub mod dofs;
pub mod grading;
pub mod minimize;
pub mod roots;
