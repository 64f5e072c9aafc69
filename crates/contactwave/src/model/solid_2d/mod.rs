//! The 2D model (`[model] kind = "solid_2d"`, model.md section 15): a scenario planned
//! into the spectral-element solver ([`crate::solver::solid_2d`]), run, and its receivers
//! analysed by the library's methods (model.md section 6.1: band peak, pulse inversion with
//! a second run of the negated sources, linear reference with a second run of the cracks
//! linearised at their static state, plateau fit over the gate; A1...A5 of each
//! receiver's velocity, after the optional time gate); files `summary.json`,
//! `receivers.csv` and `crack.csv`, and with the `plot` feature the plots
//! and pictures of [`pictures`].

mod fields;
pub mod pictures;

use crate::analysis::methods::{gated_bands, leakage_floor, Quantity, Signal};
use crate::analysis::{set_record_harmonics, AnalysisMethod, Summary};
use crate::error::{Error, Result};
use crate::excitation::Scaled;
use crate::law::point::SharedLaw;
use crate::model::half_space::methods::{linearised_law, linearised_tangential};
use crate::model::record::summary_record;
use crate::model::template::{FromSpec, SpecTemplate};
use crate::model::{Kind, Model, Outcome, Record, RunControl, Template, Value, Waveform};
use crate::render::{csv_columns, summary_json, time_series, OutputFile, Rows};
use crate::scenario::solid_2d::{component_names, Solid2dScenario, Solid2dSpec, DEFAULT_HARMONIC};
use crate::scenario::BuildCache;
use crate::solver::solid_2d::dispersion::worst_phase_error;
use crate::solver::solid_2d::{Solid2d, Solid2dOutput};
use pictures::{Geometry, Snapshots2d};
use std::any::Any;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The 2D kind: tables with `[model] kind = "solid_2d"`.
#[derive(Debug)]
pub struct Solid2dKind;

/// The registered instance.
pub static KIND: Solid2dKind = Solid2dKind;

impl Kind for Solid2dKind {
    fn name(&self) -> &'static str {
        <Solid2dScenario as FromSpec>::KIND
    }

    fn matches(&self, table: &toml::Table) -> bool {
        Solid2dScenario::is_solid_2d(table)
    }

    fn frequency_key(&self) -> &'static str {
        "source.0.signal.frequency"
    }

    fn plan(&self, table: toml::Table, path: &Path) -> Arc<dyn Template> {
        Arc::new(SpecTemplate::<Solid2dScenario>::new(table, path))
    }
}

impl FromSpec for Solid2dScenario {
    type Spec = Solid2dSpec;
    const KIND: &'static str = "solid_2d";

    fn to_spec(table: toml::Table, file: &str) -> Result<Solid2dSpec> {
        Solid2dSpec::from_table(table, file)
    }

    fn from_spec(spec: Solid2dSpec, file: &str, dir: &Path, cache: &BuildCache) -> Result<Self> {
        Solid2dScenario::from_spec(spec, file, dir, cache)
    }

    fn base_dir(path: &Path) -> PathBuf {
        path.parent().unwrap_or(Path::new(".")).to_path_buf()
    }
}

/// A 2D run: the solver's output, the receivers' names and the summary.
#[derive(Debug, Clone)]
pub struct Solid2dResult {
    /// Scenario file.
    pub file: String,
    /// The solver's output.
    pub output: Solid2dOutput,
    /// Velocity receivers' names, in the order of the output's traces.
    pub receivers: Vec<String>,
    /// Component names of a velocity receiver (`["x", "z"]` or `["y"]`).
    pub component_names: Vec<&'static str>,
    /// Stress receivers' names, in the order of the output's stress traces.
    pub stress_receivers: Vec<String>,
    /// Component names of a stress receiver (`["xx", "zz", "xz"]` or `["yx", "yz"]`).
    pub stress_component_names: Vec<&'static str>,
    /// Nodes of the mesh.
    pub nodes: usize,
    /// Summary scalars.
    pub summary: Summary,
    /// The wavefield snapshots (`[snapshots]`), on their pixel grid.
    pub snapshots: Option<Snapshots2d>,
    /// What the pictures draw besides the field (the velocity receivers' positions in
    /// the order of `receivers`).
    pub geometry: Geometry,
    /// Positions of the stress receivers `[x, z]` (m), in the order of `stress_receivers`.
    pub stress_points: Vec<[f64; 2]>,
    /// Fundamental of the analysis, Hz.
    pub f0: f64,
}

