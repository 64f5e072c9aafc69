//! Exact solver of the half-space problem with two degrees of freedom (model.md section
//! 13): a normal gap `[u]_N` and a tangential gap `[u]_T`, driven by a normally incident
//! longitudinal wave `s_inc`, a shear wave `tau_inc`, or both, under a static pressure p0
//! and a static shear q0.
//!
//! d'Alembert's solution reduces the problem exactly to two ODEs at the interface,
//!
//! ```text
//! d[u]_N/dt = 2 s_inc/Z1  - (sigma + p0) (1/Z1  + 1/Z2)
//! d[u]_T/dt = 2 tau_inc/Z1T - (tau - q0)  (1/Z1T + 1/Z2T)
//! ```
//!
//! coupled through the contact law: Coulomb friction `|tau_f| <= mu N` takes the normal
//! contact pressure N, and the full RCCM law's damage is driven by the energy of both gaps.
//! Each phase (normal: held, compression, traction; tangential: free, stick, slip in each
//! direction; damage on or off) is integrated with the 3-stage Radau IIA method on the
//! output grid, split at the waveforms' breakpoints; every switch (opening, closing, stick
//! to slip, slip reversal and arrest, damage onset and arrest) is located by a bracketing
//! root-finder on its event function. Rigid branches hold their gap exactly and give the
//! constraint stress. Energies (fluxes, stored, damage, friction) are integrated with the
//! same quadrature, so the audit closes to the integration error.

mod oblique;
mod state;

use self::state::{Eval, Interface, Normal, Phase, Scales, SliderPhase};
use super::exact_loop::{self, Driven, Grid, GridSolver};
use super::half_space::{HalfSpace, HalfSpaceSettings};
use super::output::HalfSpaceOutput;
use super::quadrature::{StageSums, WaveIntegrals};
use super::radau::{self, System, B, C};
use super::Solver;
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::law::TangentialLaw;
use crate::material::admittance as inv;
use std::sync::Arc;

/// Number of interface unknowns, `y = ([u]_N, beta, [u]_T)`.
const N: usize = 3;

/// The interface of the current phase as a Radau system: no analytic Jacobian (the
/// step's difference quotients), the phase's evolving unknowns.
impl System<N> for Interface<'_> {
    fn rhs_forced(&self, t: f64, _g: f64, y: [f64; N]) -> [f64; N] {
        self.eval(t, &y).rate
    }
    fn active(&self) -> [bool; N] {
        Interface::active(self)
    }
}

/// The coupled problem: the normal half-space problem plus shear impedances, the
/// tangential law and the incident shear wave.
#[derive(Debug, Clone)]
pub struct CoupledHalfSpace {
    /// Normal problem: media, normal law, incident longitudinal wave.
    pub normal: HalfSpace,
    /// Shear impedance of medium 1 `Z1T = rho1 c_T1`, Pa s/m.
    pub z1t: f64,
    /// Shear impedance of medium 2, Pa s/m (`inf`: rigid wall).
    pub z2t: f64,
    /// Tangential law (static shear q0 and branch).
    pub tangential: Arc<TangentialLaw>,
    /// Incident shear stress at the interface `tau_inc(t)`, Pa.
    pub shear_incident: Arc<dyn Excitation>,
    /// Oblique incidence (model.md section 14): the plane-wave compliances that replace
    /// the impedances above, and `normal.incident` / `shear_incident` are the normal and
    /// tangential tractions of the incident wave at the interface. `None`: normal
    /// incidence.
    pub oblique: Option<ObliqueCoupling>,
}

/// The plane-wave coupling of the interface at oblique incidence (model.md section 14),
/// matrices `[normal, tangential]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObliqueCoupling {
    /// Compliance of medium 1 (its down-going P/SV pair), m/(Pa s): the incident wave's
    /// face velocity is `v_inc = -C1 sigma_inc`, the reflected waves' `v_ref = C1^T sigma_ref`.
    pub c1: [[f64; 2]; 2],
    /// Compliance of medium 2 (zero for a rigid wall), m/(Pa s): `v_tr = -C2 sigma_tr`.
    pub c2: [[f64; 2]; 2],
    /// Reflected P and SV particle velocities per unit reflected traction, m/(Pa s).
    pub reflected_waves: [[f64; 2]; 2],
    /// Energy flux of the reflected P and SV waves per unit squared particle velocity,
    /// `rho c cos(angle)`, Pa s/m.
    pub reflected_flux: [f64; 2],
    /// Transmitted P and SV particle velocities per unit transmitted traction (zero for a
    /// rigid wall), m/(Pa s).
    pub transmitted_waves: [[f64; 2]; 2],
    /// Energy flux of the transmitted P and SV waves per unit squared particle velocity,
    /// Pa s/m.
    pub transmitted_flux: [f64; 2],
}

