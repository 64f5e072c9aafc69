//! One scalar displacement field of the finite-difference scheme: the longitudinal
//! displacement (wave speed `c_L = sqrt(E / rho)`) or the transverse one of a shear wave
//! (`c_T = sqrt(G / rho)`), each on its own mesh at the common time step. The bulk update,
//! the end conditions that need no interface law, and the injection of an incident wave
//! through a transparent first end live here; the schemes that move the fields and couple
//! them at their interfaces are configurations of it: [`super::BarStack::run`] (any
//! Courant number `<= 1`, [`Field::new`]) and the half-space cross-checks
//! ([`crate::solver::half_space_fd_shear`]: bars of whole cells at Courant 1 given by
//! their impedances, [`Field::courant_one`]). Nothing here allocates after construction.

use super::{BarStack, Mesh};
use crate::excitation::Excitation;
use crate::numeric::gauss4;

/// Stencil coefficients of a segment.
#[derive(Debug, Clone, Copy)]
struct Coef {
    a: f64,
    b: f64,
    c: f64,
    a_end: f64,
    b_end: f64,
    exact: bool,
}

impl Coef {
    /// Interior `u+ = a u + b (u_l + u_r) - c u-`, end nodes with half mass
    /// `u+ = a_end u + b_end u_neighbour - c u-`, at the squared Courant number `r2` and
    /// the damping `h dt`.
    fn new(r2: f64, h: f64) -> Self {
        let dp = 1.0 + 0.5 * h;
        let dm = 1.0 - 0.5 * h;
        Coef {
            a: 2.0 * (1.0 - r2) / dp,
            b: r2 / dp,
            c: dm / dp,
            a_end: 2.0 * (1.0 - r2) / dp,
            b_end: 2.0 * r2 / dp,
            exact: r2 == 1.0 && h == 0.0,
        }
    }
}

/// Incident displacement F(tau) at the right end of segment 0, tabulated.
#[derive(Debug)]
struct IncidentTable {
    h: f64,
    v: Vec<f64>,
}

impl IncidentTable {
    /// `F(tau) = -(1/Z) int_0^tau s_inc` at `tau_max` and below, on a fine table at
    /// `dt / 4` (exact Gauss-Legendre integrals, linear between).
    fn new(inc: &dyn Excitation, z: f64, dt: f64, tau_max: f64) -> Self {
        let h = dt / 4.0;
        let m = (tau_max / h).ceil().max(1.0) as usize + 2;
        let mut v = Vec::with_capacity(m + 1);
        let mut acc = 0.0;
        v.push(0.0);
        for k in 0..m {
            acc += gauss4(k as f64 * h, (k + 1) as f64 * h, |s| inc.stress(s));
            v.push(-acc / z);
        }
        IncidentTable { h, v }
    }

    #[inline]
    fn at(&self, tau: f64) -> f64 {
        if tau <= 0.0 {
            return 0.0;
        }
        let x = tau / self.h;
        let i = x.floor() as usize;
        if i + 1 >= self.v.len() {
            return *self.v.last().unwrap_or(&0.0);
        }
        let f = x - i as f64;
        self.v[i] * (1.0 - f) + self.v[i + 1] * f
    }
}

/// The incident displacement at the levels `tau = m dt`, `F(m dt)` for `m = 0..=levels`:
/// the running sum of each step's integral (4 Gauss-Legendre panels per step).
fn incident_levels(inc: &dyn Excitation, z: f64, dt: f64, levels: usize) -> Vec<f64> {
    let step = |m: usize| {
        let h = 0.25 * dt;
        let t0 = m as f64 * dt;
        let mut s = 0.0;
        for i in 0..4 {
            let a = t0 + i as f64 * h;
            s += gauss4(a, a + h, |x| inc.stress(x));
        }
        -s / z
    };
    let mut v = Vec::with_capacity(levels + 1);
    v.push(0.0);
    if levels > 0 {
        v.push(step(0));
    }
    for m in 1..levels {
        v.push(v[m] + step(m));
    }
    v
}

