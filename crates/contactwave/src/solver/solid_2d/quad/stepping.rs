//! A quadrilateral-mesh plan's step as a scheme of the explicit solvers' one time loop
//! ([`crate::solver::stepping`]): sources (plane waves by eq. 15.13j), the kernel's forces, the node-wise predicted
//! motion (a periodic group moving as one node), the PML frame (section 15.7's layers,
//! eq. 15.13i), the absorbing sides' dashpots (implicit in the velocity: `(M + dt C / 2)
//! v^{n+1/2} = (M - dt C / 2) v^{n-1/2} + dt F`, eq. 15.13d), the cracks' split-node update
//! and the energy audit.

use super::{Dashpot, QuadPlan};
use crate::error::{Error, Result};
use crate::law::{NormalPart, TangentialPart};
use crate::solver::solid_2d::crack::CrackNodes;
use crate::solver::solid_2d::kernel::advance_nodes;
use crate::solver::solid_2d::plane_wave::Injection;
use crate::solver::solid_2d::pml::Band;
use crate::solver::solid_2d::stepping::Records;
use crate::solver::solid_2d::{Energy2d, Solid2dOutput};
use crate::solver::stepping::{self, Recorder, Schedule, Scheme};
use rayon::prelude::*;

/// The state of a running plan.
struct Run<'p, L> {
    plan: &'p QuadPlan<L>,
    cracks: Vec<CrackNodes<L>>,
    /// The PML frame's fields.
    band: Band,
    /// The plane waves' injections (their buffers).
    plane_waves: Vec<Injection>,
    u: Vec<f64>,
    v: Vec<f64>,
    f: Vec<f64>,
    /// The dashpot nodes' velocities of the last half level.
    v_dash: Vec<[f64; 2]>,
    v_load: Vec<f64>,
    input: f64,
    absorbed: f64,
}

impl<L> QuadPlan<L> {
    /// Keep the velocity field after each of `steps` (0-based; the field of the half level
    /// `(n + 1/2) dt`); steps at or beyond [`QuadPlan::steps`] are never reached. The
    /// caller checks [`crate::solver::solid_2d::snapshot::Capture::bytes`] against the
    /// memory budget first.
    pub fn capture_at(&mut self, steps: Vec<usize>) {
        self.snapshot_steps = steps;
    }
}

impl<L: NormalPart + TangentialPart + Clone> QuadPlan<L> {
    /// Run from rest (a fresh copy of the cracks at rest: the plan is not changed).
    pub fn run(&self) -> Result<Solid2dOutput> {
        self.run_with(None)
    }

    /// [`QuadPlan::run`] reporting `(steps done, steps)` to `progress`.
    pub fn run_with(
        &self,
        progress: Option<&(dyn Fn(usize, usize) + Send + Sync)>,
    ) -> Result<Solid2dOutput> {
        let c = self.components;
        let len = c * self.nodes;
        let mut recorder = Records::sized(
            self.steps,
            c,
            self.receivers.len(),
            self.stress_probes.len(),
            &self.cracks,
            self.crack_every,
            self.snapshot_steps.clone(),
            c * self.mesh.n_nodes(),
        );
        let mut run = Run {
            plan: self,
            cracks: self.cracks.clone(),
            band: self.band.clone(),
            plane_waves: self.plane_waves.clone(),
            u: vec![0.0; len],
            v: vec![0.0; len],
            f: vec![0.0; len],
            v_dash: vec![[0.0; 2]; self.dashpots.len()],
            v_load: vec![0.0; self.loads.len()],
            input: 0.0,
            absorbed: 0.0,
        };
        let schedule = Schedule {
            t0: 0.0,
            dt: self.dt,
            steps: self.steps,
            record_every: 1,
            check_every: (4_000_000 / len.max(1)).clamp(1, 64),
            progress,
        };
        stepping::run(&schedule, &mut run, &mut recorder)?;
        Ok(self.output(recorder, run))
    }

    fn output(&self, recorder: Records, run: Run<'_, L>) -> Solid2dOutput {
        let Run {
            cracks,
            u,
            v,
            mut f,
            input,
            absorbed,
            ..
        } = run;
        let (c, dt) = (self.components, self.dt);
        f.iter_mut().for_each(|x| *x = 0.0);
        self.op.add_forces(&u, &mut f);
        let mut solid = 0.0;
        for i in 0..c * self.mesh.n_nodes() {
            solid += 0.5 * self.mass[i / c] * v[i] * v[i];
            solid += 0.5 * (u[i] - dt * v[i]) * -f[i];
        }
        let energy = Energy2d::audit(input, solid, absorbed, &cracks);
        let (time, receivers, stresses, stress_components, mut records, snapshots) =
            recorder.into_parts();
        for (rec, cr) in records.iter_mut().zip(&cracks) {
            rec.points = cr
                .faces
                .iter()
                .map(|&(g, _)| self.mesh.position[g])
                .collect();
        }
        Solid2dOutput {
            dt,
            time,
            receivers,
            components: c,
            stresses,
            stress_components,
            cracks: records,
            energy,
            snapshots,
        }
    }
}

