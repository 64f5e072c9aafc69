//! What an identification file resolves to: the unknowns ([`Parameter`], [`Scale`]), the
//! measured data ([`Measured`], [`Observed`]), the estimation options ([`FitOptions`]), the
//! design candidates ([`DesignSpec`]), all held by an [`IdentifySpec`].
//!
//! Plain data at the bottom of the inverse modules: reading the file is `parse`, running
//! the scenarios is `model`.

use std::path::PathBuf;

/// How a parameter is searched and reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// The fit works on `log10(value)` (value > 0).
    Log,
    /// The fit works on the value itself.
    Linear,
}

/// One unknown parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Dotted scenario key, e.g. `interface.traction.stiffness` (unit: that of the key).
    pub key: String,
    /// Lower bound (key's unit).
    pub lower: f64,
    /// Upper bound (key's unit).
    pub upper: f64,
    /// Search scale.
    pub scale: Scale,
    /// Starting value (key's unit).
    pub initial: f64,
    /// Further keys set to the same value (a parameter shared by several interfaces,
    /// e.g. `interface.1.compression.c` tied to `interface.0.compression.c`).
    pub also: Vec<String>,
}

impl Parameter {
    /// Value -> scaled coordinate (log10 for log parameters).
    pub fn to_scaled(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Log => v.log10(),
            Scale::Linear => v,
        }
    }
    /// Scaled coordinate -> value.
    pub fn from_scaled(&self, z: f64) -> f64 {
        match self.scale {
            Scale::Log => 10f64.powf(z),
            Scale::Linear => z,
        }
    }
    /// Bounds in the scaled space.
    pub fn scaled_bounds(&self) -> (f64, f64) {
        (self.to_scaled(self.lower), self.to_scaled(self.upper))
    }
}

/// One observed column with its uncertainties.
#[derive(Debug, Clone, PartialEq)]
pub struct Observed {
    /// Summary key, e.g. `A2_over_A1`.
    pub key: String,
    /// Measured values, one per row.
    pub values: Vec<f64>,
    /// Standard uncertainties (> 0), one per row.
    pub sigma: Vec<f64>,
}

/// The measured data: conditions per row and observed columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Dotted keys set at each row (the control variable first).
    pub conditions: Vec<String>,
    /// `rows[i][k]`: value of `conditions[k]` at row `i`.
    pub rows: Vec<Vec<f64>>,
    /// Observed columns.
    pub observed: Vec<Observed>,
}

impl Measured {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }
    /// True when there is no row.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
    /// Number of residuals (rows x observed columns).
    pub fn residual_count(&self) -> usize {
        self.rows.len() * self.observed.len()
    }
    /// The control variable (first condition).
    pub fn control(&self) -> &str {
        self.conditions.first().map(String::as_str).unwrap_or("")
    }
}

/// Options of the estimation.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Default relative uncertainty of the observed values (without `sigma_` column).
    pub relative_noise: f64,
    /// Default absolute uncertainty added to it (unit of the observed key).
    pub absolute_noise: f64,
    /// Particles of the swarm (0: skip the global stage).
    pub particles: usize,
    /// Swarm iterations.
    pub iterations: u64,
    /// Nelder-Mead iterations.
    pub local_iterations: u64,
    /// Local refinements started from the best distinct points of the swarm (>= 1).
    pub local_starts: usize,
    /// Bootstrap resamples (0: none).
    pub bootstrap: usize,
    /// Nelder-Mead iterations per bootstrap refit.
    pub bootstrap_iterations: u64,
    /// Seed of the swarm and of the bootstrap.
    pub seed: u64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            relative_noise: 0.01,
            absolute_noise: 0.0,
            particles: 16,
            iterations: 20,
            local_iterations: 80,
            local_starts: 3,
            bootstrap: 20,
            bootstrap_iterations: 20,
            seed: 1,
        }
    }
}

/// `[design]`: candidate values of a condition key to rank (`identify --design`).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpec {
    /// Dotted key varied between candidates (default the base's frequency:
    /// `incident.frequency`, or `source.0.signal.frequency` for a 2D base).
    pub key: String,
    /// Candidate values (key's unit).
    pub values: Vec<f64>,
    /// Control-variable values of each candidate experiment (default: those of the data).
    pub control_values: Option<Vec<f64>>,
}

/// A loaded identification file.
#[derive(Debug, Clone)]
pub struct IdentifySpec {
    /// The identification file (or `<dict>`).
    pub file: PathBuf,
    /// The base scenario file.
    pub base: PathBuf,
    /// Base scenario with the `[set]` overrides applied.
    pub base_table: toml::Table,
    /// The data file (`None` when the data were given inline).
    pub data_file: Option<PathBuf>,
    /// The measured data.
    pub measured: Measured,
    /// The unknowns.
    pub parameters: Vec<Parameter>,
    /// Estimation options.
    pub fit: FitOptions,
    /// Experiment design candidates.
    pub design: Option<DesignSpec>,
    /// Raw records as the data (`[records]`): the observed values are their analysis, and
    /// each forward run's signal is reduced alike ([`super::records`]).
    pub records: Option<super::records::RecordsSpec>,
}

impl Measured {
    /// CSV text of the data: conditions, then observed columns (`# comment` lines first).
    pub fn to_csv(&self, comment: &str) -> String {
        let mut s = String::new();
        for line in comment.lines() {
            s.push_str(&format!("# {line}\n"));
        }
        let mut h = self.conditions.clone();
        h.extend(self.observed.iter().map(|o| o.key.clone()));
        s.push_str(&h.join(","));
        s.push('\n');
        for (i, r) in self.rows.iter().enumerate() {
            let mut cells: Vec<String> = r.iter().map(|v| v.to_string()).collect();
            cells.extend(self.observed.iter().map(|o| o.values[i].to_string()));
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }
}
