//! Plausibility warnings: values that are legal but almost surely a unit slip
//! (`frequency = 1` meant as 1 MHz, `static_pressure = 0.082` meant as MPa), judged from
//! the scenario's own scales. They are values, not errors: the CLI prints each as one line
//! on stderr (and writes them into `summary.json`), Python raises a `UserWarning`. A few are
//! slips that cannot be meant ([`Warning::blocking`]: a 2D run with no wave in it, a plate
//! tens of metres wide): `contactwave run` and `sweep` refuse those unless `--yes`.

use super::bar_stack::BarStackScenario;
use super::solid_2d::{Solid2dScenario, DEFAULT_HARMONIC, DISPERSION_BUDGET};
use super::{IncidentKind, Scenario};
use crate::human::number;
use crate::solver::solid_2d::dispersion::{element_size_for, worst_phase_error};
use crate::solver::solid_2d::Side;

pub use super::warning::Warning;

/// Lowest frequency of a tone burst into a half-space taken at face value, Hz (the bottom
/// of the audio range; the thesis' lowest is 5 kHz).
pub const LOWEST_FREQUENCY: f64 = 20.0;
/// Highest fundamental of a measured record taken at face value, Hz (10 GHz, beyond
/// acoustic microscopy: a record whose time stamps are not in seconds).
pub const HIGHEST_FREQUENCY: f64 = 1e10;
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
/// Lowest wave speed of a solid taken at face value, m/s.
pub const LOWEST_SPEED: f64 = 100.0;
/// A 2D burst whose S wavelength exceeds this many times the rectangle's larger side is
/// taken as a frequency in the wrong unit.
pub const LONGEST_WAVELENGTH: f64 = 10.0;
/// Strain (a stress over the P-wave modulus rho c_P^2) above which a 2D source's amplitude
/// or a crack's closure is taken as a unit slip: linear elasticity and small gaps hold
/// far below it.
pub const LARGEST_STRAIN: f64 = 1e-2;
/// Friction coefficient above which it is taken as a slip (solids' dry friction lies
/// between about 0.05 and 1.5).
pub const LARGEST_FRICTION: f64 = 2.0;
/// A 2D rectangle's side over 1 m and over this many S wavelengths at f0 is taken as a
/// length in the wrong unit (a 2 m plate under a 50 kHz guided wave is 30 wavelengths).
pub const MOST_WAVELENGTHS: f64 = 1e3;
/// Node-updates (nodes times steps) of a 2D run above which it is announced with its size:
/// 1e10, minutes on any machine (the reference case is 4e9; a width in mm read as m gives
/// 1.6e10). How long it takes is measured while it runs (the CLI's time estimate).
pub const LONG_RUN_UPDATES: f64 = 1e10;

