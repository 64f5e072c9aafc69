//! Convergence of a 2D run in space (`contactwave convergence` on a `solid_2d` scenario,
//! docs/model.md section 15.4): the scenario run at a sequence of element sizes, from its
//! own (`model.element_size` or its default) down by a constant ratio `r`,
//!
//! ```text
//! h_k = h_0 / r^k,   k = 0 ... levels - 1
//! ```
//!
//! (the time step follows: the smaller of its accuracy bound at the highest analysed
//! harmonic and the stability limit of the finer mesh). For every receiver and harmonic `n`
//! the study reports `A_n/A1` at each level, its relative change against the finest level,
//! the observed order from the last three levels (Richardson, model.md eq. 15.6c)
//!
//! ```text
//! p = ln((f_{k-1} - f_{k-2}) / (f_k - f_{k-1})) / ln r,    f* = f_k + (f_k - f_{k-1}) / (r^p - 1)
//! ```
//!
//! and the estimated error of the scenario's own level, `(f_0 - f*) / f*`: against the
//! extrapolated value where the last three levels converge monotonically at an order of at
//! least [`MIN_ORDER`], else against the finest level (a lower bound, flagged).
//!
//! ```
//! use contactwave::study::convergence_2d::{run_convergence_2d, Convergence2dSpec};
//! let t = contactwave::model::from_toml_str(r#"
//!     [model]
//!     kind = "solid_2d"
//!     width = 6e-3
//!     duration = 1.5e-6
//!     harmonic = 2
//!     [[layer]]
//!     thickness = 2e-3
//!     material = "aluminium"
//!     [[crack]]
//!     start = [2.5e-3, 1e-3]
//!     length = 1e-3
//!     static_pressure = 1e6
//!     [[source]]
//!     x0 = 1e-3
//!     x1 = 2e-3
//!     signal = { frequency = 5e6, cycles = 3, amplitude = 10e6, window = "hann" }
//!     [[receiver]]
//!     name = "below"
//!     at = [3e-3, 2e-3]
//! "#, "doc.toml").unwrap();
//! let spec = Convergence2dSpec { levels: Some(3), ..Convergence2dSpec::default() };
//! let r = run_convergence_2d(t.as_ref(), &spec, &|_, _| {}).unwrap();
//! assert_eq!(r.levels.len(), 3);
//! assert!(r.levels[2].element_size < r.levels[0].element_size);
//! assert_eq!(r.levels[2].change[0], 0.0);
//! ```

use crate::error::{Error, Result};
use crate::model::{Model, Template};
use crate::run::{Executor, Progress};
use crate::scenario::solid_2d::Solid2dScenario;
use std::sync::Arc;

/// Smallest observed order taken as convergence: below it (or where the last three levels
/// oscillate) the default's error is estimated against the finest level instead of the
/// extrapolated value.
pub const MIN_ORDER: f64 = 0.5;

/// Most levels of a study (the finest of 8 at ratio 1.5 has 290 times the nodes).
pub const MAX_LEVELS: usize = 8;

/// What to compute.
#[derive(Debug, Clone)]
pub struct Convergence2dSpec {
    /// Number of element sizes, 3 to [`MAX_LEVELS`] (the scenario's own first; default 6
    /// on a rectangle: 15 to 25 s for `examples/solid_2d/plate_crack_quick.toml` on 2
    /// cores, the finest level two thirds of it, each more level about 3.5 times as long;
    /// 3 on a mesh).
    pub levels: Option<usize>,
    /// Ratio of one element size to the next, in [1.1, 4] (default 1.5); on a mesh an
    /// integer (default 2): each level splits each element of the one before into
    /// `ratio x ratio` (`mesh.refine`, at most [`crate::scenario::solid_2d::mesh::REFINE`]).
    pub ratio: Option<f64>,
    /// Harmonics `n` whose `A_n/A1` is studied at every receiver, each 2 to 5.
    pub harmonics: Vec<usize>,
}

impl Default for Convergence2dSpec {
    fn default() -> Self {
        Convergence2dSpec {
            levels: None,
            ratio: None,
            harmonics: vec![2, 3],
        }
    }
}

