//! Identification from raw waveforms (`[records]` in an identification file, docs/identify.md
//! section 6): measured time records (any format `contactwave analyze` reads) are reduced by
//! [`crate::measured::analyze`] into the observed values, one row per record, and each
//! forward run's signal at the same probe ([`crate::model::Outcome::waveform`]) is reduced
//! by exactly the same analysis (the same fundamental, method and gate, the same receiving
//! transducer response) before it is compared with them.
//!
//! ```toml
//! [records]
//! files = ["echoes.csv"]              # record files, relative to the identification file
//! condition = "incident.amplitude"    # the dotted scenario key set at each record
//! values = [0.5e6, 1e6, 2e6]          # its value per record (or the name of an array of
//!                                     #   the first file: values = "drive_Pa")
//! waveform = "reflected_velocity"     # the forward run's signal (probe.csv / receivers.csv column)
//! method = "band_peak"                # band_peak | pulse_inversion | linear_reference | plateau_fit
//! gate = [2e-6, 12e-6]                # s: [start, end] or [start, end, taper] (default: none)
//! model_gate = [2e-6, 12e-6]          # s: the gate on the forward signal's time base (default: gate)
//! f0 = 1e6                            # Hz (default: detected from the records, then used for both)
//! band_pass = { centre = 4e6, q = 0.7 }  # the receiving transducer (default: none)
//! # datasets = ["echo"], time = "t", sample_rate = 100e6, keep_dc = false,
//! # inverse = ["inverted.csv"], linear = "low.csv"     (as `contactwave analyze`)
//! ```

use crate::analysis::{AnalysisMethod, Gate, Summary};
use crate::error::{Error, Result};
use crate::measured::{self, Amplitudes, BandPass, Layout, RecordAnalysis, Series, Settings};
use crate::model::{Model, RunControl, Waveform, Workspace};
use std::path::{Path, PathBuf};

/// `[records]` as written.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RecordsFile {
    files: Vec<String>,
    condition: String,
    values: toml::Value,
    waveform: String,
    method: Option<String>,
    gate: Option<Vec<f64>>,
    model_gate: Option<Vec<f64>>,
    f0: Option<f64>,
    band_pass: Option<BandPassFile>,
    datasets: Option<Vec<String>>,
    time: Option<String>,
    sample_rate: Option<f64>,
    keep_dc: Option<bool>,
    inverse: Option<Vec<String>>,
    linear: Option<String>,
    full_scale: Option<f64>,
    allow_clipped: Option<bool>,
}

/// `band_pass = { centre, q }` as written.
#[derive(Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct BandPassFile {
    centre: f64,
    q: f64,
}

/// A checked `[records]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordsSpec {
    /// The record files, resolved.
    pub sources: measured::Sources,
    /// The dotted scenario key set at each record.
    pub condition: String,
    /// The forward run's signal ([`crate::model::Outcome::waveform`]).
    pub waveform: String,
    /// The analysis of the records (its `f0` is the measured one, given or detected).
    pub settings: Settings,
    /// The gate on the forward signal's time base, s.
    pub model_gate: Option<Gate>,
    /// The receiving transducer, applied to the forward signal.
    pub band_pass: Option<BandPass>,
    /// The records' analysis (what the observed values came from).
    pub analysis: Option<measured::Analysis>,
    /// The identification file (for errors).
    pub file: String,
    /// Identify from clipped records too (`allow_clipped = true`; refused by default: their
    /// harmonics are the clipping's).
    pub allow_clipped: bool,
}

/// The data rows of a `[records]` table: the condition's value per record (`rows[i][0]`)
/// and each observed key's values and uncertainties.
#[derive(Debug, Clone, PartialEq)]
pub struct Rows {
    /// `rows[i] = [condition value]`, one per record.
    pub rows: Vec<Vec<f64>>,
    /// `(key, values, sigma)` per observed key.
    pub observed: Vec<(String, Vec<f64>, Vec<f64>)>,
}

