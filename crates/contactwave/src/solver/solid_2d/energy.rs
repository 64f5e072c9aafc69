//! The energy audit of a 2D run (docs/model.md section 15.3, eq. 15.5): what the sources
//! put in, what the solid holds at the end, what the cracks and the absorbing layers took,
//! and the cracks' losses as the contact update tallies them.

/// The energy audit of a run, J/m (per unit length along y).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy2d {
    /// Work of the sources.
    pub input: f64,
    /// Discrete energy of the solid at the end (`E^{N-1/2}`).
    pub solid: f64,
    /// Energy taken by the cracks (stored in their laws, dissipated by friction, damage
    /// and the discrete impacts of rigid contact).
    pub cracks: f64,
    /// Energy that flowed into the absorbing layers: the work done on them through the
    /// nodes of their inner boundary (discrete, exact).
    pub absorbed: f64,
    /// Of `cracks`, the work of the shear tractions on the tangential gaps (the rest is
    /// the normal tractions' on the normal gaps).
    pub cracks_tangential: f64,
    /// The work of the cracks' static shear q0 through their final slip, `sum B q0 s`
    /// (with friction; 0 without): done by the pre-stress, not by the sources, and
    /// dissipated by friction too (the coupled 1D solver's `static_shear_work`).
    pub static_shear_work: f64,
    /// The energy dissipated by friction, `sum B tau_f Delta s` over the points and steps
    /// (the per-point tally of the contact update, model.md 15.3): on a crack that stays
    /// shut with rigid stick it is `cracks_tangential + static_shear_work` to within the
    /// tally's own time discretisation (6e-4 in the test
    /// `sh_wave_on_a_frictional_interface_slips_within_coulomb`); a clapping crack also
    /// loses tangential work when its faces are arrested at closure.
    pub friction: f64,
    /// The energy released by damage, `sum B (dpsi/dbeta) (-Delta beta)` (the per-point
    /// tally).
    pub damage: f64,
}

impl Energy2d {
    /// The audit of a run from the sources' work `input`, the solid's final energy `solid`
    /// and the flux `absorbed` (J/m), and the cracks' own tallies: their work, its
    /// tangential part, the static shear's work through the final slip (with friction)
    /// and the per-point friction and damage over the points' lengths.
    pub fn audit<L: crate::law::NormalPart + crate::law::TangentialPart>(
        input: f64,
        solid: f64,
        absorbed: f64,
        cracks: &[super::crack::CrackNodes<L>],
    ) -> Energy2d {
        let tally = |f: fn(&crate::law::contact::PointState) -> f64| -> f64 {
            cracks
                .iter()
                .flat_map(|c| c.weight.iter().zip(&c.state).map(move |(b, s)| b * f(s)))
                .sum()
        };
        let static_shear_work = cracks
            .iter()
            .flat_map(|c| {
                (0..c.weight.len()).map(move |k| {
                    let law = &c.law[k];
                    if crate::law::TangentialBranch::friction(law.branch()) > 0.0 {
                        c.weight[k] * law.static_shear() * c.state[k].shear.slip
                    } else {
                        0.0
                    }
                })
            })
            .sum();
        Energy2d {
            input,
            solid,
            cracks: cracks.iter().map(|c| c.work).sum(),
            absorbed,
            cracks_tangential: cracks.iter().map(|c| c.tangential_work).sum(),
            static_shear_work,
            friction: tally(|s| s.friction),
            damage: tally(|s| s.damage),
        }
    }

    /// `|input - solid - cracks - absorbed| / input`.
    pub fn closure_error(&self) -> f64 {
        (self.input - self.solid - self.cracks - self.absorbed).abs()
            / self.input.abs().max(f64::MIN_POSITIVE)
    }
}