impl Solid2dScenario {
    /// The whole run's memory ([`Model::memory_estimate`]) against the budget, naming the
    /// key of its larger part (`model.element_size` or `model.pml_thickness` for the mesh,
    /// `model.duration` for the records).
    pub fn budget(&self) -> Result<()> {
        if let Some(q) = &self.mesh {
            return crate::budget::check_or(
                &self.file,
                "mesh.file",
                &q.input.source,
                self.memory_bytes()?,
                &format!(
                    "a 2D run on a mesh of about {:.3e} nodes",
                    q.node_estimate()
                ),
                "a coarser mesh, a lower `mesh.order` or a shorter `model.duration`",
            );
        }
        let e = self.problem.memory_estimate(&self.file)?;
        let stress = self.stress_bytes(e.steps);
        let (key, value, change) = if stress > e.mesh.max(e.series) {
            self.stress_receiver_key()
        } else if e.mesh >= e.series {
            let (key, value, change) = self.problem.mesh_key(e.nodes);
            (key.to_string(), value.to_string(), change.to_string())
        } else {
            let t = self.problem.duration;
            let dt = e.stable_time_step.min(self.problem.max_time_step);
            // what sets the step: the scenario's `time_step`, the phase accuracy at the
            // highest analysed harmonic, or the smallest element's stability
            let by_accuracy = self.problem.max_time_step < e.stable_time_step;
            match (by_accuracy, self.spec.model.time_step) {
                (true, Some(ts)) => (
                    "model.time_step".to_string(),
                    ts.to_string(),
                    "raise `model.time_step` (fewer steps; at most the stable step) or lower \
                     `model.duration`"
                        .to_string(),
                ),
                (true, None) => (
                    "model.duration".to_string(),
                    t.to_string(),
                    format!(
                        "lower `model.duration`; the step, {dt:.2e} s, is set by the phase \
                         accuracy at the highest analysed harmonic (`model.harmonic`)"
                    ),
                ),
                (false, _) => (
                    "model.duration".to_string(),
                    t.to_string(),
                    format!(
                        "lower `model.duration`; the step, {dt:.2e} s, is set by the smallest \
                         element, which a short crack or layer or a receiver near a mesh \
                         line makes small"
                    ),
                ),
            }
        };
        let bytes = self.memory_estimate()?.unwrap_or(0.0);
        crate::budget::check_or(
            &self.file,
            &key,
            value,
            bytes,
            &format!(
                "a 2D run of about {:.3e} nodes and {:.3e} steps",
                e.nodes, e.steps
            ),
            &change,
        )?;
        Ok(())
    }