impl ObliqueCoupling {
    /// The coupling of a plane-wave geometry (`crate::analytic::oblique`).
    pub fn new(g: &crate::analytic::oblique::Geometry) -> Self {
        use crate::analytic::oblique::Geometry;
        let (c2, tw, tf) = match &g.transmitted {
            Some(t) => (
                Geometry::compliance(t),
                Geometry::traction_to_waves(t),
                [t[0].flux, t[1].flux],
            ),
            None => ([[0.0; 2]; 2], [[0.0; 2]; 2], [0.0; 2]),
        };
        ObliqueCoupling {
            c1: Geometry::compliance(&g.down1),
            c2,
            reflected_waves: Geometry::traction_to_waves(&g.reflected),
            reflected_flux: [g.reflected[0].flux, g.reflected[1].flux],
            transmitted_waves: tw,
            transmitted_flux: tf,
        }
    }
}

impl CoupledHalfSpace {
    /// Fundamental f0 of the analysis and of the tail, Hz: the longitudinal wave's, or the
    /// shear wave's when it is the only one.
    pub fn fundamental(&self) -> f64 {
        let (n, s) = (&self.normal.incident, &self.shear_incident);
        if n.peak() > 0.0 || s.peak() == 0.0 {
            n.fundamental()
        } else {
            s.fundamental()
        }
    }

    /// Highest frequency of either wave (sets the time step), Hz.
    pub fn highest_frequency(&self) -> f64 {
        self.normal
            .incident
            .highest_frequency()
            .max(self.shear_incident.highest_frequency())
    }

    /// Duration of the longer wave (delay included), s.
    pub fn duration(&self) -> f64 {
        self.normal
            .incident
            .duration()
            .max(self.shear_incident.duration())
    }
}

/// Histories of a coupled run.
#[derive(Debug, Clone, Default)]
pub struct CoupledOutput {
    /// Normal histories (the same form as the normal-only solver's).
    pub normal: HalfSpaceOutput,
    /// Tangential histories in the same form: `gap` is `[u]_T` (m), `contact_stress` the
    /// shear stress tau (Pa, q0 at rest), incident/reflected/transmitted the shear
    /// stresses and displacements; `energy` holds the shear fluxes and the tangential
    /// stored energy.
    pub shear: HalfSpaceOutput,
    /// Accumulated slip s, m (equal to `[u]_T` for rigid stick).
    pub slip: Vec<f64>,
    /// Friction limit `mu N`, Pa.
    pub friction_limit: Vec<f64>,
    /// Slider state at each sample: 0 stick, +1 / -1 slipping in that direction, NaN
    /// free (no friction load).
    pub slip_state: Vec<f64>,
    /// Energy dissipated by friction `int tau_f ds`, J/m^2.
    pub friction_dissipation: f64,
    /// Work of the static shear through the final slip, `q0 s_end`, J/m^2.
    pub static_shear_work: f64,
    /// Time spent slipping while a burst was at the interface, s.
    pub slip_time_in_burst: f64,
    /// Number of stick/slip switches located.
    pub slip_events: usize,
    /// At oblique incidence, the energy carried away by the reflected P, reflected SV,
    /// transmitted P and transmitted SV waves (flux normal to the interface), J/m^2; zero
    /// at normal incidence.
    pub wave_energy: [f64; 4],
}

impl CoupledOutput {
    /// Empty for a new run of output step `dt` (s) and burst duration `burst_duration`
    /// (s): every series cleared with its allocation kept, every scalar reset.
    pub fn reset(&mut self, dt: f64, burst_duration: f64) {
        let mut fresh = CoupledOutput::default();
        std::mem::swap(&mut fresh.normal, &mut self.normal);
        std::mem::swap(&mut fresh.shear, &mut self.shear);
        fresh.normal.reset(dt, burst_duration);
        fresh.shear.reset(dt, burst_duration);
        for (new, old) in [
            (&mut fresh.slip, &mut self.slip),
            (&mut fresh.friction_limit, &mut self.friction_limit),
            (&mut fresh.slip_state, &mut self.slip_state),
        ] {
            std::mem::swap(new, old);
            new.clear();
        }
        *self = fresh;
    }

