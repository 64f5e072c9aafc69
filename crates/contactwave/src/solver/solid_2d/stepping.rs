//! A 2D plan's step (docs/model.md section 15, eqs. 15.2-15.5) as a scheme of the one time
//! loop of the explicit solvers ([`crate::solver::stepping`]): the kernel's forces, the
//! sources, the node-wise predicted motion, the absorbing layers ([`super::pml`]), the cracks'
//! split-node update and the energy audit; a recorder keeps the receivers' velocities and
//! the cracks' fields.

use super::crack::CrackNodes;
use super::kernel::advance_nodes;
use super::plane_wave::Injection;
use super::pml::Band;
use super::probe::StressProbe;
use super::snapshot::Capture;
use super::{CrackRecord, Energy2d, Load, Plan, Solid2dOutput};
use crate::error::{Error, Result};
use crate::law::{NormalPart, TangentialPart};
use crate::solver::stepping::{self, Recorder, Schedule, Scheme};

/// Steps between two interruption checks and progress reports of a 2D run: at most 64,
/// and fewer on large meshes, about every 2e6 node-updates (under 0.1 s on 2 cores: a mesh
/// of 1e7 nodes is checked every step), so that Ctrl-C is answered within a fraction of
/// a second whatever the size. `values`: the length of the state vectors (nodes times
/// components).
fn check_every(values: usize) -> usize {
    (4_000_000 / values.max(1)).clamp(1, 64)
}

/// The state of a running 2D plan: displacements (level n), velocities (level n - 1/2),
/// forces, the cracks', plane waves' and absorbing layers' own state (copies of the
/// plan's at rest: the plan is not changed), and the energy terms accumulated so far.
struct Run2d<'p, L> {
    plan: &'p Plan<L>,
    cracks: Vec<CrackNodes<L>>,
    plane_waves: Vec<Injection>,
    band: Band,
    u: Vec<f64>,
    v: Vec<f64>,
    f: Vec<f64>,
    /// Each load's velocity of the previous half level (its work).
    v_load: Vec<f64>,
    input: f64,
    absorbed: f64,
}

impl<L: NormalPart + TangentialPart + Clone> Plan<L> {
    /// The signal of load `l` at time t, N/m.
    #[inline]
    pub(super) fn load_value(&self, l: &Load, t: f64) -> f64 {
        l.weight * self.signals[l.source].stress(t - l.delay)
    }

    /// Run from rest (every run of a plan starts from the same state: the plan is not
    /// changed), checking for Ctrl-C every [`check_every`] steps.
    pub fn run(&self) -> Result<Solid2dOutput> {
        self.run_with(None)
    }

    /// [`Plan::run`] reporting `(steps done, steps)` to `progress` every 64 steps.
    pub fn run_with(
        &self,
        progress: Option<&(dyn Fn(usize, usize) + Send + Sync)>,
    ) -> Result<Solid2dOutput> {
        let c = self.components;
        let len = c * self.mesh.n_nodes;
        let (dt, n_t) = (self.dt, self.steps);
        let mut recorder = Records::new(self);
        let mut run = Run2d {
            cracks: self.cracks.clone(),
            plane_waves: self.plane_waves.clone(),
            band: self.band.clone(),
            u: vec![0.0; len],
            v: vec![0.0; len],
            f: vec![0.0; len],
            v_load: vec![0.0; self.loads.len()],
            input: 0.0,
            absorbed: 0.0,
            plan: self,
        };
        let schedule = Schedule {
            t0: 0.0,
            dt,
            steps: n_t,
            record_every: 1,
            check_every: check_every(len),
            progress,
        };
        stepping::run(&schedule, &mut run, &mut recorder)?;
        let Run2d {
            cracks,
            u,
            v,
            mut f,
            input,
            absorbed,
            ..
        } = run;
        Ok(self.output(recorder, &cracks, &u, &v, &mut f, input, absorbed))
    }

    /// The run's output from its recorder, its cracks and last level (`u` m, `v` m/s; `f`
    /// N/m, overwritten): the energy audit with the solid's discrete energy
    /// `E^{N-1/2} = v M v / 2 + u^{N-1} K u^N / 2`, `u^{N-1} = u^N - dt v^{N-1/2}` (J/m).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn output(
        &self,
        recorder: Records,
        cracks: &[CrackNodes<L>],
        u: &[f64],
        v: &[f64],
        f: &mut [f64],
        input: f64,
        absorbed: f64,
    ) -> Solid2dOutput {
        let c = self.components;
        let dt = self.dt;
        self.stiffness.apply(u, f);
        let mut solid = 0.0;
        for i in 0..u.len() {
            let m = self.mass[i / c];
            solid += 0.5 * m * v[i] * v[i];
            solid += 0.5 * (u[i] - dt * v[i]) * -f[i];
        }
        Solid2dOutput {
            dt,
            time: recorder.time,
            receivers: recorder.receivers,
            components: c,
            stresses: recorder.stresses,
            stress_components: recorder.stress_components,
            cracks: recorder.cracks,
            snapshots: recorder.snapshots,
            energy: Energy2d::audit(input, solid, absorbed, cracks),
        }
    }
}

