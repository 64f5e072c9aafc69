//! Angle and mode conversion: the second and third harmonics of the P wave a finite
//! frictional crack reflects and of the SV wave it converts, against the incidence angle of
//! a plane P wave, at a few closures (after Blanloeuil, Meziane and Bacon, Wave Motion 51,
//! 2014: the pre-stress and the angle set whether the crack claps or rubs).
//!
//! An aluminium rectangle with absorbing sides, top and bottom; a horizontal crack two P
//! wavelengths long (Signorini in the normal direction, Coulomb friction mu = 0.3 with rigid
//! stick) under the closure p0 = xi sigma_max; a plane P wave (a 1 MHz 5-cycle Hann burst of
//! stress amplitude sigma_max = 1 MPa, total-field/scattered-field, model.md 15.8) at the
//! angle `a`. Two receivers in the scattered region, three P wavelengths from the crack's
//! centre: on the specular ray of the reflected P wave (at `a` from the vertical) and on the
//! ray of the converted SV wave (Snell: `sin b = sin a c_S / c_P`). Each receiver's velocity
//! is split by polarisation about the direction from the crack's centre: the radial
//! component is the P wave (analysed at the P receiver), the transverse one the SV wave (at
//! the SV receiver), each gated to its own arrival. The line's ends at the absorbing sides
//! send waves into the scattered region that do not depend on the crack: a run of the same
//! geometry with the crack bonded (p0 = 1000 sigma_max, stuck everywhere, which is the
//! uncracked solid) is subtracted from every record, so that what is analysed is what the
//! crack scatters. Harmonics by pulse inversion (a second run with the burst negated), over
//! the incident wave's particle velocity amplitude `A_inc` (the band amplitude at f0 of
//! `s(t) / (rho c_P)`).
//!
//! Where the crack opens and where it slips follows, at onset, from the incident wave alone:
//! while the crack is bonded it is invisible, and the stresses on its plane are the plane
//! wave's, `sigma_zz = f_n s`, `sigma_xz = f_t s` with `f_n = 1 - 2 (c_S/c_P)^2 sin^2 a`,
//! `f_t = 2 (c_S/c_P)^2 sin a cos a`; it opens where `f_n s_max > p0` and (closed) slips
//! where `f_t s_max > mu (p0 - f_n s_max)`.

use super::super::{finding, fmt_value, panel, Figure, Finding, AMPLITUDE_FLOOR};
use super::{lambda, Cost, Resolution, CYCLES, F0};
use crate::analysis::methods::{gated_bands, Quantity, Signal};
use crate::analysis::{AnalysisMethod, Gate};
use crate::error::{Error, Result};
use crate::excitation::Scaled;
use crate::output::plot::Series;
use crate::reproduce::Ctx;
use crate::scenario::solid_2d::{Solid2dScenario, Solid2dSpec};
use crate::scenario::{parse_toml, BuildCache};
use std::path::Path;
use std::sync::Arc;

/// The wave's stress amplitude sigma_max, Pa (p0 = xi sigma_max).
const AMPLITUDE: f64 = 1e6;
/// Coulomb friction coefficient.
const FRICTION: f64 = 0.3;
/// Load ratio of the bonded reference run (stuck and shut at every angle).
const BONDED_XI: f64 = 1e3;
/// Crack length, P wavelengths.
const LENGTH: f64 = 2.0;
/// Distance of the receivers from the crack's centre, P wavelengths.
const DISTANCE: f64 = 3.0;
/// The total-field/scattered-field line above the crack, P wavelengths.
const LINE_ABOVE: f64 = 0.5;
/// The receiver at normal incidence below the absorbing top, and the crack above the
/// absorbing bottom, P wavelengths.
const MARGIN: f64 = 0.75;
/// The crack's left tip right of the shadow boundary of the line's left end, P wavelengths
/// (the incident wave there is the plane wave).
const LIT: f64 = 2.5;
/// Gate after the burst's end, periods.
const TAIL: f64 = 1.0;
/// Name of the generated scenarios in errors.
const FILE: &str = "<finite_crack angle>";

/// Incidence angles, degrees.
pub(crate) fn angles(res: Resolution) -> Vec<f64> {
    if res.quick {
        vec![0.0, 20.0, 40.0, 60.0]
    } else {
        (0..=6).map(|k| 10.0 * k as f64).collect()
    }
}

