//! Scenarios: the TOML contract ([`spec`]) and its validated, resolved form
//! ([`Scenario`]) that the solvers run. Validation names the file, the field, the value and
//! what is allowed; nothing downstream sees an invalid value.

pub mod bar_stack;
pub mod budget;
mod cache;
mod oblique;
mod plausible;
pub mod snapshots;
pub mod solid_2d;
pub mod spec;
pub mod units;
mod value;
mod warning;
pub(crate) use value::whole_numbers;

pub use cache::{BuildCache, Columns};
pub use oblique::ObliqueSetup;
pub use plausible::{HIGHEST_FREQUENCY, LOWEST_FREQUENCY};
pub use value::{
    apply_set, deserialize_format, parse_toml, read_base, read_table, same_key, set_dotted,
    table_to_spec, FieldProblem,
};
pub use warning::Warning;

use crate::error::{Error, Result};
use crate::excitation::{Excitation, FileWaveform, ToneBurst, TwoTone, Window};
use crate::law::spec::TangentialSpec;
use crate::law::{ContactLaw, TangentialLaw};
use crate::material::Material;
use spec::{CounterpartKind, IncidentKind, IncidentSpec, MaterialSpec, ScenarioSpec, WindowKind};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A validated scenario, ready to run.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The raw spec it came from.
    pub spec: ScenarioSpec,
    /// File it came from (`<memory>` if built in code).
    pub file: String,
    /// Medium 1.
    pub medium: Material,
    /// Medium 2, or `None` for a rigid wall.
    pub counterpart: Option<Material>,
    /// The contact law.
    pub law: Arc<ContactLaw>,
    /// The incident wave (amplitude resolved).
    pub incident: Arc<dyn Excitation>,
    /// Load ratio xi (model.md section 2), resolved from `amplitude` if not given.
    pub xi: f64,
    /// Probe position x, m (< 0).
    pub probe_x: f64,
    /// The tangential degree of freedom (model.md section 13): present when the scenario
    /// has a shear wave, a tangential law other than `free` or a static shear, and at
    /// oblique incidence.
    pub shear: Option<ShearSetup>,
    /// Oblique incidence (model.md section 14): `None` at normal incidence. When present,
    /// `incident` and `shear.incident` are the incident wave's normal and tangential
    /// tractions at the interface.
    pub oblique: Option<ObliqueSetup>,
}

/// The tangential half of a scenario.
#[derive(Debug, Clone)]
pub struct ShearSetup {
    /// Tangential law (static shear q0 and branch).
    pub tangential: Arc<TangentialLaw>,
    /// Incident shear wave `tau_inc(t)` at the interface (zero when the scenario has none).
    pub incident: Arc<dyn Excitation>,
    /// Whether the scenario has an incident shear wave.
    pub has_wave: bool,
    /// Shear impedance of medium 1, Pa s/m.
    pub z1t: f64,
    /// Shear impedance of medium 2, Pa s/m (`inf`: rigid wall).
    pub z2t: f64,
}

/// A wave of zero amplitude at frequency `f` (Hz): one cycle, for the absent component of
/// a scenario with a single wave type.
fn silent(f: f64) -> Arc<dyn Excitation> {
    Arc::new(ToneBurst::new(0.0, f, 1.0, Window::Rectangular))
}

impl Scenario {
    /// Load and validate a scenario file.
    pub fn load(path: &Path) -> Result<Scenario> {
        let table = value::read_table(path)?;
        Scenario::from_table(table, path)
    }

    /// Validate a parsed TOML table that came from (or stands for) `path`; relative paths in
    /// it are resolved against `path`'s folder.
    pub fn from_table(table: toml::Table, path: &Path) -> Result<Scenario> {
        let file = path.display().to_string();
        let spec = table_to_spec(table, &file)?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scenario::from_spec(spec, &file, &dir)
    }

