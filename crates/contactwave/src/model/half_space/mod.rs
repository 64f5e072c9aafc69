//! The half-space model (model.md section 4): an incident wave in medium 1 meets one
//! interface backed by a rigid wall or a second half-space; the exact solver (or the FD
//! scheme, `solver.method = "fd"`) gives the interface histories, the probe the reflected
//! wave, the analysis its harmonics.

pub mod files;
pub mod methods;
pub mod oblique;
pub mod shear;
mod simulate;

pub use simulate::{
    half_space, settings, simulate, simulate_in, simulate_summary, simulate_summary_in,
    ProbeSeries, RunResult,
};

use super::record::summary_record;
use super::template::{FromSpec, SpecTemplate};
use super::{Kind, Model, Outcome, Record, RunControl, Template, Value, Waveform, Workspace};
use crate::analysis::{AnalysisMethod, BandAmplitudes, Summary};
use crate::error::Result;
use crate::render::OutputFile;
use crate::scenario::spec::ScenarioSpec;
use crate::scenario::{table_to_spec, BuildCache, Scenario};
use std::any::Any;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The half-space kind: every scenario table that no other kind claims.
#[derive(Debug)]
pub struct HalfSpaceKind;

/// The registered instance.
pub static KIND: HalfSpaceKind = HalfSpaceKind;

impl Kind for HalfSpaceKind {
    fn name(&self) -> &'static str {
        <Scenario as FromSpec>::KIND
    }

    fn matches(&self, _table: &toml::Table) -> bool {
        true
    }

    fn plan(&self, table: toml::Table, path: &Path) -> Arc<dyn Template> {
        Arc::new(HalfSpaceTemplate::new(table, path))
    }
}

/// A planned half-space scenario with typed parameters.
pub type HalfSpaceTemplate = SpecTemplate<Scenario>;

impl FromSpec for Scenario {
    type Spec = ScenarioSpec;
    const KIND: &'static str = "half_space";

    fn to_spec(table: toml::Table, file: &str) -> Result<ScenarioSpec> {
        table_to_spec(table, file)
    }

    fn from_spec(spec: ScenarioSpec, file: &str, dir: &Path, cache: &BuildCache) -> Result<Self> {
        Scenario::from_spec_cached(spec, file, dir, cache)
    }

    fn base_dir(path: &Path) -> PathBuf {
        path.parent().map(Path::to_path_buf).unwrap_or_default()
    }
}

impl Model for Scenario {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn file(&self) -> &str {
        &self.file
    }

    fn load_ratio(&self) -> f64 {
        self.xi
    }

    fn summary(&self) -> Result<Summary> {
        simulate_summary(self)
    }

    fn summary_for(&self, keys: &[&str]) -> Result<Summary> {
        self.summary_for_in(keys, &mut Workspace::new())
    }

    fn summary_in(&self, ws: &mut Workspace) -> Result<Summary> {
        simulate_summary_in(self, ws)
    }

    fn summary_for_in(&self, keys: &[&str], ws: &mut Workspace) -> Result<Summary> {
        // the floor keys (`A*_floor_over_Ainc`, `harmonic_floor_warning`) need the
        // linearised solve
        simulate::simulate_summary_with(self, keys.iter().any(|k| k.contains("floor")), ws)
    }

    fn warnings(&self) -> Vec<crate::scenario::Warning> {
        Scenario::warnings(self)
    }

    fn run(&self, control: &RunControl) -> Result<Box<dyn Outcome>> {
        self.run_in(control, &mut Workspace::new())
    }

    fn twin(&self, method: AnalysisMethod) -> Result<Option<Arc<dyn Model>>> {
        let twin = match method {
            AnalysisMethod::PulseInversion => Some(methods::inverted(self)),
            AnalysisMethod::LinearReference => {
                Some(methods::linearised(self).ok_or_else(|| {
                    crate::error::Error::invalid(
                        &self.file,
                        "analysis.method",
                        "linear_reference",
                        "needs a compression stiffness K(p0) > 0 at the static pressure (a \
                     power law at p0 = 0 has none); use pulse_inversion",
                    )
                })?)
            }
            AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit => None,
        };
        Ok(twin.map(|mut s| {
            s.spec.analysis.method = AnalysisMethod::BandPeak;
            Arc::new(s) as Arc<dyn Model>
        }))
    }