/// Load ratios xi = p0 / sigma_max: clapping at every angle (0.3), clapping up to 40
/// degrees then friction alone (0.75), friction alone, at oblique incidence only (1.2).
pub(crate) fn xis(_res: Resolution) -> Vec<f64> {
    vec![0.3, 0.75, 1.2]
}

/// The rectangle, in whole elements of the resolution.
#[derive(Debug, Clone, Copy)]
struct Layout {
    /// Element size, m.
    e: f64,
    /// Crack's left tip, elements from the left side.
    x0: usize,
    /// Crack length, elements (even: the centre on an element edge).
    crack: usize,
    /// Width, elements.
    width: usize,
    /// Depths of the line, the crack and the bottom, elements.
    z_l: usize,
    z_c: usize,
    depth: usize,
}

impl Layout {
    /// The rectangle for incidence `deg` (degrees): the crack's left tip [`LIT`]
    /// wavelengths right of the shadow boundary of the line's left end, the right side as
    /// far from the crack as the left at normal incidence (a mirror-symmetric rectangle)
    /// and beyond the receivers by [`MARGIN`] otherwise.
    fn new(res: Resolution, deg: f64) -> Layout {
        let n = res.per_wavelength() as f64;
        let el = |v: f64| (v * n).ceil() as usize;
        let a = deg.to_radians();
        let crack = 2 * el(LENGTH / 2.0);
        let x0 = el(LINE_ABOVE * a.tan() + LIT);
        let right = el(LIT).max(el(DISTANCE * a.sin() + MARGIN).saturating_sub(crack / 2));
        let z_c = el(DISTANCE + MARGIN);
        Layout {
            e: res.element(),
            x0,
            crack,
            width: x0 + crack + right,
            z_l: z_c - el(LINE_ABOVE),
            z_c,
            depth: z_c + el(MARGIN),
        }
    }

    /// The crack's centre `[x, z]`, m.
    fn centre(&self) -> [f64; 2] {
        [
            (self.x0 + self.crack / 2) as f64 * self.e,
            self.z_c as f64 * self.e,
        ]
    }

    /// The point [`DISTANCE`] wavelengths from the crack's centre on the up-going ray at
    /// `theta` (radians) from the vertical, toward +x.
    fn on_ray(&self, theta: f64) -> [f64; 2] {
        let [x, z] = self.centre();
        let r = DISTANCE * lambda();
        [x + r * theta.sin(), z - r * theta.cos()]
    }
}

/// The two outgoing directions at incidence `a` (radians): the specular P ray and the
/// converted SV ray, radians from the vertical.
fn rays(a: f64, cp: f64, cs: f64) -> [f64; 2] {
    [a, (a.sin() * cs / cp).asin()]
}

/// The scenario of the crack at load ratio `xi` under a P wave at `deg` degrees.
fn text(lay: &Layout, res: Resolution, job: &Job, speeds: (f64, f64), duration: f64) -> String {
    let (deg, xi) = (job.deg, job.xi);
    let e = lay.e;
    let [cx, cz] = lay.centre();
    let a = deg.to_radians();
    let (cp, cs) = speeds;
    let [tp, ts] = rays(a, cp, cs);
    let (p, s) = (lay.on_ray(tp), lay.on_ray(ts));
    format!(
        "[model]\nkind = \"solid_2d\"\nwave = \"p_sv\"\nwidth = {:e}\nduration = {duration:e}\n\
         element_size = {e:e}\norder = 4\nharmonic = {}\ntop = \"absorbing\"\nbottom = \"absorbing\"\n\
         sides = \"absorbing\"\ncrack_every = 5\n\
         [[layer]]\nthickness = {:e}\nmaterial = \"aluminium\"\n\
         [[crack]]\nstart = [{:e}, {cz:e}]\nlength = {:e}\nstatic_pressure = {:e}\n\
         compression = {{ law = \"rigid\" }}\ntraction = {{ law = \"free\" }}\n\
         tangential = {{ law = \"coulomb\", friction = {FRICTION} }}\n\
         [[source]]\nkind = \"plane_wave\"\nwave = \"P\"\nz = {:e}\nangle = {deg}\n\
         signal = {{ frequency = {F0:e}, cycles = {CYCLES}, amplitude = {AMPLITUDE:e}, window = \"hann\" }}\n\
         [[receiver]]\nname = \"p\"\nat = [{:e}, {:e}]\n\
         [[receiver]]\nname = \"sv\"\nat = [{:e}, {:e}]\n",
        lay.width as f64 * e,
        res.harmonic(),
        lay.depth as f64 * e,
        cx - lay.crack as f64 * e / 2.0,
        lay.crack as f64 * e,
        xi * AMPLITUDE,
        lay.z_l as f64 * e,
        p[0],
        p[1],
        s[0],
        s[1],
    )
}

