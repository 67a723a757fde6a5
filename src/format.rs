//! Numbers as text, for files and messages alike (a leaf module: the error type and the writers
//! both use it).

/// Shortest round-trip text of a number, scientific when very small or large.
pub fn format_number(x: f64) -> String {
    if x == 0.0 || (1e-4..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