/// `v` given in a unit 10^`k` times SI, written in SI as a person types it: `71e9` for 71
/// (GPa), the product where `v` is in exponent form already (`5e-5` MHz is `50`).
fn in_si(v: f64, k: i32) -> String {
    let shown = number(v);
    if shown.contains(['e', 'N', 'i']) {
        number(v * 10f64.powi(k))
    } else {
        format!("{shown}e{k}")
    }
}

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
            blocking: false,
            file: self.file.to_string(),
            field,
            value,
            reason,
        })
    }

    /// [`Warnings::warn`] of a slip that cannot be meant ([`Warning::blocking`]).
    fn stop(&mut self, field: String, value: String, reason: String) {
        self.warn(field, value, reason);
        if let Some(w) = self.out.last_mut() {
            w.blocking = true;
        }
    }

    /// A tone burst's frequencies into a half-space (`prefix.frequency`,
    /// `prefix.frequency2`), Hz, against the bottom of the audio range; `speed` (m/s) gives
    /// the wavelength in the message.
    fn frequencies(&mut self, prefix: &str, freqs: [Option<f64>; 2], speed: f64) {
        for (key, f) in ["frequency", "frequency2"].into_iter().zip(freqs) {
            match f {
                Some(f) if f < LOWEST_FREQUENCY => self.warn(
                    format!("{prefix}.{key}"),
                    format!("{} Hz", number(f)),
                    format!(
                        "below the audio range for a burst into a half-space (wavelength {:.3e} m); \
                         a frequency in MHz? write \"{f} MHz\" or {}",
                        speed / f,
                        in_si(f, 6),
                        f = number(f)
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
                    format!("{} Pa", number(v)),
                    format!(
                        "below 1 MPa, softer than any solid; a modulus in GPa? write \
                         \"{v} GPa\" or {} (SI units: Pa)",
                        in_si(v, 9),
                        v = number(v)
                    ),
                ),
                _ => {}
            }
        }
        match rho {
            Some(rho) if rho < LOWEST_DENSITY => self.warn(
                format!("{prefix}.density"),
                format!("{} kg/m^3", number(rho)),
                format!(
                    "lighter than any solid; a density in g/cm^3? write \"{} g/cm^3\" \
                     or {} (SI units: kg/m^3)",
                    number(rho),
                    number(rho * 1e3)
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
                format!("{} Pa", number(p0)),
                format!(
                    "below 1 kPa; a pressure in MPa? write \"{p0} MPa\" or {} (SI units: Pa)",
                    in_si(p0, 6),
                    p0 = number(p0)
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
                    format!("{} m", number(seg.length)),
                    format!(
                        "a bar longer than {LONGEST_SEGMENT} m; a length in mm? write \
                         \"{} mm\" or {} (SI units: m)",
                        number(seg.length),
                        number(seg.length * 1e-3)
                    ),
                );
            }
        }
        w.out
    }
}

impl Solid2dScenario {
    /// Values of this 2D scenario that are allowed but almost surely a slip: a layer's
    /// moduli, density or wave speeds (km/s for m/s), a width or layer thicker than 10 m,
    /// or than 1 m and [`MOST_WAVELENGTHS`] S wavelengths (mm for m), a crack's closure
    /// under 1 kPa (MPa for Pa), a closure or a source's stress beyond
    /// [`LARGEST_STRAIN`] of rho c_P^2, a friction coefficient over [`LARGEST_FRICTION`],
    /// a source whose S wavelength is more than ten times the rectangle (MHz for Hz: a run
    /// with no wave in it), and an `element_size` (or `time_step`) coarser than the
    /// phase-velocity budget at the highest analysed harmonic (the harmonics then carry
    /// numerical dispersion), a velocity receiver on a rigid side (zero velocity), a
    /// stress receiver of a traction component on a free side (zero), a run over
    /// [`LONG_RUN_UPDATES`] node-updates (announced with its size), and a crack the mesh
    /// resolves too coarsely for its harmonics
    /// ([`Solid2dScenario::crack_resolution_warnings`]). Empty for every shipped
    /// example. A side over 10 m and a source without a wave in the rectangle are
    /// [`Warning::blocking`].
    ///
    /// ```
    /// use contactwave::model;
    /// let m = model::from_toml_str(r#"
    ///     [model]
    ///     kind = "solid_2d"
    ///     width = 4e-3
    ///     duration = 1e-6
    ///     element_size = 0.25e-3
    ///     [[layer]]
    ///     thickness = 2e-3
    ///     material = "aluminium"
    ///     [[source]]
    ///     x0 = 1e-3
    ///     x1 = 3e-3
    ///     signal = { frequency = 5, cycles = 3, amplitude = 1e6 }   # meant: MHz
    /// "#, "slip.toml").unwrap().base().unwrap();
    /// let w = m.warnings();
    /// let slip = w.iter().find(|w| w.field == "source.0.signal.frequency").unwrap();
    /// // no wave fits the plate: a slip that cannot be meant (`run` refuses it without --yes)
    /// assert!(slip.blocking && slip.value == "5 Hz", "{slip:?}");
    /// ```
    pub fn warnings(&self) -> Vec<Warning> {
        let mut w = Warnings::new(&self.file);
        let spec = &self.spec;
        // (a slip that cannot be meant: meshed at the waves' scale, a side of tens of
        // metres is a run of hours to days)
        let long = |w: &mut Warnings, field: String, v: f64| {
            if v > LONGEST_SEGMENT {
                w.stop(
                    field,
                    format!("{} m", number(v)),
                    format!(
                        "longer than {LONGEST_SEGMENT} m; a length in mm? write \"{} mm\" \
                         or {} (SI units: m)",
                        number(v),
                        number(v * 1e-3)
                    ),
                );
            }
        };
        long(&mut w, "model.width".into(), spec.model.width);
        for (i, l) in spec.layers.iter().enumerate() {
            let prefix = format!("layer.{i}");
            long(&mut w, format!("{prefix}.thickness"), l.thickness);
            w.material(&prefix, l.youngs_modulus, None, l.density);
            for (key, v) in [("p_speed", l.p_speed), ("s_speed", l.s_speed)] {
                if let Some(v) = v.filter(|&v| v < LOWEST_SPEED) {
                    w.warn(
                        format!("{prefix}.{key}"),
                        format!("{} m/s", number(v)),
                        format!(
                            "slower than any solid's waves; a speed in km/s? write \
                             \"{} km/s\" or {} (SI units: m/s)",
                            number(v),
                            number(v * 1e3)
                        ),
                    );
                }
            }
        }
        let p = &self.problem;
        // the stiffest and softest P-wave moduli rho c_P^2 of the layers, Pa
        let modulus = |m: &crate::solver::solid_2d::Elastic| m.density * m.p_speed * m.p_speed;
        let soft = p
            .layers
            .iter()
            .map(|l| modulus(&l.material))
            .fold(f64::INFINITY, f64::min);
        let strained = |w: &mut Warnings, field: String, v: f64, what: &str| {
            if soft.is_finite() && v.abs() > LARGEST_STRAIN * soft {
                w.warn(
                    field,
                    format!("{} Pa", number(v)),
                    format!(
                        "{what} strains the solid by {:.1e} (over {LARGEST_STRAIN:e} of \
                         rho c_P^2 = {soft:.3e} Pa): beyond linear elasticity and small gaps; \
                         a value in the wrong unit? (SI units: Pa)",
                        v.abs() / soft
                    ),
                );
            }
        };
        for (i, c) in spec.cracks.iter().enumerate() {
            strained(
                &mut w,
                format!("crack.{i}.static_pressure"),
                c.static_pressure,
                "a closure that",
            );
            let mut tangential = c.tangential.clone();
            if let Some(crate::law::param::ParamMut::F64(mu)) = tangential.param_mut("friction")
                && *mu > LARGEST_FRICTION
            {
                w.warn(
                    format!("crack.{i}.tangential.friction"),
                    mu.to_string(),
                    format!(
                        "a friction coefficient over {LARGEST_FRICTION}: solids' dry \
                             friction lies between about 0.05 and 1.5; a percentage? write {}",
                        *mu / 100.0
                    ),
                );
            }
            let p0 = c.static_pressure;
            if p0 > 0.0 && p0 < LOWEST_PRESSURE {
                w.warn(
                    format!("crack.{i}.static_pressure"),
                    format!("{} Pa", number(p0)),
                    format!(
                        "below 1 kPa; a pressure in MPa? write \"{p0} MPa\" or {} \
                         (SI units: Pa)",
                        in_si(p0, 6),
                        p0 = number(p0)
                    ),
                );
            }
        }
        let cs = p
            .layers
            .iter()
            .map(|l| l.material.s_speed)
            .fold(f64::INFINITY, f64::min);
        let size = p.width.max(p.layers.last().map_or(0.0, |l| l.bottom));
        // a side of thousands of wavelengths at f0 (and over 1 m): a length in mm read as m
        // (over LONGEST_SEGMENT it is said above already)
        if self.f0 > 0.0 && cs.is_finite() {
            let wavelength = cs / self.f0;
            let sides = std::iter::once(("model.width".to_string(), spec.model.width)).chain(
                spec.layers
                    .iter()
                    .enumerate()
                    .map(|(k, l)| (format!("layer.{k}.thickness"), l.thickness)),
            );
            for (field, v) in sides {
                if v > 1.0 && v <= LONGEST_SEGMENT && v > MOST_WAVELENGTHS * wavelength {
                    w.warn(
                        field,
                        format!("{} m", number(v)),
                        format!(
                            "{:.0} S wavelengths at f0 ({wavelength:.3e} m): a length in mm? \
                             write \"{} mm\" or {} (SI units: m)",
                            v / wavelength,
                            number(v),
                            number(v * 1e-3)
                        ),
                    );
                }
            }
        }
        for (i, src) in spec.sources.iter().enumerate() {
            // a traction or a plane wave's stress, Pa (a force is in N/m)
            if src.kind != "force"
                && let Some(a) = src.signal.amplitude
            {
                strained(
                    &mut w,
                    format!("source.{i}.signal.amplitude"),
                    a,
                    "an amplitude that",
                );
            }
            for (key, f) in [
                ("frequency", src.signal.frequency),
                ("frequency2", src.signal.frequency2),
            ] {
                // (a slip that cannot be meant: every harmonic of such a run is null)
                if let Some(f) = f.filter(|&f| cs / f > LONGEST_WAVELENGTH * size) {
                    w.stop(
                        format!("source.{i}.signal.{key}"),
                        format!("{} Hz", number(f)),
                        format!(
                            "its S wavelength ({:.3e} m) is over {LONGEST_WAVELENGTH} times the \
                             rectangle ({size:.3e} m): the run would hold no wave (every A2/A1 \
                             null); a frequency in MHz? write \"{f} MHz\" or {}",
                            cs / f,
                            in_si(f, 6),
                            f = number(f)
                        ),
                    );
                }
            }
        }
        // a run that ends before a source's burst does: the harmonics of a cut burst
        for (i, src) in spec.sources.iter().enumerate() {
            let burst = match (src.signal.kind, src.signal.frequency) {
                (IncidentKind::File, _) | (_, None) => continue,
                (_, Some(f)) => {
                    src.signal.delay.unwrap_or(0.0) + src.signal.cycles.unwrap_or(15.0) / f
                }
            };
            if burst.is_finite() && p.duration < burst {
                w.warn(
                    "model.duration".into(),
                    format!("{} s", number(p.duration)),
                    format!(
                        "shorter than source {i}'s burst ({burst:.3e} s with its delay): the \
                         run ends before the source does, and its harmonics are those of a \
                         cut burst (A2/A1 of a few samples means nothing); a duration longer \
                         than {burst:.3e} s, plus the waves' time of flight to the receivers, \
                         takes the whole burst in"
                    ),
                );
            }
        }
        // a velocity receiver on a rigid side records zeros (no harmonics to analyse)
        let depth = p.depth();
        for (i, r) in spec.receivers.iter().enumerate() {
            let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * size;
            if r.quantity == "stress" {
                // a traction component on a free side is zero: what it records is the
                // scheme's error there (the free surface holds in the weak sense)
                let sh = p.wave == crate::solver::solid_2d::WaveType::Sh;
                let c = r
                    .component
                    .as_deref()
                    .unwrap_or(if sh { "yz" } else { "zz" });
                let horizontal = matches!(c, "zz" | "xz" | "yz");
                let vertical = matches!(c, "xx" | "xz" | "yx");
                let free_at = |at: [f64; 2]| {
                    (horizontal
                        && ((p.top == Side::Free && near(at[1], 0.0))
                            || (p.bottom == Side::Free && near(at[1], depth))))
                        || (vertical
                            && p.sides == Side::Free
                            && (near(at[0], 0.0) || near(at[0], p.width)))
                };
                for (k, at) in std::iter::once(r.at).chain(r.to).enumerate() {
                    if free_at(at) {
                        w.warn(
                            format!("receiver.{i}.{}", if k == 0 { "at" } else { "to" }),
                            format!("[{}, {}] m", at[0], at[1]),
                            format!(
                                "a stress receiver of `{c}` on a free side, where that \
                                 traction is zero: it records the scheme's error there (the \
                                 free surface holds in the weak sense), and its harmonics mean \
                                 nothing; move it inside, record a component along the side \
                                 (`xx` on the top or bottom, `zz` on a side) or the velocity"
                            ),
                        );
                    }
                }
                continue;
            }
            if r.quantity != "velocity" {
                continue;
            }
            for (k, at) in std::iter::once(r.at).chain(r.to).enumerate() {
                let rigid = (p.top == Side::Rigid && near(at[1], 0.0))
                    || (p.bottom == Side::Rigid && near(at[1], depth))
                    || (p.sides == Side::Rigid && (near(at[0], 0.0) || near(at[0], p.width)));
                if rigid {
                    w.warn(
                        format!("receiver.{i}.{}", if k == 0 { "at" } else { "to" }),
                        format!("[{}, {}] m", at[0], at[1]),
                        "on a rigid side: its velocity is zero, so it has no harmonics \
                         (null A2/A1 in summary.json); move it inside or record the stress \
                         (quantity = \"stress\")"
                            .into(),
                    );
                }
            }
        }
        // a run far longer than usual (a crack end, a receiver or a layer that forces tiny
        // elements, or a long duration): say how large before it starts; how long it takes
        // depends on the machine and its load, so the CLI measures it over the first steps
        // (not for a run beyond the memory budget: its refusal says what to change)
        if let Some(e) = p
            .memory_estimate(&self.file)
            .ok()
            .filter(|e| crate::budget::fits(self.runs() * e.total()))
        {
            let updates = e.nodes * e.steps;
            if updates > LONG_RUN_UPDATES {
                w.warn(
                    "model.duration".into(),
                    format!("{} s", number(p.duration)),
                    format!(
                        "about {:.1e} nodes x {:.1e} steps = {updates:.1e} node-updates, over \
                         {LONG_RUN_UPDATES:.0e} (the reference case takes 4e9; `contactwave run` \
                         prints the time it will take from the rate of its first steps); the \
                         smallest element is set by the mesh lines of the cracks' ends, the \
                         receivers and the layers (model.md 15.1): check the units of short \
                         features, model.element_size and model.duration",
                        e.nodes, e.steps,
                    ),
                );
            }
        }
        // absorbing layers many wavelengths thick absorb no better and cost their nodes
        let cp = p
            .layers
            .iter()
            .map(|l| l.material.p_speed)
            .fold(0.0, f64::max);
        if let Some(t) = spec.model.pml_thickness {
            let wavelength = cp / self.f0;
            if self.f0 > 0.0 && t > LONGEST_WAVELENGTH * wavelength {
                w.warn(
                    "model.pml_thickness".into(),
                    format!("{} m", number(t)),
                    format!(
                        "over {LONGEST_WAVELENGTH} P wavelengths at f0 ({wavelength:.3e} m): the \
                         layers absorb no better and their nodes cost time; a thickness in mm? \
                         (SI units: m; the default is 4 elements)"
                    ),
                );
            }
        }
        // the phase velocity at the highest analysed harmonic, where the user chose the
        // element size or the time step (the defaults meet the budget by construction)
        let harmonic = spec.model.harmonic.unwrap_or(DEFAULT_HARMONIC);
        let f_max = harmonic * self.f0;
        let dt = if p.max_time_step.is_finite() {
            p.max_time_step
        } else {
            0.0
        };
        let slip = w.out.iter().any(|x| x.field.starts_with("source."));
        let chosen = spec.model.element_size.is_some() || spec.model.time_step.is_some();
        // (a signal without a known fundamental has no harmonic to judge)
        if chosen && !slip && f_max > 0.0 && f_max.is_finite() {
            // the worst over the layers; `None`: a wave beyond the elements' band edge
            let worst = p.layers.iter().try_fold((0.0f64, None), |acc, l| {
                let (e, branch, deg) =
                    worst_phase_error(p.order, p.element_size, dt, &l.material, p.wave, f_max)
                        .ok()?;
                Some(if e.abs() > acc.0.abs() {
                    (e, Some((branch, deg)))
                } else {
                    acc
                })
            });
            let materials: Vec<_> = p.layers.iter().map(|l| l.material).collect();
            let fits = || {
                element_size_for(p.order, dt, &materials, p.wave, f_max, DISPERSION_BUDGET)
                    .map_or(String::new(), |h| {
                        format!("; the default element_size for it would be {h:.3e} m")
                    })
            };
            let (field, value) = match spec.model.element_size {
                Some(h) => ("model.element_size", format!("{} m", number(h))),
                None => ("model.time_step", format!("{} s", number(dt))),
            };
            let at = format!("{harmonic} f0 ({f_max:.3e} Hz, model.harmonic)");
            match worst {
                None => w.warn(
                    field.into(),
                    value,
                    format!(
                        "the elements do not resolve the waves at {at}: the harmonics computed \
                         there would be numerical artefacts{}",
                        fits()
                    ),
                ),
                Some((e, Some((branch, deg)))) if e.abs() > DISPERSION_BUDGET => w.warn(
                    field.into(),
                    value,
                    format!(
                        "the phase velocity of {branch:?} waves at {at} is {:.2} % off at {deg} \
                         degrees, over the {:.2} % that harmonics need{}",
                        100.0 * e,
                        100.0 * DISPERSION_BUDGET,
                        fits()
                    ),
                ),
                Some(_) => {}
            }
        }
        // a crack too coarse for its harmonics (model.md 15.4): known before the run
        w.out.extend(self.crack_resolution_warnings());
        w.out
    }
}

#[cfg(test)]
mod tests {
    use crate::model;

    /// The plate of `examples/solid_2d/plate_crack_quick.toml` (40 x 10 mm, a 1 MHz
    /// transducer), with `edit` applied to its text.
    fn plate(edit: impl Fn(String) -> String) -> Vec<super::Warning> {
        let text = edit(
            r#"
            [model]
            kind = "solid_2d"
            width = 40e-3
            duration = 20e-6
            harmonic = 2
            [[layer]]
            thickness = 10e-3
            material = "aluminium"
            [[crack]]
            start = [19e-3, 5e-3]
            end = [21e-3, 5e-3]
            static_pressure = 1e6
            [[source]]
            x0 = 8e-3
            x1 = 12e-3
            signal = { frequency = 1e6, cycles = 5, amplitude = 10e6, window = "hann" }
            [[receiver]]
            name = "top_far"
            at = [30e-3, 0.0]
            "#
            .to_string(),
        );
        let m = model::from_toml_str(&text, "plate.toml")
            .and_then(|t| t.base())
            .unwrap_or_else(|e| panic!("{e}"));
        m.warnings()
    }

    /// Issue 56 (8a, 8b): a source whose wave does not fit the plate (5 Hz for 5 MHz) and
    /// a plate tens of metres wide (mm read as m) are slips that cannot be meant; a short
    /// duration or a soft closure only warn, and the plate as shipped draws nothing.
    #[test]
    fn slips_that_cannot_be_meant_block() {
        assert_eq!(plate(|t| t), vec![]);
        let w = plate(|t| t.replace("frequency = 1e6", "frequency = 5"));
        let f = w.iter().find(|w| w.field == "source.0.signal.frequency");
        assert!(f.is_some_and(|f| f.blocking && f.value == "5 Hz"), "{w:?}");
        // the width and the positions along it in mm, read as m: the plate is 40 m wide
        // (coarse elements keep the mesh within any budget)
        let mm = |t: String| {
            t.replace("width = 40e-3", "width = 40\nelement_size = 2e-3")
                .replace("[19e-3, 5e-3]", "[19, 5e-3]")
                .replace("[21e-3, 5e-3]", "[21, 5e-3]")
                .replace("x0 = 8e-3", "x0 = 8")
                .replace("x1 = 12e-3", "x1 = 12")
                .replace("[30e-3, 0.0]", "[30, 0.0]")
        };
        let w = plate(mm);
        let width = w.iter().find(|w| w.field == "model.width");
        assert!(
            width.is_some_and(|w| w.blocking && w.value == "40 m"),
            "{w:?}"
        );
        let w = plate(|t| t.replace("duration = 20e-6", "duration = \"3 us\""));
        assert!(
            !w.is_empty() && w.iter().all(|w| !w.blocking && w.field == "model.duration"),
            "{w:?}"
        );
    }

    /// Issue 56 (8e): a value is shown short, without the round-off of its unit's
    /// conversion ("30 us" is 2.9999999999999997e-5 s), and the long-run line assumes no
    /// machine speed (the CLI measures it).
    #[test]
    fn values_are_shown_short_and_no_speed_is_assumed() {
        let w = plate(|t| {
            t.replace("duration = 20e-6", "duration = \"30 ns\"")
                .replace("cycles = 5", "cycles = 40")
        });
        let d = w.iter().find(|w| w.field == "model.duration").unwrap();
        assert_eq!(d.value, "3e-8 s", "{d:?}");
        // what to write instead reads as a number too
        assert_eq!(super::in_si(71.0, 9), "71e9");
        assert_eq!(super::in_si(0.082, 6), "0.082e6");
        assert_eq!(super::in_si(5e-5, 6), "50");
        assert!(!d.to_string().contains("0000000"), "{d}");
        // a plate 4 m wide at 1 MHz: over 1e10 node-updates
        let w = plate(|t| {
            t.replace("width = 40e-3", "width = 4")
                .replace("harmonic = 2", "harmonic = 1")
                .replace("duration = 20e-6", "duration = 4e-3")
        });
        let long = w.iter().find(|w| w.reason.contains("node-updates"));
        let long = long.unwrap_or_else(|| panic!("{w:?}"));
        assert!(
            !long.reason.contains("1e8") && !long.reason.contains("minutes"),
            "{long}"
        );
        assert!(
            long.reason.contains("from the rate of its first steps"),
            "{long}"
        );
    }
}