    /// Parse TOML text (syntax, unknown keys, types), then validate. `file` names the text
    /// in error messages; relative paths in it (excitation files) resolve against the
    /// current folder.
    ///
    /// ```
    /// use contactwave::scenario::Scenario;
    /// let s = Scenario::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"           # E = 5 GPa, nu = 0.35, rho = 1190 kg/m^3
    ///     [interface]
    ///     static_pressure = 0.1e6     # p0, Pa; rigid compression, free traction (defaults)
    ///     [incident]
    ///     frequency = 1e6             # Hz
    ///     cycles = 10
    ///     xi = 0.5                    # load ratio instead of an amplitude
    /// "#, "example.toml").unwrap();
    /// // a plane wave in a half-space: the P-wave modulus M = E (1 - nu) / ((1 + nu) (1 - 2 nu)),
    /// // Z1 = sqrt(M rho), Pa s/m; the counterpart is a rigid wall by default
    /// let m = 5e9 * 0.65 / (1.35 * 0.3);
    /// assert!((s.medium.impedance() / (m * 1190.0_f64).sqrt() - 1.0).abs() < 1e-12);
    /// assert_eq!(s.blocked_factor(), 2.0);
    /// // rigid compression against a rigid wall: xi = p0 / (2 A), so A = 0.1 MPa;
    /// // 10 cycles at 1 MHz last 10 µs
    /// assert!((s.incident.peak() - 0.1e6).abs() < 1e-6);
    /// assert!((s.incident.duration() - 10e-6).abs() < 1e-15);
    /// // an invalid value is an error naming the file, the field and what is allowed
    /// let err = Scenario::from_toml_str(r#"
    ///     [medium]
    ///     material = "pmma"
    ///     [interface]
    ///     static_pressure = -1.0
    ///     [incident]
    ///     frequency = 1e6
    ///     cycles = 10
    ///     xi = 0.5
    /// "#, "bad.toml").unwrap_err();
    /// assert!(err.to_string().contains("bad.toml: field `interface.static_pressure`"));
    /// ```
    pub fn from_toml_str(text: &str, file: &str) -> Result<Scenario> {
        let table = parse_toml(text, file)?;
        let spec = table_to_spec(table, file)?;
        Scenario::from_spec(spec, file, Path::new("."))
    }

    /// Validate and resolve a spec. `base_dir` resolves relative file paths.
    pub fn from_spec(spec: ScenarioSpec, file: &str, base_dir: &Path) -> Result<Scenario> {
        Scenario::from_spec_cached(spec, file, base_dir, &BuildCache::new())
    }