    fn run_in(&self, _control: &RunControl, ws: &mut Workspace) -> Result<Box<dyn Outcome>> {
        crate::scenario::budget::check_half_space_run(self)?;
        Ok(Box::new(simulate_in(self, ws)?))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

fn bands_record(b: &BandAmplitudes, two_tone: bool) -> Record {
    let mut r = Record::new();
    for n in 1..=5 {
        r.push(&format!("A{n}"), b.harmonic[n].into());
    }
    r.push("Asub", b.subharmonic.into());
    if two_tone {
        r.push("Af2", b.f2.into());
        r.push("Asum", b.sum.into());
        r.push("Adiff", b.difference.into());
    }
    r
}

impl Outcome for RunResult {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn summary(&self) -> &Summary {
        &self.summary
    }

    fn files(&self) -> Result<Vec<OutputFile>> {
        files::run_files(self)
    }

    /// Interface arrays (`t`, `gap`, ...), probe arrays (`probe_t`, ...), `summary`,
    /// `spectrum` (frequency, incident, reflected), `incident_bands` / `reflected_bands`
    /// (m/s), `A_inc` (m/s), `dt` (s), `probe_x` (m), `analysis_method` (name) and
    /// `floor_bands` (the method on the linear response, m/s); with a tangential part also
    /// `shear_gap` (m), `shear_stress`, `shear_incident_stress`, `shear_reflected_stress`,
    /// `shear_transmitted_stress` (Pa), `slip` (m), `friction_limit` (Pa), `slip_state`,
    /// `shear_reflected_bands` / `shear_transmitted_bands` (m/s), `shear_A_inc` (m/s).
    fn record(&self) -> Record {
        let o = &self.interface;
        let p = &self.probe;
        let n = self
            .incident_spectrum
            .frequency
            .len()
            .min(self.reflected_spectrum.magnitude.len());
        let cut = |v: &[f64]| Value::Array(v[..n.min(v.len())].to_vec());
        let r = Record::new()
            .with("kind", Value::Text(KIND.name().into()))
            .with("dt", o.dt.into())
            .with("t", o.t.clone().into())
            .with("gap", o.gap.clone().into())
            .with("contact_stress", o.contact_stress.clone().into())
            .with("beta", o.beta.clone().into())
            .with("incident_stress", o.incident_stress.clone().into())
            .with("reflected_stress", o.reflected_stress.clone().into())
            .with("transmitted_stress", o.transmitted_stress.clone().into())
            .with("probe_x", p.x.into())
            .with("probe_t", p.t.clone().into())
            .with("probe_incident_stress", p.incident_stress.clone().into())
            .with("probe_reflected_stress", p.reflected_stress.clone().into())
            .with(
                "probe_incident_velocity",
                p.incident_velocity.clone().into(),
            )
            .with(
                "probe_reflected_velocity",
                p.reflected_velocity.clone().into(),
            )
            .with("probe_displacement", p.displacement.clone().into())
            .with(
                "summary",
                summary_record(Some(&self.file), &files::summary_with_waves(self)).into(),
            )
            .with(
                "spectrum",
                Value::Tuple(vec![
                    cut(&self.incident_spectrum.frequency),
                    cut(&self.incident_spectrum.magnitude),
                    cut(&self.reflected_spectrum.magnitude),
                ]),
            )
            .with(
                "incident_bands",
                bands_record(&self.incident_bands, self.two_tone).into(),
            )
            .with(
                "reflected_bands",
                bands_record(&self.reflected_bands, self.two_tone).into(),
            )
            .with("A_inc", self.a_inc.into())
            .with("analysis_method", Value::Text(self.method.name().into()))
            .with(
                "floor_bands",
                bands_record(&self.floor_bands, self.two_tone).into(),
            );
        match &self.shear {
            Some(sh) => {
                let o = &sh.interface;
                r.with("shear_gap", o.gap.clone().into())
                    .with("shear_stress", o.contact_stress.clone().into())
                    .with("shear_incident_stress", o.incident_stress.clone().into())
                    .with("shear_reflected_stress", o.reflected_stress.clone().into())
                    .with(
                        "shear_transmitted_stress",
                        o.transmitted_stress.clone().into(),
                    )
                    .with("slip", sh.slip.clone().into())
                    .with("friction_limit", sh.friction_limit.clone().into())
                    .with("slip_state", sh.slip_state.clone().into())
                    .with(
                        "shear_reflected_bands",
                        bands_record(&sh.reflected_bands, false).into(),
                    )
                    .with(
                        "shear_transmitted_bands",
                        bands_record(&sh.transmitted_bands, false).into(),
                    )
                    .with("shear_A_inc", sh.a_inc.into())
            }
            None => r,
        }
    }

    fn waveform(&self, name: &str) -> Option<Waveform> {
        let p = &self.probe;
        let samples = match name {
            "incident_stress" => &p.incident_stress,
            "reflected_stress" => &p.reflected_stress,
            "incident_velocity" => &p.incident_velocity,
            "reflected_velocity" => &p.reflected_velocity,
            "displacement" => &p.displacement,
            _ => return None,
        };
        Some(Waveform {
            t0: p.t.first().copied().unwrap_or(0.0),
            dt: self.interface.dt,
            samples: samples.clone(),
        })
    }

    fn waveform_names(&self) -> Vec<String> {
        files::PROBE_HEADER
            .split(',')
            .skip(1)
            .map(String::from)
            .collect()
    }

    fn report(&self) -> Vec<String> {
        let get = |k: &str| self.summary.get(k).unwrap_or(f64::NAN);
        let mut lines = Vec::new();
        // the wave speeds and impedances used, one line per side
        for side in ["medium", "counterpart"] {
            let w = |k: &str| {
                let key = format!("{side}_{k}");
                self.waves.iter().find(|(n, _)| *n == key).map(|(_, v)| *v)
            };
            let Some(c) = w("wave_speed") else {
                lines.push(format!("{side:<23}rigid wall"));
                continue;
            };
            let mut line = format!(
                "{side:<23}c {c:.1} m/s, Z {:.4e} Pa s/m",
                w("impedance").unwrap_or(f64::NAN)
            );
            if let (Some(ct), Some(zt)) = (w("shear_wave_speed"), w("shear_impedance")) {
                line.push_str(&format!("; shear c {ct:.1} m/s, Z {zt:.4e} Pa s/m"));
            }
            lines.push(line);
        }
        let oblique = self.summary.get("angle").is_some();
        if oblique {
            // the outgoing waves, over the incident wave's A_inc (not the interface components)
            lines.push(format!("xi                     {:.6}", get("xi")));
            lines.push(format!("angle                  {:.6} deg", get("angle")));
            lines.push(format!(
                "{:<22} {:>13} {:>13} {:>13}",
                "wave", "A1/Ainc", "A2/A1", "A3/A1"
            ));
            for w in oblique::WAVES {
                if self.summary.get(&format!("{w}_A1_over_Ainc")).is_some() {
                    lines.push(format!(
                        "{:<22} {:>13.6e} {:>13.6e} {:>13.6e}",
                        w.replace('_', " "),
                        get(&format!("{w}_A1_over_Ainc")),
                        get(&format!("{w}_A2_over_A1")),
                        get(&format!("{w}_A3_over_A1"))
                    ));
                }
            }
        } else if self.a_inc > 0.0 {
            lines.extend([
                format!("xi                     {:.6}", get("xi")),
                format!("A1/Ainc                {:.6e}", get("A1_over_Ainc")),
                format!("A2/Ainc                {:.6e}", get("A2_over_Ainc")),
                format!("A2/A1                  {:.6e}", get("A2_over_A1")),
            ]);
        }
        lines.extend([
            format!("beta_end               {:.6}", get("beta_end")),
            format!("contact loss fraction  {:.6}", get("contact_loss_fraction")),
        ]);
        if self.shear.is_some() {
            lines.push(format!(
                "mu p0 / tau_inc        {:.6}",
                get("friction_ratio")
            ));
            if !oblique {
                lines.extend([
                    format!("shear A1/Ainc (refl.)  {:.6e}", get("shear_A1_over_Ainc")),
                    format!("shear A3/A1 (refl.)    {:.6e}", get("shear_A3_over_A1")),
                ]);
            }
            lines.extend([
                format!("slip fraction          {:.6}", get("slip_fraction")),
                format!(
                    "friction dissipation   {:.6e} J/m^2 ({:.4} of incident)",
                    get("friction_dissipation"),
                    get("friction_dissipation_fraction")
                ),
            ]);
            if self.summary.get("shear_tr_A3_over_A1").is_some() {
                lines.push(format!(
                    "shear A3/A1 (transm.)  {:.6e}",
                    get("shear_tr_A3_over_A1")
                ));
            }
        }
        lines.push(format!(
            "energy closure error   {:.3e}",
            get("energy_closure_error")
        ));
        if self.a_inc > 0.0 {
            lines.push(format!("analysis method        {}", self.method.name()));
        }
        lines.extend(
            Outcome::warnings(self)
                .iter()
                .map(|w| format!("warning: {w}")),
        );
        lines
    }

    fn warnings(&self) -> Vec<String> {
        if !(self.a_inc > 0.0) {
            return Vec::new();
        }
        let prefix = if self.summary.get("angle").is_some() {
            "reflected_normal_"
        } else {
            ""
        };
        let near = crate::analysis::harmonics_near_floor(&self.summary, prefix);
        if near.is_empty() {
            return Vec::new();
        }
        let get = |k: String| self.summary.get(&k).unwrap_or(f64::NAN);
        let readings: Vec<String> = near
            .iter()
            .filter_map(|n| {
                crate::analysis::floor_reading(
                    &format!("{prefix}A{n}"),
                    get(format!("{prefix}A{n}_over_Ainc")),
                    get(format!("{prefix}A{n}_floor_over_Ainc")),
                )
            })
            .collect();
        vec![format!(
            "{} (the analysis floor: {} on the linear response, {prefix}A*_floor_over_Ainc); pulse_inversion or linear_reference remove the leakage floor",
            readings.join("; "),
            self.method.name()
        )]
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

#[cfg(test)]
mod tests {
    use crate::model::Model;
    use crate::scenario::Scenario;

    /// A run asked only for non-floor keys gives those keys exactly as the full summary
    /// (the floor's linearised solve is independent of the run), and no floor; asked for a
    /// floor key it gives the floor too.
    #[test]
    fn summary_for_skips_only_the_floor() {
        let s = Scenario::from_toml_str(
            r#"
            [medium]
            material = "pmma"
            [interface]
            static_pressure = 0.082e6
            traction = { law = "rccm", stiffness = 2e13, energy = 0.1, viscosity = 1e-8 }
            [incident]
            frequency = 1e6
            cycles = 10
            xi = 0.5
            [solver]
            samples_per_period = 64
            "#,
            "floor.toml",
        )
        .unwrap();
        let full = s.summary().unwrap();
        let lean = s.summary_for(&["A2_over_Ainc", "beta_end"]).unwrap();
        for key in [
            "A1_over_Ainc",
            "A2_over_Ainc",
            "A3_over_Ainc",
            "beta_end",
            "max_gap",
        ] {
            assert_eq!(full.get(key), lean.get(key), "{key}");
        }
        // the floor of this clapping interface is the burst's leakage: small but not zero
        let floor = full.get("A2_floor_over_Ainc").unwrap();
        assert!(floor > 0.0 && floor < 0.1 * full.get("A2_over_Ainc").unwrap());
        assert!(lean.get("A2_floor_over_Ainc").unwrap().is_nan());
        let with_floor = s.summary_for(&["A2_floor_over_Ainc"]).unwrap();
        assert_eq!(with_floor.get("A2_floor_over_Ainc"), Some(floor));
    }
}
