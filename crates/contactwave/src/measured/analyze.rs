//! The analysis of measured records (model.md section 16.2): the simulator's own
//! [`gated_bands`] on each record, the fundamental given or detected, each harmonic's
//! floor, and over a series of drive amplitudes the least-squares fit of A2 against A1^2.
//!
//! Per record, in order:
//! 1. the baseline (the record's mean, a DC offset) is removed, unless
//!    [`Settings::keep_dc`];
//! 2. the gate weights the record (and its opposite-polarity twin and linear reference);
//!    a linear reference is first scaled to the record by least squares over the gate
//!    (a low-amplitude record of the same echo stands for the linear response);
//! 3. `A1`...`A5` by the method (band peak, pulse inversion, linear reference, plateau
//!    fit), the records taken as point samples;
//! 4. the floor of each harmonic: the larger of the method's leakage (what it gives on
//!    the record's fundamental alone: the record band-limited to `[f0/2, 3 f0/2)`; none
//!    for the plateau fit, exact over whole periods) and
//!    the noise (the band-peak amplitudes of the samples outside the gate, placed in the
//!    gate: what noise alone gives; without a gate, the samples of the record's quiet part
//!    before the arrival, [`quiet_part`], or none: the noise floor unknown), with a
//!    warning when a harmonic is within a factor 10 of its floor;
//! 5. clipping ([`clipping`]): samples in flat runs at the record's extremes (an
//!    overranged scope), or at the full scale given: the harmonics are the clipping's, and
//!    are marked unreliable.

use super::series::{Measured, Series};
use crate::analysis::methods::{gated_bands, leakage_floor, Quantity, Signal};
use crate::analysis::{spectral_peak, with_analyzer, AnalysisMethod, Gate};
use crate::error::{Error, Result};
use crate::numeric::t975;

/// How records are analysed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Settings {
    /// Fundamental, Hz (default: detected, the peak of the largest record's spectrum).
    pub f0: Option<f64>,
    /// The time gate around the echo of interest (default: the whole record).
    pub gate: Option<Gate>,
    /// The analysis method (default `band_peak`).
    pub method: AnalysisMethod,
    /// Keep the records' mean (default: removed, a DC offset).
    pub keep_dc: bool,
    /// The digitiser's full scale, in the records' unit: a sample at `±full_scale` is
    /// clipped (default: clipping detected as flat runs at a record's extremes).
    pub full_scale: Option<f64>,
}

/// The clipped samples of a record (an overranged scope): flat runs at its extremes, or
/// samples at the full scale given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clipping {
    /// Samples clipped (inside the gate).
    pub samples: usize,
    /// The level clipped at below, in the record's unit as read (NaN: none below).
    pub low: f64,
    /// The level clipped at above (NaN: none above).
    pub high: f64,
}

/// The per-record values of an analysis by name ([`RecordAnalysis::value`]): the
/// harmonics' amplitudes, the ratios and beta* (the keys of a 2D receiver's summary).
pub use crate::analysis::HARMONIC_KEYS;

/// The analysis of one record.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordAnalysis {
    /// Name of the record.
    pub name: String,
    /// Drive amplitude, if given.
    pub amplitude: Option<f64>,
    /// `A_n`, n = 1..5, in the record's unit (index 0 unused).
    pub harmonics: [f64; 6],
    /// The method's leakage floor of `A_n` (index 0 unused).
    pub leakage: [f64; 6],
    /// The noise floor of `A_n` (NaN: no samples outside the gate to measure it from).
    pub noise: [f64; 6],
    /// Harmonics 2..5 within a factor 10 of their floor (the larger of the two).
    pub near_floor: Vec<usize>,
    /// The record's mean that was removed, in its unit (0 with [`Settings::keep_dc`]).
    pub dc: f64,
    /// The factor the linear reference was scaled by (linear reference only).
    pub linear_scale: Option<f64>,
    /// The record's clipping, if any: its harmonics are then the clipping's.
    pub clipped: Option<Clipping>,
    /// The samples the noise floor was measured on, s (`[start, end)`: outside the gate,
    /// or the quiet part before the arrival); `None`: the noise floor is unknown.
    pub noise_window: Option<(f64, f64)>,
}