/// c_P and c_S of the aluminium preset as the 2D scenarios build it, m/s.
fn speeds() -> Result<(f64, f64)> {
    let t = "[model]\nkind = \"solid_2d\"\nwidth = 1e-2\nduration = 1e-6\n\
             [[layer]]\nthickness = 1e-2\nmaterial = \"aluminium\"\n\
             [[source]]\nkind = \"force\"\nat = [5e-3, 5e-3]\n\
             signal = { frequency = 1e6, cycles = 1, amplitude = 1 }\n";
    let spec = Solid2dSpec::from_table(parse_toml(t, FILE)?, FILE)?;
    let scen = Solid2dScenario::from_spec(spec, FILE, Path::new("."), &BuildCache::new())?;
    let m = scen
        .problem
        .layers
        .first()
        .map(|l| l.material)
        .ok_or_else(|| Error::invalid(FILE, "layer", "none", "one layer"))?;
    Ok((m.p_speed, m.s_speed))
}

/// The plane wave's stresses on the crack's plane per unit wave stress at incidence `a`
/// (radians): `(f_n, f_t)`, `sigma_zz = f_n s`, `sigma_xz = f_t s`.
fn plane_stresses(a: f64, cp: f64, cs: f64) -> (f64, f64) {
    let k = 2.0 * (cs / cp).powi(2);
    (1.0 - k * a.sin().powi(2), k * a.sin() * a.cos())
}

/// One run.
#[derive(Debug, Clone, Copy)]
struct Job {
    /// Incidence, degrees.
    deg: f64,
    /// Load ratio.
    xi: f64,
    /// The burst negated (pulse inversion's twin).
    negated: bool,
}

/// What one run keeps: the P wave at its receiver and the SV wave at its, gated windows,
/// and the crack's state.
#[derive(Debug, Clone)]
struct Record {
    /// Radial velocity at the P receiver, m/s.
    p: Vec<f64>,
    /// Transverse velocity at the SV receiver, m/s.
    sv: Vec<f64>,
    /// Gates of the P and SV receivers.
    gates: [Gate; 2],
    /// Time of the first sample and the step, s.
    t0: f64,
    dt: f64,
    /// Largest opening and largest tangential gap of the crack, m.
    max_gap: f64,
    max_slip: f64,
    /// Energy closure error of the run.
    closure: f64,
    /// `A_inc`: the band amplitude at f0 of the incident particle velocity, m/s.
    a_inc: f64,
    /// Peak of the incident wave stress over its amplitude.
    peak: f64,
}

/// The duration a run at `deg` needs: the front at the crack's centre, the SV wave's
/// travel to its receiver, the burst and the tail.
fn duration(lay: &Layout, deg: f64, cp: f64, cs: f64) -> f64 {
    let a = deg.to_radians();
    let [cx, cz] = lay.centre();
    // the origin: the top of the element row above the line at x = 0 (a >= 0)
    let tau = (cx * a.sin() + (cz - (lay.z_l as f64 - 1.0) * lay.e) * a.cos()) / cp;
    tau + DISTANCE * lambda() / cs + (CYCLES + TAIL + 1.0) / F0
}

