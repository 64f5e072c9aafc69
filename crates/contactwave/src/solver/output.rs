//! What the solvers return: interface histories of the half-space problem (the same form
//! from the exact and the finite-difference solver, so that they check each other) and
//! the recorded histories of a bar-stack run.

/// Energy audit of one run, J/m^2 (model.md; thesis has none).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyAudit {
    /// Energy brought by the incident wave, `int s_inc^2 / Z1 dt`.
    pub incident: f64,
    /// Energy carried away by the reflected wave, `int s_ref^2 / Z1 dt`.
    pub reflected: f64,
    /// Energy carried away by the transmitted wave, `int s_tr^2 / Z2 dt`.
    pub transmitted: f64,
    /// Energy stored in the interface at the end.
    pub stored: f64,
    /// Energy released by damage, `int (dpsi/dbeta) (-dbeta/dt) dt`.
    pub damage: f64,
    /// Decrease of the adhesion energy term (`w (beta_0 - beta_end)` for RCCM).
    pub adhesion_decrease: f64,
}

impl EnergyAudit {
    /// `|incident - reflected - transmitted - stored - damage| / incident`.
    pub fn closure_error(&self) -> f64 {
        (self.incident - self.reflected - self.transmitted - self.stored - self.damage).abs()
            / self.incident.max(f64::MIN_POSITIVE)
    }
}

/// Time histories at the interface (x = 0) on a uniform grid, SI units.
#[derive(Debug, Clone, Default)]
pub struct HalfSpaceOutput {
    /// Time step, s.
    pub dt: f64,
    /// Times t_k = k dt, s (t = 0: the incident front reaches the interface).
    pub t: Vec<f64>,
    /// Gap `[u]`, m.
    pub gap: Vec<f64>,
    /// Interface stress sigma, Pa (tension positive; -p0 at rest).
    pub contact_stress: Vec<f64>,
    /// Adhesion beta.
    pub beta: Vec<f64>,
    /// Incident stress at x = 0, Pa.
    pub incident_stress: Vec<f64>,
    /// Reflected stress at x = 0, Pa.
    pub reflected_stress: Vec<f64>,
    /// Transmitted stress at x = 0+, Pa.
    pub transmitted_stress: Vec<f64>,
    /// Reflected particle displacement at x = 0, `int s_ref/Z1 dt`, m (exact at the grid
    /// points: differences give cell-averaged velocities free of aliasing from jumps).
    pub reflected_displacement: Vec<f64>,
    /// Incident particle displacement at x = 0, `-int s_inc/Z1 dt`, m.
    pub incident_displacement: Vec<f64>,
    /// Transmitted particle displacement at x = 0+, `-int s_tr/Z2 dt`, m (0 for a wall).
    pub transmitted_displacement: Vec<f64>,
    /// Energy audit.
    pub energy: EnergyAudit,
    /// Time the interface spent open (contact lost) while the burst was at it, s.
    pub open_time_in_burst: f64,
    /// Largest gap reached, m.
    pub max_gap: f64,
    /// Number of opening/closing/damage events located.
    pub events: usize,
    /// Duration of the incident burst, s.
    pub burst_duration: f64,
}

impl HalfSpaceOutput {
    /// Record the series a summary reads at one grid point: time `t` (s), adhesion `beta`
    /// and the reflected displacement (m). The one recording path of every solver of the
    /// half-space problems (exact and FD, normal and coupled), with
    /// [`HalfSpaceOutput::push_fields`].
    #[inline(always)]
    pub(crate) fn push_summary(&mut self, t: f64, beta: f64, reflected_displacement: f64) {
        self.t.push(t);
        self.beta.push(beta);
        self.reflected_displacement.push(reflected_displacement);
    }

    /// Record the other series at the same grid point: the gap (m), the contact stress and
    /// the incident stress (Pa), the dynamic stress `S` (contact stress less its static
    /// value, Pa: the transmitted stress, and `S` less the incident the reflected one), and
    /// the incident and transmitted displacements (m).
    #[inline(always)]
    pub(crate) fn push_fields(
        &mut self,
        gap: f64,
        contact_stress: f64,
        incident_stress: f64,
        dynamic_stress: f64,
        [incident_displacement, transmitted_displacement]: [f64; 2],
    ) {
        self.gap.push(gap);
        self.contact_stress.push(contact_stress);
        self.incident_stress.push(incident_stress);
        self.reflected_stress.push(dynamic_stress - incident_stress);
        self.transmitted_stress.push(dynamic_stress);
        self.incident_displacement.push(incident_displacement);
        self.transmitted_displacement.push(transmitted_displacement);
    }