impl RecordAnalysis {
    /// The value of one of [`HARMONIC_KEYS`] (m/s or the signal's unit; ratios
    /// dimensionless, beta* in 1/(signal unit)); NaN for another key.
    pub fn value(&self, key: &str) -> f64 {
        match key {
            "A2_over_A1" => self.a2_over_a1(),
            "A3_over_A1" => self.a3_over_a1(),
            "beta_star" => self.beta_star(),
            k => k
                .strip_prefix('A')
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|n| (1..=5).contains(n))
                .map_or(f64::NAN, |n| self.harmonics[n]),
        }
    }

    /// `A2 / A1`.
    pub fn a2_over_a1(&self) -> f64 {
        self.harmonics[2] / self.harmonics[1]
    }
    /// `A3 / A1`.
    pub fn a3_over_a1(&self) -> f64 {
        self.harmonics[3] / self.harmonics[1]
    }
    /// `beta* = A2 / A1^2` (the inverse of the record's unit).
    pub fn beta_star(&self) -> f64 {
        self.harmonics[2] / (self.harmonics[1] * self.harmonics[1])
    }
    /// The floor of `A_n`: the larger of leakage and noise (NaN-free where one is known).
    pub fn floor(&self, n: usize) -> f64 {
        let (l, z) = (self.leakage[n], self.noise[n]);
        if z.is_nan() {
            l
        } else {
            l.max(z)
        }
    }
}

/// Least-squares fit `A2 = slope A1^2 + intercept` over a series (the relative
/// nonlinearity parameter is the slope).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesFit {
    /// Records fitted.
    pub count: usize,
    /// Slope, the inverse of the records' unit.
    pub slope: f64,
    /// Intercept, the records' unit.
    pub intercept: f64,
    /// Coefficient of determination (NaN for 2 records: a line through two points says
    /// nothing of the fit).
    pub r_squared: f64,
    /// 95% interval of the slope (Student t, `count - 2` degrees of freedom; NaN for 2
    /// records, which a line passes through exactly: no fit statistics).
    pub slope_interval: (f64, f64),
    /// 95% interval of the intercept.
    pub intercept_interval: (f64, f64),
}

/// The analysis of a series.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// Fundamental, Hz.
    pub f0: f64,
    /// Whether `f0` was detected (not given).
    pub f0_detected: bool,
    /// The records' spectral peak, Hz (what detection gives; NaN where there is none):
    /// a given `f0` far from it reads A1 in a band without the fundamental.
    pub peak: f64,
    /// Method.
    pub method: AnalysisMethod,
    /// Gate.
    pub gate: Option<Gate>,
    /// The digitiser's full scale given, in the records' unit.
    pub full_scale: Option<f64>,
    /// The window of `plateau_fit`, s (whole periods of f0 inside the gate's flat part).
    pub plateau: (f64, f64),
    /// Time step, s.
    pub dt: f64,
    /// Time of the first sample, s.
    pub t0: f64,
    /// Each record's analysis, in the series' order.
    pub records: Vec<RecordAnalysis>,
    /// The fit of A2 against A1^2 (two records or more).
    pub fit: Option<SeriesFit>,
}

