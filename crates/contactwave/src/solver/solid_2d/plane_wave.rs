//! Plane P, SV and SH waves by total-field/scattered-field injection (docs/model.md section
//! 15.8, eqs. 15.8a-15.8f).
//!
//! A horizontal line `z = z_s` along element edges across the whole width splits the
//! rectangle: below it (and on it) the nodes hold the total field, above it the scattered
//! field alone. A plane wave `u_inc(x, t) = -G(t - tau(x)) d / (rho c)` travelling down at
//! `angle` from the z axis (`G` the time integral of the source's signal `s`, the wave's
//! stress; `d` its polarisation; `tau` its delay) is then the difference between the two
//! sides, and the equations of motion of the nodes that see the other side (the nodes of the
//! element row just above the line: the line's nodes `L` and the others `S`) receive the
//! stiffness coupling across the line applied to the incident displacement:
//!
//! ```text
//! f_S += K_SL u_inc,L        f_L -= K_LS u_inc,S                         (15.8c)
//! ```
//!
//! The mass is diagonal: no inertial coupling, nothing else to add. The couplings `K_ij`
//! come from the element operator itself (probed once per element when the plan is built),
//! the delays once per sample node; each step evaluates `G` once per sample node (a table of
//! `G` with the exact derivative `s`: cubic Hermite, fourth order in the table's step
//! `dt / 8`) and applies the couplings in a fixed order: no allocation, the same bits for
//! any thread count. The forces are external forces of the scheme: their work enters the
//! energy audit like any source's.

use super::kernel::{ElementData, Stiffness};
use super::mesh::Mesh;
use super::{Elastic, WaveType};
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use std::sync::Arc;

/// The type of an injected plane wave.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Incidence {
    /// Longitudinal: polarised along the propagation direction `k = (sin a, cos a)`.
    P,
    /// Shear in the plane: polarised along `(cos a, -sin a)` (along +x at normal incidence).
    Sv,
    /// Antiplane shear (SH runs): polarised along y.
    Sh,
}

/// The table of `G(t) = integral_0^t s`, with `s` itself as its derivative.
#[derive(Debug, Clone)]
pub(super) struct Integral {
    /// Step, s.
    pub(super) step: f64,
    /// `G(k step)`, Pa s.
    pub(super) g: Vec<f64>,
    /// `s(k step)`, Pa.
    pub(super) s: Vec<f64>,
}

impl Integral {
    /// Tabulate over `[0, end]` with about `step` s between entries.
    fn new(signal: &dyn Excitation, end: f64, step: f64) -> Self {
        let n = (end / step).ceil().max(1.0) as usize + 1;
        // Gauss-Legendre, 4 points on [0, 1]
        const X: [f64; 4] = [
            0.069_431_844_202_973_71,
            0.330_009_478_207_571_9,
            0.669_990_521_792_428_1,
            0.930_568_155_797_026_3,
        ];
        const W: [f64; 4] = [
            0.173_927_422_568_726_9,
            0.326_072_577_431_273_1,
            0.326_072_577_431_273_1,
            0.173_927_422_568_726_9,
        ];
        let mut g = Vec::with_capacity(n);
        let mut s = Vec::with_capacity(n);
        let mut acc = 0.0;
        for k in 0..n {
            let t = k as f64 * step;
            g.push(acc);
            s.push(signal.stress(t));
            acc += step
                * X.iter()
                    .zip(&W)
                    .map(|(x, w)| w * signal.stress(t + x * step))
                    .sum::<f64>();
        }
        Integral { step, g, s }
    }

    /// `G(t)`, Pa s: 0 before 0, the last entry after the table.
    #[inline]
    fn at(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let r = t / self.step;
        let k = r as usize;
        if k + 1 >= self.g.len() {
            return self.g[self.g.len() - 1];
        }
        let x = r - k as f64;
        let h = self.step;
        let (g0, g1, s0, s1) = (self.g[k], self.g[k + 1], self.s[k], self.s[k + 1]);
        // cubic Hermite
        let x2 = x * x;
        let x3 = x2 * x;
        (2.0 * x3 - 3.0 * x2 + 1.0) * g0
            + (x3 - 2.0 * x2 + x) * h * s0
            + (-2.0 * x3 + 3.0 * x2) * g1
            + (x3 - x2) * h * s1
    }
}

