//! Structured meshes of the bilayer (in progress).