/// Analyse `series` (`file` names it in errors).
pub fn analyze(series: &Series, settings: &Settings, file: &str) -> Result<Analysis> {
    let dt = series.dt;
    if !(dt > 0.0) || !dt.is_finite() {
        return Err(Error::invalid(file, "dt", dt, "must be > 0 s"));
    }
    let Some(first) = series.records.first() else {
        return Err(Error::invalid(
            file,
            "records",
            "none",
            "at least one record",
        ));
    };
    let n = first.samples.len();
    let duration = n as f64 * dt;
    let t0 = series.t0;
    if n < 16 {
        return Err(Error::invalid(
            file,
            &first.name,
            format!("{n} samples"),
            "at least 16 samples",
        ));
    }
    for r in &series.records {
        if r.samples.len() != n {
            return Err(Error::invalid(
                file,
                &r.name,
                format!("{} samples", r.samples.len()),
                format!(
                    "as many samples as {} ({n}): every record on one time base",
                    first.name
                ),
            ));
        }
        let companions = [("inverse", &r.inverse), ("linear", &r.linear)];
        for (what, c) in companions {
            if let Some(c) = c
                && c.len() != r.samples.len()
            {
                return Err(Error::invalid(
                    file,
                    format!("{}.{what}", r.name),
                    format!("{} samples", c.len()),
                    format!("as many samples as the record ({})", r.samples.len()),
                ));
            }
        }
        if r.samples.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                file,
                &r.name,
                "a non-finite sample",
                "finite samples",
            ));
        }
    }
    if let Some(g) = &settings.gate {
        let end = t0 + (n - 1) as f64 * dt;
        if !g.is_valid() || g.start < t0 - 0.5 * dt || g.end > end + 0.5 * dt {
            return Err(Error::invalid(
                file,
                "gate",
                format!("{:e}, {:e} (taper {:e})", g.start, g.end, g.taper),
                format!(
                    "start < end inside the record ({t0:e} .. {end:e} s), the taper at most half the gate"
                ),
            ));
        }
    }
    if let Some(fs) = settings.full_scale
        && !(fs > 0.0 && fs.is_finite())
    {
        return Err(Error::invalid(
            file,
            "full_scale",
            fs,
            "the digitiser's full scale, > 0 in the records' unit",
        ));
    }
    let method = settings.method;
    for r in &series.records {
        let missing = match method {
            AnalysisMethod::PulseInversion if r.inverse.is_none() => Some(
                "an opposite-polarity record for each record (--inverse; `inverse` in Python and in an identification's [records])",
            ),
            AnalysisMethod::LinearReference if r.linear.is_none() => Some(
                "a low-amplitude record as the linear reference (--linear; `linear` in Python and in an identification's [records])",
            ),
            AnalysisMethod::PlateauFit if settings.gate.is_none() => {
                Some("a gate over the echo's flat top (--gate START,END)")
            }
            _ => None,
        };
        if let Some(m) = missing {
            return Err(Error::invalid(
                file,
                "method",
                method.name(),
                format!("{} needs {m}", method.name()),
            ));
        }
        // a companion record the method does not read would be listed as an input
        // without being used
        let unused = if r.inverse.is_some() && method != AnalysisMethod::PulseInversion {
            Some(("inverse", "pulse_inversion"))
        } else if r.linear.is_some() && method != AnalysisMethod::LinearReference {
            Some(("linear", "linear_reference"))
        } else {
            None
        };
        if let Some((what, needs)) = unused {
            return Err(Error::invalid(
                file,
                what,
                format!("given with method {}", method.name()),
                format!("only with method {needs}, which reads it"),
            ));
        }
    }
    // the records without their mean
    let prepared: Vec<Prepared> = series
        .records
        .iter()
        .map(|r| Prepared::of(r, settings))
        .collect();
    // the fundamental
    // the fundamental is detected on the records without their mean, whatever keep_dc (a
    // kept DC offset's leakage would hide the peak, and the error would name an f0 the
    // user never gave)
    let detected = if settings.keep_dc {
        let centred: Vec<Prepared> = series
            .records
            .iter()
            .map(|r| {
                Prepared::of(
                    r,
                    &Settings {
                        keep_dc: false,
                        ..*settings
                    },
                )
            })
            .collect();
        detect_f0(&centred, settings.gate.as_ref(), t0, dt, file)
    } else {
        detect_f0(&prepared, settings.gate.as_ref(), t0, dt, file)
    };
    let peak = detected.as_ref().copied().unwrap_or(f64::NAN);
    let (f0, f0_detected) = match settings.f0 {
        Some(f) => {
            let nyquist = 0.5 / dt;
            if !(f > 0.0) || !(f < nyquist) {
                return Err(Error::invalid(
                    file,
                    "f0",
                    f,
                    format!("must be > 0 and below the Nyquist frequency {nyquist:e} Hz"),
                ));
            }
            (f, false)
        }
        None => (detected?, true),
    };
    let periods = duration * f0;
    if periods < 3.0 {
        return Err(Error::invalid(
            file,
            "f0",
            f0,
            format!(
                "at least 3 periods in the record ({periods:.2} here): a longer record or a higher f0"
            ),
        ));
    }
    if let Some(g) = &settings.gate {
        let periods = (g.end - g.start) * f0;
        if periods < 3.0 {
            return Err(Error::invalid(
                file,
                "gate",
                format!("{:e}, {:e}", g.start, g.end),
                format!(
                    "at least 3 periods of f0 = {f0:e} Hz inside the gate ({periods:.2} here): \
                     a longer gate"
                ),
            ));
        }
    }
    if 5.0 * f0 > 0.5 / dt {
        return Err(Error::invalid(
            file,
            "f0",
            f0,
            format!(
                "5 f0 below the Nyquist frequency {:e} Hz (the record is sampled too slowly for A5)",
                0.5 / dt
            ),
        ));
    }
    let plateau = plateau_window(settings.gate.as_ref(), f0, t0, duration);
    if method == AnalysisMethod::PlateauFit
        && let Some(g) = &settings.gate
    {
        // the fit needs whole periods inside the gate's flat part (between its ramps)
        let flat = (g.end - g.taper) - (g.start + g.taper);
        if flat * f0 < 1.0 {
            return Err(Error::invalid(
                file,
                "gate",
                format!("{:e}, {:e}, {:e}", g.start, g.end, g.taper),
                format!(
                    "plateau_fit fits whole periods of f0 inside the gate's flat part, between \
                     its ramps: this one leaves {flat:e} s, {:.2} periods of f0 = {f0:e} Hz \
                     (a shorter taper, or a longer gate over the echo's flat top)",
                    (flat * f0).max(0.0)
                ),
            ));
        }
    }
    let sig = Signal {
        quantity: Quantity::Samples,
        dt,
        t0,
        f0,
        f2: None,
        plateau,
    };
    let gate = settings.gate.as_ref();
    let records = series
        .records
        .iter()
        .zip(&prepared)
        .map(|(r, p)| {
            let mut linear_scale = None;
            let linear = p.linear.as_ref().map(|l| {
                let k = scale_onto(&p.samples, l, gate, t0, dt);
                linear_scale = Some(k);
                l.iter().map(|v| k * v).collect::<Vec<f64>>()
            });
            let h = gated_bands(
                method,
                gate,
                &sig,
                &p.samples,
                p.inverse.as_deref(),
                linear.as_deref(),
            )
            .unwrap_or_default()
            .harmonic;
            // plateau fit over whole periods has no leakage (its floor is the noise's);
            // otherwise the floor is what the method reads at n f0 from the record's
            // fundamental alone (band-limited before the gate, so that the gate's edges
            // spread it as they spread the record)
            let leakage = leakage_floor(method, &p.samples, gate, &sig);
            // a linear reference is scaled onto the record before it is subtracted: its
            // noise, scaled alike, adds to the record's
            let window = noise_window(&p.samples, gate, &sig);
            let mut noise = noise_floor(&p.samples, window, gate, &sig);
            if let Some(l) = &linear {
                let reference = noise_floor(l, window, gate, &sig);
                for (a, b) in noise.iter_mut().zip(reference) {
                    *a = a.hypot(b);
                }
            }
            let mut a = RecordAnalysis {
                name: r.name.clone(),
                amplitude: r.amplitude,
                harmonics: h,
                leakage,
                noise,
                near_floor: Vec::new(),
                dc: p.dc,
                linear_scale,
                clipped: clipping(&r.samples, gate, &sig, settings.full_scale),
                noise_window: window.map(|(a, b)| (t0 + a as f64 * dt, t0 + b as f64 * dt)),
            };
            a.near_floor = (2..=5)
                .filter(|&k| {
                    let f = a.floor(k);
                    f > 0.0 && a.harmonics[k] < 10.0 * f
                })
                .collect();
            a
        })
        .collect::<Vec<_>>();
    if let Some(r) = records.iter().find(|r| !(r.harmonics[1] > 0.0)) {
        return Err(Error::invalid(
            file,
            &r.name,
            format!("A1 = {:e} at f0 = {f0:e} Hz", r.harmonics[1]),
            "a record with content at f0 (with pulse inversion, an opposite-polarity record \
             that is not the record itself)",
        ));
    }
    let fit = fit_series(&records);
    Ok(Analysis {
        f0,
        f0_detected,
        peak,
        method,
        gate: settings.gate,
        full_scale: settings.full_scale,
        plateau,
        dt,
        t0,
        records,
        fit,
    })
}