    /// Plan and run, reporting progress. The whole run's memory
    /// ([`Model::memory_estimate`]) is checked against the budget first, naming the key of
    /// its larger part (`model.element_size` or `model.pml_thickness` for the mesh,
    /// `model.duration` for the records).
    pub fn simulate(&self, control: &RunControl) -> Result<Solid2dResult> {
        self.budget()?;
        let progress = control.progress.as_ref().map(|p| &*p.0);
        // where each receiver records: the node nearest the position asked for (the
        // rectangle), the position itself (a mesh: interpolated)
        let (mut output, nodes, snapshots, at, geometry): (_, _, _, Vec<[f64; 2]>, _) = match self
            .mesh_problem(&self.problem)
        {
            Some(q) => {
                let mut plan = q.plan(&self.file)?;
                self.prepare_mesh_snapshots(&mut plan)?;
                let mut out = plan.run_with(progress)?;
                let capture = std::mem::take(&mut out.snapshots);
                let snapshots = self.mesh_snapshots_of(&plan, capture);
                let at = self
                    .receivers
                    .iter()
                    .map(|r| {
                        if r.stress {
                            self.stress_points[r.index]
                        } else {
                            self.problem.receivers[r.index]
                        }
                    })
                    .collect();
                let geometry = Geometry::of_mesh(self, &plan, &out);
                (out, plan.nodes, snapshots, at, geometry)
            }
            None => {
                let mut plan = self.problem.plan(&self.file)?;
                plan.add_stress_receivers(&self.stress_points, &self.problem.layers, &self.file)?;
                self.prepare_snapshots(&mut plan)?;
                let out = plan.run_on(self.backend, &self.file, progress)?;
                let snapshots = self.snapshots_of(&plan, &out.snapshots);
                let at = self
                    .receivers
                    .iter()
                    .map(|spec| {
                        plan.node_position(if spec.stress {
                            self.stress_points[spec.index]
                        } else {
                            self.problem.receivers[spec.index]
                        })
                    })
                    .collect();
                let nodes = plan.mesh.n_nodes;
                (out, nodes, snapshots, at, Geometry::of(self))
            }
        };
        // the nodal fields are on the pixel grid now
        output.snapshots = Default::default();
        let mut s = Summary::new();
        s.set("nodes", nodes as f64);
        s.set("steps", output.time.len() as f64);
        s.set("dt", output.dt);
        s.set("element_size", self.problem.element_size);
        s.set("phase_error_max", self.phase_error_max(output.dt));
        let e = output.energy;
        if !(e.input.is_finite() && e.solid.is_finite() && e.closure_error().is_finite()) {
            // (the fields stayed finite, or the time loop would have stopped: their squares
            // did not)
            return Err(Error::numerical(
                output.time.last().copied().unwrap_or(0.0),
                "the energies overflow double precision (amplitudes or moduli too large)",
                "solid_2d energy audit",
            ));
        }
        s.set("energy_input", e.input);
        s.set("energy_solid", e.solid);
        s.set("energy_cracks", e.cracks);
        s.set("energy_absorbed", e.absorbed);
        s.set("energy_cracks_tangential", e.cracks_tangential);
        s.set("energy_static_shear_work", e.static_shear_work);
        s.set("energy_friction", e.friction);
        s.set("energy_damage", e.damage);
        s.set("energy_closure_error", e.closure_error());
        for (i, c) in output.cracks.iter().enumerate() {
            s.set(&format!("crack_max_gap_{i}"), c.peak_normal_gap);
            s.set(&format!("crack_max_slip_{i}"), c.peak_slip);
            s.set(&format!("crack_min_adhesion_{i}"), c.least_adhesion);
        }
        let method = self.spec.analysis.method;
        s.set("analysis_method", method.code());
        // the second run a method needs: the sources negated, or the cracks linearised
        let twin = match method {
            AnalysisMethod::PulseInversion => Some(self.inverted()),
            AnalysisMethod::LinearReference => Some(self.linearised()?),
            AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit => None,
        };
        let twin = match twin {
            Some(p) => Some(self.run_problem(&p, control)?.0),
            None => None,
        };
        let (dt, duration) = (output.dt, self.problem.duration);
        for (spec, at) in self.receivers.iter().zip(&at) {
            // each receiver's own window (its [[receiver]] gate, or [analysis]'s)
            let gate = spec.gate.as_ref();
            let sig = Signal {
                quantity: Quantity::Samples,
                dt,
                t0: output.time.first().copied().unwrap_or(0.0),
                f0: self.f0,
                f2: None,
                plateau: gate.map_or((0.0, duration), |g| (g.start, g.end)),
            };
            s.set(&format!("{}_x", spec.name), at[0]);
            s.set(&format!("{}_z", spec.name), at[1]);
            let trace = |o: &'_ Solid2dOutput| -> Vec<f64> {
                if spec.stress {
                    o.stress_trace(spec.index, spec.component).to_vec()
                } else {
                    o.trace(spec.index, spec.component).to_vec()
                }
            };
            let response = trace(&output);
            let other = twin.as_ref().map(trace);
            let pick = |m: AnalysisMethod| other.as_deref().filter(|_| method == m);
            let h = gated_bands(
                method,
                gate,
                &sig,
                &response,
                pick(AnalysisMethod::PulseInversion),
                pick(AnalysisMethod::LinearReference),
            )
            .unwrap_or_default()
            .harmonic;
            set_record_harmonics(&mut s, &format!("{}_", spec.name), &h);
            // the analysis floor: what the method reads at n f0 from the receiver's
            // fundamental alone (the gate's and the record's edges; no noise in a run)
            let floor = leakage_floor(method, &response, gate, &sig);
            let mut near = false;
            for n in 2..=5 {
                s.set(&format!("{}_A{n}_floor", spec.name), floor[n]);
                near |= floor[n] > 0.0 && h[n] < 10.0 * floor[n];
            }
            s.set(
                &format!("{}_harmonic_floor_warning", spec.name),
                if near { 1.0 } else { 0.0 },
            );
        }
        let names = |stress: bool| {
            self.receivers
                .iter()
                .filter(|r| r.stress == stress)
                .map(|r| r.name.clone())
                .collect()
        };
        let wave = self.problem.wave;
        Ok(Solid2dResult {
            file: self.file.clone(),
            receivers: names(false),
            component_names: component_names(false, wave).to_vec(),
            stress_receivers: names(true),
            stress_component_names: component_names(true, wave).to_vec(),
            nodes,
            output,
            summary: s,
            snapshots,
            geometry,
            stress_points: self.stress_points.clone(),
            f0: self.f0,
        })
    }
}