/// Run one job.
fn run_job(res: Resolution, job: &Job) -> Result<Record> {
    let lay = &Layout::new(res, job.deg);
    let (cp0, cs0) = speeds()?;
    let t = text(lay, res, job, (cp0, cs0), duration(lay, job.deg, cp0, cs0));
    let table = parse_toml(&t, FILE)?;
    let spec = Solid2dSpec::from_table(table, FILE)?;
    let scen = Solid2dScenario::from_spec(spec, FILE, Path::new("."), &BuildCache::new())?;
    let mut problem = scen.problem;
    let mat = problem
        .layers
        .first()
        .map(|l| l.material)
        .ok_or_else(|| Error::invalid(FILE, "layer", "none", "one layer"))?;
    let (rho, cp, cs) = (mat.density, mat.p_speed, mat.s_speed);
    let signal = problem
        .sources
        .first()
        .map(|s| s.signal.clone())
        .ok_or_else(|| Error::invalid(FILE, "source", "none", "one plane wave"))?;
    if job.negated {
        for s in &mut problem.sources {
            s.signal = Arc::new(Scaled::negated(s.signal.clone()));
        }
    }
    let plan = problem.plan(FILE)?;
    let centre = lay.centre();
    let tau = plan
        .plane_waves
        .first()
        .map(|w| w.delay_at(centre))
        .ok_or_else(|| Error::invalid(FILE, "source", "none", "one plane wave"))?;
    let out = plan.run()?;
    let [tp, ts] = rays(job.deg.to_radians(), cp, cs);
    let (vx, vz) = (out.trace(0, 0), out.trace(0, 1));
    let p: Vec<f64> = vx
        .iter()
        .zip(vz)
        .map(|(x, z)| x * tp.sin() - z * tp.cos())
        .collect();
    let (vx, vz) = (out.trace(1, 0), out.trace(1, 1));
    let sv: Vec<f64> = vx
        .iter()
        .zip(vz)
        .map(|(x, z)| x * ts.cos() + z * ts.sin())
        .collect();
    let period = 1.0 / F0;
    let gate = |c: f64| {
        let arrival = tau + DISTANCE * lambda() / c;
        Gate {
            start: arrival - 0.5 * period,
            end: arrival + (CYCLES + TAIL) * period,
            taper: 0.5 * period,
        }
    };
    let c = out.cracks.first();
    let max_gap = c.map_or(0.0, |c| c.normal_gap.iter().fold(0.0f64, |m, &g| m.max(g)));
    let max_slip = c.map_or(0.0, |c| {
        c.tangential_gap.iter().fold(0.0f64, |m, &g| m.max(g.abs()))
    });
    // the incident particle velocity s(t) / (rho c_P), sampled at the run's step
    let dt = out.dt;
    let n = (signal.duration() / dt).ceil() as usize + 1;
    let inc: Vec<f64> = (0..n)
        .map(|k| signal.stress(k as f64 * dt) / (rho * cp))
        .collect();
    let whole = Signal {
        quantity: Quantity::Samples,
        dt,
        t0: 0.0,
        f0: F0,
        f2: None,
        plateau: (0.0, n as f64 * dt),
    };
    let a_inc = gated_bands(AnalysisMethod::BandPeak, None, &whole, &inc, None, None)
        .map_or(f64::NAN, |b| b.harmonic[1]);
    Ok(Record {
        p,
        sv,
        gates: [gate(cp), gate(cs)],
        t0: out.time.first().copied().unwrap_or(0.0),
        dt,
        max_gap,
        max_slip,
        closure: out.energy.closure_error(),
        a_inc,
        peak: signal.peak() / AMPLITUDE,
    })
}

/// One case measured: harmonics of the reflected P and of the converted SV over `A_inc`
/// (index n = 1..3), the crack's state and the plane-wave prediction of it.
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    /// Incidence, degrees.
    pub deg: f64,
    /// Load ratio.
    pub xi: f64,
    /// `A_n / A_inc` of the reflected P wave (index 0 unused).
    pub p: [f64; 4],
    /// `A_n / A_inc` of the converted SV wave (index 0 unused).
    pub sv: [f64; 4],
    /// Largest opening, m (either run).
    pub max_gap: f64,
    /// Largest tangential gap, m (either run).
    pub max_slip: f64,
    /// Largest energy closure error of the two runs.
    pub closure: f64,
    /// The plane wave's prediction: the crack opens.
    pub opens: bool,
    /// The plane wave's prediction: the crack, closed, slips.
    pub slips: bool,
}