    /// [`Scenario::from_spec`] taking laws and files from `cache` when their inputs are
    /// unchanged (what a template does for each point).
    pub fn from_spec_cached(
        spec: ScenarioSpec,
        file: &str,
        base_dir: &Path,
        cache: &BuildCache,
    ) -> Result<Scenario> {
        let medium = material_of(&spec.medium, file, "medium", Geometry::HalfSpace)?;
        let counterpart = match spec.counterpart.kind {
            CounterpartKind::Rigid => {
                let c = &spec.counterpart;
                if c.material.is_some()
                    || c.youngs_modulus.is_some()
                    || c.density.is_some()
                    || c.poisson_ratio.is_some()
                    || c.shear_modulus.is_some()
                    || c.cl.is_some()
                    || c.ct.is_some()
                {
                    return Err(Error::invalid(
                        file,
                        "counterpart.kind",
                        "rigid",
                        "a rigid wall takes no material; use kind = \"medium\"",
                    ));
                }
                None
            }
            CounterpartKind::Medium => {
                let c = &spec.counterpart;
                Some(material_of(
                    &MaterialSpec {
                        material: c.material.clone(),
                        youngs_modulus: c.youngs_modulus,
                        density: c.density,
                        poisson_ratio: c.poisson_ratio,
                        shear_modulus: c.shear_modulus,
                        cl: c.cl,
                        ct: c.ct,
                    },
                    file,
                    "counterpart",
                    Geometry::HalfSpace,
                )?)
            }
        };
        let p0 = spec.interface.static_pressure;
        let law = cache.law(
            p0,
            &spec.interface.compression,
            &spec.interface.traction,
            file,
            "interface",
        )?;
        let probe_x = spec.probe.x;
        if !probe_x.is_finite() || probe_x >= 0.0 {
            return Err(Error::invalid(
                file,
                "probe.x",
                probe_x,
                "must be < 0 (the probe lies in medium 1, x < 0; the interface is at x = 0)",
            ));
        }
        let spp = spec.solver.samples_per_period();
        if !spec::SAMPLES_PER_PERIOD.contains(&spp) {
            return Err(Error::invalid(
                file,
                "solver.samples_per_period",
                spp,
                "must lie in [16, 100000]",
            ));
        }
        if let Some(tp) = spec.solver.tail_periods
            && !(tp.is_finite() && tp > 0.0 && tp <= 1e5)
        {
            return Err(Error::invalid(
                file,
                "solver.tail_periods",
                tp,
                "must lie in (0, 1e5]",
            ));
        }
        let z1 = medium.impedance();
        let z2 = counterpart.map(|m| m.impedance()).unwrap_or(f64::INFINITY);
        let xi_ref = XiReference {
            law: &law,
            static_pressure: spec.interface.static_pressure,
            z1,
            z2,
            pressure_key: "interface.static_pressure",
        };
        let shear_wave = spec
            .shear_incident
            .as_ref()
            .map(|inc| build_shear_wave(inc, file, base_dir, cache, None))
            .transpose()?;
        let (incident, xi) = match &shear_wave {
            Some(w) if spec.incident.is_absent() => (silent(w.fundamental()), 0.0),
            _ => build_incident_cached(&spec.incident, file, base_dir, Some(&xi_ref), cache)?,
        };
        let request = oblique::requested(&spec, file)?;
        let i = &spec.interface;
        let shear = if shear_wave.is_some()
            || !matches!(i.tangential, TangentialSpec::Free(_))
            || i.static_shear != 0.0
            || request.is_some()
        {
            let tangential = Arc::new(crate::law::registry::build_tangential(
                &i.tangential,
                i.static_shear,
                &law,
                file,
                "interface",
            )?);
            let need = |m: &Material, prefix: &str| {
                m.shear_impedance().ok_or_else(|| {
                    Error::invalid(
                        file,
                        format!("{prefix}.poisson_ratio"),
                        "(missing)",
                        format!(
                            "a shear wave or a tangential law needs the shear modulus of \
                             {prefix}: give `poisson_ratio` in (-1, 0.5), `shear_modulus` \
                             (Pa) or `ct` (m/s), or a preset `material`"
                        ),
                    )
                })
            };
            let z1t = need(&medium, "medium")?;
            let z2t = match &counterpart {
                Some(m) => need(m, "counterpart")?,
                None => f64::INFINITY,
            };
            Some(ShearSetup {
                tangential,
                has_wave: shear_wave.is_some(),
                incident: shear_wave.unwrap_or_else(|| silent(incident.fundamental())),
                z1t,
                z2t,
            })
        } else {
            None
        };
        let (incident, shear, oblique) = match (request, shear) {
            (Some(req), Some(sh)) => {
                let (n, sh, o) =
                    oblique::apply(req, &medium, counterpart.as_ref(), incident, sh, file)?;
                (n, Some(sh), Some(o))
            }
            (_, shear) => (incident, shear, None),
        };
        let scenario = Scenario {
            file: file.to_string(),
            medium,
            counterpart,
            law,
            incident,
            xi,
            probe_x,
            shear,
            oblique,
            spec,
        };
        budget::check_half_space(&scenario)?;
        Ok(scenario)
    }

    /// Acoustic impedance of medium 2, Pa s/m (`inf` for a rigid wall).
    pub fn z2(&self) -> f64 {
        self.counterpart
            .map(|m| m.impedance())
            .unwrap_or(f64::INFINITY)
    }

    /// The wave speeds (m/s) and impedances (Pa s/m) the run uses, named as in
    /// `summary.json`: `medium_wave_speed`, `medium_impedance` (the longitudinal wave: the
    /// P wave in a half-space built from a preset), `medium_shear_wave_speed`,
    /// `medium_shear_impedance` (with a shear modulus), and the same of `counterpart_`
    /// (none for a rigid wall).
    pub fn wave_table(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        let sides = [
            ("medium", Some(&self.medium)),
            ("counterpart", self.counterpart.as_ref()),
        ];
        for (side, m) in sides {
            let Some(m) = m else { continue };
            out.push((format!("{side}_wave_speed"), m.wave_speed()));
            out.push((format!("{side}_impedance"), m.impedance()));
            if let (Some(c), Some(z)) = (m.shear_wave_speed(), m.shear_impedance()) {
                out.push((format!("{side}_shear_wave_speed"), c));
                out.push((format!("{side}_shear_impedance"), z));
            }
        }
        out
    }