impl Solid2dScenario {
    /// The largest phase velocity error (signed) of the run's waves at its highest
    /// analysed harmonic over every direction and layer, at its element size and time
    /// step `dt` (s), by the Bloch analysis (model.md section 15.4); NaN where a wave sits
    /// on a band edge of the elements.
    fn phase_error_max(&self, dt: f64) -> f64 {
        let p = &self.problem;
        let f_max = self.spec.model.harmonic.unwrap_or(DEFAULT_HARMONIC) * self.f0;
        let mut worst = 0.0f64;
        for layer in &p.layers {
            match worst_phase_error(p.order, p.element_size, dt, &layer.material, p.wave, f_max) {
                Ok((e, _, _)) if e.abs() > worst.abs() => worst = e,
                Ok(_) => {}
                Err(_) => return f64::NAN,
            }
        }
        worst
    }

    /// Plan `problem` with the scenario's stress receivers and run it, reporting progress:
    /// the output and the mesh's node count.
    fn run_problem(
        &self,
        problem: &Solid2d<SharedLaw>,
        control: &RunControl,
    ) -> Result<(Solid2dOutput, usize)> {
        let progress = control.progress.as_ref().map(|p| &*p.0);
        if let Some(q) = self.mesh_problem(problem) {
            let plan = q.plan(&self.file)?;
            return Ok((plan.run_with(progress)?, plan.nodes));
        }
        let mut plan = problem.plan(&self.file)?;
        plan.add_stress_receivers(&self.stress_points, &problem.layers, &self.file)?;
        let nodes = plan.mesh.n_nodes;
        let output = plan.run_on(self.backend, &self.file, progress)?;
        Ok((output, nodes))
    }

    /// The problem with every source's signal negated (pulse inversion's twin).
    fn inverted(&self) -> Solid2d<SharedLaw> {
        let mut p = self.problem.clone();
        for src in &mut p.sources {
            src.signal = Arc::new(Scaled::negated(src.signal.clone()));
        }
        p
    }

    /// The problem with every crack's law linearised at its static state (linear
    /// reference's twin; model/half_space/methods.rs): a law without a finite positive
    /// stiffness there (a power law at zero pressure) is refused.
    fn linearised(&self) -> Result<Solid2d<SharedLaw>> {
        let mut p = self.problem.clone();
        for (i, c) in p.cracks.iter_mut().enumerate() {
            let normal = linearised_law(&c.law.normal).ok_or_else(|| {
                Error::invalid(
                    &self.file,
                    "analysis.method",
                    "linear_reference",
                    format!(
                        "a method other than linear_reference: crack {i}'s law has no finite \
                         positive stiffness at its static state"
                    ),
                )
            })?;
            let p0 = c.law.normal.static_pressure;
            c.law = SharedLaw {
                tangential: Arc::new(linearised_tangential(&c.law.tangential, p0)),
                normal: Arc::new(normal),
            };
        }
        Ok(p)
    }
}

impl Model for Solid2dScenario {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn file(&self) -> &str {
        &self.file
    }

