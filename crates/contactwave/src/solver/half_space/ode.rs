//! The gap equation of one phase as a Radau system, and the incident stress tabulated on
//! the solver's grid (model.md section 4; thesis eqs. 2.3-2.9, 5.5).

use super::HalfSpace;
use crate::excitation::Excitation;
use crate::numeric::GL4_NODES;
use crate::solver::radau::{self, Affine, System};

/// The nodes of a stuck step: the four Gauss-Legendre nodes and the step end.
pub(super) const STUCK_NODES: [f64; 5] =
    [GL4_NODES[0], GL4_NODES[1], GL4_NODES[2], GL4_NODES[3], 1.0];

/// Largest table of [`IncidentGrid`], steps (7 values a step: 56 MB).
const MAX_GRID_STEPS: usize = 1 << 20;

/// The incident stress at the nodes of every whole step `[k h, (k + 1) h]` of the solver's
/// grid inside the burst, tabulated once per run ([`Excitation::stress_grid`]): the Radau
/// stage nodes and the nodes of a stuck step ([`STUCK_NODES`]), Pa. Steps split by an
/// event or a breakpoint, and steps after the burst, are evaluated directly. The table of
/// the last run on a [`Workspace`] is kept there and used again, as it is, by a run of the
/// same incident wave ([`Excitation::grid_key`]) on the same grid: the runs of a sweep
/// over the interface or the pressure, of an identification, of a repeated scenario.
pub(super) struct IncidentGrid {
    /// The waveform's grid key with the step, the step count and the node set (empty:
    /// the waveform has no key, and the table is not for another run).
    key: Vec<u64>,
    /// Tabulated steps.
    steps: usize,
    /// `table[i * steps + k]`: stress at `t_k + GRID_NODES[i] h`, Pa.
    table: Vec<f64>,
    /// The solver's current grid step `(ta, tb, k)`.
    current: std::cell::Cell<(f64, f64, usize)>,
    /// Grid step, s.
    h: f64,
    /// Duration of the burst, s (its stress is 0 after it).
    duration: f64,
}

/// What a run of the exact solver leaves for the next run on the same worker (a plan
/// cache: it never changes a result): the incident wave tabulated on the solver's grid
/// (`IncidentGrid`), used again as it is by a run of the same incident wave
/// ([`Excitation::grid_key`]) on the same grid (the runs of a sweep over the interface or
/// the pressure, of an identification, of a repeated scenario), its buffer (up to 8 MB)
/// by any other. Owned by the caller, one per worker (a [`crate::solver::Plan`] run on it).
#[derive(Debug, Default)]
pub struct Workspace {
    /// The kept table's key (empty: none).
    key: Vec<u64>,
    /// The kept table.
    table: Vec<f64>,
}

impl Workspace {
    /// An empty workspace (the first run on it tabulates its wave).
    pub fn new() -> Self {
        Workspace::default()
    }

    /// Forget the kept table: the next run tabulates its wave again (what a first run
    /// costs; the benchmarks of cold runs call it).
    pub fn clear(&mut self) {
        *self = Workspace::default();
    }

    /// Keep the table of `grid` for the next run (up to 8 MB).
    pub(super) fn keep(&mut self, grid: &mut IncidentGrid) {
        let table = std::mem::take(&mut grid.table);
        if table.capacity() <= 1 << 20 {
            self.key = std::mem::take(&mut grid.key);
            self.table = table;
        }
    }
}

/// The tabulated nodes: Radau's three stage nodes (the last is the step end, which is also
/// the last of [`STUCK_NODES`]), then the four Gauss-Legendre nodes of a stuck step.
const GRID_NODES: [f64; 7] = [
    radau::C[0],
    radau::C[1],
    radau::C[2],
    STUCK_NODES[0],
    STUCK_NODES[1],
    STUCK_NODES[2],
    STUCK_NODES[3],
];

/// Row of the table holding the stuck step's node `i` ([`STUCK_NODES`]): the GL nodes from
/// row 3, the end (`c = 1`) in Radau's last row.
const STUCK_ROWS: [usize; 5] = [3, 4, 5, 6, 2];

