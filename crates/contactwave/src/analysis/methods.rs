//! Harmonic analysis methods (model.md section 6.1): how the band amplitudes of a run are
//! obtained from one or more records, and the floor each method has on a linear response.
//!
//! - `band_peak`: the thesis' method, the peak of the band-filtered signal in
//!   `[n f0 - f0/2, n f0 + f0/2)` ([`super::Analyzer`]). The fundamental's own spectral
//!   leakage into the harmonic bands is its floor.
//! - `pulse_inversion`: the responses `x+` to the burst and `x-` to its phase-inverted copy;
//!   even harmonics (and the two-tone sum and difference frequencies, second order) from
//!   `(x+ + x-)/2`, odd harmonics (and `f2`) from `(x+ - x-)/2`, each band-filtered; the
//!   sub-harmonic from `x+`. A linear response cancels exactly in the sum.
//! - `linear_reference`: `A1` (and `f2`) from the full response `x`, every other component
//!   from the nonlinear residual `x - x_lin`, `x_lin` the response of the interface
//!   linearised at its static state.
//! - `plateau_fit`: least-squares fit of `a cos + b sin` at every analysed frequency, plus a
//!   quadratic baseline, over the whole periods of `f0` where the incident burst's envelope
//!   is flat; no band filter, so nothing depends on a filter's shape.

use super::spectrum::{with_analyzer, BandAmplitudes};
use crate::numeric::solve_dense;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How harmonic amplitudes are extracted (`[analysis] method`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AnalysisMethod {
    /// Peak of the band-filtered record (the thesis' method; the default).
    #[default]
    BandPeak,
    /// Sum and difference of the responses to the burst and its inverse.
    PulseInversion,
    /// Band-filtered residual after subtracting the linearised interface's response.
    LinearReference,
    /// Least-squares fit of each component over the burst's flat top.
    PlateauFit,
}

impl AnalysisMethod {
    /// Every method, in the order of their codes.
    pub const ALL: [AnalysisMethod; 4] = [
        AnalysisMethod::BandPeak,
        AnalysisMethod::PulseInversion,
        AnalysisMethod::LinearReference,
        AnalysisMethod::PlateauFit,
    ];

    /// Name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            AnalysisMethod::BandPeak => "band_peak",
            AnalysisMethod::PulseInversion => "pulse_inversion",
            AnalysisMethod::LinearReference => "linear_reference",
            AnalysisMethod::PlateauFit => "plateau_fit",
        }
    }

    /// Numeric code of the summary key `analysis_method` (0 band_peak, 1 pulse_inversion,
    /// 2 linear_reference, 3 plateau_fit).
    pub fn code(self) -> f64 {
        match self {
            AnalysisMethod::BandPeak => 0.0,
            AnalysisMethod::PulseInversion => 1.0,
            AnalysisMethod::LinearReference => 2.0,
            AnalysisMethod::PlateauFit => 3.0,
        }
    }

    /// The method of a name, if any.
    pub fn from_name(name: &str) -> Option<AnalysisMethod> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// The records an analysis reads: displacements (m) on the grid `t0 + k dt`.
#[derive(Debug, Clone, Copy)]
pub struct Records<'a> {
    /// Response to the burst.
    pub response: &'a [f64],
    /// Response to the phase-inverted burst (pulse inversion).
    pub inverse: Option<&'a [f64]>,
    /// Response of the linearised interface to the burst.
    pub linear: Option<&'a [f64]>,
}

/// What a record holds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Quantity {
    /// Displacements (m) at the grid points, analysed as the cell-averaged velocity (their
    /// differences over `dt`; the exact solvers' records).
    #[default]
    Displacement,
    /// Samples analysed as they are (a velocity in m/s at the grid points, as the 2D
    /// receivers record, or any measured signal in its own unit).
    Samples,
}

/// What the analysis needs to know about the signal.
#[derive(Debug, Clone, Copy)]
pub struct Signal {
    /// What the records hold.
    pub quantity: Quantity,
    /// Time step, s.
    pub dt: f64,
    /// Time of the first sample, s.
    pub t0: f64,
    /// Fundamental f0, Hz.
    pub f0: f64,
    /// Second frequency of a two-tone burst, Hz.
    pub f2: Option<f64>,
    /// Flat top of the burst `(start, end)`, s (whole periods of f0), for `plateau_fit`.
    pub plateau: (f64, f64),
}