    /// Energy brought by both incident waves, J/m^2.
    pub fn incident_energy(&self) -> f64 {
        self.normal.energy.incident + self.shear.energy.incident
    }

    /// Relative closure error of the energy audit: incident - reflected - transmitted
    /// (both wave types) against stored + damage + friction - q0 s_end.
    pub fn closure_error(&self) -> f64 {
        let n = &self.normal.energy;
        let s = &self.shear.energy;
        let flux =
            n.incident - n.reflected - n.transmitted + s.incident - s.reflected - s.transmitted;
        let sink =
            n.stored + s.stored + n.damage + self.friction_dissipation - self.static_shear_work;
        (flux - sink).abs() / self.incident_energy().max(f64::MIN_POSITIVE)
    }
}

/// The coupled exact solver as a [`Solver`].
#[derive(Debug, Clone, Copy, Default)]
pub struct CoupledSolver {
    /// Sampling and tail settings (`summary_only` is ignored: every history is kept).
    pub settings: HalfSpaceSettings,
}

impl Solver for CoupledSolver {
    type Problem = CoupledHalfSpace;
    /// (nothing kept from run to run)
    type Workspace = ();
    type Output = CoupledOutput;
    fn run_in(
        &self,
        problem: &CoupledHalfSpace,
        _: &mut (),
        out: &mut CoupledOutput,
    ) -> Result<()> {
        CoupledRun::new(problem, &self.settings).run(out)
    }
}

/// The running integrals of a run over time, `[normal, shear]` where paired: the wave
/// energies (J/m^2) and displacements (m), the energy released by damage and dissipated
/// by friction (J/m^2), the time open and slipping while a burst was at the interface (s),
/// and at oblique incidence the four outgoing waves' energies (J/m^2).
#[derive(Debug, Default, Clone, Copy)]
struct Integrals {
    wave: [WaveIntegrals; 2],
    damage: f64,
    friction: f64,
    open_in_burst: f64,
    slip_in_burst: f64,
    wave_energy: [f64; 4],
}

/// One run of the coupled solver: the interface of the current phase, its scales, the
/// grid step and the event counts (the time loop is [`exact_loop::run`], driving it
/// as a [`Driven`] run).
struct CoupledRun<'a> {
    p: &'a CoupledHalfSpace,
    settings: HalfSpaceSettings,
    iface: Interface<'a>,
    scales: Scales,
    h: f64,
    f0: f64,
    duration: f64,
    /// The waveforms' breakpoints, s.
    breaks: Vec<f64>,
    events: usize,
    slip_events: usize,
    max_gap: f64,
    /// Impedances in effect: `(Z1, Z2, Z1T, Z2T)` at normal incidence, the inverses of the
    /// compliances' diagonals at oblique incidence, Pa s/m.
    z: [f64; 4],
}

