//! The identification driver: [`identify`] runs the estimation, the identifiability
//! analysis and the fitted curve and gathers them into an [`Identification`];
//! [`synthesize`] makes synthetic measured data from the forward model.
//!
//! The top of the inverse modules: nothing imports it back.

use super::estimate::estimate;
use super::identifiability;
use super::model::Model;
use super::result::Identification;
use super::spec::IdentifySpec;
use crate::error::{Error, Result};

/// Run a whole identification: estimate, identifiability (Jacobian SVD, linearised and
/// bootstrap intervals, verdicts). `progress` receives one-line messages.
///
/// A round trip on a tiny problem (one unknown, three load ratios, a coarse time step, the
/// local stage only; about 200 forward runs):
///
/// ```
/// use contactwave::inverse::{identify, synthesize, IdentifySpec};
/// use contactwave::scenario::parse_toml;
/// let dir = std::env::temp_dir().join(format!("contactwave-doc-identify-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// std::fs::write(dir.join("base.toml"), r#"
///     [medium]
///     material = "pmma"
///     [interface]
///     static_pressure = 0.1e6                             # Pa
///     compression = { law = "linear", stiffness = 1e12 }  # Pa/m
///     [incident]
///     frequency = 1e6                                     # Hz
///     cycles = 5
///     xi = 0.5
///     [solver]
///     samples_per_period = 32
/// "#).unwrap();
/// let table = parse_toml(r#"
///     base = "base.toml"
///     observed = ["A2_over_A1"]
///     [data]                      # placeholders, replaced by synthetic data below
///     "incident.xi" = [0.3, 0.5, 0.8]
///     A2_over_A1 = [1.0, 1.0, 1.0]
///     [[parameter]]
///     key = "interface.compression.stiffness"
///     bounds = [1e10, 1e14]       # Pa/m
///     scale = "log"
///     initial = 1e11
///     [fit]
///     particles = 0               # no swarm: Nelder-Mead from `initial`
///     local_iterations = 30
///     local_starts = 1
///     bootstrap = 0
/// "#, "identify.toml").unwrap();
/// let spec = IdentifySpec::from_table(table, &dir.join("identify.toml")).unwrap();
/// // data simulated with K = 1e12 Pa/m (no noise), then K identified from them
/// let key = "interface.compression.stiffness";
/// let data = synthesize(&spec, &[(key.to_string(), 1e12)], 0.0, 1).unwrap();
/// let result = identify(&data, &|_| {}).unwrap();
/// let k = result.estimate_of(key).unwrap();
/// assert!((k / 1e12 - 1.0).abs() < 1e-3, "K = {k:e} Pa/m");
/// assert!(result.identified(key));
/// let (lo, hi) = result.interval_of(key).unwrap();
/// assert!(lo <= k && k <= hi);
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn identify(spec: &IdentifySpec, progress: &(dyn Fn(&str) + Sync)) -> Result<Identification> {
    let t0 = std::time::Instant::now();
    let model = Model::new(spec);
    let est = estimate(&model, progress)?;
    progress(&format!(
        "estimate: cost {:.6e} after {} forward runs",
        est.cost,
        model.forward_runs()
    ));
    let ident = identifiability::analyse(&model, &est, progress)?;
    let fitted = model.curves(&est.z)?;
    Ok(Identification {
        parameters: spec.parameters.clone(),
        estimate: est,
        identifiability: ident,
        measured: spec.measured.clone(),
        fitted,
        forward_runs: model.forward_runs(),
        failed_runs: model.failed_runs(),
        first_failure: model.first_failure(),
        wall_seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Standard normal deviates (Box-Muller) from a generator seeded with `seed`: the noise of
/// [`synthesize`] and [`synthesize_records`].
fn gaussian(seed: u64) -> impl FnMut() -> f64 {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    move || {
        let u1: f64 = rng.random_range(f64::MIN_POSITIVE..1.0);
        let u2: f64 = rng.random_range(0.0..1.0);
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// The scaled coordinates of a synthesis' parameter values: `truth` (key, value) where
/// given, the starting values elsewhere; checks the keys and the noise level.
pub(super) fn truth_coordinates(
    spec: &IdentifySpec,
    truth: &[(String, f64)],
    noise: f64,
) -> Result<Vec<f64>> {
    let file = spec.file.display().to_string();
    for (k, v) in truth {
        let Some(p) = spec.parameters.iter().find(|p| &p.key == k) else {
            return Err(Error::invalid(
                &file,
                "synthesize",
                k,
                "a key of one of the file's [[parameter]] tables",
            ));
        };
        // a value the parameter's scale cannot hold (a log scale's value <= 0)
        if !p.to_scaled(*v).is_finite() {
            return Err(Error::invalid(
                "--synthesize",
                k,
                v,
                "a value > 0: the parameter's scale is log",
            ));
        }
    }
    if !(noise >= 0.0 && noise.is_finite()) {
        return Err(Error::invalid(&file, "noise", noise, "finite, >= 0"));
    }
    Ok(spec
        .parameters
        .iter()
        .map(|p| {
            let v = truth
                .iter()
                .find(|(k, _)| k == &p.key)
                .map_or(p.initial, |t| t.1);
            p.to_scaled(v)
        })
        .collect())
}

/// Synthetic data: the spec's rows simulated with the parameters at `truth` (key, value;
/// keys not given stay at their starting values), each observed value multiplied by
/// `1 + noise g` with `g` standard normal (seeded), uncertainties reset to
/// `fit.relative_noise |y| + fit.absolute_noise`. Returns the spec with these data.
pub fn synthesize(
    spec: &IdentifySpec,
    truth: &[(String, f64)],
    noise: f64,
    seed: u64,
) -> Result<IdentifySpec> {
    let z = truth_coordinates(spec, truth, noise)?;
    let model = Model::new(spec);
    let curves = model.curves(&z)?;
    let mut gauss = gaussian(seed);
    let mut out = spec.clone();
    for (k, o) in out.measured.observed.iter_mut().enumerate() {
        for (i, c) in curves.iter().enumerate() {
            let y = c[k] * (1.0 + noise * gauss());
            o.values[i] = y;
            o.sigma[i] = spec.fit.relative_noise * y.abs() + spec.fit.absolute_noise;
        }
    }
    Ok(out)
}

/// Synthetic raw records of a spec with `[records]` (`identify --synthesize`): each row's
/// forward signal (`records.waveform`) at the parameter values `truth` (key, value;
/// keys not given stay at their starting values), through the spec's transducer, plus
/// white Gaussian noise of standard deviation `noise` times the record's largest
/// magnitude (seeded). Returns the CSV text: `t` (s), then `record_1`, ... (the signal's
/// unit), `#` comment lines first.
pub fn synthesize_records(
    spec: &IdentifySpec,
    truth: &[(String, f64)],
    noise: f64,
    seed: u64,
    comment: &str,
) -> Result<String> {
    let file = spec.file.display().to_string();
    let Some(rec) = &spec.records else {
        return Err(Error::invalid(
            &file,
            "records",
            "missing",
            "a [records] table",
        ));
    };
    if !matches!(
        rec.settings.method,
        crate::analysis::AnalysisMethod::BandPeak | crate::analysis::AnalysisMethod::PlateauFit
    ) {
        return Err(Error::invalid(
            &file,
            "records.method",
            rec.settings.method.name(),
            "band_peak or plateau_fit to synthesise records (one record per row; the \
             twins of pulse inversion and linear reference are not written)",
        ));
    }
    let z = truth_coordinates(spec, truth, noise)?;
    let model = Model::new(spec);
    let values = model.values(&z);
    let mut ws = crate::model::Workspace::new();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let mut time: Option<(f64, f64, usize)> = None;
    for i in 0..spec.measured.len() {
        let m = model.scenario(i, &values)?;
        let (w, _) = rec.forward_waveforms(&*m, &mut ws)?;
        match time {
            None => time = Some((w.t0, w.dt, w.samples.len())),
            Some((t0, dt, n)) => {
                if (w.t0 - t0).abs() > 1e-6 * dt
                    || (w.dt - dt).abs() > 1e-9 * dt
                    || w.samples.len() != n
                {
                    return Err(Error::invalid(
                        &file,
                        format!("row {}", i + 1),
                        format!("t0 {}, dt {}, {} samples", w.t0, w.dt, w.samples.len()),
                        format!(
                            "the first row's time base (t0 {t0}, dt {dt}, {n} samples): the \
                             condition must not change the run's duration or step"
                        ),
                    ));
                }
            }
        }
        columns.push(w.samples);
    }
    let (t0, dt, n) = time.unwrap_or((0.0, 1.0, 0));
    let mut gauss = gaussian(seed);
    for c in &mut columns {
        let peak = c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for v in c.iter_mut() {
            *v += noise * peak * gauss();
        }
    }
    let mut s = String::new();
    for line in comment.lines() {
        s.push_str(&format!("# {line}\n"));
    }
    s.push('t');
    for i in 0..columns.len() {
        s.push_str(&format!(",record_{}", i + 1));
    }
    s.push('\n');
    for k in 0..n {
        s.push_str(&format!("{:e}", t0 + k as f64 * dt));
        for c in &columns {
            s.push_str(&format!(",{:e}", c[k]));
        }
        s.push('\n');
    }
    Ok(s)
}