/// `wa a + wb b` over the longer record, the shorter one held at its last value (a
/// record ends when its interface is back at rest).
fn combine(a: &[f64], b: &[f64], wa: f64, wb: f64) -> Vec<f64> {
    let n = a.len().max(b.len());
    let at = |x: &[f64], k: usize| x.get(k).or(x.last()).copied().unwrap_or(0.0);
    (0..n).map(|k| wa * at(a, k) + wb * at(b, k)).collect()
}

fn band(x: &[f64], s: &Signal) -> BandAmplitudes {
    with_analyzer(|a| match s.quantity {
        Quantity::Displacement => a.displacement_bands(x, s.dt, s.f0, s.f2),
        Quantity::Samples => a.point_bands(x, s.dt, s.f0, s.f2),
    })
}

/// Band amplitudes (m/s of the velocity; the samples' unit for [`Quantity::Samples`]) by
/// `method`. Returns `None` when a record the
/// method needs is missing.
pub fn method_bands(method: AnalysisMethod, r: &Records, s: &Signal) -> Option<BandAmplitudes> {
    Some(match method {
        AnalysisMethod::BandPeak => band(r.response, s),
        AnalysisMethod::PulseInversion => {
            let minus = r.inverse?;
            let even = band(&combine(r.response, minus, 0.5, 0.5), s);
            let odd = band(&combine(r.response, minus, 0.5, -0.5), s);
            let plus = band(r.response, s);
            pulse_inversion_parts(&even, &odd, &plus)
        }
        AnalysisMethod::LinearReference => {
            let lin = r.linear?;
            let full = band(r.response, s);
            let residual = band(&combine(r.response, lin, 1.0, -1.0), s);
            linear_reference_parts(&full, &residual)
        }
        AnalysisMethod::PlateauFit => plateau_fit(r.response, s),
    })
}

/// [`method_bands`] of records gated by `gate` (each record a copy, weighted by the gate
/// at `s.t0 + k s.dt`): the one analysis of a receiver, simulated (2D runs) or measured
/// (`contactwave analyze`). `None` when a record the method needs is missing.
pub fn gated_bands(
    method: AnalysisMethod,
    gate: Option<&super::Gate>,
    s: &Signal,
    response: &[f64],
    inverse: Option<&[f64]>,
    linear: Option<&[f64]>,
) -> Option<BandAmplitudes> {
    let gated = |x: &[f64]| {
        let mut x = x.to_vec();
        if let Some(g) = gate {
            g.apply(&mut x, s.t0, s.dt);
        }
        x
    };
    let response = gated(response);
    let inverse = inverse.map(gated);
    let linear = linear.map(gated);
    let records = Records {
        response: &response,
        inverse: inverse.as_deref(),
        linear: linear.as_deref(),
    };
    method_bands(method, &records, s)
}

fn pulse_inversion_parts(
    even: &BandAmplitudes,
    odd: &BandAmplitudes,
    plus: &BandAmplitudes,
) -> BandAmplitudes {
    let mut out = *even;
    for n in [1, 3, 5] {
        out.harmonic[n] = odd.harmonic[n];
    }
    out.f2 = odd.f2;
    out.subharmonic = plus.subharmonic;
    out
}

fn linear_reference_parts(full: &BandAmplitudes, residual: &BandAmplitudes) -> BandAmplitudes {
    let mut out = *residual;
    out.harmonic[1] = full.harmonic[1];
    out.f2 = full.f2;
    out
}

/// The floor of `method` (m/s): what it gives on the linear response `linear` of the same
/// scenario. The linear response to the inverted burst is `-linear` (linearity), so pulse
/// inversion's even components and linear reference's residual components are exactly 0.
pub fn method_floor(method: AnalysisMethod, linear: &[f64], s: &Signal) -> BandAmplitudes {
    match method {
        AnalysisMethod::BandPeak => band(linear, s),
        AnalysisMethod::PulseInversion => {
            let lin = band(linear, s);
            pulse_inversion_parts(&BandAmplitudes::default(), &lin, &lin)
        }
        AnalysisMethod::LinearReference => {
            linear_reference_parts(&band(linear, s), &BandAmplitudes::default())
        }
        AnalysisMethod::PlateauFit => plateau_fit(linear, s),
    }
}