/// A record and its companions, their means removed.
struct Prepared {
    samples: Vec<f64>,
    inverse: Option<Vec<f64>>,
    linear: Option<Vec<f64>>,
    dc: f64,
}

impl Prepared {
    fn of(r: &Measured, s: &Settings) -> Prepared {
        let strip = |x: &[f64]| -> (Vec<f64>, f64) {
            if s.keep_dc {
                return (x.to_vec(), 0.0);
            }
            let m = x.iter().sum::<f64>() / x.len().max(1) as f64;
            (x.iter().map(|v| v - m).collect(), m)
        };
        let (samples, dc) = strip(&r.samples);
        Prepared {
            samples,
            inverse: r.inverse.as_deref().map(|x| strip(x).0),
            linear: r.linear.as_deref().map(|x| strip(x).0),
            dc,
        }
    }
}

/// The fundamental of the largest gated record: its spectrum's peak above two bins (Hz).
fn detect_f0(
    records: &[Prepared],
    gate: Option<&Gate>,
    t0: f64,
    dt: f64,
    file: &str,
) -> Result<f64> {
    let energy = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>();
    let largest = records
        .iter()
        .max_by(|a, b| energy(&a.samples).total_cmp(&energy(&b.samples)))
        .map(|p| p.samples.clone())
        .unwrap_or_default();
    let mut x = largest;
    if let Some(g) = gate {
        // a Hann window over the gate (ramps half its length), whatever its own taper: a
        // rectangular window's leakage (the negative frequency's sidelobes) moves the
        // peak by a thousandth
        let hann = Gate {
            taper: 0.5 * (g.end - g.start),
            ..*g
        };
        hann.apply(&mut x, t0, dt);
    }
    let nyquist = 0.5 / dt;
    let spec = with_analyzer(|a| a.spectrum(&x, dt, nyquist));
    let df = spec.frequency.get(1).copied().unwrap_or(f64::NAN);
    let (f, peak) = spectral_peak(&spec.magnitude, df, 2.0 * df, nyquist);
    if !(f > 0.0) || !(peak > 0.0) {
        return Err(Error::invalid(
            file,
            "f0",
            "not detected",
            "a record with a spectral peak (or give the fundamental with --f0 HZ)",
        ));
    }
    Ok(refine_peak(&x, dt, f, df))
}