/// The transparent ends of a field and the incident wave a transparent first end injects.
#[derive(Debug)]
enum Ends {
    /// Any Courant number (the bar stack): the first-order absorbing ends, the incident
    /// displacement read between levels from a table at `dt / 4`.
    General {
        /// Incident displacement table of a transparent first end.
        inc: Option<IncidentTable>,
        /// Wave speed of the first segment, m/s.
        c0: f64,
        /// Length of the first segment as meshed, m.
        len0: f64,
    },
    /// Courant 1 at both ends and the levels on the incident wave's grid `tau = m dt` (the
    /// half-space cross-checks): the absorbing ends in their exact form, `u0+ = F(tau +
    /// dt) + u1 - F(tau - dt)` and `uN+ = u_(N-1)`, with `F` tabulated at the levels. The
    /// general form gives the same values up to round-off; the bar stack keeps it at
    /// Courant 1 too, so that its outputs stay bit-identical.
    CourantOne {
        /// `F(m dt)`, m.
        levels: Vec<f64>,
    },
}

/// A scalar displacement field on the stack, with its state at three time levels.
#[derive(Debug)]
pub(crate) struct Field {
    /// The mesh of this field.
    pub mesh: Mesh,
    coef: Vec<Coef>,
    /// `dt^2 / (rho dx A)` per node (half mass at segment ends), s^2/kg.
    inv_mass: Vec<f64>,
    /// `1 + h dt / 2` per node.
    damp_p: Vec<f64>,
    /// Cross-section, m^2.
    area: f64,
    /// Displacements at the previous, current and next level, m.
    pub u_prev: Vec<f64>,
    pub u: Vec<f64>,
    pub u_next: Vec<f64>,
    /// Transparent ends and the incident wave.
    ends: Ends,
    /// Index of the current level (`u`), from 0 at the start.
    level: usize,
}

impl Field {
    /// The field of `stack` on `mesh`, with wave speed `c0` (m/s) and meshed length `len0`
    /// (m) of the first segment, and the incident wave `incident` (its stress where it
    /// meets the first interface, and the first segment's impedance for this wave type,
    /// Pa s/m) injected through a transparent first end up to `tau_max` (s).
    pub fn new(
        stack: &BarStack,
        mesh: Mesh,
        (c0, len0): (f64, f64),
        incident: Option<(&dyn Excitation, f64)>,
        tau_max: f64,
    ) -> Self {
        let n = mesh.nodes;
        let dt = mesh.dt;
        let mut damp_p = vec![1.0; n];
        let mut inv_mass = vec![0.0; n];
        for (s, seg) in stack.segments.iter().enumerate() {
            let o = mesh.offset[s];
            let k = mesh.cells[s];
            let rho = seg.material.density;
            for j in 0..=k {
                damp_p[o + j] = 1.0 + 0.5 * seg.damping * dt;
                let m = rho * mesh.dx[s] * stack.area * if j == 0 || j == k { 0.5 } else { 1.0 };
                inv_mass[o + j] = dt * dt / m;
            }
        }
        let coef: Vec<Coef> = (0..stack.segments.len())
            .map(|s| {
                let r2 = mesh.courant[s] * mesh.courant[s];
                Coef::new(r2, stack.segments[s].damping * dt)
            })
            .collect();
        let inc = incident.map(|(exc, z)| IncidentTable::new(exc, z, dt, tau_max + len0 / c0));
        Field {
            coef,
            inv_mass,
            damp_p,
            area: stack.area,
            u_prev: vec![0.0; n],
            u: vec![0.0; n],
            u_next: vec![0.0; n],
            ends: Ends::General { inc, c0, len0 },
            level: 0,
            mesh,
        }
    }