impl IncidentGrid {
    /// Tabulate `incident` on the grid of step `h` (s) over its duration (nothing when the
    /// table would exceed [`MAX_GRID_STEPS`]).
    /// With `stuck_only` (a locked interface: no ODE phase ever) only the stuck-step nodes
    /// are tabulated (rows 2 to 6); the first two Radau rows are then not to be read.
    /// The table kept in `ws` is used again as it is for the same key, else its buffer.
    pub(super) fn new(
        incident: &dyn Excitation,
        h: f64,
        stuck_only: bool,
        ws: &mut Workspace,
    ) -> Self {
        let n = (incident.duration() / h).ceil();
        let steps = if n.is_finite() && n >= 0.0 && n <= MAX_GRID_STEPS as f64 {
            n as usize
        } else {
            0
        };
        let key = incident.grid_key().map_or(Vec::new(), |mut k| {
            k.extend([h.to_bits(), steps as u64, stuck_only as u64]);
            k
        });
        // the table of the workspace's previous run: as it is for the same key, else its
        // buffer (no allocation in a sweep; stress_grid writes every entry: only a longer
        // table than the last is zeroed)
        let mut table = std::mem::take(&mut ws.table);
        let n = GRID_NODES.len() * steps;
        if key.is_empty() || key != ws.key || table.len() != n {
            table.truncate(n);
            table.resize(n, 0.0);
            if stuck_only {
                // the end and the GL nodes: rows 2 to 6
                incident.stress_grid(h, &GRID_NODES[2..], steps, &mut table[2 * steps..]);
            } else {
                incident.stress_grid(h, &GRID_NODES, steps, &mut table);
            }
        }
        IncidentGrid {
            key,
            steps,
            table,
            current: std::cell::Cell::new((f64::NAN, f64::NAN, usize::MAX)),
            h,
            duration: incident.duration(),
        }
    }

    /// Set the grid step the solver is in: `k`, from `ta = k h` to `tb = (k + 1) h` (s).
    #[inline]
    pub(super) fn enter_step(&self, k: usize, ta: f64, tb: f64) {
        self.current.set((ta, tb, k));
    }

    /// The index `k` when `[t, t + h]` is the whole current grid step `k` and it is in the
    /// table (`h` as the solver forms it: `tb - ta`).
    #[inline]
    fn step(&self, t: f64, h: f64) -> Option<usize> {
        let (ta, tb, k) = self.current.get();
        (t == ta && h == tb - ta && k < self.steps).then_some(k)
    }

    /// Whether grid step `k` starts after the burst (beyond the table): the incident stress
    /// is 0 at all its nodes (the `Excitation` contract).
    #[inline]
    pub(super) fn after_burst(&self, k: usize) -> bool {
        k >= self.steps && k as f64 * self.h > self.duration
    }

    /// The stuck-step nodes of grid step `k` when it is tabulated.
    #[inline]
    pub(super) fn stuck_at(&self, k: usize) -> Option<[f64; 5]> {
        let n = self.steps;
        (k < n).then(|| std::array::from_fn(|i| self.table[STUCK_ROWS[i] * n + k]))
    }

    /// The Radau stage nodes of grid step `k` when it is tabulated.
    #[inline]
    pub(super) fn radau_at(&self, k: usize) -> Option<[f64; 3]> {
        let n = self.steps;
        (k < n).then(|| std::array::from_fn(|j| self.table[j * n + k]))
    }

    /// The stuck-step nodes of `[t, t + h]` when it is a tabulated grid step.
    #[inline]
    pub(super) fn stuck(&self, t: f64, h: f64) -> Option<[f64; 5]> {
        let k = self.step(t, h)?;
        let n = self.steps;
        Some(std::array::from_fn(|i| self.table[STUCK_ROWS[i] * n + k]))
    }