/// The cases `(degrees, xi)` at `res`, in parallel: for each angle one bonded reference
/// run, for each case two runs (pulse inversion).
pub(crate) fn measure(ctx: &Ctx, res: Resolution, cases: &[(f64, f64)]) -> Result<Vec<Measured>> {
    let mut degs: Vec<f64> = Vec::new();
    for (d, _) in cases {
        if !degs.contains(d) {
            degs.push(*d);
        }
    }
    let mut jobs: Vec<Job> = degs
        .iter()
        .map(|&deg| Job {
            deg,
            xi: BONDED_XI,
            negated: false,
        })
        .collect();
    for &(deg, xi) in cases {
        for negated in [false, true] {
            jobs.push(Job { deg, xi, negated });
        }
    }
    let recs = ctx.map("finite crack: angle and mode conversion", &jobs, |j| {
        run_job(res, j)
    })?;
    let (cp, cs) = speeds()?;
    let mut out = Vec::new();
    for (i, &(deg, xi)) in cases.iter().enumerate() {
        let reference = &recs[degs.iter().position(|d| *d == deg).unwrap_or(0)];
        let (plus, minus) = (&recs[degs.len() + 2 * i], &recs[degs.len() + 2 * i + 1]);
        let bands = |w: usize| -> [f64; 4] {
            let pick = |r: &Record| if w == 0 { r.p.clone() } else { r.sv.clone() };
            let r0 = pick(reference);
            let response: Vec<f64> = pick(plus).iter().zip(&r0).map(|(a, b)| a - b).collect();
            let inverse: Vec<f64> = pick(minus).iter().zip(&r0).map(|(a, b)| a + b).collect();
            let g = plus.gates[w];
            let sig = Signal {
                quantity: Quantity::Samples,
                dt: plus.dt,
                t0: plus.t0,
                f0: F0,
                f2: None,
                plateau: (g.start, g.end),
            };
            let h = gated_bands(
                AnalysisMethod::PulseInversion,
                Some(&g),
                &sig,
                &response,
                Some(&inverse),
                None,
            )
            .map_or([f64::NAN; 6], |b| b.harmonic);
            [0.0, h[1], h[2], h[3]].map(|v| v / plus.a_inc)
        };
        let (f_n, f_t) = plane_stresses(deg.to_radians(), cp, cs);
        let s = plus.peak;
        out.push(Measured {
            deg,
            xi,
            p: bands(0),
            sv: bands(1),
            max_gap: plus.max_gap.max(minus.max_gap),
            max_slip: plus.max_slip.max(minus.max_slip),
            closure: plus.closure.abs().max(minus.closure.abs()),
            opens: f_n * s > xi,
            slips: f_t * s > FRICTION * (xi - f_n * s),
        });
    }
    Ok(out)
}

/// The opening and slip the solver sees above round-off, m.
const MOVES: f64 = 1e-13;

