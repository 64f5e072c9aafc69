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
//!
//! Time levels of what a point records ([`PointFields`]): the gaps, the adhesion and a
//! compliant branch's stress (`sigma(U^{n+1})`, a spring's, an elastic stick's) belong to
//! the new level `t_{n+1}` of the update that finds them. A constraint's reaction (the
//! normal stress closed on a rigid compression branch or bonded on a rigid traction branch,
//! a rigid-stick slider's stress in stick and in slip, whose limit is `mu N` of the normal
//! stress applied over the same step) is the force of the central-difference step that
//! starts at level n: it enforces the constraint at `t_{n+1}` but belongs to `t_n`, where
//! it acts in `M (u^{n+1} - 2 u^n + u^{n-1}) / dt^2 = f^n - K u^n + B S^n`. So the fields of
//! level n are complete only after the update n -> n + 1: it keeps them in
//! [`CrackNodes::fields`], each stress at its own level.

use crate::error::Result;
use crate::law::contact::{update_point, InterfaceScheme, PointState, StepContext, Trial};
use crate::law::{CompressionBranch, NormalPart, TangentialBranch, TangentialPart, TractionBranch};

/// One point's recorded fields at one time level (a row of `crack.csv`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointFields {
    /// Normal gap `U_N`, m.
    pub normal_gap: f64,
    /// Tangential gap `U_T`, m.
    pub tangential_gap: f64,
    /// Normal contact stress sigma (tension positive, `-p0` at rest), Pa.
    pub normal_stress: f64,
    /// Contact shear stress tau (`q0` at rest), Pa.
    pub shear_stress: f64,
    /// Adhesion beta.
    pub adhesion: f64,
    /// Contact state: 0 open (the normal gap beyond the law's contact-loss gap), 1 stick,
    /// 2 slip (sliding, or closed without friction), the slider's of the step whose shear
    /// stress is recorded.
    pub state: f64,
}

impl PointFields {
    /// The fields of a point at rest in `state` (Pa, m): its static stresses.
    pub fn at_rest<L: NormalPart + TangentialPart>(law: &L, state: &PointState) -> Self {
        Self::of_level(law, state, state, [0.0; 2])
    }

    /// The fields of level n of a point from its state `old` of level n, its state `new`
    /// of level n + 1 and the dynamic stresses `applied` (`[S_N, S_T]`, Pa) of the update
    /// between them: a stress of `old` that is a constraint's reaction belongs to level
    /// n - 1, and the reaction of level n is the update's `applied` (whatever the update
    /// found: a point that opens over the step has the open law's stress there, none for
    /// traction-free faces); every other field is `old`'s own.
    fn of_level<L: NormalPart + TangentialPart>(
        law: &L,
        old: &PointState,
        new: &PointState,
        applied: [f64; 2],
    ) -> Self {
        let uc = law.critical_gap();
        let normal_reaction = (old.gap <= uc && law.compression().is_rigid())
            || (old.gap >= uc && law.traction().is_rigid());
        // a rigid-stick slider under load (NaN: free, no slider stress: the law's own)
        let shear_reaction =
            law.branch().stick_stiffness().is_infinite() && !old.shear.state.is_nan();
        let normal_stress = if normal_reaction {
            applied[0] - law.static_pressure()
        } else {
            old.stress
        };
        let (shear_stress, slider) = if shear_reaction {
            (applied[1] + law.static_shear(), new.shear.state)
        } else {
            (old.shear_stress(law), old.shear.state)
        };
        PointFields {
            normal_gap: old.gap,
            tangential_gap: old.shear.gap,
            normal_stress,
            shear_stress,
            adhesion: old.beta,
            // open: on the law's traction side, beyond the gap where the compression
            // branch lets go (0 for Signorini; a compliant branch still presses its faces
            // at a positive gap from rest)
            state: if old.gap > uc {
                0.0
            } else if slider == 0.0 {
                1.0
            } else {
                2.0
            },
        }
    }
}

/// One crack's split nodes and their state.
#[derive(Debug, Clone)]
pub struct CrackNodes<L> {
    /// Unit normal of each point (from face 1 to face 2), `[x, z]`: one value along a
    /// straight crack, the averaged normal of the edges at a kink, exact at the GLL points
    /// of a curved (second-order) edge.
    pub normal: Vec<[f64; 2]>,
    /// Unit tangent of each point `[x, z]` (plane strain; antiplane runs use `y`).
    pub tangent: Vec<[f64; 2]>,
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
    /// The fields of each point at the level the last update started from (`t_n` of the
    /// update n -> n + 1, s), each stress at its own level (the module's top comment):
    /// what the recorder writes.
    pub fields: Vec<PointFields>,
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
        for k in 0..self.faces.len() {
            let (i1, i2) = self.faces[k];
            let [nx, nz] = self.normal[k];
            let [tx, tz] = self.tangent[k];
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
            let old = *st;
            let [sn, stt] = update_point(law, Some(law), &trial, ctx, st)?;
            self.fields[k] = PointFields::of_level(law, &old, st, [sn, stt]);
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
