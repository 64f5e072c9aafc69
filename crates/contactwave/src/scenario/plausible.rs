//! Plausibility warnings: values that are legal but almost surely a unit slip
//! (`frequency = 1` meant as 1 MHz, `static_pressure = 0.082` meant as MPa), judged from
//! the scenario's own scales. They are values, not errors: the run goes on; the CLI prints
//! each as one line on stderr, Python raises a `UserWarning`.

use super::Scenario;
use std::fmt;

/// A value that is allowed but looks like a unit slip.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
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

/// Lowest frequency of a tone burst into a half-space taken at face value, Hz (the bottom
/// of the audio range; the thesis' lowest is 5 kHz).
pub const LOWEST_FREQUENCY: f64 = 20.0;
/// Lowest static pressure taken at face value, Pa (1 kPa).
pub const LOWEST_PRESSURE: f64 = 1e3;
/// Lowest elastic modulus of a solid taken at face value, Pa (1 MPa).
pub const LOWEST_MODULUS: f64 = 1e6;
/// Lowest density of a solid taken at face value, kg/m^3.
pub const LOWEST_DENSITY: f64 = 10.0;
/// Longest wave (burst and delay) taken at face value, s: the thesis' bursts last
/// microseconds to milliseconds.
pub const LONGEST_WAVE: f64 = 1.0;

impl Scenario {
    /// Values of this scenario that are allowed but almost surely a unit slip, one
    /// [`Warning`] each (empty for every shipped example).
    ///
    /// ```
    /// use contactwave::scenario::Scenario;
    /// let s = Scenario::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = 0.082     # meant: MPa
    ///     [incident]
    ///     frequency = 1e6
    ///     xi = 0.5
    /// "#, "slip.toml").unwrap();
    /// let w = s.warnings();
    /// assert_eq!(w.len(), 1);
    /// assert!(w[0].to_string().starts_with("slip.toml: interface.static_pressure = 0.082 Pa: "));
    /// ```
    pub fn warnings(&self) -> Vec<Warning> {
        let mut out = Vec::new();
        let mut warn = |field: String, value: String, reason: String| {
            out.push(Warning {
                file: self.file.clone(),
                field,
                value,
                reason,
            })
        };
        let spec = &self.spec;
        let c = self.medium.wave_speed();
        let waves = [
            ("incident", Some(&spec.incident)),
            ("shear_incident", spec.shear_incident.as_ref()),
        ];
        for (prefix, inc) in waves {
            let Some(inc) = inc.filter(|i| !i.is_absent()) else {
                continue;
            };
            for (key, f) in [("frequency", inc.frequency), ("frequency2", inc.frequency2)] {
                match f {
                    Some(f) if f < LOWEST_FREQUENCY => warn(
                        format!("{prefix}.{key}"),
                        format!("{f} Hz"),
                        format!(
                            "below the audio range for a burst into a half-space (wavelength \
                             {:.3e} m); a frequency in MHz? write \"{f} MHz\" or {f}e6",
                            c / f
                        ),
                    ),
                    _ => {}
                }
            }
        }
        let long = self.incident.duration()
            + spec.incident.delay.unwrap_or(0.0)
            + self.shear.as_ref().map_or(0.0, |s| s.incident.duration());
        if long >= LONGEST_WAVE {
            warn(
                "incident".into(),
                format!("{long:.3} s (burst and delay)"),
                "simulates seconds of waves where the thesis' bursts last microseconds to \
                 milliseconds; a frequency or a delay in the wrong unit?"
                    .into(),
            );
        }
        let p0 = spec.interface.static_pressure;
        if p0 > 0.0 && p0 < LOWEST_PRESSURE {
            warn(
                "interface.static_pressure".into(),
                format!("{p0} Pa"),
                format!(
                    "below 1 kPa; a pressure in MPa? write \"{p0} MPa\" or {p0}e6 (SI units: Pa)"
                ),
            );
        }
        let (m, cp) = (&spec.medium, &spec.counterpart);
        let materials = [
            ("medium", m.youngs_modulus, m.shear_modulus, m.density),
            (
                "counterpart",
                cp.youngs_modulus,
                cp.shear_modulus,
                cp.density,
            ),
        ];
        for (prefix, e, g, rho) in materials {
            for (key, v) in [("youngs_modulus", e), ("shear_modulus", g)] {
                match v {
                    Some(v) if v < LOWEST_MODULUS => warn(
                        format!("{prefix}.{key}"),
                        format!("{v} Pa"),
                        format!(
                            "below 1 MPa, softer than any solid; a modulus in GPa? write \
                             \"{v} GPa\" or {v}e9 (SI units: Pa)"
                        ),
                    ),
                    _ => {}
                }
            }
            match rho {
                Some(rho) if rho < LOWEST_DENSITY => warn(
                    format!("{prefix}.density"),
                    format!("{rho} kg/m^3"),
                    format!(
                        "lighter than any solid; a density in g/cm^3? write \"{rho} g/cm^3\" \
                         or {} (SI units: kg/m^3)",
                        rho * 1e3
                    ),
                ),
                _ => {}
            }
        }
        out
    }
}