impl<L: NormalPart + TangentialPart + Clone> Scheme for Run2d<'_, L> {
    /// Levels n -> n + 1 in place: `u` and `v` hold the new level when it returns.
    fn step(&mut self, t: f64, t1: f64) -> Result<()> {
        let p = self.plan;
        let (c, dt) = (p.components, p.dt);
        let (u, v, f) = (&mut self.u, &mut self.v, &mut self.f);
        // the forces of level n other than the elements' (`f` is zero here: cleared by
        // the last step's node-wise update, or new): sources, plane waves, the absorbing
        // layers' forces on their inner nodes
        for l in &p.loads {
            f[l.index] += p.load_value(l, t);
        }
        for pw in &mut self.plane_waves {
            pw.add_forces(t, f);
        }
        self.band
            .forces(&p.stiffness.weights, &p.stiffness.derivative, v, f);
        // the elements' forces, and the predicted velocities and displacements of the new
        // level without the cracks' tractions: the kernel's node rows as it completes them
        // (parallel and deterministic), then the nodes outside them; the forces are cleared
        // as they are read (the next step accumulates into them)
        let (rows, outside) = &p.rows;
        p.stiffness.step(u, v, f, &p.inv_mass, dt, *rows);
        for &g in outside {
            let g = g as usize;
            advance_nodes(c, u, v, f, &p.inv_mass, g..g + 1, dt);
        }
        // the absorbing layers: their nodes' split velocities, the flux into them, and
        // their stresses of level n + 1
        self.absorbed += self.band.nodes(u, v, &p.inv_mass, dt);
        self.band
            .stresses(&p.stiffness.weights, &p.stiffness.derivative, v, dt);
        for cr in &mut self.cracks {
            cr.update(u, v, dt, t1, c == 1)?;
        }
        // the sources' work f^n (u^{n+1} - u^{n-1}) / 2 = f^n dt (v^{n+1/2} + v^{n-1/2}) / 2
        for (l, vo) in p.loads.iter().zip(&mut self.v_load) {
            let fv = l.weight * p.signals[l.source].stress(t - l.delay);
            self.input += fv * dt * 0.5 * (v[l.index] + *vo);
            *vo = v[l.index];
        }
        for pw in &mut self.plane_waves {
            self.input += pw.work(v, dt);
        }
        Ok(())
    }

    fn check_finite(&self, t1: f64) -> Result<()> {
        if self.u.iter().chain(&self.v).all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(Error::numerical(
                t1,
                "2D solver: non-finite displacement or velocity",
                format!("time step {:e} s", self.plan.dt),
            ))
        }
    }

    fn advance(&mut self) {}
}

/// What a 2D run keeps: the receivers' velocities at every half level and the cracks'
/// fields every `crack_every` levels (and at the last complete one), room reserved up
/// front (the budget was checked when the plan was built): recording allocates nothing.
pub(super) struct Records {
    /// Times of the receiver samples, s.
    time: Vec<f64>,
    /// `[receiver][component][sample]`, m/s.
    pub(super) receivers: Vec<f64>,
    /// `[stress receiver][component][sample]`, Pa.
    pub(super) stresses: Vec<f64>,
    stress_components: usize,
    /// Each stress receiver's stresses of the last level, Pa.
    last_stress: Vec<f64>,
    cracks: Vec<CrackRecord>,
    /// Steps taken so far.
    steps: usize,
    /// Time of the level the last step started from, s: the level whose crack fields the
    /// step completed.
    level_time: f64,
    /// Whether the level at rest has gone by (it is not recorded).
    started: bool,
    pub(super) n_t: usize,
    crack_every: usize,
    /// The whole velocity field at the plan's snapshot steps.
    pub(super) snapshots: Capture,
}

impl Records {
    /// Sample `n` of the stress receivers `probes` from the displacements `u` of the level
    /// after the step (`components` per node): the half level's stress, the mean of the
    /// levels around it, Pa.
    pub(super) fn stresses_at(
        &mut self,
        n: usize,
        probes: &[StressProbe],
        u: &[f64],
        components: usize,
    ) {
        let sc = self.stress_components;
        let mut now = [0.0; 3];
        for (r, probe) in probes.iter().enumerate() {
            probe.stress(u, components, &mut now);
            for (cc, &new) in now.iter().enumerate().take(sc) {
                let last = &mut self.last_stress[r * sc + cc];
                self.stresses[(r * sc + cc) * self.n_t + n] = 0.5 * (*last + new);
                *last = new;
            }
        }
    }

    pub(super) fn new<L>(plan: &Plan<L>) -> Self {
        Records::sized(
            plan.steps,
            plan.components,
            plan.receiver_nodes.len(),
            plan.stress_probes.len(),
            &plan.cracks,
            plan.crack_every,
            plan.snapshot_steps.clone(),
            plan.components * plan.mesh.n_nodes,
        )
    }

