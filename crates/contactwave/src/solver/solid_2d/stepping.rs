//! The time loop of a 2D plan (docs/model.md section 15, eqs. 15.2-15.5): the kernel's
//! forces, the sources, the node-wise predicted motion, the absorbing sides' dashpots, the
//! cracks' split-node update, the records and the energy audit.

use super::{CrackRecord, Energy2d, Load, Plan, Solid2dOutput, CHUNK};
use crate::error::Result;
use crate::law::{NormalPart, TangentialPart};
use rayon::prelude::*;

impl<L: NormalPart + TangentialPart> Plan<L> {
    /// The signal of load `l` at time t, N/m.
    #[inline]
    fn load_value(&self, l: &Load, t: f64) -> f64 {
        l.weight * self.signals[l.source].stress(t - l.delay)
    }

    /// Run from rest, checking for Ctrl-C every 256 steps.
    pub fn run(&mut self) -> Result<Solid2dOutput> {
        self.run_with(None)
    }

    /// [`Plan::run`] reporting `(steps done, steps)` to `progress` every 256 steps.
    pub fn run_with(
        &mut self,
        progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    ) -> Result<Solid2dOutput> {
        let c = self.components;
        let len = c * self.mesh.n_nodes;
        let dt = self.dt;
        let mut u = vec![0.0; len];
        let mut v = vec![0.0; len];
        let mut f = vec![0.0; len];
        let nr = self.receiver_nodes.len();
        let n_t = self.steps;
        let mut rec = vec![0.0; nr * c * n_t];
        let mut time = Vec::with_capacity(n_t);
        let mut records: Vec<CrackRecord> = self
            .cracks
            .iter()
            .map(|cr| CrackRecord {
                position: cr.position.clone(),
                ..Default::default()
            })
            .collect();
        let mut input = 0.0;
        let mut absorbed = 0.0;
        let mut v_old = vec![0.0; self.loads.len()];
        let mut v_damped = vec![0.0; self.dampers.len()];
        for n in 0..n_t {
            let t = n as f64 * dt;
            self.stiffness.apply(&u, &mut f);
            for l in &self.loads {
                f[l.index] += self.load_value(l, t);
            }
            for (vd, &(i, _)) in v_damped.iter_mut().zip(&self.dampers) {
                *vd = v[i];
            }
            // the predicted velocities and displacements of the new level, without the
            // cracks' tractions (node-wise: parallel and deterministic)
            let inv_mass = &self.inv_mass;
            u.par_chunks_mut(CHUNK * c)
                .zip(v.par_chunks_mut(CHUNK * c))
                .zip(f.par_chunks(CHUNK * c))
                .zip(inv_mass.par_chunks(CHUNK))
                .for_each(|(((u, v), f), im)| {
                    for (((un, vn), fnode), im) in u
                        .chunks_exact_mut(c)
                        .zip(v.chunks_exact_mut(c))
                        .zip(f.chunks_exact(c))
                        .zip(im)
                    {
                        for ((ui, vi), fi) in un.iter_mut().zip(vn.iter_mut()).zip(fnode) {
                            *vi += dt * im * fi;
                            *ui += dt * *vi;
                        }
                    }
                });
            // the dashpots at the mean velocity of the step: v = (v~ - a v_old) / (1 + a),
            // a = dt C / (2 M); their work dt C v_mean^2 leaves the solid
            for (&vo, &(i, cd)) in v_damped.iter().zip(&self.dampers) {
                let a = 0.5 * dt * cd * self.inv_mass[i / c];
                let pred = v[i];
                let new = (pred - a * vo) / (1.0 + a);
                u[i] += dt * (new - pred);
                v[i] = new;
                let mean = 0.5 * (new + vo);
                absorbed += dt * cd * mean * mean;
            }
            for cr in &mut self.cracks {
                cr.update(&mut u, &mut v, dt, t + dt, c == 1)?;
            }
            for (k, l) in self.loads.iter().enumerate() {
                let fv = self.load_value(l, t);
                input += fv * dt * 0.5 * (v[l.index] + v_old[k]);
                v_old[k] = v[l.index];
            }
            time.push(t + 0.5 * dt);
            for (r, &g) in self.receiver_nodes.iter().enumerate() {
                for cc in 0..c {
                    rec[(r * c + cc) * n_t + n] = v[c * g + cc];
                }
            }
            if n % self.crack_every == 0 || n + 1 == n_t {
                for (cr, out) in self.cracks.iter().zip(&mut records) {
                    out.time.push(t + dt);
                    for (st, law) in cr.state.iter().zip(&cr.law) {
                        out.normal_gap.push(st.gap);
                        out.tangential_gap.push(st.shear.gap);
                        out.normal_stress.push(st.stress);
                        out.shear_stress.push(st.shear_stress(law));
                        out.adhesion.push(st.beta);
                    }
                }
            }
            if n % 256 == 255 {
                crate::interrupt::check()?;
                if let Some(p) = progress {
                    p(n + 1, n_t);
                }
            }
        }
        // E^{N-1/2} = v M v / 2 + u^{N-1} K u^N / 2 with u^{N-1} = u^N - dt v^{N-1/2}
        self.stiffness.apply(&u, &mut f);
        let mut solid = 0.0;
        for i in 0..len {
            let m = self.mass[i / c];
            let ku = -f[i];
            solid += 0.5 * m * v[i] * v[i];
            solid += 0.5 * (u[i] - dt * v[i]) * ku;
        }
        let cracks = self.cracks.iter().map(|c| c.work).sum();
        Ok(Solid2dOutput {
            dt,
            time,
            receivers: rec,
            components: c,
            cracks: records,
            energy: Energy2d {
                input,
                solid,
                cracks,
                absorbed,
            },
        })
    }
}
