//! Windowed sinusoidal tone burst (thesis Figure 20, chapter 3 "smooth rectangular"
//! window; chapter 5 half-Hann ramps each covering 1/4 of the burst).

use super::{grid_by_steps, numeric_peak, Excitation};
use multiversion::multiversion;

/// Burst window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Window {
    /// Flat top with half-Hann ramps, each covering `ramp_fraction` of the burst.
    HannRamps {
        /// Fraction of the burst per ramp, in (0, 0.5].
        ramp_fraction: f64,
    },
    /// Full Hann window.
    Hann,
    /// No window.
    Rectangular,
}

impl Window {
    /// Window value at normalised time `s = t / duration` in [0, 1].
    pub fn value(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        match *self {
            Window::Rectangular => 1.0,
            Window::Hann => 0.5 * (1.0 - (2.0 * std::f64::consts::PI * s).cos()),
            Window::HannRamps { ramp_fraction: r } => {
                if s < r {
                    0.5 * (1.0 - (std::f64::consts::PI * s / r).cos())
                } else if s > 1.0 - r {
                    0.5 * (1.0 - (std::f64::consts::PI * (1.0 - s) / r).cos())
                } else {
                    1.0
                }
            }
        }
    }

    /// The window on the piece of [0, 1] that holds `s`, as `0.5 (1 - cos(k s + phi))`
    /// (`Some((k, phi))`), or `None` where it is 1 (flat top, rectangular).
    fn hann_piece(&self, s: f64) -> Option<(f64, f64)> {
        use std::f64::consts::PI;
        match *self {
            Window::Rectangular => None,
            Window::Hann => Some((2.0 * PI, 0.0)),
            Window::HannRamps { ramp_fraction: r } => {
                if s < r {
                    Some((PI / r, 0.0))
                } else if s > 1.0 - r {
                    // cos(pi (1 - s) / r) = cos(pi s / r - pi / r)
                    Some((PI / r, -PI / r))
                } else {
                    None
                }
            }
        }
    }

    /// The window as numbers: a tag (0 Hann ramps, 1 Hann, 2 rectangular) and its ramp
    /// fraction (0 without ramps).
    pub(crate) fn tag(&self) -> (u64, f64) {
        match *self {
            Window::HannRamps { ramp_fraction } => (0, ramp_fraction),
            Window::Hann => (1, 0.0),
            Window::Rectangular => (2, 0.0),
        }
    }

    /// Whether normalised times `a <= b` lie on the same smooth piece of the window.
    fn same_piece(&self, a: f64, b: f64) -> bool {
        match *self {
            Window::HannRamps { ramp_fraction: r } => {
                let piece = |s: f64| (s >= r) as u8 + (s > 1.0 - r) as u8;
                piece(a) == piece(b)
            }
            _ => true,
        }
    }

    fn joints(&self) -> Vec<f64> {
        match *self {
            Window::HannRamps { ramp_fraction: r } => vec![r, 1.0 - r],
            _ => vec![],
        }
    }
}

/// `s_inc(t) = -A / n * window(t/D) * sin(2 pi f0 t)`, `D = cycles / f0`, where the
/// normalisation `n` makes the peak of |s_inc| exactly `A`.
#[derive(Debug, Clone)]
pub struct ToneBurst {
    amplitude: f64,
    frequency: f64,
    duration: f64,
    window: Window,
    norm: f64,
    /// `amplitude / norm`, Pa (computed once: the same value `stress` computed per call).
    scale: f64,
    /// `2 pi frequency`, rad/s.
    omega: f64,
}

impl ToneBurst {
    /// A burst of `cycles` cycles at `frequency` (Hz) whose |stress| peaks at `amplitude` (Pa).
    pub fn new(amplitude: f64, frequency: f64, cycles: f64, window: Window) -> Self {
        let duration = cycles / frequency;
        let mut b = ToneBurst {
            amplitude,
            frequency,
            duration,
            window,
            norm: 1.0,
            scale: amplitude,
            omega: 2.0 * std::f64::consts::PI * frequency,
        };
        let n = ((cycles * 64.0) as usize).clamp(256, 1 << 20);
        b.norm = numeric_peak(|t| b.raw(t), duration, n).max(1e-300);
        b.scale = b.amplitude / b.norm;
        b
    }

    /// The same burst with peak `amplitude` (Pa): identical to [`ToneBurst::new`] with
    /// that amplitude, without recomputing the window's normalisation (a sweep over the
    /// amplitude or `xi` builds its bursts from one).
    pub fn with_amplitude(&self, amplitude: f64) -> Self {
        ToneBurst {
            amplitude,
            scale: amplitude / self.norm,
            ..self.clone()
        }
    }

