//! Nonlinear plane-strain finite elements (in progress).
