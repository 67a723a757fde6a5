//! The library's error type: every failure a user can cause or meet, with a message that names
//! the culprit and, for bad input, the allowed range.

use thiserror::Error;

/// Everything that can go wrong in fiberfold's library.
#[derive(Debug, Error)]
pub enum Error {
    /// A parameter value outside its allowed range (user input).
    #[error("invalid value {value} for `{name}`: allowed range is {allowed}")]
    InvalidParameter {
        name: String,
        value: String,
        allowed: String,
    },

    /// A parameter name that does not exist (user input).
    #[error("unknown parameter `{name}`; known parameters are: {known}")]
    UnknownParameter { name: String, known: String },

    /// A law constant that the law in use needs and that was not given (user input).
    #[error("`{name}` is missing: the {law} law needs it ({allowed})")]
    MissingConstant { name: String, law: String, allowed: String },

    /// A law constant given for a law that does not have it (user input).
    #[error("`{name}` is not a constant of the {law} law in use (its constants: {constants}); set the law first")]
    NotAConstant {
        name: String,
        law: String,
        constants: String,
    },

    /// An option given a value of the wrong type, e.g. a string for a number (user input).
    #[error("`{name}` takes {expected}, not {value}")]
    WrongType {
        name: String,
        value: String,
        expected: String,
    },

    /// A parameter file or `--set` value that cannot be parsed (user input).
    #[error("cannot read parameters: {0}")]
    ParameterSyntax(String),

    /// A deformation with `J = det F <= 0`: the material is inverted or crushed.
    #[error("deformation gradient with J = det F = {jacobian:.6e} <= 0 (inverted material)")]
    NonPositiveJacobian { jacobian: f64 },

    /// A deformation beyond a Gent law's limiting extensibility, where its energy is infinite.
    #[error("deformation beyond the limiting extensibility of a Gent law ((Ibar1 - 3) / Jm = {ratio:.6} >= 1)")]
    BeyondExtensibility { ratio: f64 },

    /// A scalar equation without a root in the searched interval.
    #[error("no root of {what} in [{}, {}]", short(*.lower), short(*.upper))]
    NoRoot { what: String, lower: f64, upper: f64 },

    /// A computation that produced a non-finite number.
    #[error("non-finite value in {0}")]
    NonFinite(String),

    /// Reading or writing a file.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },

    /// A nonlinear solve or a load path that failed (not user input): names where and why.
    #[error("{0}")]
    Solver(String),

    /// The caller asked the computation to stop (e.g. Ctrl-C in Python): says where it was.
    #[error("interrupted: {0}")]
    Interrupted(String),

    /// A checkpoint that a run cannot continue from (user input): says why.
    #[error("cannot resume from {0}")]
    Resume(String),

    /// Rendering a plot.
    #[error("plot {path}: {message}")]
    Plot { path: String, message: String },
}

impl Error {
    /// Whether the error was caused by bad user input (the CLI exits with code 2 for these).
    pub fn is_user_input(&self) -> bool {
        matches!(
            self,
            Error::InvalidParameter { .. }
                | Error::UnknownParameter { .. }
                | Error::ParameterSyntax(_)
                | Error::MissingConstant { .. }
                | Error::NotAConstant { .. }
                | Error::WrongType { .. }
                | Error::Resume(_)
        )
    }

    /// A helper for range violations.
    pub fn invalid(name: &str, value: impl ToString, allowed: &str) -> Self {
        Error::InvalidParameter {
            name: name.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    /// [`Error::invalid`] for a number, written shortly (`1e308`, not its 309 digits).
    pub fn invalid_number(name: &str, value: f64, allowed: &str) -> Self {
        Self::invalid(name, crate::format::format_number(value), allowed)
    }

    /// Attaches a path to an I/O error.
    pub fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.display().to_string(),
            source,
        }
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A number as CSV writes it (`2.25e-6`, not `0.0000022500040889396213`).
fn short(x: f64) -> String {
    crate::format::format_number(x)
}
