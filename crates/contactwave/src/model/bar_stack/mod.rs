//! The bar-stack model (model.md section 9, thesis chapter 4): segments joined by contact
//! interfaces, hit by a hammer, driven by an imposed displacement or crossed by an
//! incident wave; the explicit FD scheme gives the histories, the analysis the FRF, the
//! first mode and its harmonic, or the reflected and transmitted harmonics.

mod fields;
pub mod files;
mod shear;
mod simulate;
mod waves;

pub use files::{bar_stack_files, FRF_HEADER};
pub use shear::{BarShear, ShearProbeHistory};
pub use simulate::{
    simulate_bar_stack, simulate_bar_stack_with_progress, BarStackResult, Frf, ProbeHistory,
    FRF_FORCE_FLOOR_DB,
};
pub use waves::WaveHistories;

use super::record::summary_record;
use super::template::{FromSpec, SpecTemplate};
use super::{Kind, Model, Outcome, Record, RunControl, Template, Value};
use crate::analysis::Summary;
use crate::error::Result;
use crate::render::{OutputFile, Rows};
use crate::scenario::bar_stack::{BarStackScenario, BarStackSpec};
use crate::scenario::BuildCache;
use std::any::Any;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The bar-stack kind: tables with `[model] kind = "bar_stack"`.
#[derive(Debug)]
pub struct BarStackKind;

/// The registered instance.
pub static KIND: BarStackKind = BarStackKind;

impl Kind for BarStackKind {
    fn name(&self) -> &'static str {
        <BarStackScenario as FromSpec>::KIND
    }

    fn matches(&self, table: &toml::Table) -> bool {
        BarStackScenario::is_bar_stack(table)
    }

    fn plan(&self, table: toml::Table, path: &Path) -> Arc<dyn Template> {
        Arc::new(BarStackTemplate::new(table, path))
    }
}

/// A planned bar-stack scenario with typed parameters.
pub type BarStackTemplate = SpecTemplate<BarStackScenario>;

impl FromSpec for BarStackScenario {
    type Spec = BarStackSpec;
    const KIND: &'static str = "bar_stack";

    fn to_spec(table: toml::Table, file: &str) -> Result<BarStackSpec> {
        BarStackSpec::from_table(table, file)
    }

    fn from_spec(spec: BarStackSpec, file: &str, dir: &Path, cache: &BuildCache) -> Result<Self> {
        BarStackScenario::from_spec_cached(spec, file, dir, cache)
    }

    fn base_dir(path: &Path) -> PathBuf {
        path.parent().unwrap_or(Path::new(".")).to_path_buf()
    }
}

impl Model for BarStackScenario {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn warnings(&self) -> Vec<crate::scenario::Warning> {
        BarStackScenario::warnings(self)
    }

    fn file(&self) -> &str {
        &self.file
    }

    fn load_ratio(&self) -> f64 {
        self.xi
    }

    fn summary(&self) -> Result<Summary> {
        Ok(simulate_bar_stack(self)?.summary)
    }

