//! Incident waves: `s_inc(t)`, the dynamic stress the incident wave alone would have at the
//! interface, t = 0 when its front arrives (model.md section 2). A tone burst starts with
//! its compressive half-cycle: `s_inc = -A window(t) sin(2 pi f0 t)`.

mod delayed;
mod file;
mod scaled;
mod tone_burst;
mod two_tone;

pub use delayed::Delayed;
pub use file::FileWaveform;
pub use scaled::Scaled;
pub use tone_burst::{ToneBurst, Window};
pub use two_tone::TwoTone;

use std::fmt::Debug;
use std::sync::Arc;

/// A waveform apart from its amplitude ([`Excitation::unit_shape`]): the waveform at unit
/// peak, and a key of its shape. Equal keys give the same unit waveform, bit for bit,
/// whatever the amplitudes of the waveforms they came from.
#[derive(Debug, Clone)]
pub struct UnitShape {
    /// Identifies the shape (numbers as bits, each kind of waveform tagged).
    pub key: Vec<u64>,
    /// The waveform with `peak() == 1` Pa.
    pub unit: Arc<dyn Excitation>,
}

/// [`Excitation::stress_grid`] step by step through [`Excitation::stress_nodes`].
pub(crate) fn grid_by_steps<E: Excitation + ?Sized>(
    e: &E,
    h: f64,
    c: &[f64],
    steps: usize,
    out: &mut [f64],
) {
    let mut v = [0.0; 16];
    for k in 0..steps {
        let (ta, tb) = (k as f64 * h, (k + 1) as f64 * h);
        for (ci, i) in c.chunks(16).zip((0..).step_by(16)) {
            e.stress_nodes(ta, tb - ta, ci, &mut v[..ci.len()]);
            for (j, vj) in v[..ci.len()].iter().enumerate() {
                out[(i + j) * steps + k] = *vj;
            }
        }
    }
}

/// The largest signal amplitude a scenario takes (Pa, or N/m for a 2D point force): a
/// thousand times the strength of any solid, and far from double precision's overflow in
/// the energies (squares of the fields).
pub const MAX_AMPLITUDE: f64 = 1e12;

/// An incident stress waveform.
pub trait Excitation: Debug + Send + Sync {
    /// Incident stress at the interface `s_inc(t)`, Pa (tension positive); 0 outside
    /// `[0, duration]`.
    fn stress(&self, t: f64) -> f64;
    /// Incident stress at the nodes `t + c[i] h` of one solver step, Pa, written to
    /// `out[i]` (`t`, `h` in s; `c` in [0, 1]; `out` at least as long as `c`). The same
    /// values as [`Excitation::stress`] at those times up to round-off (a tone burst
    /// evaluates its transcendental functions once per step and steps to the nodes by
    /// angle addition).
    fn stress_nodes(&self, t: f64, h: f64, c: &[f64], out: &mut [f64]) {
        for (o, ci) in out.iter_mut().zip(c) {
            *o = self.stress(t + ci * h);
        }
    }
    /// Incident stress at the nodes of `steps` consecutive steps of the uniform grid
    /// `t_k = k h`, node by node: `out[i * steps + k]` at `t_k + c[i] (t_{k+1} - t_k)`, Pa
    /// (`h` in s, `c` in [0, 1], `out` at least `steps * c.len()` long). The same values as
    /// [`Excitation::stress_nodes`] step by step up to round-off; a solver tabulates the
    /// burst once per run with it (a tone burst rotates an exact `sin_cos` at the start of
    /// each block of up to 128 steps to every node of the block).
    fn stress_grid(&self, h: f64, c: &[f64], steps: usize, out: &mut [f64]) {
        grid_by_steps(self, h, c, steps, out);
    }
    /// Duration of the waveform, s.
    fn duration(&self) -> f64;
    /// Fundamental frequency f0 used by the analysis and by xi, Hz.
    fn fundamental(&self) -> f64;
    /// Highest frequency of interest (sets the time step), Hz.
    fn highest_frequency(&self) -> f64 {
        self.fundamental()
    }
    /// Second frequency of a two-tone input, Hz.
    fn second_frequency(&self) -> Option<f64> {
        None
    }
    /// Times where the waveform is not smooth (window joints, file samples), s.
    fn breakpoints(&self) -> Vec<f64>;
    /// Peak of |s_inc|, Pa.
    fn peak(&self) -> f64;
    /// The waveform at unit peak, built from its shape alone, with the key of that shape:
    /// `self` is `peak()` times it, so that what is linear in the amplitude (the response
    /// of a linear interface) can be computed once per shape. `None` (the default): the
    /// waveform cannot say, and nothing is shared between its runs.
    fn unit_shape(&self) -> Option<UnitShape> {
        None
    }
    /// The numbers (as bits, each kind of waveform tagged) that determine
    /// [`Excitation::stress_grid`] exactly: two waveforms with equal keys give the same
    /// tables, bit for bit, so that a solver may keep the table of its last run. `None`
    /// (the default): the waveform cannot say, and its table is made for every run.
    fn grid_key(&self) -> Option<Vec<u64>> {
        None
    }
}

/// Peak of |f| over [0, d], found on a fine grid refined by golden-section search.
pub(crate) fn numeric_peak(f: impl Fn(f64) -> f64, d: f64, n: usize) -> f64 {
    let mut best_i = 0;
    let mut best = 0.0;
    for i in 0..=n {
        let v = f(d * i as f64 / n as f64).abs();
        if v > best {
            best = v;
            best_i = i;
        }
    }
    let h = d / n as f64;
    let (mut a, mut b) = (
        (best_i as f64 - 1.0).max(0.0) * h,
        ((best_i + 1) as f64 * h).min(d),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let x1 = b - g * (b - a);
        let x2 = a + g * (b - a);
        if f(x1).abs() > f(x2).abs() {
            b = x2;
        } else {
            a = x1;
        }
    }
    best.max(f(0.5 * (a + b)).abs())
}
