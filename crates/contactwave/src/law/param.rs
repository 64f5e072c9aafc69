//! A law's scenario parameters: the handle `[set]` and sweep axes change them through, and
//! the range checks every law's builder uses (errors name file, field, value and the allowed
//! range).

use crate::error::{Error, Result};

/// A law parameter that `[set]` and sweep axes may change.
#[derive(Debug)]
pub enum ParamMut<'a> {
    /// A required number.
    F64(&'a mut f64),
    /// An optional number (setting it gives it a value).
    OptF64(&'a mut Option<f64>),
}

/// `v` finite and > 0, else an error naming `file`, `field` and the value.
pub(crate) fn positive(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            file,
            field,
            v,
            "must be a finite number > 0",
        ))
    }
}

/// `v` finite and >= 0, else an error naming `file`, `field` and the value.
pub(crate) fn non_negative(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            file,
            field,
            v,
            "must be a finite number >= 0",
        ))
    }
}