    /// Empty for a new run of output step `dt` (s) and burst duration `burst_duration`
    /// (s): every series cleared with its allocation kept, every scalar reset.
    pub fn reset(&mut self, dt: f64, burst_duration: f64) {
        let mut fresh = HalfSpaceOutput {
            dt,
            burst_duration,
            ..Default::default()
        };
        for (new, old) in [
            (&mut fresh.t, &mut self.t),
            (&mut fresh.gap, &mut self.gap),
            (&mut fresh.contact_stress, &mut self.contact_stress),
            (&mut fresh.beta, &mut self.beta),
            (&mut fresh.incident_stress, &mut self.incident_stress),
            (&mut fresh.reflected_stress, &mut self.reflected_stress),
            (&mut fresh.transmitted_stress, &mut self.transmitted_stress),
            (
                &mut fresh.reflected_displacement,
                &mut self.reflected_displacement,
            ),
            (
                &mut fresh.incident_displacement,
                &mut self.incident_displacement,
            ),
            (
                &mut fresh.transmitted_displacement,
                &mut self.transmitted_displacement,
            ),
        ] {
            std::mem::swap(new, old);
            new.clear();
        }
        *self = fresh;
    }
}

/// What the solver records every `record_every` steps.
#[derive(Debug, Clone, Default)]
pub struct FdOutput {
    /// Times, s.
    pub t: Vec<f64>,
    /// Displacement at each probe node (one Vec per probe), m.
    pub displacement: Vec<Vec<f64>>,
    /// Gap of each interface (obstacles last), m.
    pub gap: Vec<Vec<f64>>,
    /// Contact stress sigma of each interface, Pa.
    pub stress: Vec<Vec<f64>>,
    /// Adhesion beta of each interface.
    pub beta: Vec<Vec<f64>>,
    /// Node updates performed (of both fields with a shear field).
    pub node_updates: u64,
    /// The transverse field's records, when the stack has one.
    pub shear: Option<FdShearOutput>,
}

impl FdOutput {
    /// Empty records reserved for `n` levels of `probes` probes and `interfaces`
    /// interfaces, with `shear_probes` transverse probes when there is a shear field.
    pub fn with_capacity(
        n: usize,
        probes: usize,
        interfaces: usize,
        shear_probes: Option<usize>,
    ) -> Self {
        // (`vec![..; k]` clones: only the last of the `k` records has the capacity, the
        // others grow as they are pushed. Giving every record its capacity up front
        // measured 7 % slower on `fd_tribobrake_0.02s` (6.55 against 6.1 ms, A/B), so the
        // records grow.)
        let v = |k: usize| vec![Vec::with_capacity(n); k];
        FdOutput {
            t: Vec::with_capacity(n),
            displacement: v(probes),
            gap: v(interfaces),
            stress: v(interfaces),
            beta: v(interfaces),
            node_updates: 0,
            shear: shear_probes.map(|p| FdShearOutput {
                displacement: v(p),
                gap: v(interfaces),
                stress: v(interfaces),
                slip: v(interfaces),
                state: v(interfaces),
                friction_dissipation: vec![0.0; interfaces],
                damage_dissipation: vec![0.0; interfaces],
            }),
        }
    }
}

/// What a bar-stack run with a shear field records of it, at the levels of [`FdOutput`].
#[derive(Debug, Clone, Default)]
pub struct FdShearOutput {
    /// Transverse displacement at each shear probe node, m.
    pub displacement: Vec<Vec<f64>>,
    /// Tangential gap `[u]_T` of each interface (obstacles last), m.
    pub gap: Vec<Vec<f64>>,
    /// Contact shear stress tau = T + q0 of each interface, Pa.
    pub stress: Vec<Vec<f64>>,
    /// Accumulated slip of each interface's slider, m.
    pub slip: Vec<Vec<f64>>,
    /// Slider state of each interface: 0 stick, +1 / -1 slipping, NaN free.
    pub state: Vec<Vec<f64>>,
    /// Frictional dissipation of each interface over the run, `sum tau_f Delta s`, J/m^2.
    pub friction_dissipation: Vec<f64>,
    /// Energy released by damage at each interface over the run, J/m^2.
    pub damage_dissipation: Vec<f64>,
}