/// What `[records]` allows (for errors).
pub(super) const ALLOWED: &str = "a [records] table has files, condition, values, waveform, \
    method, gate, model_gate, f0, band_pass, datasets, time, sample_rate, keep_dc, inverse, \
    linear, full_scale, allow_clipped";

fn gate_of(v: &[f64], file: &str, field: &str) -> Result<Gate> {
    Gate::from_values(v).ok_or_else(|| {
        Error::invalid(
            file,
            field,
            format!("{v:?}"),
            "[start, end] or [start, end, taper] in s, end > start, 0 <= taper <= (end - \
             start) / 2",
        )
    })
}

impl RecordsFile {
    /// Check the table; `dir` resolves the file names.
    pub(super) fn check(self, file: &str, dir: &Path) -> Result<RecordsSpec> {
        let field = |k: &str| format!("records.{k}");
        if self.files.is_empty() {
            return Err(Error::invalid(
                file,
                field("files"),
                "[]",
                "at least one record file",
            ));
        }
        if !self.condition.contains('.') {
            return Err(Error::invalid(
                file,
                field("condition"),
                &self.condition,
                "a dotted scenario key of a number, e.g. incident.amplitude",
            ));
        }
        let amplitudes = match &self.values {
            toml::Value::String(s) => Amplitudes::Array(s.clone()),
            toml::Value::Array(a) => Amplitudes::Values(
                a.iter()
                    .map(|x| {
                        x.as_float()
                            .or_else(|| x.as_integer().map(|i| i as f64))
                            .filter(|v| v.is_finite())
                            .ok_or_else(|| {
                                Error::invalid(file, field("values"), x, "a finite number")
                            })
                    })
                    .collect::<Result<Vec<f64>>>()?,
            ),
            other => {
                return Err(Error::invalid(
                    file,
                    field("values"),
                    other,
                    "a list of the condition's values, one per record, or the name of an \
                     array of the first record file",
                ));
            }
        };
        let method = match self.method.as_deref() {
            None => AnalysisMethod::BandPeak,
            Some(m) => AnalysisMethod::from_name(m).ok_or_else(|| {
                Error::invalid(
                    file,
                    field("method"),
                    m,
                    "band_peak, pulse_inversion, linear_reference or plateau_fit",
                )
            })?,
        };
        let gate = self
            .gate
            .as_deref()
            .map(|g| gate_of(g, file, &field("gate")))
            .transpose()?;
        let model_gate = match self.model_gate.as_deref() {
            Some(g) => Some(gate_of(g, file, &field("model_gate"))?),
            None => gate,
        };
        if let Some(f0) = self.f0
            && !(f0.is_finite() && f0 > 0.0)
        {
            return Err(Error::invalid(
                file,
                field("f0"),
                f0,
                "a frequency > 0 (Hz)",
            ));
        }
        let band_pass = self
            .band_pass
            .map(|b| BandPass::new(b.centre, b.q, file, &field("band_pass")))
            .transpose()?;
        let paths = |v: &[String]| -> Vec<PathBuf> { v.iter().map(|f| dir.join(f)).collect() };
        let sources = measured::Sources {
            records: paths(&self.files),
            layout: Layout {
                sample_rate: self.sample_rate,
                time: self.time,
                records: self.datasets.unwrap_or_default(),
            },
            inverse: paths(self.inverse.as_deref().unwrap_or_default()),
            linear: self.linear.map(|l| dir.join(l)),
            amplitudes: Some(amplitudes),
        };
        Ok(RecordsSpec {
            sources,
            condition: self.condition,
            waveform: self.waveform,
            settings: Settings {
                f0: self.f0,
                gate,
                method,
                keep_dc: self.keep_dc.unwrap_or(false),
                full_scale: self.full_scale,
            },
            allow_clipped: self.allow_clipped.unwrap_or(false),
            model_gate,
            band_pass,
            analysis: None,
            file: file.to_string(),
        })
    }
}