/// One plane-wave source, planned: its sample nodes, their couplings, and the buffers of a
/// step.
#[derive(Debug, Clone)]
pub struct Injection {
    /// Index of the source (its signal).
    pub source: usize,
    /// Each sample node's delay `tau` (s).
    pub(super) delay: Vec<f64>,
    /// Each sample node's displacement per unit `G`: `-d_c / (rho c)`, its dof `c` in
    /// `dof_of_sample` (one sample per node and component).
    pub(super) scale: Vec<f64>,
    /// The couplings `(target, sample, weight)`: the force on target dof `targets[target]`
    /// is the sum of `weight * u_inc(sample)` (N/m per m).
    pub(super) pairs: Vec<(u32, u32, f64)>,
    /// The dofs the forces act on (increasing).
    pub(super) targets: Vec<usize>,
    /// The time integral of the signal.
    pub(super) integral: Integral,
    /// Scratch: each sample's incident displacement of the step, m.
    u_inc: Vec<f64>,
    /// Scratch: each target's force of the step, N/m.
    force: Vec<f64>,
    /// Each target's velocity of the previous half level (the forces' work).
    v_prev: Vec<f64>,
    /// Speed of the wave, m/s.
    speed: f64,
    /// Unit propagation direction `[x, z]`.
    direction: [f64; 2],
    /// `k . x` of the earliest sample node, m (the time origin of the wave).
    origin: f64,
}