    /// Ratio of blocked stress to incident stress, `2 Z2 / (Z1 + Z2)` (2 for a rigid wall).
    pub fn blocked_factor(&self) -> f64 {
        blocked_factor(self.medium.impedance(), self.z2())
    }
}

/// `2 Z2 / (Z1 + Z2)`, 2 when Z2 is infinite.
pub fn blocked_factor(z1: f64, z2: f64) -> f64 {
    if z2.is_infinite() {
        2.0
    } else {
        2.0 * z2 / (z1 + z2)
    }
}

/// `sqrt(1 + (omega/omega1)^2)` of xi (thesis eq. 5.9) with `omega1 = K (1/Z1 + 1/Z2)`.
pub fn xi_factor(law: &ContactLaw, z1: f64, z2: f64, frequency: f64) -> f64 {
    let k = law.compression.stiffness_at_rest();
    if k.is_infinite() {
        return 1.0;
    }
    let omega1 = k * (1.0 / z1 + 1.0 / z2);
    let omega = 2.0 * std::f64::consts::PI * frequency;
    (1.0 + (omega / omega1).powi(2)).sqrt()
}

/// Where a material carries its longitudinal wave: what its preset's modulus becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Geometry {
    /// A bar (thesis chapter 4, the bar stack): Young's modulus E.
    Bar,
    /// A half-space with a plane wave: a preset's P-wave modulus
    /// `E (1 - nu) / ((1 + nu) (1 - 2 nu))`; a stated `youngs_modulus` is used as given
    /// (the thesis' 1D convention), `cl` as `rho cl^2`.
    HalfSpace,
}

pub(crate) fn material_of(
    spec: &MaterialSpec,
    file: &str,
    prefix: &str,
    geometry: Geometry,
) -> Result<Material> {
    let key = |k: &str| format!("{prefix}.{k}");
    let preset = match &spec.material {
        Some(name) => Some(Material::preset(name).ok_or_else(|| {
            Error::invalid(
                file,
                key("material"),
                format!("\"{name}\""),
                format!("must be one of {}", Material::PRESETS.join(", ")),
            )
        })?),
        None => None,
    };
    let density = spec.density.or(preset.map(|m| m.density));
    let Some(density) = density else {
        return Err(Error::invalid(
            file,
            key("material"),
            "(missing)",
            "give a preset `material` or both `youngs_modulus` (Pa) and `density` (kg/m^3)",
        ));
    };
    if !(density.is_finite() && density > 0.0) {
        return Err(Error::invalid(
            file,
            key("density"),
            density,
            "must be a finite number > 0",
        ));
    }
    let finite_pos = |k: &str, v: f64| -> Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(Error::invalid(
                file,
                key(k),
                v,
                "must be a finite number > 0",
            ))
        }
    };
    let both = |a: &str, b: &str, v: f64| {
        Error::invalid(file, key(b), v, format!("give `{a}` or `{b}`, not both"))
    };
    // the modulus is the preset's Young's modulus E when neither key states one
    let from_preset = spec.youngs_modulus.is_none() && spec.cl.is_none();
    let youngs = match (spec.youngs_modulus, spec.cl) {
        (Some(_), Some(cl)) => return Err(both("youngs_modulus", "cl", cl)),
        (Some(e), None) => finite_pos("youngs_modulus", e)?,
        (None, Some(cl)) => density * finite_pos("cl", cl)?.powi(2),
        (None, None) => match preset {
            Some(m) => m.youngs_modulus,
            None => {
                return Err(Error::invalid(
                    file,
                    key("material"),
                    "(missing)",
                    "give a preset `material` or both `youngs_modulus` (Pa) and `density` \
                     (kg/m^3)",
                ));
            }
        },
    };
    let shear = match (spec.poisson_ratio, spec.shear_modulus, spec.ct) {
        (Some(_), Some(g), _) => return Err(both("poisson_ratio", "shear_modulus", g)),
        (Some(_), _, Some(ct)) => return Err(both("poisson_ratio", "ct", ct)),
        (_, Some(_), Some(ct)) => return Err(both("shear_modulus", "ct", ct)),
        (Some(nu), None, None) => {
            if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
                return Err(Error::invalid(
                    file,
                    key("poisson_ratio"),
                    nu,
                    "must lie in (-1, 0.5)",
                ));
            }
            Some(youngs / (2.0 * (1.0 + nu)))
        }
        (None, Some(g), None) => Some(finite_pos("shear_modulus", g)?),
        (None, None, Some(ct)) => Some(density * finite_pos("ct", ct)?.powi(2)),
        (None, None, None) => preset.and_then(|m| {
            // the preset's Poisson ratio, applied to the modulus in effect
            let g = m.shear_modulus?;
            let nu = m.youngs_modulus / (2.0 * g) - 1.0;
            Some(youngs / (2.0 * (1.0 + nu)))
        }),
    };
    let m = Material {
        youngs_modulus: youngs,
        density,
        shear_modulus: shear,
    };
    // a preset in a half-space: the plane P wave travels with the P-wave modulus
    let m = match (geometry, preset) {
        (Geometry::HalfSpace, Some(p)) if from_preset => {
            match spec.poisson_ratio.or_else(|| p.poisson_ratio()) {
                Some(nu) => m.half_space(nu),
                None => m,
            }
        }
        _ => m,
    };
    check_derived(&m, file, prefix)?;
    Ok(m)
}