impl<'a> CoupledRun<'a> {
    fn new(p: &'a CoupledHalfSpace, settings: &HalfSpaceSettings) -> Self {
        let hs = &p.normal;
        let law = &*hs.law;
        let tl = &*p.tangential;
        let (sn, st) = (hs.incident.peak(), p.shear_incident.peak());
        let f0 = p.fundamental();
        let h = 1.0 / (settings.samples_per_period.max(1) as f64 * p.highest_frequency());
        let duration = p.duration();
        let breaks: Vec<f64> = hs
            .incident
            .breakpoints()
            .into_iter()
            .chain(p.shear_incident.breakpoints())
            .collect();
        let z = match &p.oblique {
            None => [hs.z1, hs.z2, p.z1t, p.z2t],
            Some(o) => [
                1.0 / o.c1[0][0],
                inv(o.c2[0][0]),
                1.0 / o.c1[1][1],
                inv(o.c2[1][1]),
            ],
        };
        let k_n = 1.0 / z[0] + inv(z[1]);
        let k_t = 1.0 / z[2] + inv(z[3]);
        // K = C1^T + C2: off-diagonal terms at oblique incidence
        let (k_nt, k_tn) = match &p.oblique {
            None => (0.0, 0.0),
            Some(o) => (o.c1[1][0] + o.c2[0][1], o.c1[0][1] + o.c2[1][0]),
        };
        let stress = sn
            .max(st)
            .max(law.static_pressure)
            .max(tl.static_shear.abs())
            .max(1.0);
        let omega = 2.0 * std::f64::consts::PI * f0;
        let velocity = stress * k_n.max(k_t);
        let gap = velocity / omega;
        let scales = Scales {
            stress,
            gap,
            velocity,
            energy: stress * gap,
            power: stress * velocity,
        };
        let rigid_c = law.compression.is_rigid();
        let mu = tl.branch.friction();
        let phase = Phase {
            normal: if rigid_c {
                Normal::Held
            } else {
                Normal::Compression
            },
            tangential: if mu > 0.0 && law.static_pressure > 0.0 {
                SliderPhase::Stick
            } else {
                SliderPhase::Free
            },
            damaging: false,
        };
        let iface = Interface {
            law,
            tangential: tl,
            s_inc: &*hs.incident,
            tau_inc: &*p.shear_incident,
            two_over_z1: 2.0 / z[0],
            k_n,
            two_over_z1t: 2.0 / z[2],
            k_t,
            k_nt,
            k_tn,
            uc: law.critical_gap(),
            held_gap: 0.0,
            beta_frozen: 1.0,
            slip: 0.0,
            path: 0.0,
            phase_slip: 0.0,
            phase,
            fd_dt: 1e-4 * h,
        };
        CoupledRun {
            p,
            settings: *settings,
            iface,
            scales,
            h,
            f0,
            duration,
            breaks,
            events: 0,
            slip_events: 0,
            max_gap: 0.0,
            z,
        }
    }

    fn y_scale(&self) -> [f64; N] {
        [self.scales.gap, 1.0, self.scales.gap]
    }

    /// One step of the current phase; split in halves when Newton fails.
    fn step(&self, t: f64, y: &[f64; N], h: f64, depth: usize) -> Result<radau::Step<N>> {
        if let Some(s) = radau::step(&self.iface, t, *y, h, self.y_scale()) {
            return Ok(s);
        }
        if depth >= 30 {
            return Err(Error::numerical(
                t,
                format!("coupled interface solver: Newton iteration failed (step {h:e} s)"),
                format!("y = {y:?}, phase {:?}", self.iface.phase),
            ));
        }
        let a = self.step(t, y, 0.5 * h, depth + 1)?;
        let b = self.step(t + 0.5 * h, &a.end(), 0.5 * h, depth + 1)?;
        // stages of the combined step are only used for quadrature of smooth integrands:
        // take the end state and re-evaluate stage states by the halves' stages
        Ok(radau::Step {
            stages: [a.stages[2], b.stages[1], b.stages[2]],
            forcing: [0.0; 3],
        })
    }

    /// Integrals over a substep `[t, t + h]` from the stage values.
    fn accumulate(&self, acc: &mut Integrals, t: f64, h: f64, step: &radau::Step<N>) {
        let [z1, z2, z1t, z2t] = self.z;
        let p0 = self.iface.law.static_pressure;
        let q0 = self.iface.tangential.static_shear;
        let mut sums = [StageSums::default(); 2];
        for j in 0..3 {
            let w = h * B[j];
            let tj = t + C[j] * h;
            let y = step.stages[j];
            let e = self.iface.eval(tj, &y);
            let (sn, st) = (e.sigma + p0, e.tau - q0);
            sums[0].add(B[j], e.s_inc, sn);
            sums[1].add(B[j], e.tau_inc, st);
            if let Some(o) = &self.p.oblique {
                let (rn, rt) = (sn - e.s_inc, st - e.tau_inc);
                oblique::accumulate(o, acc, w, [e.s_inc, e.tau_inc], [rn, rt], [sn, st]);
            }
            // friction: tau_f ds/dt (the slider's work; zero while sticking)
            let slip_rate = match self.iface.phase.tangential {
                _ if self.iface.tangential.branch.friction() == 0.0 => 0.0,
                SliderPhase::Stick => 0.0,
                _ => e.slip_rate,
            };
            acc.friction += w * e.tau_f * slip_rate;
            // damage: dpsi/dbeta (-dbeta/dt)
            if self.iface.phase.damaging {
                let beta_dot = if e.rate[1] != 0.0 {
                    e.rate[1]
                } else {
                    let d = self.iface.fd_dt;
                    let mut yp = y;
                    for i in 0..N {
                        yp[i] += d * e.rate[i];
                    }
                    (self.iface.beta(&yp) - e.beta) / d
                };
                acc.damage += w * e.psi_beta * (-beta_dot).max(0.0);
            }
            if tj < self.duration {
                if self.iface.phase.normal == Normal::Traction {
                    acc.open_in_burst += w;
                }
                if matches!(self.iface.phase.tangential, SliderPhase::Slip(_)) {
                    acc.slip_in_burst += w;
                }
            }
        }
        let plane = self.p.oblique.is_none();
        acc.wave[0].add(h, 1.0 / z1, inv(z2), &sums[0], plane);
        acc.wave[1].add(h, 1.0 / z1t, inv(z2t), &sums[1], plane);
    }