/// The analysis floor of observed `key` (the harmonic's floor, over A1 or A1^2 for ratios).
fn record_floor(r: &RecordAnalysis, key: &str) -> f64 {
    let a1 = r.harmonics[1];
    match key {
        "A2_over_A1" => r.floor(2) / a1,
        "A3_over_A1" => r.floor(3) / a1,
        "beta_star" => r.floor(2) / (a1 * a1),
        k => k
            .strip_prefix('A')
            .and_then(|n| n.parse::<usize>().ok())
            .filter(|n| (1..=5).contains(n))
            .map_or(0.0, |n| r.floor(n)),
    }
}

/// The observed keys of a records identification (default `A2_over_A1`), checked.
fn observed_keys(observed: Option<&[String]>, file: &str) -> Result<Vec<String>> {
    let keys: Vec<String> = match observed {
        None => vec!["A2_over_A1".to_string()],
        Some([]) => {
            return Err(Error::invalid(
                file,
                "observed",
                "[]",
                "a non-empty list of observed keys",
            ));
        }
        Some(k) => k.to_vec(),
    };
    if let Some(k) = keys
        .iter()
        .find(|k| !measured::HARMONIC_KEYS.contains(&k.as_str()))
    {
        return Err(Error::invalid(
            file,
            "observed",
            k,
            format!(
                "with [records], keys of the records' analysis: {}",
                measured::HARMONIC_KEYS.join(", ")
            ),
        ));
    }
    Ok(keys)
}

impl RecordsSpec {
    /// Read and analyse the records: the measured data (one row per record, the condition
    /// the control variable), `observed` the fitted keys (default `A2_over_A1`). The
    /// uncertainty of each value is `noise.0 |y| + noise.1` (the fit's relative and
    /// absolute noise) plus its
    /// analysis floor (leakage and noise, [`RecordAnalysis::floor`]). Keeps the analysis;
    /// the fundamental found is used for the forward signals too.
    pub fn measure(
        &mut self,
        observed: Option<&[String]>,
        file: &str,
        noise: (f64, f64),
    ) -> Result<Rows> {
        let keys = observed_keys(observed, file)?;
        let series = measured::load(&self.sources).map_err(|e| match e {
            Error::Invalid {
                field,
                value,
                allowed,
                ..
            } if field == "amplitudes" => Error::invalid(
                file,
                "records.values",
                value,
                allowed.replace("drive amplitude", "condition value"),
            ),
            other => other,
        })?;
        let first = self.sources.records[0].display().to_string();
        let analysis = measured::analyze(&series, &self.settings, &first)?;
        if !self.allow_clipped
            && let Some((r, c)) = analysis
                .records
                .iter()
                .find_map(|r| r.clipped.map(|c| (r, c)))
        {
            return Err(Error::invalid(
                file,
                "records.files",
                format!(
                    "{}: {} clipped samples ({})",
                    r.name,
                    c.samples,
                    measured::clip_levels(&c)
                ),
                "records within the digitiser's range (the harmonics of a clipped record are \
                 the clipping's): re-record them, or allow_clipped = true in [records] to \
                 identify from them anyway",
            ));
        }
        let mut rows = Vec::new();
        for (r, rec) in analysis.records.iter().zip(&series.records) {
            let v = rec.amplitude.ok_or_else(|| {
                Error::invalid(
                    file,
                    "records.values",
                    &r.name,
                    "a condition value for every record",
                )
            })?;
            rows.push(vec![v]);
        }
        let observed = keys
            .iter()
            .map(|key| {
                let values: Vec<f64> = analysis.records.iter().map(|r| r.value(key)).collect();
                let sigma: Vec<f64> = analysis
                    .records
                    .iter()
                    .zip(&values)
                    .map(|(r, y)| noise.0 * y.abs() + noise.1 + record_floor(r, key).max(0.0))
                    .collect();
                (key.clone(), values, sigma)
            })
            .collect::<Vec<_>>();
        for (key, values, sigma) in &observed {
            if let Some(i) = values
                .iter()
                .zip(sigma)
                .position(|(v, s)| !v.is_finite() || !(*s > 0.0))
            {
                return Err(Error::invalid(
                    &first,
                    format!("record {} {key}", analysis.records[i].name),
                    values[i],
                    "a finite value with an uncertainty > 0 (a record without its \
                     fundamental in the gate?)",
                ));
            }
        }
        self.settings.f0 = Some(analysis.f0);
        self.analysis = Some(analysis);
        Ok(Rows { rows, observed })
    }

