//! Plausibility warnings: values that are legal but almost surely a unit slip
//! (`frequency = 1` meant as 1 MHz, `static_pressure = 0.082` meant as MPa), judged from
//! the scenario's own scales. They are values, not errors: the run goes on; the CLI prints
//! each as one line on stderr, Python raises a `UserWarning`.

use super::bar_stack::BarStackScenario;
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
/// Longest bar segment taken at face value, m (the Tribobrake's guide bar is 0.3 m).
pub const LONGEST_SEGMENT: f64 = 10.0;

/// Collects the warnings of one scenario file.
struct Warnings<'a> {
    file: &'a str,
    out: Vec<Warning>,
}

impl<'a> Warnings<'a> {
    fn new(file: &'a str) -> Self {
        Warnings {
            file,
            out: Vec::new(),
        }
    }

    fn warn(&mut self, field: String, value: String, reason: String) {
        self.out.push(Warning {
            file: self.file.to_string(),
            field,
            value,
            reason,
        })
    }

    /// A tone burst's frequencies into a half-space (`prefix.frequency`,
    /// `prefix.frequency2`), Hz, against the bottom of the audio range; `speed` (m/s) gives
    /// the wavelength in the message.
    fn frequencies(&mut self, prefix: &str, freqs: [Option<f64>; 2], speed: f64) {
        for (key, f) in ["frequency", "frequency2"].into_iter().zip(freqs) {
            match f {
                Some(f) if f < LOWEST_FREQUENCY => self.warn(
                    format!("{prefix}.{key}"),
                    format!("{f} Hz"),
                    format!(
                        "below the audio range for a burst into a half-space (wavelength {:.3e} m); \
                         a frequency in MHz? write \"{f} MHz\" or {f}e6",
                        speed / f
                    ),
                ),
                _ => {}
            }
        }
    }

    /// A wave lasting `long` seconds (burst and delay) at `field`.
    fn duration(&mut self, field: &str, long: f64) {
        if long >= LONGEST_WAVE {
            self.warn(
                field.into(),
                format!("{long:.3} s (burst and delay)"),
                "simulates seconds of waves where the thesis' bursts last microseconds to \
                 milliseconds; a frequency or a delay in the wrong unit?"
                    .into(),
            );
        }
    }

    /// A solid's moduli (Pa) and density (kg/m^3) as given under `prefix`.
    fn material(&mut self, prefix: &str, e: Option<f64>, g: Option<f64>, rho: Option<f64>) {
        for (key, v) in [("youngs_modulus", e), ("shear_modulus", g)] {
            match v {
                Some(v) if v < LOWEST_MODULUS => self.warn(
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
            Some(rho) if rho < LOWEST_DENSITY => self.warn(
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
}

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
        let mut w = Warnings::new(&self.file);
        let spec = &self.spec;
        let c = self.medium.wave_speed();
        let waves = [
            ("incident", Some(&spec.incident)),
            ("shear_incident", spec.shear_incident.as_ref()),
        ];
        for (prefix, inc) in waves {
            if let Some(inc) = inc.filter(|i| !i.is_absent()) {
                w.frequencies(prefix, [inc.frequency, inc.frequency2], c);
            }
        }
        w.duration(
            "incident",
            // the excitations' durations hold their delays
            self.incident
                .duration()
                .max(self.shear.as_ref().map_or(0.0, |s| s.incident.duration())),
        );
        let p0 = spec.interface.static_pressure;
        if p0 > 0.0 && p0 < LOWEST_PRESSURE {
            w.warn(
                "interface.static_pressure".into(),
                format!("{p0} Pa"),
                format!(
                    "below 1 kPa; a pressure in MPa? write \"{p0} MPa\" or {p0}e6 (SI units: Pa)"
                ),
            );
        }
        let (m, cp) = (&spec.medium, &spec.counterpart);
        w.material("medium", m.youngs_modulus, m.shear_modulus, m.density);
        w.material(
            "counterpart",
            cp.youngs_modulus,
            cp.shear_modulus,
            cp.density,
        );
        w.out
    }
}

impl BarStackScenario {
    /// Values of this bar stack that are allowed but almost surely a unit slip: a
    /// segment's moduli and density (as for a half-space) and a segment longer than
    /// 10 m (a length in mm?). Empty for every shipped example. (A burst
    /// frequency in MHz given in Hz needs cells longer than the bars: the scenario is
    /// refused with the key to change before any warning.)
    pub fn warnings(&self) -> Vec<Warning> {
        let mut w = Warnings::new(&self.file);
        for (i, seg) in self.spec.segments.iter().enumerate() {
            let prefix = format!("segment.{i}");
            w.material(&prefix, seg.youngs_modulus, seg.shear_modulus, seg.density);
            if seg.length > LONGEST_SEGMENT {
                w.warn(
                    format!("{prefix}.length"),
                    format!("{} m", seg.length),
                    format!(
                        "a bar longer than {LONGEST_SEGMENT} m; a length in mm? write \
                         \"{} mm\" or {} (SI units: m)",
                        seg.length,
                        seg.length * 1e-3
                    ),
                );
            }
        }
        w.out
    }
}