/// The frequency within half a bin `df` of `f` (Hz) where the Fourier transform of `x`
/// (time step `dt`) peaks, by golden-section search: the parabola through three bins is
/// off by up to a tenth of a bin under a rectangular gate, which a fit over many periods
/// (`plateau_fit`) turns into percent errors in A2.
fn refine_peak(x: &[f64], dt: f64, f: f64, df: f64) -> f64 {
    // the samples the gate kept
    let (Some(a), Some(b)) = (
        x.iter().position(|v| *v != 0.0),
        x.iter().rposition(|v| *v != 0.0),
    ) else {
        return f;
    };
    let x = &x[a..=b];
    let magnitude = |f: f64| {
        let (s, c) = (2.0 * std::f64::consts::PI * f * dt).sin_cos();
        // the phasor e^{-i w k} by rotation, the sums in one pass
        let (mut pr, mut pi, mut re, mut im) = (1.0f64, 0.0f64, 0.0, 0.0);
        for v in x {
            re += v * pr;
            im += v * pi;
            (pr, pi) = (pr * c + pi * s, pi * c - pr * s);
        }
        re.hypot(im)
    };
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (f - 0.5 * df, f + 0.5 * df);
    let (mut p, mut q) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
    let (mut mp, mut mq) = (magnitude(p), magnitude(q));
    for _ in 0..40 {
        if mp > mq {
            hi = q;
            (q, mq) = (p, mp);
            p = hi - ratio * (hi - lo);
            mp = magnitude(p);
        } else {
            lo = p;
            (p, mp) = (q, mq);
            q = lo + ratio * (hi - lo);
            mq = magnitude(q);
        }
    }
    0.5 * (lo + hi)
}