/// The wave speed and impedance of a material must be finite and > 0: E and rho that are
/// each in range can still overflow them (e.g. E = 1e300 Pa with rho = 1e-300 kg/m^3).
/// The error names both inputs.
pub(crate) fn check_derived(m: &Material, file: &str, prefix: &str) -> Result<()> {
    let (c, z) = (m.wave_speed(), m.impedance());
    let ok = |c: f64, z: f64| c.is_finite() && c > 0.0 && z.is_finite() && z > 0.0;
    if let (Some(ct), Some(zt)) = (m.shear_wave_speed(), m.shear_impedance())
        && !ok(ct, zt)
    {
        return Err(Error::invalid(
            file,
            format!("{prefix}.shear_modulus, {prefix}.density"),
            format!(
                "{:e} Pa, {:e} kg/m^3",
                m.shear_modulus.unwrap_or(0.0),
                m.density
            ),
            format!(
                "give a finite shear wave speed sqrt(G/rho) and impedance (here {ct:e} \
                     m/s, {zt:e} Pa s/m)"
            ),
        ));
    }
    if ok(c, z) {
        return Ok(());
    }
    Err(Error::invalid(
        file,
        format!("{prefix}.youngs_modulus, {prefix}.density"),
        format!("{:e} Pa, {:e} kg/m^3", m.youngs_modulus, m.density),
        format!(
            "give a finite wave speed sqrt(E/rho) and impedance sqrt(E rho) (here {c:e} m/s, \
             {z:e} Pa s/m)"
        ),
    ))
}

fn positive_opt(file: &str, key: &str, v: Option<f64>, default: Option<f64>) -> Result<f64> {
    match v.or(default) {
        None => Err(Error::invalid(
            file,
            key,
            "(missing)",
            "required: a finite number > 0",
        )),
        Some(x) if x.is_finite() && x > 0.0 => Ok(x),
        Some(x) => Err(Error::invalid(file, key, x, "must be a finite number > 0")),
    }
}

/// What the load ratio xi of an incident wave refers to (model.md section 2): the interface
/// it first meets, its static pressure and the impedances on both sides.
pub(crate) struct XiReference<'a> {
    /// The interface law.
    pub law: &'a ContactLaw,
    /// Static pressure p0 of the interface, Pa.
    pub static_pressure: f64,
    /// Impedance before the interface, Pa s/m.
    pub z1: f64,
    /// Impedance after it (`inf` for a rigid obstacle), Pa s/m.
    pub z2: f64,
    /// The scenario key that sets p0 (named in the error when p0 = 0 and xi is given).
    pub pressure_key: &'static str,
}