/// Run the study: its figure and findings are appended to the chapter's.
pub(crate) fn run(
    ctx: &Ctx,
    res: Resolution,
    figures: &mut Vec<Figure>,
    findings: &mut Vec<Finding>,
) -> Result<()> {
    let cost = Cost::start(ctx);
    let degs = angles(res);
    let xi = xis(res);
    let cases: Vec<(f64, f64)> = xi
        .iter()
        .flat_map(|&x| degs.iter().map(move |&d| (d, x)))
        .collect();
    let m = measure(ctx, res, &cases)?;
    let na = degs.len();
    let of = |k: usize| &m[k * na..(k + 1) * na];
    let col =
        |k: usize, f: &dyn Fn(&Measured) -> f64| -> Vec<f64> { of(k).iter().map(f).collect() };
    let label = |x: f64| format!("xi = {}", fmt_value(x));
    let mut panels = Vec::new();
    for (title, y, f) in [
        (
            "(a) reflected P: A2 / A_inc",
            "A2/A_inc",
            &(|r: &Measured| r.p[2]) as &dyn Fn(&Measured) -> f64,
        ),
        (
            "(b) converted SV: A2 / A_inc",
            "A2/A_inc",
            &|r: &Measured| r.sv[2],
        ),
        (
            "(c) reflected P: A3 / A_inc",
            "A3/A_inc",
            &|r: &Measured| r.p[3],
        ),
        (
            "(d) converted SV: A3 / A_inc",
            "A3/A_inc",
            &|r: &Measured| r.sv[3],
        ),
    ] {
        let series = (0..xi.len())
            .map(|k| Series::new(label(xi[k]), &degs, &col(k, f)))
            .collect();
        panels.push(panel(title, "incidence angle (degrees)", y, series));
    }
    let mut fund = Vec::new();
    for (k, x) in xi.iter().enumerate() {
        fund.push(Series::new(
            format!("P, {}", label(*x)),
            &degs,
            &col(k, &|r| r.p[1]),
        ));
        fund.push(Series::new(
            format!("SV, {}", label(*x)),
            &degs,
            &col(k, &|r| r.sv[1]),
        ));
    }
    panels.push(panel(
        "(e) fundamental: A1 / A_inc",
        "incidence angle (degrees)",
        "A1/A_inc",
        fund,
    ));
    let lay = Layout::new(res, degs[na - 1]);
    let mut fig = Figure::new(
        "finite_crack_angle",
        "Second and third harmonics of the reflected P and converted SV waves of a frictional crack against the incidence angle",
        format!(
            "Beyond the thesis; after Blanloeuil, Meziane and Bacon (Wave Motion 51, 2014). A \
             plane 1 MHz P wave (5-cycle Hann burst, sigma_max = 1 MPa, total-field/\
             scattered-field) at {} to {} degrees on a horizontal crack {} P wavelengths long \
             in aluminium (Signorini, Coulomb friction mu = {FRICTION} with rigid stick) under \
             the closure p0 = xi sigma_max, xi = {}; a rectangle (at the largest angle) {} x {} mm with absorbing \
             sides, top and bottom. Receivers in the scattered region {} P wavelengths from \
             the crack's centre on the specular P ray and on the converted SV ray (sin b = \
             sin a c_S / c_P); P is the radial and SV the transverse velocity about the \
             crack's centre, each gated to its arrival; a run with the crack bonded (the \
             uncracked solid) is subtracted; pulse inversion. A_inc: the incident wave's \
             particle velocity amplitude. Resolution: {}.",
            fmt_value(degs[0]),
            fmt_value(degs[na - 1]),
            fmt_value(LENGTH),
            xi.iter()
                .map(|v| fmt_value(*v))
                .collect::<Vec<_>>()
                .join(", "),
            fmt_value(lay.width as f64 * lay.e * 1e3),
            fmt_value(lay.depth as f64 * lay.e * 1e3),
            fmt_value(DISTANCE),
            res.name()
        ),
        panels,
    );

    // the regime: measured against the plane wave's prediction
    let mut mismatches = Vec::new();
    let mut checked = 0usize;
    for r in &m {
        let opened = r.max_gap > MOVES;
        checked += 1;
        if opened != r.opens {
            mismatches.push(format!(
                "{} deg xi {} (opening)",
                fmt_value(r.deg),
                fmt_value(r.xi)
            ));
        }
        // slip is measured where the crack stays shut (an open crack's faces also move
        // apart tangentially)
        if !r.opens && !opened {
            checked += 1;
            if (r.max_slip > MOVES) != r.slips {
                mismatches.push(format!(
                    "{} deg xi {} (slip)",
                    fmt_value(r.deg),
                    fmt_value(r.xi)
                ));
            }
        }
    }
    let regime = |r: &Measured| match (r.max_gap > MOVES, r.max_slip > MOVES) {
        (true, _) => "claps",
        (false, true) => "slips",
        (false, false) => "bonded",
    };
    for (k, x) in xi.iter().enumerate() {
        let rows = of(k);
        let list =
            |f: &dyn Fn(&Measured) -> String| rows.iter().map(f).collect::<Vec<_>>().join(", ");
        fig = fig.compare(format!(
            "{}: regime by angle {}; reflected P A2/A_inc {}; converted SV A2/A_inc {}; \
             A3/A2 of P {}; of SV {}",
            label(*x),
            list(&|r| format!("{} {}", fmt_value(r.deg), regime(r))),
            list(&|r| fmt_value(r.p[2])),
            list(&|r| fmt_value(r.sv[2])),
            list(&|r| fmt_value(r.p[3] / r.p[2])),
            list(&|r| fmt_value(r.sv[3] / r.sv[2])),
        ));
    }
    fig = fig.compare(format!(
        "Blanloeuil, Meziane and Bacon: the pre-stress is a governing parameter that changes \
         the mechanism at the crack (clapping or friction) and so the harmonics / here: the \
         crack opens where the incident wave's tension on its plane exceeds p0 and, closed, \
         slips where its shear exceeds mu times the contact pressure, as the plane wave \
         predicts at {} of {} checks{}",
        checked - mismatches.len(),
        checked,
        if mismatches.is_empty() {
            String::new()
        } else {
            format!(" (not at {})", mismatches.join(", "))
        }
    ));
    fig = fig.compare(cost.line(ctx, res));
    figures.push(fig);

    let closure = m.iter().fold(0.0f64, |a, r| a.max(r.closure));
    let first = &of(0)[0];
    let sym = first.sv[2] / first.p[2];
    let last = of(xi.len() - 1);
    let bonded_0 = last[0].p[2].max(last[0].sv[2]).max(last[0].p[3]);
    let oblique_min = last[1..]
        .iter()
        .map(|r| r.p[2].max(r.sv[2]))
        .fold(f64::INFINITY, f64::min);
    // odd over even harmonics, rubbing (the highest closure) over clapping (the lowest)
    let clap = of(0);
    let odd = last
        .iter()
        .zip(clap)
        .filter(|(r, _)| r.deg > 0.0)
        .map(|(f, c)| (f.p[3] / f.p[2]) / (c.p[3] / c.p[2]))
        .fold(f64::INFINITY, f64::min);
    // clapping: the reflected P's A2 against the converted SV's
    let falls = clap.windows(2).all(|w| w[1].p[2] < w[0].p[2]);
    let rises = clap.windows(2).all(|w| w[1].sv[2] > w[0].sv[2]);
    let cross = clap
        .windows(2)
        .find(|w| w[0].sv[2] < w[0].p[2] && w[1].sv[2] >= w[1].p[2])
        .map_or(f64::NAN, |w| {
            let (d0, d1) = (w[0].p[2] - w[0].sv[2], w[1].p[2] - w[1].sv[2]);
            w[0].deg + (w[1].deg - w[0].deg) * d0 / (d0 - d1)
        });
    findings.extend([
        finding(
            "finite_crack_angle_rubbing_over_clapping_p_a3_over_a2",
            odd,
            "",
            &format!(
                "(not in the thesis) friction alone (Coulomb at a constant pressure) makes odd \
                 harmonics only, clapping mostly even ones: the reflected P's A3/A2 at xi = {} \
                 (rubbing) over its A3/A2 at xi = {} (clapping), smallest over the oblique \
                 angles, above 1",
                fmt_value(xi[xi.len() - 1]),
                fmt_value(xi[0])
            ),
            Some(odd > 1.0),
        ),
        finding(
            "finite_crack_angle_clapping_sv_overtakes_p_deg",
            cross,
            "degree",
            &format!(
                "(not in the thesis) clapping (xi = {}): the opening radiates P along the \
                 crack's normal and SV obliquely, and opens less as the angle grows: the \
                 reflected P's A2 falls and the converted SV's rises with the angle; the angle \
                 where the SV's overtakes the P's",
                fmt_value(xi[0])
            ),
            Some(falls && rises && cross.is_finite()),
        ),
        finding(
            "finite_crack_angle_sv_a2_over_p_a2_normal_incidence",
            sym,
            "",
            "(not in the thesis) by symmetry a P wave at normal incidence on a centred crack \
             converts no SV straight back: the converted SV's A2 over the reflected P's at 0 \
             degrees (the clapping closure) below 0.01",
            Some(sym.abs() < 0.01),
        ),
        finding(
            "finite_crack_angle_regime_mismatches",
            mismatches.len() as f64,
            "",
            "Blanloeuil, Meziane and Bacon (2014): the pre-stress and the angle set the \
             mechanism (clapping or stick-slip friction); here the crack opens or slips \
             exactly where the incident plane wave's stresses on its plane predict (count of \
             cases where it does not: 0)",
            Some(mismatches.is_empty()),
        ),
        finding(
            "finite_crack_angle_friction_normal_incidence_harmonic",
            bonded_0,
            "",
            &format!(
                "(not in the thesis) xi = {}: above the incident tension and without shear at \
                 normal incidence the crack stays bonded: no harmonic (largest A2, A3 over \
                 A_inc at 0 degrees below the floor)",
                fmt_value(xi[xi.len() - 1])
            ),
            Some(bonded_0 < AMPLITUDE_FLOOR),
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "finite_crack_angle_friction_oblique_a2_min",
            oblique_min,
            "",
            &format!(
                "(not in the thesis) xi = {}: at oblique incidence the crack slips and both \
                 waves carry a second harmonic (the friction limit mu N follows the wave's \
                 own normal stress): smallest A2/A_inc of P or SV over the oblique angles, \
                 above 1e-4",
                fmt_value(xi[xi.len() - 1])
            ),
            Some(oblique_min > 1e-4),
        )
        .with_floor(AMPLITUDE_FLOOR),
        finding(
            "finite_crack_angle_energy_closure_error",
            closure,
            "",
            "(not in the thesis) energy audit of the 2D runs (model.md eq. 15.5)",
            Some(closure < 1e-9),
        ),
    ]);
    for (k, x) in xi.iter().enumerate() {
        let rows = of(k);
        let tag = format!("{x}").replace('.', "p");
        let best = rows
            .iter()
            .max_by(|a, b| a.p[2].total_cmp(&b.p[2]))
            .map_or(f64::NAN, |r| r.deg);
        let peak = rows.iter().map(|r| r.p[2]).fold(0.0, f64::max);
        findings.push(
            finding(
                &format!("finite_crack_angle_p_a2_max_xi{tag}"),
                peak,
                "",
                &format!(
                    "(not in the thesis) largest A2/A_inc of the reflected P over the angles, \
                     xi = {} (at {} degrees)",
                    fmt_value(*x),
                    fmt_value(best)
                ),
                None,
            )
            .with_floor(AMPLITUDE_FLOOR),
        );
        let sv = rows.iter().map(|r| r.sv[2]).fold(0.0, f64::max);
        findings.push(
            finding(
                &format!("finite_crack_angle_sv_a2_max_xi{tag}"),
                sv,
                "",
                &format!(
                    "(not in the thesis) largest A2/A_inc of the converted SV over the angles, \
                     xi = {}",
                    fmt_value(*x)
                ),
                None,
            )
            .with_floor(AMPLITUDE_FLOOR),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    fn ctx() -> Ctx<'static> {
        Ctx {
            progress: &|_, _, _| {},
            runs: AtomicUsize::new(0),
        }
    }

    /// A P wave at normal incidence on a centred clapping crack (xi = 0.3) converts no SV
    /// straight back (mirror symmetry: zero to round-off), at 40 degrees it converts as much
    /// as it reflects; the energy audit closes. 6 runs, about 10 s of CPU in release.
    #[test]
    #[ignore = "slow: full tier"]
    fn normal_incidence_converts_no_sv_and_oblique_incidence_does() {
        let m = measure(
            &ctx(),
            Resolution { quick: true },
            &[(0.0, 0.3), (40.0, 0.3)],
        )
        .unwrap();
        for r in &m {
            eprintln!("{r:?}");
            assert!(r.closure < 1e-9, "{r:?}");
            assert!(r.opens && r.max_gap > MOVES, "{r:?}");
        }
        let (normal, oblique) = (&m[0], &m[1]);
        assert!(normal.p[1] > 0.1 && normal.p[2] > 0.1, "{normal:?}");
        for n in 1..=3 {
            assert!(normal.sv[n] < 1e-12 * normal.p[n], "{normal:?}");
        }
        assert!(oblique.sv[1] > 0.1 && oblique.sv[2] > 0.1, "{oblique:?}");
        assert!(oblique.sv[2] > 0.5 * oblique.p[2], "{oblique:?}");
    }

    /// At 40 degrees: a crack held by xi = 5 stays stuck and shut (no opening, no slip) and
    /// scatters nothing (the bonded reference to round-off); at xi = 1.2 it never opens but
    /// slips and makes harmonics; at xi = 0.3 it claps and its reflected A2 is several
    /// times larger. 7 runs, about 11 s of CPU in release.
    #[test]
    #[ignore = "slow: full tier"]
    fn a_bonded_crack_scatters_nothing_and_a2_grows_as_the_closure_falls() {
        let m = measure(
            &ctx(),
            Resolution { quick: true },
            &[(40.0, 5.0), (40.0, 1.2), (40.0, 0.3)],
        )
        .unwrap();
        for r in &m {
            eprintln!("{r:?}");
            assert!(r.closure < 1e-9, "{r:?}");
        }
        let (held, rubbing, clapping) = (&m[0], &m[1], &m[2]);
        assert!(!held.opens && !held.slips, "{held:?}");
        assert!(held.max_gap < 1e-15 && held.max_slip < 1e-15, "{held:?}");
        for n in 1..=3 {
            assert!(held.p[n] < 1e-9 && held.sv[n] < 1e-9, "{held:?}");
        }
        assert!(!rubbing.opens && rubbing.slips, "{rubbing:?}");
        assert!(
            rubbing.max_gap < 1e-15 && rubbing.max_slip > 1e-10,
            "{rubbing:?}"
        );
        assert!(rubbing.p[2] > 1e-3 && rubbing.sv[2] > 1e-3, "{rubbing:?}");
        assert!(clapping.opens && clapping.max_gap > MOVES, "{clapping:?}");
        assert!(clapping.p[2] > 3.0 * rubbing.p[2], "{clapping:?}");
        assert!(clapping.sv[2] > 3.0 * rubbing.sv[2], "{clapping:?}");
    }
}