/// Whole periods of `f0` inside the gate's flat part (the whole record without a gate).
fn plateau_window(gate: Option<&Gate>, f0: f64, t0: f64, duration: f64) -> (f64, f64) {
    match gate {
        Some(g) => {
            let (a, b) = (g.start + g.taper, g.end - g.taper);
            let periods = ((b - a) * f0).floor().max(1.0);
            (a, a + periods / f0)
        }
        None => (t0, t0 + duration),
    }
}

/// The least-squares factor `k` that makes `k l` closest to `x` over the gate.
fn scale_onto(x: &[f64], l: &[f64], gate: Option<&Gate>, t0: f64, dt: f64) -> f64 {
    let (mut xl, mut ll) = (0.0, 0.0);
    for (k, (a, b)) in x.iter().zip(l).enumerate() {
        let w = gate.map_or(1.0, |g| g.weight(t0 + k as f64 * dt));
        xl += w * w * a * b;
        ll += w * w * b * b;
    }
    if ll > 0.0 {
        xl / ll
    } else {
        0.0
    }
}

/// The samples `[a, b)` of `x` that hold noise alone: with a gate, the longer side of the
/// record outside it (at least a quarter of the gate's samples); without one, the quiet
/// part before the arrival ([`quiet_part`]). `None`: none to measure the noise on.
fn noise_window(x: &[f64], gate: Option<&Gate>, s: &Signal) -> Option<(usize, usize)> {
    let n = x.len();
    match gate {
        Some(g) => {
            let idx = |t: f64| (((t - s.t0) / s.dt).round().max(0.0) as usize).min(n);
            let (a, b) = (idx(g.start), idx(g.end));
            let (before, after) = (a, n - b.min(n));
            let (w, len) = if before >= after {
                ((0, a), before)
            } else {
                ((b.min(n), n), after)
            };
            let gated = b.saturating_sub(a);
            (len > 0 && gated > 0 && 4 * len >= gated).then_some(w)
        }
        None => quiet_part(x, s.f0, s.dt).map(|b| (0, b)),
    }
}

/// The end (exclusive sample index) of a record's quiet part before the arrival: the
/// arrival is the first sample where the largest magnitude over the past period of `f0`
/// reaches a tenth of the record's peak, and the quiet part ends two periods before it
/// (the rise of a burst below a tenth of its peak kept out). `None` when that leaves fewer
/// than two periods or 16 samples: the noise cannot be measured without a gate.
pub fn quiet_part(x: &[f64], f0: f64, dt: f64) -> Option<usize> {
    let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let period = (1.0 / (f0 * dt)).round().max(1.0) as usize;
    if !(peak > 0.0) {
        return None;
    }
    let arrival = x.iter().position(|v| v.abs() >= 0.1 * peak)?;
    let end = arrival.checked_sub(2 * period)?;
    (end >= 2 * period && end >= 16).then_some(end)
}

/// The band-peak amplitudes of noise alone: the samples `window` of `x`
/// ([`noise_window`]) repeated to fill the gate (the whole record without one) and placed
/// in it (NaN without a window).
fn noise_floor(
    x: &[f64],
    window: Option<(usize, usize)>,
    gate: Option<&Gate>,
    s: &Signal,
) -> [f64; 6] {
    let Some((wa, wb)) = window else {
        return [f64::NAN; 6];
    };
    let noise = &x[wa..wb];
    let n = x.len();
    let (a, b) = match gate {
        Some(g) => {
            let idx = |t: f64| (((t - s.t0) / s.dt).round().max(0.0) as usize).min(n);
            (idx(g.start), idx(g.end))
        }
        None => (0, n),
    };
    let mut rec = vec![0.0; n];
    for (k, v) in rec[a..b].iter_mut().enumerate() {
        *v = noise[k % noise.len()];
    }
    if let Some(g) = gate {
        g.apply(&mut rec, s.t0, s.dt);
    }
    with_analyzer(|an| an.point_bands(&rec, s.dt, s.f0, None)).harmonic
}

/// The levels of a clipping as text (`at -0.6 and 0.6`, `at 0.6`), in the record's unit.
pub fn clip_levels(c: &Clipping) -> String {
    let v: Vec<String> = [c.low, c.high]
        .iter()
        .filter(|v| v.is_finite())
        .map(|v| {
            if (1e-3..1e4).contains(&v.abs()) {
                format!("{v}")
            } else {
                format!("{v:e}")
            }
        })
        .collect();
    format!("at {}", v.join(" and "))
}