/// The floor a record's fundamental alone sets on `method`'s harmonics (the record's
/// unit): what the method reads at `n f0` from `x` band-limited to `[f0/2, 3 f0/2)` before
/// the gate (so that the gate's edges spread it as they spread the record; [`band_limited`]);
/// zero for `plateau_fit`, exact over whole periods.
pub fn leakage_floor(
    method: AnalysisMethod,
    x: &[f64],
    gate: Option<&super::Gate>,
    s: &Signal,
) -> [f64; 6] {
    if method == AnalysisMethod::PlateauFit {
        return [0.0; 6];
    }
    let mut fundamental = band_limited(x, s.dt, 0.5 * s.f0, 1.5 * s.f0);
    if let Some(g) = gate {
        g.apply(&mut fundamental, s.t0, s.dt);
    }
    method_floor(method, &fundamental, s).harmonic
}

/// `x` band-limited to `(f_lo, f_hi)` (Hz): its transform weighted by 1 over the middle half
/// of the band and half-cosine ramps to 0 at its edges, 0 outside (zero-padded to twice its
/// length, so that the ringing does not wrap around). The smooth edges keep the ringing of
/// the record's own ends short (a brick-wall band would ring at its edge frequency, near
/// `2 f0` for the band around `f0`, across the whole record).
pub fn band_limited(x: &[f64], dt: f64, f_lo: f64, f_hi: f64) -> Vec<f64> {
    let n = x.len();
    let m = (2 * n).next_power_of_two();
    let mut planner = realfft::RealFftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(m);
    let inv = planner.plan_fft_inverse(m);
    let mut input = vec![0.0; m];
    input[..n].copy_from_slice(x);
    let mut spec = fwd.make_output_vec();
    if fwd.process(&mut input, &mut spec).is_err() {
        return vec![0.0; n];
    }
    let df = 1.0 / (m as f64 * dt);
    let (mid, half) = (0.5 * (f_lo + f_hi), 0.5 * (f_hi - f_lo));
    for (k, c) in spec.iter_mut().enumerate() {
        // distance from the band's centre, in half-widths: flat below 1/2, ramp to 1
        let r = (k as f64 * df - mid).abs() / half;
        let w = if r <= 0.5 {
            1.0
        } else if r < 1.0 {
            0.5 * (1.0 + (std::f64::consts::TAU * (r - 0.5)).cos())
        } else {
            0.0
        };
        *c *= w;
    }
    let mut out = inv.make_output_vec();
    if inv.process(&mut spec, &mut out).is_err() {
        return vec![0.0; n];
    }
    out.truncate(n);
    for v in &mut out {
        *v /= m as f64;
    }
    out
}

/// The flat top of a burst: the longest run of whole periods of `f0` in `[0, duration]`
/// whose fundamental amplitude (projection of `stress` over the period) is within 1e-3 of
/// the largest, as `(start, end)` in s. A window without a flat top (Hann) gives the
/// period around its peak.
pub fn plateau(stress: impl Fn(f64) -> f64, duration: f64, f0: f64) -> (f64, f64) {
    let period = 1.0 / f0;
    let n = (duration * f0 + 1e-9).floor() as usize;
    if n == 0 || !period.is_finite() {
        return (0.0, duration);
    }
    const M: usize = 64;
    // the phases of the M samples are the same in every period: their cosines and sines
    // once (the same values as computed per sample)
    let mut trig = [(0.0, 0.0); M];
    for (i, cs) in trig.iter_mut().enumerate() {
        let ph = 2.0 * PI * (i as f64 + 0.5) / M as f64;
        *cs = (ph.cos(), ph.sin());
    }
    let amp: Vec<f64> = (0..n)
        .map(|j| {
            let (mut a, mut b) = (0.0, 0.0);
            for (i, &(c, s)) in trig.iter().enumerate() {
                let v = stress((j as f64 + (i as f64 + 0.5) / M as f64) * period);
                a += v * c;
                b += v * s;
            }
            (a * a + b * b).sqrt()
        })
        .collect();
    let top = amp.iter().copied().fold(0.0f64, f64::max);
    let (mut best, mut run_start, mut best_len) = (0, 0, 0);
    for j in 0..=n {
        let flat = j < n && amp[j] >= (1.0 - 1e-3) * top;
        if !flat {
            if j - run_start > best_len {
                best_len = j - run_start;
                best = run_start;
            }
            run_start = j + 1;
        }
    }
    if best_len == 0 {
        return (0.0, duration);
    }
    (best as f64 * period, (best + best_len) as f64 * period)
}