    /// NaN: a finite crack meets the waves the solid carries to it, diffracted and
    /// converted, not one incident wave of a known amplitude.
    fn load_ratio(&self) -> f64 {
        f64::NAN
    }

    fn summary(&self) -> Result<Summary> {
        // the summary needs no pictures: a sweep point or a forward run takes no snapshots
        if self.snapshots.is_some() {
            let mut bare = self.clone();
            bare.snapshots = None;
            return Ok(bare.simulate(&RunControl::default())?.summary);
        }
        Ok(self.simulate(&RunControl::default())?.summary)
    }

    fn run(&self, control: &RunControl) -> Result<Box<dyn Outcome>> {
        Ok(Box::new(self.simulate(control)?))
    }

    fn twin(&self, method: AnalysisMethod) -> Result<Option<Arc<dyn Model>>> {
        let problem = match method {
            AnalysisMethod::PulseInversion => self.inverted(),
            AnalysisMethod::LinearReference => self.linearised()?,
            AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit => return Ok(None),
        };
        let mut twin = self.clone();
        twin.problem = problem;
        twin.spec.analysis.method = AnalysisMethod::BandPeak;
        twin.snapshots = None;
        Ok(Some(Arc::new(twin)))
    }

    /// The solver's estimate ([`Solid2d::memory_estimate`]), twice for a method with a
    /// second run (both plans and outputs are alive at the end); the summary takes no
    /// snapshots.
    fn warnings(&self) -> Vec<crate::scenario::Warning> {
        Solid2dScenario::warnings(self)
    }

    fn memory_estimate(&self) -> Result<Option<f64>> {
        self.memory_bytes().map(Some)
    }

