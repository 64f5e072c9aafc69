//! The quadrature of the exact solvers' wave integrals (model.md section 6): over a step
//! of the plane interface, the incident, reflected and transmitted displacements and
//! energies of one wave component (normal or shear) from the stress at the step's
//! quadrature nodes, shared by the normal ([`super::half_space`]) and the coupled
//! ([`super::coupled`]) solvers.
//!
//! One form: the weighted sums over the nodes first ([`StageSums`], weights of the unit
//! step), then scaled by `h / Z` ([`WaveIntegrals::add`]). The normal solver's stuck phase
//! (`S = g s_inc` with a constant gain `g`) is its specialisation
//! ([`WaveIntegrals::add_proportional`]): the sums of `s_inc` and `s_inc^2` give all.

use super::output::EnergyAudit;

/// The weighted sums over a step's quadrature nodes (weights of the unit step) of `s_inc`,
/// `s_ref`, `s_inc^2`, `s_ref^2`, `S` and `S^2`, with `S` the dynamic interface stress
/// (`sigma + p0` or `tau - q0`) and `s_ref = S - s_inc` (Pa and Pa^2).
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct StageSums([f64; 6]);

impl StageSums {
    /// Add a node of weight `w` with incident stress `sinc` and dynamic stress `s` (Pa).
    #[inline]
    pub(crate) fn add(&mut self, w: f64, sinc: f64, s: f64) {
        let sref = s - sinc;
        let v = &mut self.0;
        v[0] += w * sinc;
        v[1] += w * sref;
        v[2] += w * sinc * sinc;
        v[3] += w * sref * sref;
        v[4] += w * s;
        v[5] += w * s * s;
    }
}

/// The running integrals over time of one wave component: the incident, reflected and
/// transmitted displacements at the interface (m; `-int s_inc / Z1`, `int s_ref / Z1`,
/// `-int S / Z2`) and the energies of the three waves (J/m^2; `int s^2 / Z`).
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct WaveIntegrals {
    pub(crate) disp_inc: f64,
    pub(crate) disp_ref: f64,
    pub(crate) disp_tr: f64,
    pub(crate) e_inc: f64,
    pub(crate) e_ref: f64,
    pub(crate) e_tr: f64,
}

impl WaveIntegrals {
    /// Add a step of length `h` (s) from its node sums, with admittances `inv_z1 = 1/Z1`
    /// and `inv_z2 = 1/Z2` (m/(Pa s); 0 at a rigid wall: nothing transmitted). With
    /// `displacements` false only the energies are added (at oblique incidence the
    /// displacements are projections of both components, added by the caller).
    #[inline]
    pub(crate) fn add(
        &mut self,
        h: f64,
        inv_z1: f64,
        inv_z2: f64,
        sum: &StageSums,
        displacements: bool,
    ) {
        let sum = &sum.0;
        let (h1, h2) = (h * inv_z1, h * inv_z2);
        if displacements {
            self.disp_ref += h1 * sum[1];
            self.disp_inc -= h1 * sum[0];
            self.disp_tr -= h2 * sum[4];
        }
        self.e_inc += h1 * sum[2];
        self.e_ref += h1 * sum[3];
        self.e_tr += h2 * sum[5];
    }

    /// Add a step of length `h` (s) where the dynamic stress is proportional to the
    /// incident one, `S = gain s_inc` (a stuck interface), from the node sums of `s_inc`
    /// (`sum_inc`, Pa) and `s_inc^2` (`sum_inc2`, Pa^2); admittances as [`WaveIntegrals::add`].
    #[inline]
    pub(crate) fn add_proportional(
        &mut self,
        h: f64,
        inv_z1: f64,
        inv_z2: f64,
        gain: f64,
        sum_inc: f64,
        sum_inc2: f64,
    ) {
        let g = gain;
        let (h1, h2) = (h * inv_z1, h * inv_z2);
        self.disp_ref += h1 * ((g - 1.0) * sum_inc);
        self.disp_inc -= h1 * sum_inc;
        self.e_inc += h1 * sum_inc2;
        self.e_ref += h1 * ((g - 1.0) * (g - 1.0) * sum_inc2);
        self.disp_tr -= h2 * (g * sum_inc);
        self.e_tr += h2 * (g * g * sum_inc2);
    }

    /// The energy audit of the component with the interface's `stored` energy, the
    /// energy released by `damage` and the `adhesion_decrease` (J/m^2).
    pub(crate) fn audit(&self, stored: f64, damage: f64, adhesion_decrease: f64) -> EnergyAudit {
        EnergyAudit {
            incident: self.e_inc,
            reflected: self.e_ref,
            transmitted: self.e_tr,
            stored,
            damage,
            adhesion_decrease,
        }
    }
}