    /// Slider stress of the current phase at `(t, y)`, Pa.
    fn slider_stress(&self, t: f64, y: &[f64; N]) -> f64 {
        self.iface.eval(t, y).tau_f
    }

    /// Switch the phase after event `which` fired at `(t, y)`; then make the phase
    /// consistent (every event function >= 0 at `(t, y)`).
    fn switch(&mut self, which: usize, t: f64, y: &mut [f64; N]) {
        self.events += 1;
        for round in 0..8 {
            let comp = if round == 0 {
                Some(which)
            } else {
                let e = self.iface.eval(t, y);
                let g = self.iface.events(t, y, &e, &self.scales);
                (0..3).find(|&k| g[k] < -1e-12)
            };
            let Some(k) = comp else { return };
            self.switch_one(k, t, y);
        }
    }

    fn switch_one(&mut self, k: usize, t: f64, y: &mut [f64; N]) {
        let law = self.iface.law;
        let uc = self.iface.uc;
        match k {
            0 => {
                let before = self.iface.phase.normal;
                let after = match before {
                    Normal::Compression => {
                        if law.traction.is_rigid() {
                            self.iface.held_gap = uc;
                            y[0] = uc;
                            Normal::Held
                        } else {
                            Normal::Traction
                        }
                    }
                    Normal::Traction => {
                        if law.compression.is_rigid() {
                            self.iface.held_gap = 0.0;
                            y[0] = 0.0;
                            Normal::Held
                        } else {
                            Normal::Compression
                        }
                    }
                    Normal::Held => {
                        if self.iface.held_gap == 0.0 && law.compression.is_rigid() {
                            Normal::Traction
                        } else {
                            Normal::Compression
                        }
                    }
                };
                // the slider loses or regains its normal load
                let tau_f = self.slider_stress(t, y);
                self.iface.phase.normal = after;
                let mu = self.iface.tangential.branch.friction();
                if after == Normal::Traction {
                    self.set_tangential(SliderPhase::Free, tau_f, y);
                } else if before == Normal::Traction && mu > 0.0 {
                    self.set_tangential(SliderPhase::Stick, tau_f, y);
                }
            }
            1 => {
                let e = self.iface.eval(t, y);
                let next = match self.iface.phase.tangential {
                    SliderPhase::Free => SliderPhase::Stick,
                    SliderPhase::Stick => {
                        SliderPhase::Slip(if e.tau_f >= 0.0 { 1.0 } else { -1.0 })
                    }
                    SliderPhase::Slip(_) => SliderPhase::Stick,
                };
                self.slip_events += 1;
                self.set_tangential(next, e.tau_f, y);
            }
            _ => {
                let beta = self.iface.beta(y);
                y[1] = beta;
                self.iface.beta_frozen = beta;
                self.iface.phase.damaging = !self.iface.phase.damaging;
            }
        }
    }