/// Build the incident waveform of an `[incident]` table and its load ratio xi (0 when
/// there is no loaded interface to refer to), reading a waveform file through `cache`.
pub(crate) fn build_incident_cached(
    inc: &IncidentSpec,
    file: &str,
    base_dir: &Path,
    xi_ref: Option<&XiReference<'_>>,
    cache: &BuildCache,
) -> Result<(Arc<dyn Excitation>, f64)> {
    build_wave(inc, "incident", file, base_dir, xi_ref, cache, None)
}

/// The incident shear wave of a `[shear_incident]` table (amplitude in Pa: a shear wave
/// has no load ratio xi), reading a waveform file through `cache` (over its first
/// `window` seconds only, as [`build_incident_window`]).
pub(crate) fn build_shear_wave(
    inc: &IncidentSpec,
    file: &str,
    base_dir: &Path,
    cache: &BuildCache,
    window: Option<f64>,
) -> Result<Arc<dyn Excitation>> {
    if let Some(x) = inc.xi {
        return Err(Error::invalid(
            file,
            "shear_incident.xi",
            x,
            "a shear wave takes `amplitude` (Pa), not xi",
        ));
    }
    Ok(build_wave(inc, "shear_incident", file, base_dir, None, cache, window)?.0)
}

/// [`build_incident_cached`] of a run that simulates `window` seconds (`None`: as long as
/// the wave): a `kind = "file"` waveform is then read over its first `window` seconds
/// only (and one row beyond), however long the file; `amplitude` and `xi` refer to the
/// peak within that window.
pub(crate) fn build_incident_window(
    inc: &IncidentSpec,
    file: &str,
    base_dir: &Path,
    xi_ref: Option<&XiReference<'_>>,
    cache: &BuildCache,
    window: Option<f64>,
) -> Result<(Arc<dyn Excitation>, f64)> {
    build_wave(inc, "incident", file, base_dir, xi_ref, cache, window)
}

