//! Linear stability (in progress).