    /// Enter tangential phase `next`; `tau_f` is the slider stress just before.
    fn set_tangential(&mut self, next: SliderPhase, tau_f: f64, y: &[f64; N]) {
        let tl = self.iface.tangential;
        let kt = tl.branch.stick_stiffness();
        // the slip path: the phase that ends adds its (net) slip
        let slip_now = match self.iface.phase.tangential {
            _ if tl.branch.friction() == 0.0 => 0.0,
            SliderPhase::Stick => self.iface.slip,
            _ if kt.is_finite() => y[2] - (tau_f - tl.static_shear) / kt,
            _ => y[2],
        };
        self.iface.path += (slip_now - self.iface.phase_slip).abs();
        self.iface.phase_slip = slip_now;
        if next == SliderPhase::Stick {
            self.iface.slip = if kt.is_finite() {
                y[2] - (tau_f - tl.static_shear) / kt
            } else {
                y[2]
            };
        }
        self.iface.phase.tangential = next;
    }

    /// Accumulated slip at `(t, y)` in the current phase.
    fn slip_of(&self, e: &Eval, y: &[f64; N]) -> f64 {
        let tl = self.iface.tangential;
        let kt = tl.branch.stick_stiffness();
        match self.iface.phase.tangential {
            _ if tl.branch.friction() == 0.0 => 0.0,
            SliderPhase::Stick => self.iface.slip,
            _ if kt.is_finite() => y[2] - (e.tau_f - tl.static_shear) / kt,
            _ => y[2],
        }
    }

    /// Advance from `t` to `t_end` (no breakpoint inside), locating events.
    fn advance(
        &mut self,
        acc: &mut Integrals,
        mut t: f64,
        t_end: f64,
        y: &mut [f64; N],
    ) -> Result<()> {
        let mut guard = exact_loop::EventGuard::default();
        while t < t_end {
            guard.tick(t, "coupled interface solver", || {
                format!("y = {y:?}, phase {:?}", self.iface.phase)
            })?;
            let h = t_end - t;
            let st = self.step(t, y, h, 0)?;
            let yend = st.end();
            let e_end = self.iface.eval(t_end, &yend);
            let g_end = self.iface.events(t_end, &yend, &e_end, &self.scales);
            let crossing: Vec<usize> = (0..3).filter(|&k| g_end[k] < -1e-12).collect();
            if crossing.is_empty() {
                self.accumulate(acc, t, h, &st);
                *y = yend;
                self.after_step(y);
                return Ok(());
            }
            let e0 = self.iface.eval(t, y);
            let g0 = self.iface.events(t, y, &e0, &self.scales);
            // earliest root among the crossing events
            let mut best: Option<(f64, usize, Option<radau::Step<N>>)> = None;
            for &k in &crossing {
                let ga = g0[k].max(1e-300);
                let located = exact_loop::locate(
                    |hh| {
                        let s = self.step(t, y, hh, 0)?;
                        let ye = s.end();
                        let e = self.iface.eval(t + hh, &ye);
                        Ok((self.iface.events(t + hh, &ye, &e, &self.scales)[k], s))
                    },
                    h,
                    ga,
                    g_end[k],
                    st,
                );
                // (a trial step that fails, or no bracket: the event at the step's end)
                let (root, s_root) = match located {
                    Ok(Some(found)) => found,
                    _ => (h, None),
                };
                if best.as_ref().is_none_or(|(r, _, _)| root < *r) {
                    best = Some((root, k, s_root));
                }
            }
            let (root, k, s_root) = best.unwrap_or((h, crossing[0], None));
            let hh = root.max(f64::EPSILON * t.abs().max(h));
            let st = match s_root {
                _ if hh >= h => st,
                Some(s) if hh == root => s,
                _ => self.step(t, y, hh, 0)?,
            };
            self.accumulate(acc, t, hh, &st);
            *y = st.end();
            t = if hh >= h { t_end } else { t + hh };
            self.after_step(y);
            self.switch(k, t, y);
        }
        Ok(())
    }

    /// Keep the frozen adhesion of a rate-independent damaging phase current.
    fn after_step(&mut self, y: &mut [f64; N]) {
        if self.iface.phase.damaging && self.iface.law.traction.damage_viscosity() == 0.0 {
            let b = self.iface.beta(y);
            y[1] = b;
            self.iface.beta_frozen = b;
        }
        self.max_gap = self.max_gap.max(y[0]);
    }

