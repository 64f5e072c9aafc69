//! A scenario's warning: a value that is allowed but looks like a unit slip (the checks
//! are in `plausible`, and the 2D crack resolution's in `solid_2d::resolution`).

use std::fmt;

/// A value that is allowed but looks like a unit slip.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// A slip that cannot be meant (a run with no wave in it, a plate tens of metres
    /// wide): `contactwave run` and `sweep` refuse the scenario unless `--yes` is given;
    /// the other warnings only warn.
    pub blocking: bool,
    /// File the value comes from.
    pub file: String,
    /// Dotted key of the field, e.g. `incident.frequency`.
    pub field: String,
    /// The value, in SI, with its unit.
    pub value: String,
    /// Why it is suspicious, and what was probably meant.
    pub reason: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {} = {}: {}",
            self.file, self.field, self.value, self.reason
        )
    }
}