    /// The rows of the records without reading them (the listed condition values; the
    /// observed values 1 with uncertainty 1, placeholders), for
    /// [`crate::inverse::synthesize_records`].
    pub fn unmeasured(&self, observed: Option<&[String]>, file: &str) -> Result<Rows> {
        let keys = observed_keys(observed, file)?;
        let Some(Amplitudes::Values(values)) = &self.sources.amplitudes else {
            return Err(Error::invalid(
                file,
                "records.values",
                "an array name",
                "a list of the condition's values (to synthesise records)",
            ));
        };
        Ok(Rows {
            rows: values.iter().map(|v| vec![*v]).collect(),
            observed: keys
                .into_iter()
                .map(|key| (key, vec![1.0; values.len()], vec![1.0; values.len()]))
                .collect(),
        })
    }

    /// A forward model's signal, with the twin's where the method needs one, through the
    /// transducer: `(main, twin)`.
    pub fn forward_waveforms(
        &self,
        model: &dyn Model,
        ws: &mut Workspace,
    ) -> Result<(Waveform, Option<Waveform>)> {
        let pick = |outcome: &dyn crate::model::Outcome| -> Result<Waveform> {
            let mut w = outcome.waveform(&self.waveform).ok_or_else(|| {
                Error::invalid(
                    &self.file,
                    "records.waveform",
                    &self.waveform,
                    format!(
                        "a signal of the forward run: {}",
                        outcome.waveform_names().join(", ")
                    ),
                )
            })?;
            if let Some(bp) = &self.band_pass {
                w.samples = bp.apply(&w.samples, w.dt);
            }
            Ok(w)
        };
        let control = RunControl::default();
        let main = pick(&*model.run_in(&control, ws)?)?;
        let twin = match model.twin(self.settings.method)? {
            Some(t) => Some(pick(&*t.run_in(&control, ws)?)?),
            None => None,
        };
        Ok((main, twin))
    }

    /// A forward model's observed values: its signal reduced exactly as the records were
    /// (the records' fundamental, the method, the model gate, the transducer).
    pub fn forward(&self, model: &dyn Model, ws: &mut Workspace) -> Result<Summary> {
        let (main, twin) = self.forward_waveforms(model, ws)?;
        let mut rec = measured::Measured::new(&self.waveform, main.samples);
        match self.settings.method {
            AnalysisMethod::PulseInversion => rec.inverse = twin.map(|t| t.samples),
            AnalysisMethod::LinearReference => rec.linear = twin.map(|t| t.samples),
            AnalysisMethod::BandPeak | AnalysisMethod::PlateauFit => {}
        }
        let series = Series {
            dt: main.dt,
            t0: main.t0,
            records: vec![rec],
        };
        let settings = Settings {
            gate: self.model_gate,
            ..self.settings
        };
        // the gate is the identification file's `records.model_gate` (or its `gate`):
        // an error about it names that file and key, not the base scenario's
        let a = measured::analyze(&series, &settings, model.file()).map_err(|e| match e {
            Error::Invalid {
                field,
                value,
                allowed,
                ..
            } if field == "gate" => Error::Invalid {
                file: self.file.clone(),
                field: "records.model_gate (or records.gate), on the forward signal".into(),
                value,
                allowed,
            },
            e => e,
        })?;
        let mut s = Summary::new();
        for key in measured::HARMONIC_KEYS {
            s.set(key, a.records[0].value(key));
        }
        Ok(s)
    }
}

/// The record files of a spec with `[records]` resolved against `dir` (for provenance).
pub fn record_files(spec: &RecordsSpec) -> Vec<PathBuf> {
    let s = &spec.sources;
    s.records
        .iter()
        .chain(&s.inverse)
        .chain(&s.linear)
        .cloned()
        .collect()
}