    fn check_budget(&self) -> Result<()> {
        self.budget()
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

impl Solid2dResult {
    /// `receivers.csv`: `t` (s), each velocity receiver's components `<name>_v<c>` (m/s)
    /// and each stress receiver's `<name>_s<cc>` (Pa); none for a run without receivers.
    fn receivers_csv(&self, rows: Rows) -> Option<OutputFile> {
        if self.receivers.is_empty() && self.stress_receivers.is_empty() {
            return None;
        }
        let o = &self.output;
        let mut header = String::from("t");
        let mut cols: Vec<&[f64]> = vec![&o.time];
        for (r, name) in self.receivers.iter().enumerate() {
            for (c, comp) in self.component_names.iter().enumerate() {
                header.push_str(&format!(",{name}_v{comp}"));
                cols.push(o.trace(r, c));
            }
        }
        for (r, name) in self.stress_receivers.iter().enumerate() {
            for (c, comp) in self.stress_component_names.iter().enumerate() {
                header.push_str(&format!(",{name}_s{comp}"));
                cols.push(o.stress_trace(r, c));
            }
        }
        time_series("receivers.csv", &header, &cols, rows)
    }

    /// `crack.csv`: one row per crack node and record: crack index, time (s), position
    /// along the crack (m), normal and tangential gaps (m), normal and shear contact
    /// stresses (Pa), adhesion, state (0 open, 1 stick, 2 slip); every value of a row at the
    /// row's time level, constraint reactions included
    /// ([`crate::solver::solid_2d::CrackRecord`]).
    fn crack_csv(&self) -> OutputFile {
        let mut cols: [Vec<f64>; 9] = Default::default();
        for (i, c) in self.output.cracks.iter().enumerate() {
            let n = c.position.len();
            for (k, &t) in c.time.iter().enumerate() {
                for p in 0..n {
                    let j = k * n + p;
                    let row = [
                        i as f64,
                        t,
                        c.position[p],
                        c.normal_gap[j],
                        c.tangential_gap[j],
                        c.normal_stress[j],
                        c.shear_stress[j],
                        c.adhesion[j],
                        c.state[j],
                    ];
                    for (col, v) in cols.iter_mut().zip(row) {
                        col.push(v);
                    }
                }
            }
        }
        let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
        OutputFile {
            name: "crack.csv".into(),
            contents: csv_columns(
                "crack,t,position,normal_gap,tangential_gap,normal_stress,shear_stress,adhesion,state",
                &refs,
            ),
        }
    }
}

impl Outcome for Solid2dResult {
    fn kind(&self) -> &'static str {
        KIND.name()
    }

    fn summary(&self) -> &Summary {
        &self.summary
    }

    fn files(&self) -> Result<Vec<OutputFile>> {
        self.files_with(Rows::All)
    }

    fn files_with(&self, rows: Rows) -> Result<Vec<OutputFile>> {
        let mut files = vec![OutputFile {
            name: "summary.json".into(),
            contents: summary_json(&self.file, &self.summary),
        }];
        files.extend(self.receivers_csv(rows));
        if !self.output.cracks.is_empty() {
            files.push(self.crack_csv());
        }
        #[cfg(feature = "plot")]
        files.extend(pictures::text_files(self, self.f0)?);
        Ok(files)
    }

    /// The PNG frames and GIF of the snapshots, and the crack maps (the `plot` feature).
    fn binary_files(&self) -> Result<Vec<crate::render::BinaryFile>> {
        #[cfg(feature = "plot")]
        return pictures::binary_files(self);
        #[cfg(not(feature = "plot"))]
        Ok(Vec::new())
    }

    /// `kind`, `t` (s), `receivers` (rows: receiver-major, then component; m/s), `receiver_names`,
    /// `receiver_x`, `receiver_z` (m), `components`, `stresses` (rows like `receivers`, Pa),
    /// `stress_names`, `stress_x`, `stress_z` (m), `stress_components`, `cracks` (per
    /// crack: `position` (m along it), `x`, `z` (m), `time` (s), and rows `(n_nodes,
    /// n_records)` of `normal_gap`, `tangential_gap` (m), `normal_stress`, `shear_stress`
    /// (Pa), `adhesion`, `state` (0 open, 1 stick, 2 slip)), `dt` (s), `summary`; `snapshots` (the frames `[frame][iz][ix]`
    /// flattened, m/s; empty without `[snapshots]`), `snapshot_times` (s), `snapshot_x`,
    /// `snapshot_z` (pixel centres, m), `snapshot_field`.
    fn record(&self) -> Record {
        let o = &self.output;
        let snap = self.snapshots.as_ref();
        let mut rows = Vec::new();
        for r in 0..self.receivers.len() {
            for c in 0..o.components {
                rows.push(o.trace(r, c).to_vec());
            }
        }
        let mut stresses = Vec::new();
        for r in 0..self.stress_receivers.len() {
            for c in 0..o.stress_components {
                stresses.push(o.stress_trace(r, c).to_vec());
            }
        }
        let texts = |v: &[String]| Value::Tuple(v.iter().map(|n| Value::Text(n.clone())).collect());
        let coordinate = |v: &[[f64; 2]], i: usize| -> Value {
            v.iter().map(|p| p[i]).collect::<Vec<f64>>().into()
        };
        let labels =
            |v: &[&str]| Value::Tuple(v.iter().map(|n| Value::Text(n.to_string())).collect());
        let mut cracks = Vec::new();
        for (c, line) in o.cracks.iter().zip(&self.geometry.cracks) {
            let n = c.position.len();
            // the nodes' coordinates from the line's start along its direction
            let [x0, z0, x1, z1] = *line;
            let length = (x1 - x0).hypot(z1 - z0).max(f64::MIN_POSITIVE);
            // (a mesh's crack: each point's own coordinates, `k` 0 for x, 1 for z)
            let along = |a: f64, b: f64, k: usize| -> Value {
                if !c.points.is_empty() {
                    return c.points.iter().map(|p| p[k]).collect::<Vec<f64>>().into();
                }
                c.position
                    .iter()
                    .map(|p| a + p * (b - a) / length)
                    .collect::<Vec<f64>>()
                    .into()
            };
            let by_node = |v: &[f64]| -> Value {
                Value::Rows(
                    (0..n)
                        .map(|p| v.iter().skip(p).step_by(n).copied().collect())
                        .collect(),
                )
            };
            cracks.push(Value::Map(
                Record::new()
                    .with("position", c.position.clone().into())
                    .with("x", along(x0, x1, 0))
                    .with("z", along(z0, z1, 1))
                    .with("time", c.time.clone().into())
                    .with("normal_gap", by_node(&c.normal_gap))
                    .with("tangential_gap", by_node(&c.tangential_gap))
                    .with("normal_stress", by_node(&c.normal_stress))
                    .with("shear_stress", by_node(&c.shear_stress))
                    .with("adhesion", by_node(&c.adhesion))
                    .with("state", by_node(&c.state)),
            ));
        }
        Record::new()
            .with("kind", Value::Text(KIND.name().into()))
            .with("t", o.time.clone().into())
            .with("receivers", Value::Rows(rows))
            .with("receiver_names", texts(&self.receivers))
            .with("receiver_x", coordinate(&self.geometry.receivers, 0))
            .with("receiver_z", coordinate(&self.geometry.receivers, 1))
            .with("stress_x", coordinate(&self.stress_points, 0))
            .with("stress_z", coordinate(&self.stress_points, 1))
            .with("components", labels(&self.component_names))
            .with("stresses", Value::Rows(stresses))
            .with("stress_names", texts(&self.stress_receivers))
            .with("stress_components", labels(&self.stress_component_names))
            .with("cracks", Value::Tuple(cracks))
            .with("dt", Value::Number(o.dt))
            .with(
                "snapshots",
                Value::Array(snap.map(|s| s.raster.values.clone()).unwrap_or_default()),
            )
            .with(
                "snapshot_times",
                Value::Array(snap.map(|s| s.times.clone()).unwrap_or_default()),
            )
            .with(
                "snapshot_x",
                Value::Array(snap.map(|s| s.raster.x.clone()).unwrap_or_default()),
            )
            .with(
                "snapshot_z",
                Value::Array(snap.map(|s| s.raster.z.clone()).unwrap_or_default()),
            )
            .with(
                "snapshot_field",
                Value::Text(snap.map(|s| s.field.clone()).unwrap_or_default()),
            )
            .with("summary", Value::Map(summary_record(None, &self.summary)))
    }

    fn waveform(&self, name: &str) -> Option<Waveform> {
        let o = &self.output;
        let find = |names: &[String], comps: &[&str], tag: &str| {
            names.iter().enumerate().find_map(|(r, n)| {
                comps
                    .iter()
                    .position(|c| name == format!("{n}_{tag}{c}"))
                    .map(|c| (r, c))
            })
        };
        let samples = if let Some((r, c)) = find(&self.receivers, &self.component_names, "v") {
            o.trace(r, c)
        } else {
            let (r, c) = find(&self.stress_receivers, &self.stress_component_names, "s")?;
            o.stress_trace(r, c)
        };
        Some(Waveform {
            t0: o.time.first().copied().unwrap_or(0.0),
            dt: o.dt,
            samples: samples.to_vec(),
        })
    }

    fn waveform_names(&self) -> Vec<String> {
        let mut names = Vec::new();
        for n in &self.receivers {
            names.extend(self.component_names.iter().map(|c| format!("{n}_v{c}")));
        }
        for n in &self.stress_receivers {
            names.extend(
                self.stress_component_names
                    .iter()
                    .map(|c| format!("{n}_s{c}")),
            );
        }
        names
    }

    fn report(&self) -> Vec<String> {
        let s = &self.summary;
        let get = |k: &str| s.get(k).unwrap_or(f64::NAN);
        let mut lines = vec![
            format!(
                "mesh                   {} nodes, {} steps of {:.4e} s",
                self.nodes,
                self.output.time.len(),
                self.output.dt
            ),
            match get("phase_error_max") {
                e if e.is_nan() => "phase error max        NaN (a wave at the analysed harmonic \
                                    is beyond what the elements resolve: a smaller element_size)"
                    .to_string(),
                e => format!(
                    "phase error max        {e:.3e} (every wave and direction at the analysed harmonic)"
                ),
            },
            format!("energy input           {:.6e} J/m", get("energy_input")),
            format!("energy closure error   {:.3e}", get("energy_closure_error")),
        ];
        for i in 0..self.output.cracks.len() {
            lines.push(format!(
                "crack {i} max gap        {:.6e} m   max slip {:.6e} m",
                get(&format!("crack_max_gap_{i}")),
                get(&format!("crack_max_slip_{i}"))
            ));
        }
        // every receiver, velocity then stress, as summary.json names them (the first
        // REPORTED of a long line: all are in summary.json)
        const REPORTED: usize = 16;
        let all = self.receivers.len() + self.stress_receivers.len();
        for name in self
            .receivers
            .iter()
            .chain(&self.stress_receivers)
            .take(REPORTED)
        {
            // each ratio with its floor (the method's on the receiver's fundamental)
            let a1 = get(&format!("{name}_A1"));
            lines.push(format!(
                "{:<23}{:.6e} (floor {:.1e})   A3/A1 {:.6e} (floor {:.1e})",
                format!("{name} A2/A1"),
                get(&format!("{name}_A2_over_A1")),
                get(&format!("{name}_A2_floor")) / a1,
                get(&format!("{name}_A3_over_A1")),
                get(&format!("{name}_A3_floor")) / a1,
            ));
        }
        if all > REPORTED {
            lines.push(format!(
                "... and {} more receivers (their harmonics in summary.json)",
                all - REPORTED
            ));
        }
        let code = get("analysis_method");
        let method = AnalysisMethod::ALL.into_iter().find(|m| m.code() == code);
        if let Some(m) = method.filter(|_| all > 0) {
            lines.push(format!("analysis method        {}", m.name()));
            if matches!(m, AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit) {
                // in 2D the linear path from source to receiver shapes the spectrum, so a
                // one-run method has a floor of its own (model.md section 15.10)
                lines.push(format!(
                    "note: {} analyses one run, so A2..A5 include the linear wavefield's own content near n f0 \
                     (the source's spectrum as the solid carries it to the receiver), not only what the cracks add; \
                     pulse_inversion or linear_reference (a second run) keep only the cracks' harmonics",
                    m.name()
                ));
            }
        }
        lines.extend(
            Outcome::warnings(self)
                .iter()
                .map(|w| format!("warning: {w}")),
        );
        lines
    }

    /// The receivers' harmonics near their analysis floor (how to read each, eq. 16.2;
    /// the first few of a long line) and the receivers that record at a node other than
    /// the position asked for.
    fn warnings(&self) -> Vec<String> {
        let get = |k: &str| self.summary.get(k).unwrap_or(f64::NAN);
        let names: Vec<&String> = self
            .receivers
            .iter()
            .chain(&self.stress_receivers)
            .collect();
        let mut out = Vec::new();
        let mut readings = Vec::new();
        let mut near = 0usize;
        for name in &names {
            let r: Vec<String> = (2..=5)
                .filter_map(|n| {
                    crate::analysis::floor_reading(
                        &format!("A{n}"),
                        get(&format!("{name}_A{n}")),
                        get(&format!("{name}_A{n}_floor")),
                    )
                })
                .collect();
            if !r.is_empty() {
                near += 1;
                if readings.len() < 3 {
                    readings.push(format!("{name}: {}", r.join("; ")));
                }
            }
        }
        if near > 0 {
            let more = if near > readings.len() {
                format!(
                    "; ... {} receivers in all (<name>_harmonic_floor_warning = 1)",
                    near
                )
            } else {
                String::new()
            };
            out.push(format!(
                "{}{more} (the analysis floor: the method on the receiver's fundamental alone, <name>_A<n>_floor)",
                readings.join(" | ")
            ));
        }
        // the nodes the receivers record at, against the positions asked for
        let asked = self
            .geometry
            .receivers
            .iter()
            .chain(&self.geometry.stress_receivers);
        let (mut moved, mut worst, mut first) = (0usize, 0.0f64, None);
        for (name, a) in names.iter().zip(asked) {
            let at = [get(&format!("{name}_x")), get(&format!("{name}_z"))];
            let d = (at[0] - a[0]).hypot(at[1] - a[1]);
            if d > 1e-9 {
                moved += 1;
                if d > worst {
                    worst = d;
                    first = Some((name.to_string(), *a, at));
                }
            }
        }
        if let Some((name, a, at)) = first {
            out.push(format!(
                "{moved} receiver(s) record at the node nearest the position asked for, up to \
                 {worst:.3e} m from it (e.g. {name}: asked [{:e}, {:e}] m, records at [{:e}, {:e}] m); \
                 summary.json has each one's <name>_x, <name>_z",
                a[0], a[1], at[0], at[1]
            ));
        }
        out
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}
