//! Beyond the thesis: finite cracks in 2D (issue 27, model.md section 15). The thesis
//! models a contact as a plane interface between two half-spaces; these studies put the
//! same laws on a crack of finite length in the 2D spectral-element solver
//! ([`crate::solver::solid_2d`]) and ask when the plane-interface model holds and how a
//! finite crack changes the second harmonic. One file per study:
//!
//! - [`length`]: A2/A1 and beta* of the wave reflected at normal incidence against the
//!   crack length, Signorini and RCCM, beside the exact 1D solver;
//! - [`load_ratio`]: A2/A_inc against the load ratio xi for finite Signorini cracks beside
//!   the 1D curve (the thesis' optimum xi_opt = 0.35);
//! - [`delamination`]: an A0 Lamb wave on a closed delamination against its length;
//! - [`wavefield`]: snapshots, their GIF and the crack's state map of the length study's
//!   three-wavelength crack, embedded in the report;
//! - [`angle`]: the second and third harmonics of the reflected P and converted SV waves of
//!   a frictional crack against the incidence angle, at three closures;
//! - [`rayleigh`]: a Rayleigh wave at a closed surface-breaking crack against its depth.
//!
//! Each study runs at two resolutions: the default (12 elements per P wavelength, order 4,
//! analysed up to 3 f0) and `--quick` (8 elements per wavelength, 2 f0, fewer points), the
//! one CI runs. Every figure's comparison lines give its run count and wall time.

mod angle;
mod delamination;
mod length;
mod load_ratio;
mod rayleigh;
mod wavefield;

use super::{fmt_value, Chapter, ChapterResult, Ctx, Figure, Finding};
use crate::analysis::Summary;
use crate::error::Result;
use crate::model;
use crate::scenario::parse_toml;
use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Instant;

/// Aluminium as the 2D presets have it: density, kg/m^3.
const RHO: f64 = crate::material::Material::ALUMINIUM.density;

/// Its P-wave modulus `rho c_P^2 = E (1 - nu) / ((1 + nu) (1 - 2 nu))` (Pa, 1.052e11 for
/// E = 71 GPa, nu = 0.33): the 1D half-spaces use it as Young's modulus so that their wave
/// travels at the 2D c_P (6230.4 m/s).
fn p_modulus() -> f64 {
    let al = crate::material::Material::ALUMINIUM;
    al.half_space(al.poisson_ratio().unwrap_or(0.33))
        .youngs_modulus
}
/// Frequency of the bursts, Hz.
const F0: f64 = 1e6;
/// Cycles of the Hann bursts.
const CYCLES: f64 = 5.0;

/// c_P of aluminium, m/s.
fn c_p() -> f64 {
    (p_modulus() / RHO).sqrt()
}

/// P wavelength at f0, m.
fn lambda() -> f64 {
    c_p() / F0
}

/// The resolution the chapter runs at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Resolution {
    /// `--quick`: coarser mesh, fewer points (CI).
    pub quick: bool,
}

impl Resolution {
    /// Elements (order 4) per P wavelength at f0.
    fn per_wavelength(self) -> usize {
        if self.quick {
            8
        } else {
            12
        }
    }

    /// Highest analysed harmonic (sets the time step, `model.harmonic`).
    fn harmonic(self) -> f64 {
        if self.quick {
            2.0
        } else {
            3.0
        }
    }

    /// Element size, m.
    fn element(self) -> f64 {
        lambda() / self.per_wavelength() as f64
    }

    /// `quick` or `default`, for captions.
    fn name(self) -> &'static str {
        if self.quick {
            "--quick"
        } else {
            "default"
        }
    }
}

/// A contact law of the studies: its TOML branches, the static closure and the burst.
#[derive(Debug, Clone, Copy)]
struct Law {
    /// Short name (`signorini`, `rccm`): keys and labels.
    name: &'static str,
    /// The crack's `compression = ..., traction = ...` (TOML inline).
    branches: &'static str,
    /// Static closure p0, Pa.
    p0: f64,
    /// Wave stress amplitude, Pa.
    amplitude: f64,
}