/// `plateau_fit`: least-squares amplitudes (m/s) of the cell-averaged velocity of the
/// displacement record over the plateau. Fitted jointly: `n f0` (n = 1..5), `f0/2` and, for
/// two-tone, `f2`, `f0 + f2`, `|f2 - f0|` (a frequency closer than half a bin `1/(2T)` to
/// one already fitted takes that one's amplitude), and a quadratic baseline (the slow
/// quasi-static part of the response).
pub fn plateau_fit(record: &[f64], s: &Signal) -> BandAmplitudes {
    let (ta, tb) = s.plateau;
    let span = tb - ta;
    let mut freqs: Vec<f64> = (1..=5).map(|n| n as f64 * s.f0).collect();
    freqs.push(0.5 * s.f0);
    if let Some(f2) = s.f2 {
        freqs.extend([f2, s.f0 + f2, (f2 - s.f0).abs()]);
    }
    // distinct frequencies to fit, and which one each requested frequency reads
    let min_sep = 0.5 / span.max(f64::MIN_POSITIVE);
    let mut fit: Vec<f64> = Vec::new();
    let idx: Vec<usize> = freqs
        .iter()
        .map(
            |&f| match fit.iter().position(|&g| (g - f).abs() < min_sep) {
                Some(i) => i,
                None => {
                    fit.push(f);
                    fit.len() - 1
                }
            },
        )
        .collect();
    let nb = 3 + 2 * fit.len();
    let mut ata = vec![0.0; nb * nb];
    let mut atb = vec![0.0; nb];
    let mut row = vec![0.0; nb];
    let mid = 0.5 * (ta + tb);
    let mut used = 0usize;
    // the samples: a displacement record's cell velocities at the cells' midpoints (each a
    // cell average: its cos / sin weighted by sinc(pi f dt)), or the samples themselves at
    // the grid points
    let cell = s.quantity == Quantity::Displacement;
    let n = if cell {
        record.len().saturating_sub(1)
    } else {
        record.len()
    };
    for k in 0..n {
        let (tc, v) = if cell {
            (
                s.t0 + (k as f64 + 0.5) * s.dt,
                (record[k + 1] - record[k]) / s.dt,
            )
        } else {
            (s.t0 + k as f64 * s.dt, record[k])
        };
        if tc < ta || tc > tb {
            continue;
        }
        used += 1;
        let x = 2.0 * (tc - mid) / span;
        row[0] = 1.0;
        row[1] = x;
        row[2] = x * x;
        for (i, &f) in fit.iter().enumerate() {
            // cell average of cos / sin over [tc - dt/2, tc + dt/2]
            let a = PI * f * s.dt;
            let sinc = if a == 0.0 || !cell { 1.0 } else { a.sin() / a };
            let ph = 2.0 * PI * f * (tc - ta);
            row[3 + 2 * i] = sinc * ph.cos();
            row[4 + 2 * i] = sinc * ph.sin();
        }
        for i in 0..nb {
            atb[i] += row[i] * v;
            for j in 0..nb {
                ata[i * nb + j] += row[i] * row[j];
            }
        }
    }
    let mut out = BandAmplitudes::default();
    if used < 2 * nb || !solve_dense(&mut ata, &mut atb, nb) {
        let nan = f64::NAN;
        out.harmonic = [0.0, nan, nan, nan, nan, nan];
        out.subharmonic = nan;
        return out;
    }
    let amp = |i: usize| atb[3 + 2 * idx[i]].hypot(atb[4 + 2 * idx[i]]);
    for n in 1..=5 {
        out.harmonic[n] = amp(n - 1);
    }
    out.subharmonic = amp(5);
    if s.f2.is_some() {
        out.f2 = amp(6);
        out.sum = amp(7);
        out.difference = amp(8);
    }
    out
}