    fn run(&self, control: &RunControl) -> Result<Box<dyn Outcome>> {
        Ok(Box::new(simulate_bar_stack_with_progress(
            self,
            control.progress.clone(),
        )?))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

impl Outcome for BarStackResult {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn summary(&self) -> &Summary {
        &self.summary
    }

    fn files(&self) -> Result<Vec<OutputFile>> {
        bar_stack_files(self, &self.file, Rows::All)
    }

    fn files_with(&self, rows: Rows) -> Result<Vec<OutputFile>> {
        bar_stack_files(self, &self.file, rows)
    }

    /// `t`, `force`, `displacement`, `acceleration` (arrays), `gap`, `pressure`, `beta`,
    /// `stiffness` (interfaces x samples), `frf` (arrays `frequency`, `receptance`,
    /// `receptance_phase`, `accelerance`, `force_db`; NaN where the force is below
    /// [`FRF_FORCE_FLOOR_DB`]; empty for an incident-wave run),
    /// `waves` (arrays or none), `shear` (the transverse field: `gap`, `stress`, `slip`,
    /// `slip_state` (interfaces x samples), `friction_dissipation`, `damage_dissipation`
    /// (J per interface), `waves`; or none), `probes` (name -> arrays, with
    /// `shear_displacement`, `shear_velocity`, `shear_stress` with a transverse field),
    /// `static_pressure` (list, Pa),
    /// `dt` (s), `summary`.
    fn record(&self) -> Record {
        let frf = Record::new()
            .with("frequency", self.frf.frequency.clone().into())
            .with("receptance", self.frf.receptance.clone().into())
            .with("receptance_phase", self.frf.phase.clone().into())
            .with("accelerance", self.frf.accelerance.clone().into())
            .with("force_db", self.frf.force_db.clone().into());

        let mut probes = Record::new();
        for p in &self.probes {
            let mut r = Record::new()
                .with("x", p.x.into())
                .with("displacement", p.displacement.clone().into())
                .with("velocity", p.velocity.clone().into())
                .with("acceleration", p.acceleration.clone().into())
                .with("stress", p.stress.clone().into());
            if let Some(q) = &p.shear {
                r.push("shear_displacement", q.displacement.clone().into());
                r.push("shear_velocity", q.velocity.clone().into());
                r.push("shear_stress", q.stress.clone().into());
            }
            probes.push(&p.name, r.into());
        }
        let waves_record = |w: &WaveHistories| -> Value {
            let mut r = Record::new()
                .with("incident", w.incident.clone().into())
                .with("reflected", w.reflected.clone().into());
            if let Some(tr) = &w.transmitted {
                r.push("transmitted", tr.clone().into());
            }
            r.into()
        };
        let shear = match &self.shear {
            Some(sh) => Record::new()
                .with("gap", Value::Rows(sh.gap.clone()))
                .with("stress", Value::Rows(sh.stress.clone()))
                .with("slip", Value::Rows(sh.slip.clone()))
                .with("slip_state", Value::Rows(sh.state.clone()))
                .with(
                    "friction_dissipation",
                    Value::List(sh.friction_dissipation.clone()),
                )
                .with(
                    "damage_dissipation",
                    Value::List(sh.damage_dissipation.clone()),
                )
                .with("waves", sh.waves.as_ref().map_or(Value::None, waves_record))
                .into(),
            None => Value::None,
        };
        Record::new()
            .with("kind", Value::Text(KIND.name().into()))
            .with("dt", self.dt.into())
            .with("static_pressure", Value::List(self.static_pressure.clone()))
            .with("gap", Value::Rows(self.gap.clone()))
            .with("pressure", Value::Rows(self.pressure.clone()))
            .with("beta", Value::Rows(self.beta.clone()))
            .with("stiffness", Value::Rows(self.stiffness.clone()))
            .with("frf", frf.into())
            .with(
                "waves",
                self.waves.as_ref().map_or(Value::None, waves_record),
            )
            .with("shear", shear)
            .with("probes", probes.into())
            .with(
                "summary",
                summary_record(Some(&self.file), &self.summary).into(),
            )
            .with("t", self.t.clone().into())
            .with("force", self.force.clone().into())
            .with("displacement", self.displacement.clone().into())
            .with("acceleration", self.acceleration.clone().into())
    }

    fn report(&self) -> Vec<String> {
        let s = &self.summary;
        let get = |k: &str| s.get(k).unwrap_or(f64::NAN);
        let mut lines = Vec::new();
        for (i, p) in self.static_pressure.iter().enumerate() {
            let closure = get(&format!("static_interface_closure_{i}"));
            lines.push(format!(
                "static pressure [{i}]    {p:.6e} Pa (closure {closure:.4e} m)"
            ));
        }
        let shear_wave = self.shear.as_ref().is_some_and(|sh| sh.waves.is_some());
        if self.waves.is_some() {
            lines.push(format!("xi (first interface)   {:.6}", get("xi")));
            lines.push(format!(
                "A1/Ainc (reflected)    {:.6e}",
                get("A1_over_Ainc")
            ));
            lines.push(format!(
                "A2/Ainc (reflected)    {:.6e}",
                get("A2_over_Ainc")
            ));
            if s.get("transmitted_A1_over_Ainc").is_some() {
                lines.push(format!(
                    "A1/Ainc (transmitted)  {:.6e}",
                    get("transmitted_A1_over_Ainc")
                ));
                lines.push(format!(
                    "A2/Ainc (transmitted)  {:.6e}",
                    get("transmitted_A2_over_Ainc")
                ));
            }
            lines.push(format!(
                "energy R / T           {:.6} / {:.6}",
                get("energy_reflected_fraction"),
                s.get("energy_transmitted_fraction").unwrap_or(0.0)
            ));
        } else if !shear_wave {
            lines.push(format!(
                "first mode             {:.2} Hz",
                get("first_mode_hz")
            ));
            lines.push(format!(
                "second harmonic        {:.2} Hz",
                get("second_harmonic_hz")
            ));
            lines.push(format!("A2/A1                  {:.4e}", get("A2_over_A1")));
            lines.push(format!(
                "guide mode             {:.1} Hz",
                get("guide_mode_hz")
            ));
        }
        if shear_wave {
            // ratios are dimensionless; the dissipation is in J over the area S (summed
            // over the interfaces), with its fraction of the incident energy
            for (label, key) in [
                ("shear A1/Ainc (refl.)  ", "shear_A1_over_Ainc"),
                ("shear A3/A1 (refl.)    ", "shear_A3_over_A1"),
                ("shear A3/A1 (transm.)  ", "shear_tr_A3_over_A1"),
                ("friction ratio         ", "friction_ratio"),
                ("friction dissipation   ", "friction_dissipation"),
                ("energy closure error   ", "energy_closure_error"),
            ] {
                if let Some(v) = s.get(key) {
                    lines.push(match key {
                        "friction_dissipation" => format!(
                            "{label}{v:.6e} J ({:.4} of incident)",
                            get("friction_dissipation_fraction")
                        ),
                        _ => format!("{label}{v:.6e}"),
                    });
                }
            }
        }
        lines.push(format!(
            "min contact pressure   {:.4e} Pa",
            get("min_contact_pressure")
        ));
        lines
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}