/// One studied quantity: `A_n/A1` of one receiver.
#[derive(Debug, Clone, PartialEq)]
pub struct Quantity2d {
    /// Index into [`Convergence2dResult::receivers`].
    pub receiver: usize,
    /// Harmonic `n`.
    pub harmonic: usize,
    /// Column name: `<receiver>_A<n>_over_A1`.
    pub key: String,
}

/// One element size of the study.
#[derive(Debug, Clone)]
pub struct Level2d {
    /// Largest element size, m.
    pub element_size: f64,
    /// Nodes of the mesh.
    pub nodes: f64,
    /// Time steps.
    pub steps: f64,
    /// Time step, s.
    pub dt: f64,
    /// Split nodes of each crack.
    pub split_nodes: Vec<usize>,
    /// Each quantity's value (`A_n/A1`, dimensionless).
    pub values: Vec<f64>,
    /// Each quantity's relative change against the finest level (0 there).
    pub change: Vec<f64>,
    /// Where each receiver records (the node nearest the position asked for), `[x, z]`, m.
    pub positions: Vec<[f64; 2]>,
}

/// Result of [`run_convergence_2d`].
#[derive(Debug, Clone)]
pub struct Convergence2dResult {
    /// The scenario file.
    pub file: String,
    /// Ratio of one element size to the next.
    pub ratio: f64,
    /// Receiver names (a line's points one each).
    pub receivers: Vec<String>,
    /// Each crack's length, m.
    pub cracks: Vec<f64>,
    /// The quantities, receiver by receiver, harmonic by harmonic.
    pub quantities: Vec<Quantity2d>,
    /// The levels, the scenario's own (coarsest) first.
    pub levels: Vec<Level2d>,
    /// Each quantity's observed order from the last three levels (NaN where they
    /// oscillate or do not change).
    pub order: Vec<f64>,
    /// Each quantity's Richardson extrapolation from the last three levels (NaN where
    /// the order is below [`MIN_ORDER`] or not finite).
    pub extrapolated: Vec<f64>,
    /// Each quantity's estimated relative error at the scenario's own level: against
    /// [`Self::extrapolated`], or against the finest level where that is NaN.
    pub default_error: Vec<f64>,
    /// Each receiver's largest distance between the nodes it records at over the levels,
    /// m (0: the same point at every level; else its changes include the move).
    pub moved: Vec<f64>,
}

/// Richardson extrapolation of three values `f` at element sizes in the ratio `ratio`
/// (coarsest first): `(order, extrapolated)`. The order is NaN where the changes
/// oscillate or vanish, the extrapolation NaN where the order is below [`MIN_ORDER`].
///
/// ```
/// use contactwave::study::convergence_2d::richardson;
/// // f = 1 + h^2 at h = 4, 2, 1
/// let (p, f) = richardson([17.0, 5.0, 2.0], 2.0);
/// assert!((p - 2.0).abs() < 1e-12 && (f - 1.0).abs() < 1e-12);
/// assert!(richardson([1.0, 2.0, 1.5], 2.0).0.is_nan());
/// ```
pub fn richardson(f: [f64; 3], ratio: f64) -> (f64, f64) {
    let (d1, d2) = (f[1] - f[0], f[2] - f[1]);
    if !(d1.is_finite() && d2.is_finite()) || d1 * d2 <= 0.0 {
        return (f64::NAN, f64::NAN);
    }
    let p = (d1 / d2).ln() / ratio.ln();
    if p >= MIN_ORDER {
        (p, f[2] + d2 / (ratio.powf(p) - 1.0))
    } else {
        (p, f64::NAN)
    }
}

fn invalid(file: &str, field: &str, value: String, allowed: &str) -> Error {
    Error::invalid(file, field, value, allowed)
}