    #[inline]
    fn raw(&self, t: f64) -> f64 {
        -self.window.value(t / self.duration) * (self.omega * t).sin()
    }
}

impl Excitation for ToneBurst {
    #[inline]
    fn stress(&self, t: f64) -> f64 {
        if t < 0.0 || t > self.duration {
            return 0.0;
        }
        self.scale * self.raw(t)
    }
    /// One `sin_cos` of the carrier (and one of the window's ramp) at the step start `t`,
    /// then angle addition to each node with the sine and cosine of the small node offsets
    /// by their Taylor series; each node by [`ToneBurst::stress`] where the step leaves the
    /// burst, crosses a window joint, or is longer than 1/60 of a period.
    fn stress_nodes(&self, t: f64, h: f64, c: &[f64], out: &mut [f64]) {
        let d = self.duration;
        let (sa, sb) = (t / d, (t + h) / d);
        if !(t >= 0.0 && t + h <= d && h >= 0.0)
            || self.omega * h > SMALL_ANGLE
            || !self.window.same_piece(sa, sb)
        {
            for (o, ci) in out.iter_mut().zip(c) {
                *o = self.stress(t + ci * h);
            }
            return;
        }
        let (s0, c0) = (self.omega * t).sin_cos();
        let wh = self.omega * h;
        match self.window.hann_piece(sa) {
            None => {
                for (o, ci) in out.iter_mut().zip(c) {
                    let (sd, cd) = small_sin_cos(wh * ci);
                    *o = self.scale * -(s0 * cd + c0 * sd);
                }
            }
            Some((k, phi)) => {
                // window phase k s + phi, s = t / d
                let (ws0, wc0) = (k * sa + phi).sin_cos();
                let kh = k * h / d;
                for (o, ci) in out.iter_mut().zip(c) {
                    let (sd, cd) = small_sin_cos(wh * ci);
                    let (wsd, wcd) = small_sin_cos(kh * ci);
                    let w = 0.5 * (1.0 - (wc0 * wcd - ws0 * wsd));
                    *o = self.scale * -(w * (s0 * cd + c0 * sd));
                }
            }
        }
    }
    /// Block by block of up to `GRID_BLOCK` steps on one window piece: one exact `sin_cos`
    /// of the carrier (and one of the window's ramp) at the block's first step, then each node of each step by
    /// angle addition with the rotation from the block start to the node, tabulated once
    /// per call (`j` steps by angle addition of exact `sin_cos` of `16 a` and `b < 16`
    /// steps, plus the node's small offset). No recurrence: every value is a few roundings
    /// from exact, and the node loops over a block vectorise. A step that leaves the burst
    /// or crosses a window joint is evaluated by [`Excitation::stress_nodes`].
    fn stress_grid(&self, h: f64, c: &[f64], steps: usize, out: &mut [f64]) {
        let m = c.len();
        let d = self.duration;
        let wh = self.omega * h;
        let out = &mut out[..steps * m];
        if !(h > 0.0) || !(wh <= SMALL_ANGLE) || m > GRID_NODES_MAX {
            grid_by_steps(self, h, c, steps, out);
            return;
        }
        // window phase per step (the same on both ramps of a window)
        let kw = self.window.hann_piece(0.0).map_or(0.0, |(k, _)| k);
        let kh = kw * h / d;
        // rotations from a block's first step to node i of its step j: (sin, cos) of the
        // carrier angle (j + c_i) omega h and of the window angle (j + c_i) kw h / d
        let mut rot = [[[0.0f64; GRID_BLOCK]; 4]; GRID_NODES_MAX];
        // (sin, cos) of j steps, j = 16 a + b, by angle addition from exact values of
        // 16 a and of b steps
        let coarse: [[f64; 4]; GRID_BLOCK / 16] = std::array::from_fn(|a| {
            let (s, c) = ((16 * a) as f64 * wh).sin_cos();
            let (ws, wc) = ((16 * a) as f64 * kh).sin_cos();
            [s, c, ws, wc]
        });
        let fine: [[f64; 4]; 16] = std::array::from_fn(|b| {
            let (s, c) = (b as f64 * wh).sin_cos();
            let (ws, wc) = (b as f64 * kh).sin_cos();
            [s, c, ws, wc]
        });
        let steps_sc: [[f64; 4]; GRID_BLOCK] = std::array::from_fn(|j| {
            let ([s1, c1, ws1, wc1], [s2, c2, ws2, wc2]) = (coarse[j / 16], fine[j % 16]);
            [
                s1 * c2 + c1 * s2,
                c1 * c2 - s1 * s2,
                ws1 * wc2 + wc1 * ws2,
                wc1 * wc2 - ws1 * ws2,
            ]
        });
        for (r, ci) in rot.iter_mut().zip(c) {
            let (sd, cd) = small_sin_cos(wh * ci);
            let (wsd, wcd) = small_sin_cos(kh * ci);
            for (j, sc) in steps_sc.iter().enumerate() {
                let [s, c, ws, wc] = *sc;
                r[0][j] = s * cd + c * sd;
                r[1][j] = c * cd - s * sd;
                r[2][j] = ws * wcd + wc * wsd;
                r[3][j] = wc * wcd - ws * wsd;
            }
        }
        let inv_d = 1.0 / d;
        let scale = self.scale;
        let mut v = [0.0; GRID_NODES_MAX];
        let mut k0 = 0;
        while k0 < steps {
            let ta0 = k0 as f64 * h;
            let sa0 = ta0 * inv_d;
            // the block: up to GRID_BLOCK steps inside the burst on the piece of its start
            let inside = |k: usize| {
                let tb = (k + 1) as f64 * h;
                tb <= d && self.window.same_piece(sa0, tb * inv_d)
            };
            let mut nb = GRID_BLOCK.min(steps - k0);
            if !inside(k0 + nb - 1) {
                nb = (0..nb).take_while(|&j| inside(k0 + j)).count();
            }
            if nb == 0 {
                // a step that leaves the burst or crosses a joint: directly
                let (ta, tb) = (ta0, (k0 + 1) as f64 * h);
                self.stress_nodes(ta, tb - ta, c, &mut v[..m]);
                for (i, vi) in v[..m].iter().enumerate() {
                    out[i * steps + k0] = *vi;
                }
                k0 += 1;
                continue;
            }
            let (s0, c0) = (self.omega * ta0).sin_cos();
            let window = self
                .window
                .hann_piece(sa0)
                .map(|(kp, phi)| (kp * sa0 + phi).sin_cos());
            for (i, r) in rot.iter().take(m).enumerate() {
                let row = &mut out[i * steps + k0..i * steps + k0 + nb];
                block_row(row, r, [s0, c0], window, scale);
            }
            k0 += nb;
        }
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn fundamental(&self) -> f64 {
        self.frequency
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut v = vec![0.0, self.duration];
        v.extend(self.window.joints().into_iter().map(|s| s * self.duration));
        v
    }
    fn peak(&self) -> f64 {
        self.amplitude
    }
    /// `A / n`, the carrier's angular frequency, the duration and the window: what
    /// [`ToneBurst::stress`] and the grid compute from.
    fn grid_key(&self) -> Option<Vec<u64>> {
        let (tag, ramp) = self.window.tag();
        Some(vec![
            1,
            self.scale.to_bits(),
            self.omega.to_bits(),
            self.duration.to_bits(),
            tag,
            ramp.to_bits(),
        ])
    }
    /// Frequency, duration, window and normalisation (none depends on the amplitude).
    fn unit_shape(&self) -> Option<super::UnitShape> {
        let (tag, ramp) = self.window.tag();
        Some(super::UnitShape {
            key: vec![
                1,
                self.frequency.to_bits(),
                self.duration.to_bits(),
                self.norm.to_bits(),
                tag,
                ramp.to_bits(),
            ],
            unit: std::sync::Arc::new(self.with_amplitude(1.0)),
        })
    }
}

/// One node's row of a block of [`ToneBurst::stress_grid`]: the stress (Pa) at the
/// carrier angle of the block start (`[sin, cos]`) rotated by `r`'s carrier rotations
/// (`r[0]`, `r[1]`: sin, cos), times the window `0.5 (1 - cos)` of the window angle
/// (`window`: its sin and cos at the block start, rotated by `r[2]`, `r[3]`; `None`: 1).
#[multiversion(targets("x86_64+avx+avx2"))]
fn block_row(
    row: &mut [f64],
    r: &[[f64; GRID_BLOCK]; 4],
    [s0, c0]: [f64; 2],
    window: Option<(f64, f64)>,
    scale: f64,
) {
    let [rs, rc, rws, rwc] = r;
    match window {
        None => {
            for ((x, rs), rc) in row.iter_mut().zip(rs).zip(rc) {
                *x = scale * -(s0 * rc + c0 * rs);
            }
        }
        Some((ws0, wc0)) => {
            for (j, x) in row.iter_mut().enumerate() {
                let w = 0.5 * (1.0 - (wc0 * rwc[j] - ws0 * rws[j]));
                *x = scale * -(w * (s0 * rc[j] + c0 * rs[j]));
            }
        }
    }
}

/// Largest step phase (rad) that [`ToneBurst::stress_nodes`] steps by angle addition.
const SMALL_ANGLE: f64 = 0.11;

/// Steps per block of [`ToneBurst::stress_grid`] (one exact `sin_cos` of the carrier
/// per block).
const GRID_BLOCK: usize = 128;

/// Most nodes per step that [`ToneBurst::stress_grid`] tabulates block by block (more:
/// step by step).
const GRID_NODES_MAX: usize = 8;

/// `(sin x, cos x)` for `|x| <= SMALL_ANGLE` by their Taylor series (the first omitted
/// terms, `x^15 / 15!` and `x^14 / 14!`, are below 1e-26).
#[inline]
fn small_sin_cos(x: f64) -> (f64, f64) {
    // 1 / n! for the series, Horner in x^2
    const S: [f64; 6] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
    ];
    const C: [f64; 6] = [
        -0.5,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
    ];
    let x2 = x * x;
    let ps = S[0] + x2 * (S[1] + x2 * (S[2] + x2 * (S[3] + x2 * (S[4] + x2 * S[5]))));
    let pc = C[0] + x2 * (C[1] + x2 * (C[2] + x2 * (C[3] + x2 * (C[4] + x2 * C[5]))));
    (x + x * x2 * ps, 1.0 + x2 * pc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 15-cycle, 2 MPa, 1 MHz burst in each window.
    fn bursts() -> impl Iterator<Item = (Window, ToneBurst)> {
        [
            Window::HannRamps {
                ramp_fraction: 0.25,
            },
            Window::Hann,
            Window::Rectangular,
        ]
        .into_iter()
        .map(|w| (w, ToneBurst::new(2.0e6, 1e6, 15.0, w)))
    }

    #[test]
    fn step_nodes_match_direct_evaluation() {
        // the nodes of steps in the ramps, on the flat top, across the joints and the
        // ends agree with the direct evaluation to round-off of the peak
        let c = [0.0, 0.155, 0.5, 0.644, 1.0];
        for (w, b) in bursts() {
            for h in [5e-9, 1e-7 / 3.0, 1e-6] {
                let mut t = -2.0 * h;
                while t < 15e-6 + 2.0 * h {
                    let mut out = [0.0; 5];
                    b.stress_nodes(t, h, &c, &mut out);
                    for (ci, o) in c.iter().zip(out) {
                        let direct = b.stress(t + ci * h);
                        assert!((o - direct).abs() <= 1e-12 * 2.0e6, "{w:?} {t} {h} {ci}");
                    }
                    t += 0.37 * h;
                }
            }
        }
        // the small-angle series against libm
        for i in 0..=100 {
            let x = SMALL_ANGLE * (i as f64 / 50.0 - 1.0);
            let (s, c) = small_sin_cos(x);
            assert!(
                (s - x.sin()).abs() <= 2e-17 && (c - x.cos()).abs() <= 2.3e-16,
                "{x}"
            );
        }
    }
    #[test]
    fn grid_nodes_match_direct_evaluation() {
        // the tabulated nodes of every grid step (ramps, flat top, joints, the end of the
        // burst and beyond) agree with the direct evaluation to round-off of the peak, also
        // after hundreds of rotations and through the default (per step) path
        let c = [0.0, 0.155, 0.5, 0.644, 1.0];
        for (w, b) in bursts() {
            for h in [5e-9, 1e-7 / 3.0, 1e-6] {
                let steps = (17e-6 / h) as usize;
                let mut out = vec![f64::NAN; steps * c.len()];
                b.stress_grid(h, &c, steps, &mut out);
                for k in 0..steps {
                    let (ta, tb) = (k as f64 * h, (k + 1) as f64 * h);
                    for (i, ci) in c.iter().enumerate() {
                        let direct = b.stress(ta + ci * (tb - ta));
                        let o = out[i * steps + k];
                        assert!((o - direct).abs() <= 1e-12 * 2.0e6, "{w:?} {h} {k} {ci}");
                    }
                }
            }
        }
    }
    #[test]
    fn with_amplitude_is_new_with_that_amplitude() {
        let w = Window::HannRamps {
            ramp_fraction: 0.25,
        };
        let a = ToneBurst::new(1.0, 1e6, 15.0, w).with_amplitude(3.5e5);
        let b = ToneBurst::new(3.5e5, 1e6, 15.0, w);
        assert_eq!(a.peak(), 3.5e5);
        for k in 0..1000 {
            let t = k as f64 * 1.6e-8;
            assert_eq!(a.stress(t).to_bits(), b.stress(t).to_bits(), "{t}");
        }
    }
    #[test]
    fn starts_compressive_and_peaks_at_amplitude() {
        for (w, b) in bursts() {
            assert!(b.stress(0.1e-6) <= 0.0);
            let peak = (0..100_000)
                .map(|i| b.stress(i as f64 * 15e-6 / 100_000.0).abs())
                .fold(0.0f64, f64::max);
            assert!((peak - 2.0e6).abs() < 1e-6 * 2.0e6, "{w:?} {peak}");
        }
    }
}