/// Signorini (rigid in compression, free in traction), xi = 0.3.
const SIGNORINI: Law = Law {
    name: "signorini",
    branches: "compression = { law = \"rigid\" }\ntraction = { law = \"free\" }",
    p0: 0.3e6,
    amplitude: 1e6,
};

/// The adhesive RCCM bond with damage of examples/solid_2d/interface_reduction.toml.
const RCCM: Law = Law {
    name: "rccm",
    branches: "compression = { law = \"rigid\" }\ntraction = { law = \"rccm\", stiffness = 2e13, \
               energy = 0.01, viscosity = 1e-8 }",
    p0: 0.3e6,
    amplitude: 3e6,
};

/// The exact 1D solver's scenario for `law` (two aluminium half-spaces whose wave travels
/// at the 2D c_P), with the closure `p0` and amplitude `amplitude`.
fn one_d_text(law: &Law, p0: f64, amplitude: f64) -> String {
    let modulus = p_modulus();
    format!(
        "[medium]\nmaterial = \"aluminium\"\nyoungs_modulus = {modulus:e}\n\
         [counterpart]\nkind = \"medium\"\nmaterial = \"aluminium\"\nyoungs_modulus = {modulus:e}\n\
         [interface]\nstatic_pressure = {p0:e}\n{}\n\
         [incident]\nfrequency = {F0:e}\ncycles = {CYCLES}\nwindow = \"hann\"\namplitude = {amplitude:e}\n",
        law.branches
    )
}

/// A crack across a periodic strip under a plane P wave at normal incidence (the geometry
/// of model.md 15.8), in units of the P wavelength and whole elements: an absorbing top and
/// bottom, the receiver `reflected` at depth [`Plane::Z_R`] above the crack's centre (in the
/// scattered region: the reflected wave alone), the injection line at [`Plane::Z_L`], the
/// crack at [`Plane::Z_C`], the depth [`Plane::DEPTH`]. The receiver's record is gated to the
/// reflected burst; the sides are far enough that the neighbouring cracks' tips (the strip
/// is periodic) reach the receiver after the gate.
#[derive(Debug, Clone, Copy)]
struct Plane {
    res: Resolution,
    /// Crack length in elements (`None`: across the whole width, the plane interface).
    length: Option<usize>,
}

impl Plane {
    /// Receiver depth, wavelengths.
    const Z_R: f64 = 0.5;
    /// Injection line, wavelengths.
    const Z_L: f64 = 1.0;
    /// Crack depth, wavelengths.
    const Z_C: f64 = 2.5;
    /// Depth of the rectangle, wavelengths.
    const DEPTH: f64 = 3.5;
    /// Gate after the burst's end, periods.
    const TAIL: f64 = 1.0;

    /// Elements per wavelength.
    fn n(self) -> usize {
        self.res.per_wavelength()
    }

    /// Width in elements: one element for the plane interface; otherwise at least the
    /// crack plus two wavelengths, and wide enough that the nearest tip of a neighbouring
    /// crack is `Z_C - Z_R` plus the gate's length (in P travel) from the receiver.
    fn width_elements(self) -> usize {
        let n = self.n();
        match self.length {
            None => 1,
            Some(l) => {
                let d = Self::Z_C - Self::Z_R;
                let reach = d + CYCLES + Self::TAIL + 0.5;
                let lateral = (reach * reach - d * d).sqrt();
                let need = ((l as f64 / n as f64) / 2.0 + lateral) * n as f64;
                let w = (l + 2 * n).max(need.ceil() as usize);
                // the crack centred on whole elements
                w + (w - l) % 2
            }
        }
    }