/// Check the spec's levels, ratio and harmonics against the scenario file `file`.
fn check(levels: usize, ratio: f64, harmonics: &[usize], file: &str) -> Result<()> {
    if !(3..=MAX_LEVELS).contains(&levels) {
        return Err(invalid(
            file,
            "--levels",
            levels.to_string(),
            &format!("3 to {MAX_LEVELS} element sizes (Richardson needs three)"),
        ));
    }
    if !(1.1..=4.0).contains(&ratio) {
        return Err(invalid(
            file,
            "--ratio",
            ratio.to_string(),
            "a ratio of one element size to the next in [1.1, 4]",
        ));
    }
    if harmonics.is_empty() || harmonics.iter().any(|n| !(2..=5).contains(n)) {
        return Err(invalid(
            file,
            "--harmonic",
            format!("{harmonics:?}"),
            "2 to 5 (A_n/A1 of each receiver)",
        ));
    }
    Ok(())
}

/// On a mesh: each level's `mesh.refine` (the scenario's own times `ratio^k`), refused
/// naming `--ratio` (not an integer) or `--levels` (beyond the largest refinement).
fn mesh_levels(own: usize, levels: usize, ratio: f64, file: &str) -> Result<Vec<usize>> {
    let r = ratio.round();
    if r != ratio || r < 2.0 {
        return Err(invalid(
            file,
            "--ratio",
            ratio.to_string(),
            "on a mesh, an integer ratio from 2 (each level splits each element of the one \
             before into ratio x ratio)",
        ));
    }
    let refine: Vec<usize> = (0..levels)
        .map(|k| own.saturating_mul((r as usize).saturating_pow(k as u32)))
        .collect();
    let most = *crate::scenario::solid_2d::mesh::REFINE.end();
    if refine.iter().any(|&k| k > most) {
        return Err(invalid(
            file,
            "--levels",
            levels.to_string(),
            &format!(
                "on a mesh, levels whose finest splits each element of the file into at most \
                 {most} x {most} (mesh.refine {own} times {r}^(levels - 1))"
            ),
        ));
    }
    Ok(refine)
}

/// The 2D scenario of a model.
fn solid_2d(m: &dyn Model) -> Result<&Solid2dScenario> {
    m.as_any().downcast_ref::<Solid2dScenario>().ok_or_else(|| {
        invalid(
            m.file(),
            "model.kind",
            format!("\"{}\"", m.kind()),
            "\"solid_2d\" (the 2D convergence study refines its element size)",
        )
    })
}

/// The levels of a study, built and checked, before any runs ([`plan_convergence_2d`]).
#[derive(Debug, Clone)]
pub struct Convergence2dPlan {
    /// The scenario file.
    pub file: String,
    /// Ratio of one element size to the next.
    pub ratio: f64,
    /// Harmonics studied.
    pub harmonics: Vec<usize>,
    /// The models of the levels, the scenario's own first.
    pub models: Vec<Arc<dyn Model>>,
    /// Each level's element size, m.
    pub element_sizes: Vec<f64>,
    /// Each level's estimated node-updates (nodes times steps, times the runs of its
    /// analysis method): what its run costs.
    pub node_updates: Vec<f64>,
}