impl Injection {
    /// Plan the injection of `incidence` at `angle` (rad from +z, toward +x) in `material`
    /// across the element edge line `z_line` (m) of `mesh` (whose element row above it is in
    /// `stiffness`, the rectangle's operator: its element `(ex, ez)` is the mesh's
    /// `(ex + offset.0, ez + offset.1)`, the absorbing layers' bands before it; the line
    /// spans the rectangle only), with `signal` (the wave's stress at the front, Pa) tabulated over
    /// `duration` s at a step `dt / 8`. Errors name `key` (the source's scenario key).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        mesh: &Mesh,
        stiffness: &Stiffness,
        offset: (usize, usize),
        material: Elastic,
        incidence: Incidence,
        angle: f64,
        z_line: f64,
        signal: &Arc<dyn Excitation>,
        source: usize,
        dt: f64,
        duration: f64,
        file: &str,
        key: &str,
    ) -> Result<Self> {
        let n = mesh.gll.order;
        let m = n + 1;
        let (nex, _) = mesh.element_dims();
        let (bx, bz) = offset;
        let nx_in = stiffness.dims.0;
        let comps = if stiffness.antiplane { 1 } else { 2 };
        let ez_line = Some(super::mesh::edge_index(&mesh.z_edges, z_line))
            .filter(|&k| k > 0 && k + 1 < mesh.z_edges.len())
            .ok_or_else(|| {
                Error::invalid(
                    file,
                    format!("{key}.z"),
                    z_line,
                    "an element edge strictly inside the rectangle",
                )
            })?;
        let ez = ez_line - 1; // the element row above the line
        let speed = match incidence {
            Incidence::P => material.p_speed,
            _ => material.s_speed,
        };
        let (sin, cos) = angle.sin_cos();
        let direction = [sin, cos];
        let pol: [f64; 2] = match incidence {
            Incidence::P => [sin, cos],
            Incidence::Sv => [cos, -sin],
            Incidence::Sh => [1.0, 0.0],
        };
        let amp = -1.0 / (material.density * speed);
        // the one-element operator of each element of the row, probed column by column
        let pts = &mesh.gll.points;
        let len = comps * m * m;
        let mut unit = vec![0.0; len];
        let mut col = vec![0.0; len];
        // samples: (global dof) -> index; delays
        let mut sample_of = std::collections::BTreeMap::new();
        let mut scale = Vec::new();
        let mut kx = Vec::new();
        let mut raw: Vec<(usize, usize, f64)> = Vec::new();
        for ex in bx..bx + nx_in {
            let e = ez * nex + ex;
            let el: ElementData = stiffness.elements[(ez - bz) * nx_in + ex - bx];
            let one = Stiffness {
                order: n,
                dims: (1, 1),
                elements: vec![el],
                conn: (0..(m * m) as u32).collect(),
                weights: stiffness.weights.clone(),
                derivative: stiffness.derivative.clone(),
                antiplane: stiffness.antiplane,
                regular: Vec::new(),
                coefs: Vec::new(),
            };
            let conn = &mesh.conn[e * m * m..(e + 1) * m * m];
            let (x0, z0) = (mesh.x_edges[ex], mesh.z_edges[ez]);
            for j in 0..m * m {
                let (a, b) = (j % m, j / m);
                let on_line = b == m - 1;
                let pos = [
                    x0 + 0.5 * (pts[a] + 1.0) * el.hx,
                    z0 + 0.5 * (pts[b] + 1.0) * el.hz,
                ];
                for cj in 0..comps {
                    let dof = comps * conn[j] as usize + cj;
                    let p = if comps == 1 { 1.0 } else { pol[cj] };
                    if p == 0.0 {
                        continue;
                    }
                    let sample = *sample_of.entry(dof).or_insert_with(|| {
                        kx.push(direction[0] * pos[0] + direction[1] * pos[1]);
                        scale.push(amp * p);
                        kx.len() - 1
                    });
                    // column j, component cj of -K_e
                    unit.fill(0.0);
                    unit[comps * j + cj] = 1.0;
                    one.apply_serial(&unit, &mut col);
                    for i in 0..m * m {
                        let i_on_line = i / m == m - 1;
                        if i_on_line == on_line {
                            continue;
                        }
                        // K_ij = -col; S rows: +K_SL u_L; L rows: -K_LS u_S
                        let sign = if on_line { -1.0 } else { 1.0 };
                        for ci in 0..comps {
                            let w = sign * col[comps * i + ci];
                            if w != 0.0 {
                                raw.push((comps * conn[i] as usize + ci, sample, w));
                            }
                        }
                    }
                }
            }
        }
        Injection::from_couplings(
            source,
            (kx, scale),
            raw,
            (speed, direction),
            signal,
            (dt, duration),
            file,
            key,
        )
    }

    /// The injection of source `source` from its samples (each one's `k . x`, m, and its
    /// displacement per unit `G`, `scale`), the couplings `raw` (`(target dof, sample,
    /// weight)`, any order), the wave's speed (m/s) and unit direction, and `signal`
    /// tabulated over `duration` (s) at `dt / 8` (`timing = (dt, duration)`).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn from_couplings(
        source: usize,
        samples: (Vec<f64>, Vec<f64>),
        mut raw: Vec<(usize, usize, f64)>,
        wave: (f64, [f64; 2]),
        signal: &Arc<dyn Excitation>,
        timing: (f64, f64),
        file: &str,
        key: &str,
    ) -> Result<Self> {
        let (kx, scale) = samples;
        let (speed, direction) = wave;
        let (dt, duration) = timing;
        let mut delay = vec![0.0; kx.len()];
        let origin = kx.iter().copied().fold(f64::INFINITY, f64::min);
        for (d, k) in delay.iter_mut().zip(&kx) {
            *d = (k - origin) / speed;
        }
        // targets in increasing dof order, pairs sorted by (target, sample): a fixed order
        raw.sort_by_key(|r| (r.0, r.1));
        let mut targets: Vec<usize> = raw.iter().map(|r| r.0).collect();
        targets.dedup();
        let mut pairs = Vec::with_capacity(raw.len());
        let mut t = 0;
        for (dof, s, w) in raw {
            while targets[t] != dof {
                t += 1;
            }
            match pairs.last_mut() {
                Some((pt, ps, pw)) if *pt == t as u32 && *ps == s as u32 => *pw += w,
                _ => pairs.push((t as u32, s as u32, w)),
            }
        }
        let end = signal.duration().min(duration) + dt;
        let step = dt / 8.0;
        crate::budget::check(
            file,
            &format!("{key}.signal"),
            "plane_wave",
            (end / step + 2.0) * 16.0,
            "the table of the plane wave's time integral",
        )?;
        let integral = Integral::new(signal.as_ref(), end, step);
        Ok(Injection {
            source,
            u_inc: vec![0.0; delay.len()],
            delay,
            scale,
            force: vec![0.0; targets.len()],
            v_prev: vec![0.0; targets.len()],
            targets,
            pairs,
            integral,
            speed,
            direction,
            origin,
        })
    }

    /// The delay of the incident wave at `[x, z]` (m) after the source's time origin, s:
    /// the incident field there is `-G(t - delay) d / (rho c)`, its velocity
    /// `-s(t - delay) d / (rho c)`. (The origin is the first sample node the front reaches,
    /// in the element row above the line.)
    pub fn delay_at(&self, at: [f64; 2]) -> f64 {
        (self.direction[0] * at[0] + self.direction[1] * at[1] - self.origin) / self.speed
    }

    /// The forces at time `t` (s), added to `f` (N/m) and kept in `force`.
    pub(super) fn add_forces(&mut self, t: f64, f: &mut [f64]) {
        for ((u, &d), &s) in self.u_inc.iter_mut().zip(&self.delay).zip(&self.scale) {
            *u = s * self.integral.at(t - d);
        }
        self.force.fill(0.0);
        for &(tg, s, w) in &self.pairs {
            self.force[tg as usize] += w * self.u_inc[s as usize];
        }
        for (&dof, &fv) in self.targets.iter().zip(&self.force) {
            f[dof] += fv;
        }
    }

    /// The forces' work of the step `f^n dt (v^{n+1/2} + v^{n-1/2}) / 2`, J/m, with `v`
    /// the new velocities.
    pub(super) fn work(&mut self, v: &[f64], dt: f64) -> f64 {
        let mut w = 0.0;
        for ((&dof, &fv), vp) in self.targets.iter().zip(&self.force).zip(&mut self.v_prev) {
            w += fv * dt * 0.5 * (v[dof] + *vp);
            *vp = v[dof];
        }
        w
    }
}