    /// The records of a run of `n_t` steps with `components` per node, `receivers`
    /// velocity and `stress_probes` stress receivers, the `cracks`' fields every
    /// `crack_every` levels and the whole field (`len` values) at `snapshot_steps`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sized<L>(
        n_t: usize,
        components: usize,
        receivers: usize,
        stress_probes: usize,
        cracks: &[CrackNodes<L>],
        crack_every: usize,
        snapshot_steps: Vec<usize>,
        len: usize,
    ) -> Self {
        let sc = if components == 1 { 2 } else { 3 };
        let n_records = n_t / crack_every + 2;
        Records {
            time: Vec::with_capacity(n_t),
            receivers: vec![0.0; receivers * components * n_t],
            stresses: vec![0.0; stress_probes * sc * n_t],
            stress_components: sc,
            last_stress: vec![0.0; stress_probes * sc],
            cracks: cracks
                .iter()
                .map(|cr| {
                    let m = n_records * cr.position.len();
                    CrackRecord {
                        position: cr.position.clone(),
                        points: Vec::new(),
                        time: Vec::with_capacity(n_records),
                        normal_gap: Vec::with_capacity(m),
                        tangential_gap: Vec::with_capacity(m),
                        normal_stress: Vec::with_capacity(m),
                        shear_stress: Vec::with_capacity(m),
                        adhesion: Vec::with_capacity(m),
                        state: Vec::with_capacity(m),
                        peak_normal_gap: 0.0,
                        peak_slip: 0.0,
                        least_adhesion: 1.0,
                    }
                })
                .collect(),
            steps: 0,
            level_time: 0.0,
            started: false,
            n_t,
            crack_every,
            snapshots: Capture::new(snapshot_steps, len),
        }
    }

    /// The recorded series and crack fields (time, receivers, stresses, their components,
    /// cracks, snapshots).
    pub(super) fn into_parts(
        self,
    ) -> (
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        usize,
        Vec<CrackRecord>,
        Capture,
    ) {
        (
            self.time,
            self.receivers,
            self.stresses,
            self.stress_components,
            self.cracks,
            self.snapshots,
        )
    }
}

impl<L: NormalPart + TangentialPart + Clone> Recorder<Run2d<'_, L>> for Records {
    /// Level `t` (s) after a step: the receivers' velocities of the half level before it
    /// (`t - dt / 2`); the level at rest (`t = 0`) is not recorded.
    fn record(&mut self, t: f64, s: &Run2d<'_, L>) {
        let Some(n) = self.next_sample(s.plan.dt) else {
            return;
        };
        let p = s.plan;
        let c = p.components;
        for (r, &g) in p.receiver_nodes.iter().enumerate() {
            for cc in 0..c {
                self.receivers[(r * c + cc) * self.n_t + n] = s.v[c * g + cc];
            }
        }
        self.stresses_at(n, &p.stress_probes, &s.u, c);
        self.snapshots.take(n, n as f64 * p.dt + 0.5 * p.dt, &s.v);
        self.crack_fields(t, n, &s.cracks);
    }
}

impl Records {
    /// The sample number of the level after a step (its time pushed: the half level
    /// `n dt + dt / 2`, s, as the step computed it), or `None` for the level at rest.
    pub(super) fn next_sample(&mut self, dt: f64) -> Option<usize> {
        if !self.started {
            self.started = true;
            return None;
        }
        let n = self.steps;
        self.steps += 1;
        self.time.push(n as f64 * dt + 0.5 * dt);
        Some(n)
    }

    /// After sample `n`, the step from level n to level n + 1 (at `t`, s): the cracks'
    /// fields of level n, which that step completed (a constraint's reaction of level n
    /// is the force of the step that starts there, [`super::crack`]), at the levels 1,
    /// 1 + `crack_every`, 1 + 2 `crack_every`, ... and at the last complete one, N - 1 of a
    /// run of N steps (level 0, at rest, only in a run of one step); the extrema of the
    /// gaps and the adhesion over the levels 1 to N, at every sample.
    pub(super) fn crack_fields<L: NormalPart + TangentialPart>(
        &mut self,
        t: f64,
        n: usize,
        cracks: &[CrackNodes<L>],
    ) {
        for (cr, out) in cracks.iter().zip(&mut self.cracks) {
            for st in &cr.state {
                out.peak_normal_gap = out.peak_normal_gap.max(st.gap);
                out.peak_slip = out.peak_slip.max(st.shear.gap.abs());
                out.least_adhesion = out.least_adhesion.min(st.beta);
            }
        }
        let level_time = std::mem::replace(&mut self.level_time, t);
        let regular = n >= 1 && (n - 1).is_multiple_of(self.crack_every);
        if regular || n + 1 == self.n_t {
            for (cr, out) in cracks.iter().zip(&mut self.cracks) {
                out.time.push(level_time);
                for f in &cr.fields {
                    out.normal_gap.push(f.normal_gap);
                    out.tangential_gap.push(f.tangential_gap);
                    out.normal_stress.push(f.normal_stress);
                    out.shear_stress.push(f.shear_stress);
                    out.adhesion.push(f.adhesion);
                    out.state.push(f.state);
                }
            }
        }
    }
}
