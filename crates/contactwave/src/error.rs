//! Errors are values: every failure on user input or in the numerics is an [`Error`],
//! never a panic. Messages name the file, the field, the value and what is allowed.

use std::path::PathBuf;

/// Result alias of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// Everything that can go wrong in contactwave.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A field of a scenario, sweep or data file holds a value outside its allowed range.
    #[error("{file}: field `{field}` = {value}: {allowed}")]
    Invalid {
        /// File the value comes from (`<memory>` for scenarios built in code).
        file: String,
        /// Dotted key of the field, e.g. `interface.traction.stiffness`.
        field: String,
        /// The offending value, as the user wrote it.
        value: String,
        /// What is allowed, e.g. `must be > 0`.
        allowed: String,
    },
    /// A file could not be parsed (syntax error, unknown key, wrong type).
    #[error("{file}: {message}")]
    Parse {
        /// File being parsed.
        file: String,
        /// Parser message, one line, with the field path where known.
        message: String,
    },
    /// The numerics failed: a non-finite state or a root-finder that cannot bracket.
    #[error("numerical failure at t = {time:.9e} s: {message} (state: {state})")]
    Numerical {
        /// Simulation time of the failure, s.
        time: f64,
        /// What failed.
        message: String,
        /// The state at the failure, e.g. `gap = ..., beta = ...`.
        state: String,
    },
    /// Input/output error on a path.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The GPU backend (feature `gpu`) could not run: no driver or device, or a CUDA call
    /// failed.
    #[error("GPU backend: {message}")]
    Device {
        /// What failed, one line.
        message: String,
    },
    /// The run was interrupted (Ctrl-C) before it finished.
    #[error("interrupted")]
    Interrupted,
    /// A bug: a computation panicked (caught by [`crate::run::Executor`]).
    #[error("internal error (panic): {message}")]
    Internal {
        /// The panic's message.
        message: String,
    },
}

/// A value as a message shows it: a number written out with many zeros (`1e-9` displays as
/// `0.000000001`) in exponent form, anything else as it is.
fn shown_value(value: String) -> String {
    match value.parse::<f64>() {
        Ok(v) if v.is_finite() && v != 0.0 && (v.abs() < 1e-4 || v.abs() >= 1e16) => {
            format!("{v:e}")
        }
        _ => value,
    }
}

impl Error {
    /// The error with its field `from` named `to` instead (where the value came from
    /// elsewhere than the key the check knows: a crack's static shear set by the model's
    /// pre-stress); any other error as it is.
    pub fn renamed_field(self, from: &str, to: &str) -> Error {
        match self {
            Error::Invalid {
                file,
                field,
                value,
                allowed,
            } if field == from => Error::Invalid {
                file,
                field: to.to_string(),
                value,
                allowed,
            },
            other => other,
        }
    }

    /// The error with `ctx` (where it arose: `in sweep s.toml at point 3: ...`) in brackets
    /// at the end of its message; other errors than invalid values and parse errors as
    /// they are.
    pub fn within(self, ctx: &str) -> Error {
        match self {
            Error::Invalid {
                file,
                field,
                value,
                allowed,
            } => Error::Invalid {
                file,
                field,
                value,
                allowed: format!("{allowed} ({ctx})"),
            },
            Error::Parse { file, message } => Error::Parse {
                file,
                message: format!("{message} ({ctx})"),
            },
            other => other,
        }
    }

    /// Build an [`Error::Invalid`].
    pub fn invalid(
        file: impl Into<String>,
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            file: file.into(),
            field: field.into(),
            value: shown_value(value.to_string()),
            allowed: allowed.into(),
        }
    }

    /// Build an [`Error::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }

    /// An error writing a file into the folder `dir` (through a temporary name there):
    /// names the user's folder, not the temporary file, and says when the folder is not
    /// writable.
    pub fn write_in(dir: &std::path::Path, source: std::io::Error) -> Self {
        Self::output_folder(dir, source, "cannot write into the output folder")
    }

    /// An error creating the output folder `dir`: says so, and when its parent is not
    /// writable (`/proc/x: cannot create the output folder: No such file or directory`).
    pub fn create_dir(dir: &std::path::Path, source: std::io::Error) -> Self {
        Self::output_folder(dir, source, "cannot create the output folder")
    }

    /// An I/O error of the output folder `dir` (`.` when empty): `what: source`, or that the
    /// folder is not writable.
    fn output_folder(dir: &std::path::Path, source: std::io::Error, what: &str) -> Self {
        let kind = source.kind();
        let message = if kind == std::io::ErrorKind::PermissionDenied {
            format!("the output folder is not writable ({source})")
        } else {
            format!("{what}: {source}")
        };
        let dir = if dir.as_os_str().is_empty() {
            std::path::Path::new(".")
        } else {
            dir
        };
        Error::io(dir, std::io::Error::new(kind, message))
    }

    /// Build an [`Error::Numerical`].
    pub fn numerical(time: f64, message: impl Into<String>, state: impl Into<String>) -> Self {
        Error::Numerical {
            time,
            message: message.into(),
            state: state.into(),
        }
    }

    /// Replace the file name of an `Invalid`/`Parse` error (used when a scenario built in
    /// memory turns out to come from a file).
    pub fn in_file(self, file: &str) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
                ..
            } => Error::Invalid {
                file: file.to_string(),
                field,
                value,
                allowed,
            },
            Error::Parse { message, .. } => Error::Parse {
                file: file.to_string(),
                message,
            },
            other => other,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_and_huge_numbers_show_in_exponent_form() {
        let shown = |v: &dyn std::fmt::Display| match Error::invalid("f", "k", v, "a") {
            Error::Invalid { value, .. } => value,
            _ => unreachable!(),
        };
        assert_eq!(shown(&1.8460981591096744e-9), "1.8460981591096744e-9");
        assert_eq!(shown(&1e-6), "1e-6");
        assert_eq!(shown(&2e20), "2e20");
        assert_eq!(shown(&0.0037500000000000003), "0.0037500000000000003");
        assert_eq!(shown(&-20e12), "-20000000000000");
        assert_eq!(shown(&0.0), "0");
        assert_eq!(shown(&f64::NAN), "NaN");
        assert_eq!(shown(&"rigid"), "rigid");
        assert_eq!(shown(&"[0.019, 0.015]"), "[0.019, 0.015]");
    }
}