    /// Undamped bars of `cells[i]` cells at Courant number 1 and impedances `z[i]` (Pa s/m,
    /// unit cross-section) at time step `dt` (s): at Courant 1 the cell size drops out
    /// (the mesh's `dx` is NaN) and a half-mass end node has compliance `2 dt / Z`. The
    /// wave `incident` (its stress where it meets the end of the first bar, Pa) enters
    /// through the transparent first end, its front reaching the end of the first bar at
    /// level `cells[0]`; it is tabulated for `levels` levels.
    pub fn courant_one(
        dt: f64,
        cells: &[usize],
        z: &[f64],
        incident: &dyn Excitation,
        levels: usize,
    ) -> Self {
        let mut mesh = Mesh {
            dt,
            offset: Vec::with_capacity(cells.len()),
            cells: cells.to_vec(),
            dx: vec![f64::NAN; cells.len()],
            courant: vec![1.0; cells.len()],
            nodes: 0,
        };
        let mut inv_mass = Vec::new();
        for (&k, &zi) in cells.iter().zip(z) {
            mesh.offset.push(mesh.nodes);
            mesh.nodes += k + 1;
            // dt^2 / m with m = rho dx = Z dt (half at the ends)
            inv_mass.extend((0..=k).map(|j| {
                if j == 0 || j == k {
                    2.0 * dt / zi
                } else {
                    dt / zi
                }
            }));
        }
        let n = mesh.nodes;
        Field {
            coef: vec![Coef::new(1.0, 0.0); cells.len()],
            inv_mass,
            damp_p: vec![1.0; n],
            area: 1.0,
            u_prev: vec![0.0; n],
            u: vec![0.0; n],
            u_next: vec![0.0; n],
            ends: Ends::CourantOne {
                levels: incident_levels(incident, z[0], dt, levels),
            },
            level: 0,
            mesh,
        }
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.mesh.nodes
    }

    /// Displacement change of `node` per unit stress applied over a step, m/Pa:
    /// `dt^2 A / (m (1 + h dt / 2))`.
    #[inline]
    pub fn compliance(&self, node: usize) -> f64 {
        self.inv_mass[node] / self.damp_p[node] * self.area
    }

    /// Displacement change of `node` per unit force over a step, m/N.
    #[inline]
    pub fn force_gain(&self, node: usize) -> f64 {
        self.inv_mass[node] / self.damp_p[node]
    }

    /// Bulk and segment-end nodes at the next level with no interface or external force
    /// (the predictor). The interior stencil has constant coefficients per segment, so it
    /// auto-vectorises.
    pub fn bulk(&mut self) {
        let mesh = &self.mesh;
        for (s, c) in self.coef.iter().enumerate() {
            let o = mesh.offset[s];
            let k = mesh.cells[s];
            let (up, uc, un) = (
                &self.u_prev[o..=o + k],
                &self.u[o..=o + k],
                &mut self.u_next[o..=o + k],
            );
            // equal-length slices: no bounds checks, SIMD
            let (left, mid, right) = (&uc[..k - 1], &uc[1..k], &uc[2..]);
            let prev = &up[1..k];
            let out = &mut un[1..k];
            if c.exact {
                // Courant 1, no damping: u+ = u_{j+1} + u_{j-1} - u-
                for (((o, l), r), p) in out.iter_mut().zip(left).zip(right).zip(prev) {
                    *o = l + r - p;
                }
            } else {
                let (a, b, cc) = (c.a, c.b, c.c);
                for ((((o, l), m), r), p) in out.iter_mut().zip(left).zip(mid).zip(right).zip(prev)
                {
                    *o = a * m + b * (l + r) - cc * p;
                }
            }
            // end nodes (half mass): internal force from the one neighbour
            un[0] = c.a_end * uc[0] + c.b_end * uc[1] - c.c * up[0];
            un[k] = c.a_end * uc[k] + c.b_end * uc[k - 1] - c.c * up[k];
        }
    }