/// Build every level of the study on a 2D scenario's template and check each against the
/// memory budget, before any runs: a level too fine is refused naming `--levels`.
pub fn plan_convergence_2d(
    template: &dyn Template,
    spec: &Convergence2dSpec,
) -> Result<Convergence2dPlan> {
    let file = template.file().to_string();
    let base = template.base()?;
    let s0 = solid_2d(base.as_ref())?;
    let on_mesh = s0.spec.mesh.as_ref().map(|m| m.refine.unwrap_or(1));
    let levels = spec.levels.unwrap_or(if on_mesh.is_some() { 3 } else { 6 });
    let ratio = spec
        .ratio
        .unwrap_or(if on_mesh.is_some() { 2.0 } else { 1.5 });
    check(levels, ratio, &spec.harmonics, &file)?;
    let refine = on_mesh
        .map(|own| mesh_levels(own, levels, ratio, &file))
        .transpose()?;
    let h0 = s0.problem.element_size;
    let param = template.param(if refine.is_some() {
        "mesh.refine"
    } else {
        "model.element_size"
    })?;
    let mut models: Vec<Arc<dyn Model>> = vec![base.clone()];
    for k in 1..levels {
        let h = h0 / ratio.powi(k as i32);
        let value = refine.as_ref().map_or(h, |r| r[k] as f64);
        // (a scenario's own time step may be beyond a finer mesh's stability limit: say
        // at which level)
        let m = template.build(&[(&param, value)]).map_err(|e| match e {
            Error::Invalid {
                file,
                field,
                value,
                allowed,
            } => Error::Invalid {
                file,
                field,
                value,
                allowed: format!(
                    "{allowed} (at level {k} of the convergence study, element size {h:.3e} m)"
                ),
            },
            e => e,
        })?;
        m.check_budget().map_err(|e| {
            invalid(
                &file,
                "--levels",
                levels.to_string(),
                &format!(
                    "levels whose finest fits the memory budget: level {k} (element size \
                     {h:.3e} m) does not ({e}); fewer levels or a smaller --ratio"
                ),
            )
        })?;
        models.push(m);
    }
    let (mut element_sizes, mut node_updates) = (Vec::new(), Vec::new());
    // (a mesh's steps: the coarsest level's plan's, growing with the refinement)
    let mesh_steps = match &s0.mesh {
        Some(q) => q.plan(&file)?.steps as f64,
        None => 0.0,
    };
    for (k, m) in models.iter().enumerate() {
        let s = solid_2d(m.as_ref())?;
        match &s.mesh {
            Some(q) => {
                let grow = ratio.powi(k as i32);
                element_sizes.push(h0 / grow);
                node_updates.push(s.runs() * q.node_estimate() * mesh_steps * grow);
            }
            None => {
                let e = s.problem.memory_estimate(&file)?;
                element_sizes.push(s.problem.element_size);
                node_updates.push(s.runs() * e.nodes * e.steps);
            }
        }
    }
    Ok(Convergence2dPlan {
        file,
        ratio,
        harmonics: spec.harmonics.clone(),
        models,
        element_sizes,
        node_updates,
    })
}