/// How to read a harmonic `name` (`"A2"`) of amplitude `value` against its analysis floor
/// `floor` (the same unit): `None` from 10 floors up (or without a floor); within a factor
/// 3 of it an upper bound (the floor could be all of it), from 3 to 10 floors a value
/// uncertain by about the floor over the value.
pub fn floor_reading(name: &str, value: f64, floor: f64) -> Option<String> {
    if !(floor > 0.0) || !(value < 10.0 * floor) {
        return None;
    }
    let q = value / floor;
    Some(if q < 3.0 {
        format!("{name} at {q:.2} times its floor: read it as an upper bound (the floor could be all of it)")
    } else {
        format!(
            "{name} at {q:.1} times its floor: uncertain by about {:.0} % (the floor over the value)",
            100.0 / q
        )
    })
}

/// Harmonics `n` in 2..=5 whose amplitude is within a factor 10 of its floor (a floor of 0
/// or NaN never flags).
pub fn near_floor(a: &BandAmplitudes, floor: &BandAmplitudes) -> Vec<usize> {
    (2..=5)
        .filter(|&n| floor.harmonic[n] > 0.0 && a.harmonic[n] < 10.0 * floor.harmonic[n])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 56 item 2: a harmonic at 7.5 floors is a value with a 13 % uncertainty, not
    /// an upper bound; at 1.5 floors it is one.
    #[test]
    fn a_harmonic_near_its_floor_is_read_by_how_near() {
        let w = floor_reading("A2", 7.5e-3, 1e-3).unwrap();
        assert!(
            w.contains("7.5 times") && w.contains("13 %") && !w.contains("upper"),
            "{w}"
        );
        let w = floor_reading("A3", 1.5e-3, 1e-3).unwrap();
        assert!(w.contains("upper bound"), "{w}");
        assert!(floor_reading("A2", 1e-2, 1e-3).is_none());
        assert!(floor_reading("A2", 1e-9, 0.0).is_none());
        assert!(floor_reading("A2", 1e-9, f64::NAN).is_none());
    }

    /// Displacement whose cell-averaged velocity is `v` (integrated exactly per cell).
    fn record(v: impl Fn(f64) -> f64, dt: f64, n: usize) -> Vec<f64> {
        let mut d = vec![0.0];
        for k in 0..n {
            let t = k as f64 * dt;
            let last = *d.last().unwrap_or(&0.0);
            d.push(last + crate::numeric::gauss4(t, t + dt, &v));
        }
        d
    }

    #[test]
    fn plateau_of_a_flat_top_burst_is_its_flat_part() {
        // 16 cycles at 1 MHz with half-Hann ramps of 4 cycles each
        let f = 1e6;
        let d = 16e-6;
        let win = |t: f64| {
            let s = t / d;
            let r = 0.25;
            if !(0.0..=1.0).contains(&s) {
                0.0
            } else if s < r {
                0.5 * (1.0 - (PI * s / r).cos())
            } else if s > 1.0 - r {
                0.5 * (1.0 - (PI * (1.0 - s) / r).cos())
            } else {
                1.0
            }
        };
        let (a, e) = plateau(|t| -win(t) * (2.0 * PI * f * t).sin(), d, f);
        // flat from 4 to 12 µs (within 1e-3 of the top a little earlier and later)
        assert!((3e-6 - 1e-12..=4e-6 + 1e-12).contains(&a), "{a}");
        assert!((12e-6 - 1e-12..=13e-6 + 1e-12).contains(&e), "{e}");
    }

    #[test]
    fn samples_analyse_as_the_displacement_record_they_come_from() {
        // the velocity sampled at the grid points and the displacement whose cell averages
        // it gives: every method returns the same amplitudes (the cell average's sinc is
        // corrected on the displacement's side), to the sampling's O((f dt)^2)
        let f = 1e6;
        let dt = 1.0 / (f * 200.0);
        let w = 2.0 * PI * f;
        let burst = |t: f64| {
            if (0.0..12e-6).contains(&t) {
                (PI * t / 12e-6).sin().powi(2)
            } else {
                0.0
            }
        };
        let v = |t: f64| burst(t) * ((w * t).sin() + 0.01 * (2.0 * w * t).cos());
        let d = record(v, dt, 4000);
        let samples: Vec<f64> = (0..4000).map(|k| v(k as f64 * dt)).collect();
        let mut s = Signal {
            quantity: Quantity::Displacement,
            dt,
            t0: 0.0,
            f0: f,
            f2: None,
            plateau: (4e-6, 8e-6),
        };
        for m in [AnalysisMethod::BandPeak, AnalysisMethod::PlateauFit] {
            s.quantity = Quantity::Displacement;
            let recs = Records {
                response: &d,
                inverse: None,
                linear: None,
            };
            let a = method_bands(m, &recs, &s).unwrap_or_default();
            s.quantity = Quantity::Samples;
            let recs = Records {
                response: &samples,
                inverse: None,
                linear: None,
            };
            let b = method_bands(m, &recs, &s).unwrap_or_default();
            for n in 1..=2 {
                let e = (a.harmonic[n] / b.harmonic[n] - 1.0).abs();
                assert!(
                    e < 2e-3,
                    "{m:?} A{n}: {} vs {} ({e:.2e})",
                    a.harmonic[n],
                    b.harmonic[n]
                );
            }
        }
    }

    #[test]
    fn plateau_fit_recovers_amplitudes_next_to_a_drifting_baseline() {
        let f = 1e6;
        let dt = 1.0 / (f * 100.0);
        let w = 2.0 * PI * f;
        // a decaying drift the size of the second harmonic, as the quasi-static part of a
        // second-order response (model.md section 6.1)
        let v = |t: f64| 1e-4 * (-t * 2e5).exp() + (w * t).sin() + 1e-4 * (2.0 * w * t + 0.3).cos();
        let d = record(v, dt, 2000);
        let s = Signal {
            quantity: Quantity::Displacement,
            dt,
            t0: 0.0,
            f0: f,
            f2: None,
            plateau: (5e-6, 15e-6),
        };
        let b = plateau_fit(&d, &s);
        assert!((b.harmonic[1] - 1.0).abs() < 1e-6, "{}", b.harmonic[1]);
        assert!(
            (b.harmonic[2] / 1e-4 - 1.0).abs() < 1e-2,
            "{}",
            b.harmonic[2]
        );
        assert!(b.harmonic[3] < 1e-6);
    }

    #[test]
    fn pulse_inversion_cancels_a_linear_response_and_keeps_a_quadratic_one() {
        // x+ = l + q, x- = -l + q: the sum keeps q (even), the difference l (odd)
        let f = 1e6;
        let dt = 1.0 / (f * 100.0);
        let w = 2.0 * PI * f;
        let burst = |t: f64| {
            let s = (t * f / 15.0).clamp(0.0, 1.0);
            (PI * s).sin().powi(2)
        };
        let l = |t: f64| burst(t) * (w * t).sin();
        let q = |t: f64| 1e-5 * burst(t).powi(2) * (2.0 * w * t).cos();
        let plus = record(|t| l(t) + q(t), dt, 4000);
        let minus = record(|t| -l(t) + q(t), dt, 4000);
        let s = Signal {
            quantity: Quantity::Displacement,
            dt,
            t0: 0.0,
            f0: f,
            f2: None,
            plateau: (0.0, 15e-6),
        };
        let only_q = method_bands(
            AnalysisMethod::BandPeak,
            &Records {
                response: &record(q, dt, 4000),
                inverse: None,
                linear: None,
            },
            &s,
        )
        .map(|b| b.harmonic[2])
        .unwrap_or(f64::NAN);
        let pi = method_bands(
            AnalysisMethod::PulseInversion,
            &Records {
                response: &plus,
                inverse: Some(&minus),
                linear: None,
            },
            &s,
        )
        .unwrap_or_default();
        let bp = band(&plus, &s);
        assert!((pi.harmonic[2] / only_q - 1.0).abs() < 1e-9);
        assert!((pi.harmonic[1] - bp.harmonic[1]).abs() < 1e-3 * bp.harmonic[1]);
        // a linear reference equal to l gives the same second harmonic
        let lr = method_bands(
            AnalysisMethod::LinearReference,
            &Records {
                response: &plus,
                inverse: None,
                linear: Some(&record(l, dt, 4000)),
            },
            &s,
        )
        .unwrap_or_default();
        assert!((lr.harmonic[2] / only_q - 1.0).abs() < 1e-9);
        // the floor of pulse inversion on the linear part is 0 for even harmonics
        let fl = method_floor(AnalysisMethod::PulseInversion, &record(l, dt, 4000), &s);
        assert_eq!(fl.harmonic[2], 0.0);
        assert!(fl.harmonic[3] > 0.0);
    }

    #[test]
    fn names_round_trip() {
        for m in AnalysisMethod::ALL {
            assert_eq!(AnalysisMethod::from_name(m.name()), Some(m));
        }
    }
}