    /// Transparent first end at the step from `t` to `t + dt` (s), injecting the incident
    /// wave when there is one: the outgoing part `w = u - u_inc` obeys
    /// `w0+ = w0 + r (w1 - w0)` (first-order absorbing, exact at Courant 1).
    #[inline]
    pub fn transparent_first(&mut self, t: f64, t1: f64) {
        let (len0, c0, inc) = match &self.ends {
            Ends::General { inc, c0, len0 } => (*len0, *c0, inc),
            Ends::CourantOne { levels } => {
                let m = self.level;
                let before = if m == 0 { 0.0 } else { at(levels, m - 1) };
                self.u_next[0] = at(levels, m + 1) + self.u[1] - before;
                return;
            }
        };
        let r = self.mesh.courant[0];
        let (a, b, c) = match inc {
            Some(tab) => (
                tab.at(t1 + len0 / c0),
                tab.at(t + len0 / c0),
                tab.at(t + (len0 - self.mesh.dx[0]) / c0),
            ),
            None => (0.0, 0.0, 0.0),
        };
        let w0 = self.u[0] - b;
        let w1 = self.u[1] - c;
        self.u_next[0] = a + w0 + r * (w1 - w0);
    }

    /// Transparent last end (first-order absorbing, exact at Courant 1).
    #[inline]
    pub fn transparent_last(&mut self) {
        let last = self.mesh.nodes - 1;
        if let Ends::CourantOne { .. } = self.ends {
            self.u_next[last] = self.u[last - 1];
            return;
        }
        let r = self.mesh.courant[self.mesh.courant.len() - 1];
        self.u_next[last] = self.u[last] + r * (self.u[last - 1] - self.u[last]);
    }

    /// The outgoing displacement `u - F` at the first end at the current level, m, for a
    /// field of [`Field::courant_one`] (`None` for the bar stack's fields, whose levels are
    /// not on the incident wave's grid).
    pub fn outgoing_first(&self) -> Option<f64> {
        match &self.ends {
            Ends::CourantOne { levels } => Some(self.u[0] - at(levels, self.level)),
            Ends::General { .. } => None,
        }
    }

    /// Whether every displacement of the next level is finite.
    pub fn finite(&self) -> bool {
        self.u_next.iter().all(|v| v.is_finite())
    }

    /// Advance one level.
    #[inline]
    pub fn rotate(&mut self) {
        std::mem::swap(&mut self.u_prev, &mut self.u);
        std::mem::swap(&mut self.u, &mut self.u_next);
        self.level += 1;
    }
}

/// `levels[m]`, the last entry past the end.
#[inline]
fn at(levels: &[f64], m: usize) -> f64 {
    levels.get(m).or(levels.last()).copied().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::excitation::{ToneBurst, Window};

    /// A bar of `K` cells at Courant 1 with a free far end: the incident displacement
    /// `F` crosses it unchanged (`u_K = 2 F` at the free end, the reflection doubling it)
    /// and leaves through the transparent first end `2 K` levels after it entered, with no
    /// spurious reflection there.
    #[test]
    fn courant_one_bar_carries_the_wave_unchanged_and_the_free_end_doubles_it() {
        const K: usize = 16;
        let (z, dt) = (1.7e6, 1e-8);
        let burst = ToneBurst::new(
            2e5,
            1e6,
            3.0,
            Window::HannRamps {
                ramp_fraction: 0.25,
            },
        );
        let levels = 600;
        let mut f = Field::courant_one(dt, &[K], &[z], &burst, levels);
        let tab = match &f.ends {
            Ends::CourantOne { levels } => levels.clone(),
            Ends::General { .. } => unreachable!(),
        };
        let peak = tab.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(peak > 1e-9, "the burst moves the bar: {peak}");
        for m in 0..levels - 1 {
            f.bulk();
            f.transparent_first(0.0, 0.0);
            f.rotate();
            let level = m + 1;
            let free_end = if level >= K {
                2.0 * tab[level - K]
            } else {
                0.0
            };
            let out = if level >= 2 * K {
                tab[level - 2 * K]
            } else {
                0.0
            };
            assert!(
                (f.u[K] - free_end).abs() <= 1e-12 * peak,
                "level {level}: u_K = {:e}, 2F = {free_end:e}",
                f.u[K]
            );
            let got = f.outgoing_first().unwrap();
            assert!(
                (got - out).abs() <= 1e-12 * peak,
                "level {level}: outgoing {got:e}, F delayed {out:e}"
            );
        }
    }
}