/// Run the study on a 2D scenario's template ([`plan_convergence_2d`], then
/// [`Convergence2dPlan::run`]).
pub fn run_convergence_2d(
    template: &dyn Template,
    spec: &Convergence2dSpec,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Convergence2dResult> {
    plan_convergence_2d(template, spec)?.run(progress)
}

impl Convergence2dPlan {
    /// Run every level on the [`Executor`] (the finest first); `progress(done, total)` is
    /// called after each level. Ctrl-C ([`crate::interrupt`]) stops the runs: the study
    /// then fails with [`Error::Interrupted`]. A level whose run fails fails the study.
    pub fn run(&self, progress: &(dyn Fn(usize, usize) + Sync)) -> Result<Convergence2dResult> {
        let (file, models) = (self.file.clone(), &self.models);
        let s0 = solid_2d(models[0].as_ref())?;
        let scenarios: Vec<&Solid2dScenario> = models
            .iter()
            .map(|m| solid_2d(m.as_ref()))
            .collect::<Result<_>>()?;
        let receivers: Vec<String> = s0.receivers.iter().map(|r| r.name.clone()).collect();
        let quantities: Vec<Quantity2d> = receivers
            .iter()
            .enumerate()
            .flat_map(|(i, name)| {
                self.harmonics.iter().map(move |&n| Quantity2d {
                    receiver: i,
                    harmonic: n,
                    key: format!("{name}_A{n}_over_A1"),
                })
            })
            .collect();
        // the finest (longest) first, so that the coarse levels fill the other cores
        let order: Vec<usize> = (0..models.len()).rev().collect();
        let observer = Progress {
            report: progress,
            cancel: None,
        };
        let runs = Executor::new().map(&order, |&k| models[k].summary(), &observer)?;
        let mut summaries = vec![None; models.len()];
        for (&k, r) in order.iter().zip(runs) {
            summaries[k] = Some(r.unwrap_or(Err(Error::Interrupted))?);
        }
        let mut levels: Vec<Level2d> = Vec::with_capacity(models.len());
        for (s, sum) in scenarios.iter().zip(summaries) {
            let sum = sum.ok_or(Error::Interrupted)?;
            let get = |k: &str| sum.get(k).unwrap_or(f64::NAN);
            levels.push(Level2d {
                element_size: self.element_sizes[levels.len()],
                nodes: get("nodes"),
                steps: get("steps"),
                dt: get("dt"),
                split_nodes: s.crack_resolution().iter().map(|c| c.split_nodes).collect(),
                values: quantities
                    .iter()
                    .map(|q| {
                        let name = &receivers[q.receiver];
                        get(&format!("{name}_A{}", q.harmonic)) / get(&format!("{name}_A1"))
                    })
                    .collect(),
                change: Vec::new(),
                positions: receivers
                    .iter()
                    .map(|name| [get(&format!("{name}_x")), get(&format!("{name}_z"))])
                    .collect(),
            });
        }
        let finest = levels.last().map(|l| l.values.clone()).unwrap_or_default();
        for l in &mut levels {
            l.change = l
                .values
                .iter()
                .zip(&finest)
                .map(|(v, f)| (v - f) / f)
                .collect();
        }
        let n = levels.len();
        let (mut order, mut extrapolated, mut default_error) = (vec![], vec![], vec![]);
        for q in 0..quantities.len() {
            let f = [
                levels[n - 3].values[q],
                levels[n - 2].values[q],
                levels[n - 1].values[q],
            ];
            let (p, ext) = richardson(f, self.ratio);
            let reference = if ext.is_finite() { ext } else { f[2] };
            order.push(p);
            extrapolated.push(ext);
            default_error.push((levels[0].values[q] - reference) / reference);
        }
        let moved = (0..receivers.len())
            .map(|r| {
                let at = levels[0].positions[r];
                levels
                    .iter()
                    .map(|l| (l.positions[r][0] - at[0]).hypot(l.positions[r][1] - at[1]))
                    .fold(0.0, f64::max)
            })
            .collect();
        Ok(Convergence2dResult {
            file,
            ratio: self.ratio,
            receivers,
            cracks: s0.crack_resolution().iter().map(|c| c.length).collect(),
            quantities,
            levels,
            order,
            extrapolated,
            default_error,
            moved,
        })
    }
}

impl Convergence2dResult {
    /// `convergence.csv`: one row per level: its element size (m), nodes, steps, time step
    /// (s), each crack's split nodes, then each quantity's value and relative change
    /// against the finest level (a fraction), then where each receiver records (m).
    pub fn levels_csv(&self) -> String {
        let mut s = String::from("level,element_size_m,nodes,steps,dt_s");
        for i in 0..self.cracks.len() {
            s.push_str(&format!(",split_nodes_{i}"));
        }
        for q in &self.quantities {
            s.push_str(&format!(",{k},{k}_change", k = q.key));
        }
        for r in &self.receivers {
            s.push_str(&format!(",{r}_x_m,{r}_z_m"));
        }
        s.push('\n');
        for (k, l) in self.levels.iter().enumerate() {
            s.push_str(&format!(
                "{k},{:e},{},{},{:e}",
                l.element_size, l.nodes, l.steps, l.dt
            ));
            for n in &l.split_nodes {
                s.push_str(&format!(",{n}"));
            }
            for (v, c) in l.values.iter().zip(&l.change) {
                s.push_str(&format!(",{v:e},{c:e}"));
            }
            for p in &l.positions {
                s.push_str(&format!(",{:e},{:e}", p[0], p[1]));
            }
            s.push('\n');
        }
        s
    }

    /// `convergence_order.csv`: one row per quantity: receiver, harmonic, observed order,
    /// extrapolated value, the scenario's own value, its estimated error (fraction and
    /// percent), what the error is against (`extrapolated` or `finest`) and how far the
    /// receiver's node moves over the levels (m).
    pub fn order_csv(&self) -> String {
        let mut s = String::from(
            "receiver,harmonic,observed_order,extrapolated,default_value,default_error,\
             default_error_percent,reference,receiver_moved_m\n",
        );
        for (i, q) in self.quantities.iter().enumerate() {
            s.push_str(&format!(
                "{},{},{:e},{:e},{:e},{:e},{:e},{},{:e}\n",
                self.receivers[q.receiver],
                q.harmonic,
                self.order[i],
                self.extrapolated[i],
                self.levels[0].values[i],
                self.default_error[i],
                100.0 * self.default_error[i],
                if self.extrapolated[i].is_finite() {
                    "extrapolated"
                } else {
                    "finest"
                },
                self.moved[q.receiver]
            ));
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plate 6 x 2 mm with a 1 mm crack, a 5 MHz burst and a receiver under the crack
    /// (on a node at every level): a few thousand nodes, under a second per level.
    const TINY: &str = r#"
        [model]
        kind = "solid_2d"
        width = 6e-3
        duration = 1.5e-6
        harmonic = 2
        [[layer]]
        thickness = 2e-3
        material = "aluminium"
        [[crack]]
        start = [2.5e-3, 1e-3]
        length = 1e-3
        static_pressure = 1e6
        [[source]]
        x0 = 1e-3
        x1 = 2e-3
        signal = { frequency = 5e6, cycles = 3, amplitude = 10e6, window = "hann" }
        [[receiver]]
        name = "below"
        at = [3e-3, 2e-3]
        [[receiver]]
        name = "top"
        at = [5e-3, 0.0]
    "#;

    /// Issue 56 (5): the levels refine by the ratio, the finest's change is 0, the observed
    /// order and the default's error are finite, the split nodes grow, and the CSVs hold
    /// a row per level and per quantity.
    #[test]
    fn the_2d_study_refines_and_estimates_its_order() {
        let t = crate::model::from_toml_str(TINY, "tiny.toml").unwrap();
        let spec = Convergence2dSpec {
            levels: Some(4),
            ..Convergence2dSpec::default()
        };
        let r = run_convergence_2d(t.as_ref(), &spec, &|_, _| {}).unwrap();
        assert_eq!(r.levels.len(), 4);
        assert_eq!(r.quantities.len(), 4);
        for w in r.levels.windows(2) {
            assert!((w[0].element_size / w[1].element_size - 1.5).abs() < 1e-12);
            assert!(w[1].nodes > w[0].nodes);
            assert!(w[1].split_nodes[0] >= w[0].split_nodes[0]);
        }
        let last = r.levels.last().unwrap();
        assert!(last.change.iter().all(|&c| c == 0.0), "{:?}", last.change);
        assert!(r.levels[0].values.iter().all(|v| v.is_finite() && *v > 0.0));
        // A2/A1 under the crack: a finite order, a finite estimate of the default's error
        assert!(r.order[0].is_finite(), "{:?}", r.order);
        assert!(r.default_error[0].is_finite(), "{:?}", r.default_error);
        // the receiver under the crack records at the same node at every level
        assert_eq!(r.moved[0], 0.0);
        assert_eq!(r.levels_csv().lines().count(), 5);
        assert_eq!(r.order_csv().lines().count(), 5);
    }

    /// The spec is checked before anything runs, naming the option.
    #[test]
    fn bad_specs_are_refused_by_option() {
        let t = crate::model::from_toml_str(TINY, "tiny.toml").unwrap();
        for (spec, field) in [
            (
                Convergence2dSpec {
                    levels: Some(2),
                    ..Default::default()
                },
                "--levels",
            ),
            (
                Convergence2dSpec {
                    ratio: Some(1.0),
                    ..Default::default()
                },
                "--ratio",
            ),
            (
                Convergence2dSpec {
                    harmonics: vec![1],
                    ..Default::default()
                },
                "--harmonic",
            ),
        ] {
            let e = run_convergence_2d(t.as_ref(), &spec, &|_, _| {})
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("field `{field}`")), "{e}");
        }
    }

    #[test]
    fn richardson_recovers_the_order() {
        // f = 2 - h^1.5 at h = 1, 1/1.5, 1/2.25
        let f: Vec<f64> = (0..3).map(|k| 2.0 - 1.5f64.powi(-k).powf(1.5)).collect();
        let (p, ext) = richardson([f[0], f[1], f[2]], 1.5);
        assert!(
            (p - 1.5).abs() < 1e-9 && (ext - 2.0).abs() < 1e-9,
            "{p} {ext}"
        );
        // too slow to extrapolate: the order, no extrapolation
        let (p, ext) = richardson([1.0, 1.9, 2.7], 1.5);
        assert!(p < MIN_ORDER && ext.is_nan());
    }
}