    /// The Radau stage nodes of `[t, t + h]` when it is a tabulated grid step.
    #[inline]
    fn radau(&self, t: f64, h: f64) -> Option<[f64; 3]> {
        let k = self.step(t, h)?;
        let n = self.steps;
        Some(std::array::from_fn(|j| self.table[j * n + k]))
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// Rigid compression active: gap held at 0.
    Closed,
    /// Bonded traction active: gap held at [u]_c.
    Bonded,
    /// Both branches rigid: gap held at 0 forever.
    Locked,
    /// Compliant compression branch.
    Compression,
    /// Traction branch, beta constant.
    Traction,
    /// Traction branch, damage evolving.
    Damaging,
}

impl Phase {
    pub(super) fn is_stuck(self) -> bool {
        matches!(self, Phase::Closed | Phase::Bonded | Phase::Locked)
    }
}

/// The gap ODE in one phase, as a Radau system.
pub(super) struct GapOde<'a> {
    pub(super) hs: &'a HalfSpace,
    /// The last two evaluations of the incident stress (time, value): the end of a step is
    /// the start of the next one and the time of the recorded sample.
    pub(super) cache: std::cell::Cell<[(f64, f64); 2]>,
    /// The incident stress tabulated on the grid.
    pub(super) grid: IncidentGrid,
    pub(super) phase: Phase,
    /// `1/Z1 + 1/Z2`, m/(Pa s).
    pub(super) k: f64,
    /// Static pressure, Pa.
    pub(super) p0: f64,
    /// Critical gap of the traction branch, m.
    pub(super) uc: f64,
    /// `2 / Z1`, m/(Pa s).
    pub(super) two_over_z1: f64,
}

impl GapOde<'_> {
    /// Put the incident stress `v` (Pa) at time `t` (s) into the two-entry cache.
    #[inline]
    pub(super) fn remember(&self, t: f64, v: f64) {
        let c = self.cache.get();
        self.cache.set([c[1], (t, v)]);
    }

    /// Damage in its rate-independent limit (b = 0): beta is an algebraic function of the
    /// opening, `beta = update_adhesion(d, beta_start, inf)`, and the ODE is scalar.
    #[inline]
    pub(super) fn algebraic_damage(&self) -> bool {
        self.phase == Phase::Damaging && self.hs.law.traction.damage_viscosity() == 0.0
    }

    /// Adhesion in effect at state y.
    #[inline]
    pub(super) fn beta(&self, y: [f64; 2]) -> f64 {
        if self.algebraic_damage() {
            self.hs
                .law
                .traction
                .update_adhesion((y[0] - self.uc).max(0.0), y[1], f64::INFINITY)
        } else {
            y[1]
        }
    }

    #[inline]
    pub(super) fn sigma(&self, y: [f64; 2]) -> f64 {
        match self.phase {
            Phase::Compression => self.hs.law.compression.stress(y[0].min(self.uc)),
            _ => self
                .hs
                .law
                .traction
                .stress((y[0] - self.uc).max(0.0), self.beta(y)),
        }
    }
    #[inline]
    pub(super) fn gap_rate(&self, t: f64, y: [f64; 2]) -> f64 {
        self.two_over_z1 * self.hs.incident.stress(t) - self.k * (self.sigma(y) + self.p0)
    }
}

impl GapOde<'_> {
    /// The constant tangent `d sigma / d[u]` (Pa/m) of the phase's branch at adhesion
    /// `y[1]`, where the phase is affine ([`System::affine`]): a compliant compression
    /// branch of constant stiffness, or a traction branch linear in the opening.
    #[inline]
    pub(super) fn affine_stiffness(&self, y: [f64; 2]) -> Option<f64> {
        let law = &self.hs.law;
        match self.phase {
            Phase::Compression if law.compression.is_affine() => {
                Some(law.compression.tangent(self.uc))
            }
            Phase::Traction if law.traction.is_affine() => Some(law.traction.tangent(0.0, y[1])),
            _ => None,
        }
    }
}