    fn record(&self, out: &mut CoupledOutput, acc: &Integrals, t: f64, y: &[f64; N]) {
        let e = self.iface.eval(t, y);
        let p0 = self.iface.law.static_pressure;
        let q0 = self.iface.tangential.static_shear;
        for (o, gap, stress, inc, dyn_stress, c) in [
            (&mut out.normal, y[0], e.sigma, e.s_inc, e.sigma + p0, 0),
            (&mut out.shear, y[2], e.tau, e.tau_inc, e.tau - q0, 1),
        ] {
            o.push_summary(t, e.beta, acc.wave[c].disp_ref);
            o.push_fields(
                gap,
                stress,
                inc,
                dyn_stress,
                [acc.wave[c].disp_inc, acc.wave[c].disp_tr],
            );
        }
        out.slip.push(self.slip_of(&e, y));
        out.friction_limit.push(
            self.iface
                .tangential
                .friction_limit(e.pressure, self.iface.path(y)),
        );
        out.slip_state.push(match self.iface.phase.tangential {
            SliderPhase::Free => f64::NAN,
            SliderPhase::Stick => 0.0,
            SliderPhase::Slip(s) => s,
        });
    }

    fn at_rest(&self, t: f64, y: &[f64; N]) -> bool {
        let e = self.iface.eval(t, y);
        let v = 1e-9 * self.scales.velocity;
        !self.iface.phase.damaging
            && e.rate[0].abs() < v
            && e.rate[2].abs() < v
            && (self.iface.phase.normal != Normal::Compression
                || (y[0]).abs() < 1e-9 * self.scales.gap)
    }

    fn run(mut self, recorder: &mut CoupledOutput) -> Result<()> {
        let h = self.h;
        let grid = Grid::new(
            h,
            self.duration,
            self.f0,
            self.settings.tail_periods,
            std::mem::take(&mut self.breaks),
        );
        // the recorder's series, emptied (their allocations kept for this run)
        let mut out = std::mem::take(recorder);
        out.reset(h, self.duration);
        let acc = Integrals::default();
        let mut y = [0.0, 1.0, 0.0];
        // make the rest phase consistent (e.g. p0 = 0 with friction)
        {
            let e = self.iface.eval(0.0, &y);
            let g = self.iface.events(0.0, &y, &e, &self.scales);
            if let Some(k) = (0..3).find(|&k| g[k] < -1e-12) {
                self.switch(k, 0.0, &mut y);
                self.events = 0;
            }
        }
        self.record(&mut out, &acc, 0.0, &y);
        let mut run = Driven {
            solver: &mut self,
            acc,
            out,
        };
        let k = exact_loop::run(&grid, &mut run, &mut y)?;
        let Driven { acc, mut out, .. } = run;
        let law = self.iface.law;
        let tl = self.iface.tangential;
        let e = self.iface.eval(k as f64 * h, &y);
        let kt = tl.branch.stick_stiffness();
        let series = if kt.is_finite() {
            let f = e.tau_f - tl.static_shear;
            0.5 * f * f / kt
        } else {
            0.0
        };
        out.normal.energy = acc.wave[0].audit(
            law.stored_energy(y[0], e.beta),
            acc.damage,
            law.traction.adhesion_energy(1.0) - law.traction.adhesion_energy(e.beta),
        );
        out.shear.energy =
            acc.wave[1].audit(tl.branch.spring_energy(e.beta, y[2]) + series, 0.0, 0.0);
        out.friction_dissipation = acc.friction;
        out.static_shear_work = tl.static_shear * self.slip_of(&e, &y);
        out.normal.open_time_in_burst = acc.open_in_burst;
        out.normal.max_gap = self.max_gap;
        out.normal.events = self.events;
        out.shear.events = self.slip_events;
        out.slip_events = self.slip_events;
        out.slip_time_in_burst = acc.slip_in_burst;
        out.wave_energy = acc.wave_energy;
        *recorder = out;
        Ok(())
    }
}

/// A run of the coupled solver as [`exact_loop::run`] drives it (no fast paths).
impl GridSolver for Driven<'_, CoupledRun<'_>, Integrals, CoupledOutput> {
    type State = [f64; N];

    fn advance(&mut self, t: f64, t_end: f64, y: &mut [f64; N]) -> Result<()> {
        self.solver.advance(&mut self.acc, t, t_end, y)
    }

    fn record(&mut self, t: f64, y: &[f64; N]) {
        self.solver.record(&mut self.out, &self.acc, t, y);
    }

    fn at_rest(&self, t: f64, y: &[f64; N]) -> bool {
        self.solver.at_rest(t, y)
    }
}