/// The clipping of record `x` (as read, its mean kept) inside the gate: the samples at
/// `±full_scale` when it is given; otherwise the samples in runs at the record's maximum
/// (or minimum) longer than an unclipped crest stays there. A crest of amplitude `A`
/// sampled `P` times a period stays within one quantisation step `q` of its top for about
/// `P sqrt(2 q / A) / pi` samples (`q` the smallest step between the record's distinct
/// values): a run of 3 samples or more, and more than twice that, is a clip.
pub fn clipping(
    x: &[f64],
    gate: Option<&Gate>,
    s: &Signal,
    full_scale: Option<f64>,
) -> Option<Clipping> {
    let inside = |k: usize| gate.is_none_or(|g| g.weight(s.t0 + k as f64 * s.dt) > 0.0);
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    let range = hi - lo;
    if !(range > 0.0) {
        return None;
    }
    let (mut samples, mut low, mut high) = (0usize, f64::NAN, f64::NAN);
    if let Some(fs) = full_scale {
        let at = fs * (1.0 - 1e-9);
        for (k, &v) in x.iter().enumerate() {
            if inside(k) && v.abs() >= at {
                samples += 1;
                if v > 0.0 {
                    high = fs;
                } else {
                    low = -fs;
                }
            }
        }
    } else {
        // the quantisation step: the smallest gap between distinct values
        let mut sorted: Vec<f64> = x.to_vec();
        sorted.sort_by(f64::total_cmp);
        let q = sorted
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|d| *d > 1e-12 * range)
            .fold(f64::INFINITY, f64::min)
            .min(range);
        let period = 1.0 / (s.f0 * s.dt);
        let natural = period * (2.0 * q / (0.5 * range)).sqrt() / std::f64::consts::PI;
        let longest = (2.0 * natural).max(2.0);
        let tol = 1e-12 * range;
        for (level, slot) in [(hi, &mut high), (lo, &mut low)] {
            let mut run = 0usize;
            let flush = |run: usize, slot: &mut f64, samples: &mut usize| {
                if run as f64 > longest {
                    *samples += run;
                    *slot = level;
                }
            };
            for (k, &v) in x.iter().enumerate() {
                if inside(k) && (v - level).abs() <= tol {
                    run += 1;
                } else {
                    flush(run, slot, &mut samples);
                    run = 0;
                }
            }
            flush(run, slot, &mut samples);
        }
    }
    (samples > 0).then_some(Clipping { samples, low, high })
}

/// The fit of A2 against A1^2 over the records (`None` for fewer than two).
fn fit_series(records: &[RecordAnalysis]) -> Option<SeriesFit> {
    let pts: Vec<(f64, f64)> = records
        .iter()
        .map(|r| (r.harmonics[1] * r.harmonics[1], r.harmonics[2]))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let m = pts.len();
    if m < 2 {
        return None;
    }
    let mf = m as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / mf;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / mf;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    if !(sxx > 0.0) {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let sse: f64 = pts
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    // two points fix a line: R^2 = 1 and no interval say nothing of the fit
    let r_squared = if m < 3 {
        f64::NAN
    } else if syy > 0.0 {
        1.0 - sse / syy
    } else {
        1.0
    };
    let nan = (f64::NAN, f64::NAN);
    let (slope_interval, intercept_interval) = if m > 2 {
        let dof = m - 2;
        let t = match dof {
            1 => 12.706205,
            2 => 4.302653,
            d => t975(d),
        };
        let s2 = sse / dof as f64;
        let se_slope = (s2 / sxx).sqrt();
        let se_int = (s2 * (1.0 / mf + mx * mx / sxx)).sqrt();
        (
            (slope - t * se_slope, slope + t * se_slope),
            (intercept - t * se_int, intercept + t * se_int),
        )
    } else {
        (nan, nan)
    };
    Some(SeriesFit {
        count: m,
        slope,
        intercept,
        r_squared,
        slope_interval,
        intercept_interval,
    })
}