impl System<2> for GapOde<'_> {
    /// The gap, and the adhesion where its damage equation is a differential one.
    fn active(&self) -> [bool; 2] {
        [
            true,
            self.phase == Phase::Damaging && !self.algebraic_damage(),
        ]
    }
    fn mass(&self) -> [f64; 2] {
        if self.phase == Phase::Damaging && !self.algebraic_damage() {
            [1.0, self.hs.law.traction.damage_viscosity()]
        } else {
            [1.0, 1.0]
        }
    }
    #[inline]
    fn forcing(&self, t: f64) -> f64 {
        let c = self.cache.get();
        if c[0].0 == t {
            return c[0].1;
        }
        if c[1].0 == t {
            return c[1].1;
        }
        let v = self.hs.incident.stress(t);
        self.cache.set([c[1], (t, v)]);
        v
    }
    /// The stage values from the grid's table, or in one call to the incident wave; the
    /// end value is cached.
    fn forcing_stages(&self, t: f64, h: f64) -> [f64; 3] {
        let g = self.grid.radau(t, h).unwrap_or_else(|| {
            let mut g = [0.0; 3];
            self.hs.incident.stress_nodes(t, h, &radau::C, &mut g);
            g
        });
        let c = self.cache.get();
        self.cache.set([c[1], (t + radau::C[2] * h, g[2])]);
        g
    }
    /// One stress evaluation for the three stages (the same state).
    fn rhs_stages(&self, _t: f64, _h: f64, g: [f64; 3], y: [f64; 2]) -> [f64; 3] {
        let s = self.sigma(y) + self.p0;
        g.map(|gl| self.two_over_z1 * gl - self.k * s)
    }
    fn rhs_forced(&self, _t: f64, s_inc: f64, y: [f64; 2]) -> [f64; 2] {
        let f1 = if self.phase == Phase::Damaging && !self.algebraic_damage() {
            // b dbeta/dt = min(phi, 0): beta never increases
            self.hs
                .law
                .traction
                .damage_driving_force((y[0] - self.uc).max(0.0), y[1])
                .min(0.0)
        } else {
            0.0
        };
        [
            self.two_over_z1 * s_inc - self.k * (self.sigma(y) + self.p0),
            f1,
        ]
    }
    /// A compliant compression branch with constant stiffness (up to `[u]_c`), or a
    /// traction branch linear in the opening at the phase's fixed adhesion (from `[u]_c`):
    /// the gap equation is then linear and Radau's step needs no Newton iteration.
    fn affine(&self, y: [f64; 2]) -> Option<Affine> {
        let stiffness = self.affine_stiffness(y)?;
        let (lower, upper) = match self.phase {
            Phase::Compression => (f64::NEG_INFINITY, self.uc),
            _ => (self.uc, f64::INFINITY),
        };
        Some(Affine {
            slope: -self.k * stiffness,
            lower,
            upper,
        })
    }
    #[inline]
    fn jacobian(&self, _t: f64, y: [f64; 2]) -> Option<[[f64; 2]; 2]> {
        Some(self.gap_jacobian(y))
    }
}

impl GapOde<'_> {
    /// The Jacobian of the gap equation of the current phase at `y` (row-major).
    pub(super) fn gap_jacobian(&self, y: [f64; 2]) -> [[f64; 2]; 2] {
        match self.phase {
            Phase::Compression => [
                [
                    -self.k * self.hs.law.compression.tangent(y[0].min(self.uc)),
                    0.0,
                ],
                [0.0, 0.0],
            ],
            _ if self.algebraic_damage() => {
                let tr = &self.hs.law.traction;
                let d = (y[0] - self.uc).max(0.0);
                let beta = self.beta(y);
                let mut ds = tr.tangent(d, beta);
                if beta < y[1] {
                    // on the damage surface phi(d, beta) = 0: dbeta/dd = -phi_d / phi_beta
                    let (pd, pb) = tr.damage_driving_force_gradient(d, beta);
                    if pb != 0.0 {
                        ds += tr.stress_d_adhesion(d, beta) * (-pd / pb);
                    }
                }
                [[-self.k * ds, 0.0], [0.0, 0.0]]
            }
            _ => {
                let tr = &self.hs.law.traction;
                let d = (y[0] - self.uc).max(0.0);
                let row0 = [
                    -self.k * tr.tangent(d, y[1]),
                    -self.k * tr.stress_d_adhesion(d, y[1]),
                ];
                if self.phase == Phase::Damaging && tr.damage_driving_force(d, y[1]) < 0.0 {
                    let (a, b) = tr.damage_driving_force_gradient(d, y[1]);
                    [row0, [a, b]]
                } else {
                    [row0, [0.0, 0.0]]
                }
            }
        }
    }
}
