//! A crack as a boundary object (model.md section 9; SEM2DPACK's split-node faults): plain
//! arrays, one value per split node (the face nodes, the boundary weight, the compliances,
//! the law and its state), updated in one loop per step by the one per-point contact
//! update of `law/` ([`crate::law::contact::update_point`]). The bulk kernel knows nothing
//! of it.
//!
//! Each step the faces' predicted motion without the crack's tractions gives the trial
//! gaps `U~ = (u2 - u1).n`, `(u2 - u1).t` at the new level; the traction `(S_N n + S_T t)`
//! (dynamic, tension positive) acts as the force `+B (S_N n + S_T t)` on face 1 and its
//! opposite on face 2, so that `U = U~ - chi S` with `chi = dt^2 B (1/M1 + 1/M2)`: the
//! equation of the 1D schemes, solved exactly at the new level by the law (no penalty).

use crate::error::Result;
use crate::law::contact::{update_point, InterfaceScheme, PointState, StepContext, Trial};
use crate::law::{NormalPart, TangentialPart};

/// One crack's split nodes and their state.
#[derive(Debug, Clone)]
pub struct CrackNodes<L> {
    /// Unit normal (from face 1 to face 2) and tangent, `[x, z]`.
    pub normal: [f64; 2],
    /// Unit tangent `[x, z]` (plane strain; antiplane runs use `y`).
    pub tangent: [f64; 2],
    /// Face-1 and face-2 node of each point.
    pub faces: Vec<(usize, usize)>,
    /// Position along the crack of each point, m (from its start).
    pub position: Vec<f64>,
    /// Boundary weight B of each point (its share of the crack's length), m.
    pub weight: Vec<f64>,
    /// `dt B / M` of face 1 and face 2: the velocity change of a face per unit dynamic
    /// stress applied over one step, (m/s)/Pa.
    pub kick: Vec<(f64, f64)>,
    /// Compliance `chi = dt^2 B (1/M1 + 1/M2)` of each point, m/Pa.
    pub compliance: Vec<f64>,
    /// The law of each point (`Copy` data).
    pub law: Vec<L>,
    /// Normal gap of each point at rest, m (0: closed).
    pub initial_gap: Vec<f64>,
    /// The state of each point.
    pub state: Vec<PointState>,
    /// Normal and tangential gaps of each point at the previous and the current level
    /// (`[U^{n-1}, U^n]`, for the energy), m.
    pub gaps: Vec<[[f64; 2]; 2]>,
    /// The dynamic stresses applied over the last step, `[S_N, S_T]`, Pa.
    pub applied: Vec<[f64; 2]>,
    /// Energy taken by the crack so far, `sum B S (U^{n+1} - U^{n-1}) / 2`, J/m.
    pub work: f64,
    /// Its tangential part, the shear tractions' `sum B S_T (U_T^{n+1} - U_T^{n-1}) / 2`,
    /// J/m.
    pub tangential_work: f64,
}

impl<L: NormalPart + TangentialPart> CrackNodes<L> {
    /// Update every point of the crack to the new level and kick its faces: `u` holds the
    /// predicted displacements of the new level (m) and `v` the predicted velocities of
    /// the step (m/s), both without the crack's tractions; each face gets its velocity
    /// kick and the displacement `dt` times it (`dt` s). `antiplane`: one component per
    /// node, the tangential gap along y and no normal motion.
    pub fn update(
        &mut self,
        u: &mut [f64],
        v: &mut [f64],
        dt: f64,
        t_new: f64,
        antiplane: bool,
    ) -> Result<()> {
        let ctx = StepContext {
            scheme: InterfaceScheme::Average,
            dt,
            t: t_new,
        };
        let [nx, nz] = self.normal;
        let [tx, tz] = self.tangent;
        for k in 0..self.faces.len() {
            let (i1, i2) = self.faces[k];
            let chi = self.compliance[k];
            let (gn, gt) = if antiplane {
                (self.initial_gap[k], u[i2] - u[i1])
            } else {
                let dx = u[2 * i2] - u[2 * i1];
                let dz = u[2 * i2 + 1] - u[2 * i1 + 1];
                (self.initial_gap[k] + dx * nx + dz * nz, dx * tx + dz * tz)
            };
            let trial = Trial {
                normal_gap: gn,
                normal_compliance: chi,
                tangential_gap: gt,
                tangential_compliance: chi,
            };
            let law = &self.law[k];
            let st = &mut self.state[k];
            let [sn, stt] = update_point(law, Some(law), &trial, ctx, st)?;
            let (k1, k2) = self.kick[k];
            let mut kick = |i: usize, dv: f64| {
                v[i] += dv;
                u[i] += dt * dv;
            };
            if antiplane {
                kick(i1, k1 * stt);
                kick(i2, -k2 * stt);
            } else {
                let fx = sn * nx + stt * tx;
                let fz = sn * nz + stt * tz;
                kick(2 * i1, k1 * fx);
                kick(2 * i1 + 1, k1 * fz);
                kick(2 * i2, -k2 * fx);
                kick(2 * i2 + 1, -k2 * fz);
            }
            let new = [st.gap, st.shear.gap];
            let [old, now] = self.gaps[k];
            self.work += 0.5 * self.weight[k] * (sn * (new[0] - old[0]) + stt * (new[1] - old[1]));
            self.tangential_work += 0.5 * self.weight[k] * (stt * (new[1] - old[1]));
            self.gaps[k] = [now, new];
            self.applied[k] = [sn, stt];
        }
        Ok(())
    }
}
