//! One scalar displacement field on the stack: the longitudinal displacement (wave speed
//! `c_L = sqrt(E / rho)`) or the transverse one of a shear wave (`c_T = sqrt(G / rho)`),
//! each on its own mesh at the common time step. The bulk update, the end conditions
//! that need no interface law, and the injection of an incident wave through a
//! transparent first end live here; the time loop of [`super::BarStack::run`] moves the
//! fields and couples them at the interfaces. Nothing here allocates after
//! [`Field::new`].

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

/// A scalar displacement field on the stack, with its state at three time levels.
#[derive(Debug)]
pub(super) struct Field {
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
    /// Incident displacement table of a transparent first end.
    inc: Option<IncidentTable>,
    /// Wave speed of the first segment, m/s.
    c0: f64,
    /// Length of the first segment as meshed, m.
    len0: f64,
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
        // per-segment stencil coefficients: u+ = a u + b (u_l + u_r) - c u- (interior),
        // end nodes with half mass: u+ = a_end u + b_end u_neighbour - c u-
        let coef: Vec<Coef> = (0..stack.segments.len())
            .map(|s| {
                let r2 = mesh.courant[s] * mesh.courant[s];
                let h = stack.segments[s].damping * dt;
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
            inc,
            c0,
            len0,
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
        let r = self.mesh.courant[0];
        let (len0, c0) = (self.len0, self.c0);
        let (a, b, c) = match &self.inc {
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
        let r = self.mesh.courant[self.mesh.courant.len() - 1];
        self.u_next[last] = self.u[last] + r * (self.u[last - 1] - self.u[last]);
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
    }
}