    /// The scenario text for `law` at closure `p0` and amplitude `amplitude`.
    fn text(self, law: &Law, p0: f64, amplitude: f64) -> String {
        let e = self.res.element();
        let we = self.width_elements();
        let w = we as f64 * e;
        let z = |v: f64| (v * self.n() as f64).round() * e;
        let (z_r, z_l, z_c, depth) = (z(Self::Z_R), z(Self::Z_L), z(Self::Z_C), z(Self::DEPTH));
        let c = c_p();
        let period = 1.0 / F0;
        // the front leaves the top of the element row above the line at t = 0
        let arrival = (z_c - (z_l - e) + z_c - z_r) / c;
        let gate = (
            arrival - 0.5 * period,
            arrival + (CYCLES + Self::TAIL) * period,
        );
        let duration = gate.1 + 0.1 * period;
        let crack = match self.length {
            None => format!("start = [0.0, {z_c:e}]\nfull_width = true"),
            Some(l) => {
                let x0 = ((we - l) / 2) as f64 * e;
                format!("start = [{x0:e}, {z_c:e}]\nlength = {:e}", l as f64 * e)
            }
        };
        format!(
            "[model]\nkind = \"solid_2d\"\nwave = \"p_sv\"\nwidth = {w:e}\nduration = {duration:e}\n\
             element_size = {e:e}\norder = 4\nharmonic = {}\ntop = \"absorbing\"\nbottom = \"absorbing\"\n\
             sides = \"periodic\"\ncrack_every = 100\n\
             [[layer]]\nthickness = {depth:e}\nmaterial = \"aluminium\"\n\
             [[crack]]\n{crack}\nstatic_pressure = {p0:e}\n{}\n\
             [[source]]\nkind = \"plane_wave\"\nwave = \"P\"\nz = {z_l:e}\n\
             signal = {{ frequency = {F0:e}, cycles = {CYCLES}, amplitude = {amplitude:e}, window = \"hann\" }}\n\
             [[receiver]]\nname = \"reflected\"\nat = [{:e}, {z_r:e}]\n\
             [analysis]\ngate = [{:e}, {:e}]\ntaper = {:e}\n",
            self.res.harmonic(),
            law.branches,
            (we / 2) as f64 * e,
            gate.0,
            gate.1,
            0.5 * period,
        )
    }
}

/// Summaries of scenario texts, in parallel, counted as the chapter's runs.
fn summaries(ctx: &Ctx, study: &str, texts: &[String]) -> Result<Vec<Summary>> {
    ctx.map(study, texts, |t| {
        let table = parse_toml(t, "<finite_crack>")?;
        model::plan(table, Path::new("<finite_crack>"))
            .base()?
            .summary()
    })
}

/// Runs and wall time of one figure, measured from [`Cost::start`].
struct Cost {
    t0: Instant,
    runs0: usize,
}

impl Cost {
    fn start(ctx: &Ctx) -> Cost {
        Cost {
            t0: Instant::now(),
            runs0: ctx.runs.load(Ordering::SeqCst),
        }
    }

    /// "cost (resolution): N runs, T s wall time".
    fn line(&self, ctx: &Ctx, res: Resolution) -> String {
        format!(
            "cost ({} resolution): {} runs, {} s wall time",
            res.name(),
            ctx.runs.load(Ordering::SeqCst) - self.runs0,
            fmt_value(self.t0.elapsed().as_secs_f64())
        )
    }
}

/// Run the chapter at `res`.
pub(crate) fn run(ctx: &Ctx, res: Resolution) -> Result<ChapterResult> {
    let mut figures: Vec<Figure> = Vec::new();
    let mut findings: Vec<Finding> = Vec::new();
    length::run(ctx, res, &mut figures, &mut findings)?;
    wavefield::run(ctx, res, &mut figures)?;
    load_ratio::run(ctx, res, &mut figures, &mut findings)?;
    delamination::run(ctx, res, &mut figures, &mut findings)?;
    angle::run(ctx, res, &mut figures, &mut findings)?;
    rayleigh::run(ctx, res, &mut figures, &mut findings)?;
    Ok(ChapterResult {
        chapter: Chapter::FiniteCrack,
        title: "Beyond the thesis: finite cracks in 2D".into(),
        intro: format!(
            "Not in the thesis, whose contact is a plane interface between two half-spaces. \
             The same laws on a crack of finite length in an aluminium solid (rho = 2710 \
             kg/m^3, c_P = {} m/s), 2D spectral elements with split-node contact (model.md \
             section 15), 1 MHz 5-cycle Hann bursts; resolution: {} ({} elements of order 4 \
             per P wavelength, time step for {} f0).",
            fmt_value(c_p()),
            res.name(),
            res.per_wavelength(),
            res.harmonic()
        ),
        figures,
        findings,
        seconds: 0.0,
        runs: 0,
    })
}

#[cfg(test)]
mod tests;