impl<L: NormalPart + TangentialPart> Scheme for Run<'_, L> {
    fn step(&mut self, t: f64, t1: f64) -> Result<()> {
        let p = self.plan;
        let (c, dt) = (p.components, p.dt);
        let (u, v, f) = (&mut self.u, &mut self.v, &mut self.f);
        for l in &p.loads {
            f[l.index] += l.weight * p.signals[l.source].stress(t - l.delay);
        }
        for pw in &mut self.plane_waves {
            pw.add_forces(t, f);
        }
        p.op.add_forces(u, f);
        let g = &p.mesh.gll;
        self.band.forces(&g.weights, &g.derivative, v, f);
        // the periodic sides: each mirror's force on its primary
        for &(q, r) in &p.mirrors {
            for k in 0..c {
                f[c * r + k] += f[c * q + k];
            }
        }
        for (d, old) in p.dashpots.iter().zip(&mut self.v_dash) {
            for k in 0..c {
                old[k] = v[c * d.node + k];
            }
        }
        // the node-wise predicted motion (v += dt f / m, u += dt v, f cleared), in
        // parallel blocks of nodes (each node alone: the same bits for any threads)
        const NODES: usize = 4096;
        u.par_chunks_mut(c * NODES)
            .zip(v.par_chunks_mut(c * NODES))
            .zip(f.par_chunks_mut(c * NODES))
            .zip(p.inv_mass.par_chunks(NODES))
            .for_each(|(((u, v), f), im)| advance_nodes(c, u, v, f, im, 0..im.len(), dt));
        // the dashpots' nodes: their velocity of the new half level, and the displacement
        // moved by the difference
        for (d, old) in p.dashpots.iter().zip(&self.v_dash) {
            let i = c * d.node;
            let predicted = [v[i], if c == 2 { v[i + 1] } else { 0.0 }];
            self.absorbed += dashpot(d, c, d.mass, dt, old, v);
            for k in 0..c {
                u[i + k] += dt * (v[i + k] - predicted[k]);
            }
        }
        // the PML frame: its nodes' split velocities, the flux into it, its stresses of
        // level n + 1
        self.absorbed += self.band.nodes(u, v, &p.inv_mass, dt);
        self.band.stresses(&g.weights, &g.derivative, v, dt);
        for cr in &mut self.cracks {
            cr.update(u, v, dt, t1, c == 1)?;
        }
        // ... and each mirror takes its primary's motion
        for &(q, r) in &p.mirrors {
            for k in 0..c {
                u[c * q + k] = u[c * r + k];
                v[c * q + k] = v[c * r + k];
            }
        }
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

/// A dashpot node's velocity of the new half level from its explicit prediction `v*`
/// (in `v`) and the old one: `(M + dt C / 2) v+ = M v* - dt C v- / 2`; returns the energy
/// it absorbed over the step, `dt vbar C vbar` with `vbar = (v+ + v-) / 2` (J/m).
fn dashpot(d: &Dashpot, c: usize, m: f64, dt: f64, old: &[f64; 2], v: &mut [f64]) -> f64 {
    let h = 0.5 * dt;
    let i = c * d.node;
    if c == 1 {
        let vn = (m * v[i] - h * d.c[0] * old[0]) / (m + h * d.c[0]);
        v[i] = vn;
        let vb = 0.5 * (vn + old[0]);
        return dt * d.c[0] * vb * vb;
    }
    let [cxx, cxz, czx, czz] = d.c;
    let rx = m * v[i] - h * (cxx * old[0] + cxz * old[1]);
    let rz = m * v[i + 1] - h * (czx * old[0] + czz * old[1]);
    let (a, b, cc, dd) = (m + h * cxx, h * cxz, h * czx, m + h * czz);
    let det = a * dd - b * cc;
    let vx = (dd * rx - b * rz) / det;
    let vz = (-cc * rx + a * rz) / det;
    v[i] = vx;
    v[i + 1] = vz;
    let (bx, bz) = (0.5 * (vx + old[0]), 0.5 * (vz + old[1]));
    dt * (bx * (cxx * bx + cxz * bz) + bz * (czx * bx + czz * bz))
}

impl<L: NormalPart + TangentialPart> Recorder<Run<'_, L>> for Records {
    fn record(&mut self, t: f64, s: &Run<'_, L>) {
        let Some(n) = self.next_sample(s.plan.dt) else {
            return;
        };
        let p = s.plan;
        let c = p.components;
        let n_t = self.n_t;
        for (r, weights) in p.receivers.iter().enumerate() {
            for cc in 0..c {
                let mut val = 0.0;
                for &(g, w) in weights {
                    val += w * s.v[c * g + cc];
                }
                self.receivers[(r * c + cc) * n_t + n] = val;
            }
        }
        self.stresses_at(n, &p.stress_probes, &s.u, c);
        let field = &s.v[..c * p.mesh.n_nodes()];
        self.snapshots.take(n, n as f64 * p.dt + 0.5 * p.dt, field);
        self.crack_fields(t, n, &s.cracks);
    }
}