/// [`build_incident_window`] for the table at `prefix` (`incident`, `shear_incident`),
/// applying its `delay`.
pub(crate) fn build_wave(
    inc: &IncidentSpec,
    prefix: &str,
    file: &str,
    base_dir: &Path,
    xi_ref: Option<&XiReference<'_>>,
    cache: &BuildCache,
    simulated: Option<f64>,
) -> Result<(Arc<dyn Excitation>, f64)> {
    let key = |k: &str| format!("{prefix}.{k}");
    let f0 = positive_opt(file, &key("frequency"), inc.frequency, None)?;
    let cycles = positive_opt(file, &key("cycles"), inc.cycles, Some(15.0))?;
    let window = match inc.window {
        WindowKind::Rectangular => Window::Rectangular,
        WindowKind::Hann => Window::Hann,
        WindowKind::HannRamps => {
            let r = inc.ramp_fraction.unwrap_or(0.25);
            if !(r.is_finite() && r > 0.0 && r <= 0.5) {
                return Err(Error::invalid(
                    file,
                    key("ramp_fraction"),
                    r,
                    "must lie in (0, 0.5]",
                ));
            }
            Window::HannRamps { ramp_fraction: r }
        }
    };
    let p0 = xi_ref.map_or(0.0, |r| r.static_pressure);
    let (bf, xf) = match xi_ref {
        Some(r) => (blocked_factor(r.z1, r.z2), xi_factor(r.law, r.z1, r.z2, f0)),
        None => (2.0, 1.0),
    };
    // amplitude <-> xi:  xi = p0 * xf / (bf * amplitude)
    let amplitude = match (inc.amplitude, inc.xi) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                file,
                key("xi"),
                inc.xi.unwrap_or_default(),
                "give either `amplitude` or `xi`, not both",
            ));
        }
        (Some(a), None) => {
            if !(a.is_finite() && a > 0.0 && a <= spec::MAX_AMPLITUDE) {
                return Err(Error::invalid(
                    file,
                    key("amplitude"),
                    a,
                    format!(
                        "a number > 0 and <= {:e} (Pa, or N/m for a 2D point force)",
                        spec::MAX_AMPLITUDE
                    ),
                ));
            }
            Some(a)
        }
        (None, Some(x)) => {
            if !(x.is_finite() && x > 0.0) {
                return Err(Error::invalid(
                    file,
                    key("xi"),
                    x,
                    "must be a finite number > 0",
                ));
            }
            if p0 <= 0.0 {
                let p_key = xi_ref.map_or("an interface", |r| r.pressure_key);
                return Err(Error::invalid(
                    file,
                    key("xi"),
                    x,
                    format!("xi needs a static pressure > 0 ({p_key}); give `amplitude` instead"),
                ));
            }
            let a = p0 * xf / (bf * x);
            if !(a <= spec::MAX_AMPLITUDE) {
                return Err(Error::invalid(
                    file,
                    key("xi"),
                    x,
                    format!(
                        "an xi whose amplitude p0 xf / (bf xi) = {a:e} Pa is at most {:e} Pa",
                        spec::MAX_AMPLITUDE
                    ),
                ));
            }
            Some(a)
        }
        (None, None) => {
            if inc.kind != IncidentKind::File {
                return Err(Error::invalid(
                    file,
                    key("amplitude"),
                    "(missing)",
                    // (xi, the amplitude relative to the static pressure, needs an interface)
                    match xi_ref {
                        Some(_) => "give `amplitude` (Pa, > 0) or `xi` (> 0)",
                        None => "give `amplitude` (> 0: Pa, or N/m for a 2D point force)",
                    },
                ));
            }
            None
        }
    };
    let exc: Arc<dyn Excitation> = match inc.kind {
        IncidentKind::ToneBurst => {
            Arc::new(cache.tone_burst(amplitude.unwrap_or(0.0), f0, cycles, window))
        }
        IncidentKind::TwoTone => {
            let f2 = positive_opt(file, &key("frequency2"), inc.frequency2, None)?;
            if (f2 - f0).abs() <= 1e-9 * f0 {
                return Err(Error::invalid(
                    file,
                    key("frequency2"),
                    f2,
                    format!("must differ from {}", key("frequency")),
                ));
            }
            let r = positive_opt(
                file,
                &key("amplitude_ratio"),
                inc.amplitude_ratio,
                Some(1.0),
            )?;
            Arc::new(TwoTone::new(
                amplitude.unwrap_or(0.0),
                f0,
                f2,
                r,
                cycles,
                window,
            ))
        }
        IncidentKind::File => {
            let rel = inc.path.as_ref().ok_or_else(|| {
                Error::invalid(
                    file,
                    key("path"),
                    "(missing)",
                    "a CSV file (time s, stress Pa) is required with kind = \"file\"",
                )
            })?;
            let p: PathBuf = base_dir.join(rel);
            // a finite simulated window: only its part of the file is read (the cache key
            // holds the window); otherwise the whole file, within the memory budget
            let cols = match simulated.filter(|w| w.is_finite() && *w > 0.0) {
                Some(w) => cache.columns(&p, &format!("{}@{w:e}", key("path")), |p, _| {
                    FileWaveform::read_window(p, &key("path"), Some(w))
                })?,
                None => cache.columns(&p, &key("path"), FileWaveform::read)?,
            };
            let (t, s) = (&cols.0, &cols.1);
            Arc::new(
                FileWaveform::new(t, s, f0, amplitude)
                    .ok_or_else(|| Error::invalid(file, key("path"), rel, "invalid waveform"))?,
            )
        }
    };
    if !(exc.peak() > 0.0) {
        return Err(Error::invalid(
            file,
            key("path"),
            "waveform",
            "the waveform is identically zero",
        ));
    }
    let xi = if p0 > 0.0 {
        p0 * xf / (bf * exc.peak())
    } else {
        0.0
    };
    let delay = inc.delay.unwrap_or(0.0);
    if !(delay.is_finite() && delay >= 0.0) {
        return Err(Error::invalid(
            file,
            key("delay"),
            delay,
            "must be a finite time >= 0 (s)",
        ));
    }
    let exc: Arc<dyn Excitation> = if delay > 0.0 {
        Arc::new(crate::excitation::Delayed::new(exc, delay))
    } else {
        exc
    };
    Ok((exc, xi))
}