/// The wave type an incidence needs.
pub(super) fn fits(incidence: Incidence, wave: WaveType) -> bool {
    (incidence == Incidence::Sh) == (wave == WaveType::Sh)
}

impl<L> super::Solid2d<L> {
    /// Check plane-wave source `i`: its type against the run's wave type, its angle (0 with
    /// periodic sides: a burst at an angle does not repeat across the width), its line
    /// inside the rectangle and clear of every crack.
    pub(super) fn check_plane_wave(
        &self,
        file: &str,
        i: usize,
        incidence: Incidence,
        angle: f64,
        z: f64,
    ) -> Result<()> {
        let key = format!("source.{i}");
        if !fits(incidence, self.wave) {
            return Err(Error::invalid(
                file,
                format!("{key}.wave"),
                format!("{incidence:?}"),
                "P or SV in a P-SV run, SH in an SH run",
            ));
        }
        if !(angle.abs() < 0.5 * std::f64::consts::PI) {
            return Err(Error::invalid(
                file,
                format!("{key}.angle"),
                crate::numeric::shown_degrees(angle),
                "in (-90, 90) degrees",
            ));
        }
        if angle != 0.0 && self.sides == super::Side::Periodic {
            return Err(Error::invalid(
                file,
                format!("{key}.angle"),
                crate::numeric::shown_degrees(angle),
                "0 with periodic sides (an oblique burst does not repeat across the width: use absorbing sides)",
            ));
        }
        let depth = self.layers.last().map_or(0.0, |l| l.bottom);
        if !(z > 0.0 && z < depth) {
            return Err(Error::invalid(
                file,
                format!("{key}.z"),
                z,
                format!("inside (0, {depth}) m"),
            ));
        }
        for (ci, c) in self.cracks.iter().enumerate() {
            let (z0, z1) = (c.start[1].min(c.end[1]), c.start[1].max(c.end[1]));
            if z >= z0 && z <= z1 {
                return Err(Error::invalid(
                    file,
                    format!("{key}.z"),
                    z,
                    format!("clear of crack.{ci} (a line that no crack touches)"),
                ));
            }
        }
        Ok(())
    }
}
