//! Result files of a bar-stack run: `summary.json` (per-interface values as arrays),
//! `timeseries.csv`, and `frf.csv` for a hammer or imposed-displacement run, `waves.csv`
//! (incident, reflected, transmitted displacements) for an `[incident]` run, `probes.csv`
//! with `[[probe]]` points.

use super::BarStackResult;
use crate::analysis::json_number;
use crate::error::Result;
use crate::render::{csv_columns, time_series, OutputFile, Rows};

/// Header of `frf.csv`: frequency (Hz), |X/F| (m/N), its phase (rad), |A/F| ((m/s^2)/N),
/// and the force spectrum's level re its peak (dB); the three FRF columns are NaN where
/// `force_db` is below [`super::FRF_FORCE_FLOOR_DB`].
pub const FRF_HEADER: &str = "frequency,receptance,receptance_phase,accelerance,force_db";

/// The files of a bar-stack run, rendered in memory, with the rows of the time-series
/// files (`timeseries.csv`, `waves.csv`, `shear.csv`, `probes.csv`) picked by `rows`.
pub fn bar_stack_files(
    r: &BarStackResult,
    scenario_file: &str,
    rows: Rows,
) -> Result<Vec<OutputFile>> {
    let mut obj = serde_json::Map::new();
    obj.insert("scenario".into(), scenario_file.into());
    let mut per: std::collections::BTreeMap<String, Vec<f64>> = Default::default();
    for (k, v) in r.summary.iter() {
        match k
            .rsplit_once('_')
            .filter(|(_, i)| i.parse::<usize>().is_ok())
        {
            // one value per interface: an array under the base name
            Some((base, _)) => per.entry(base.to_string()).or_default().push(v),
            None => {
                obj.insert(k.to_string(), json_number(v));
            }
        }
    }
    for (k, v) in per {
        let key = match k.as_str() {
            "min_contact_pressure" => "min_contact_pressure_per_interface".to_string(),
            _ => k,
        };
        obj.insert(key, v.into_iter().map(json_number).collect());
    }
    let mut summary =
        serde_json::to_string_pretty(&serde_json::Value::Object(obj)).unwrap_or_default();
    summary.push('\n');
    let f = &r.frf;
    let frf = csv_columns(
        FRF_HEADER,
        &[
            &f.frequency,
            &f.receptance,
            &f.phase,
            &f.accelerance,
            &f.force_db,
        ],
    );
    let mut header = String::from("t,force,displacement,acceleration");
    let mut cols: Vec<&[f64]> = vec![&r.t, &r.force, &r.displacement, &r.acceleration];
    for i in 0..r.gap.len() {
        header.push_str(&format!(",gap_{i},pressure_{i},beta_{i},stiffness_{i}"));
        cols.push(&r.gap[i]);
        cols.push(&r.pressure[i]);
        cols.push(&r.beta[i]);
        cols.push(&r.stiffness[i]);
    }
    let ts = time_series("timeseries.csv", &header, &cols, rows);
    let mut extra = Vec::new();
    if let Some(w) = &r.waves {
        let mut header = String::from("t,incident_displacement,reflected_displacement");
        let mut cols: Vec<&[f64]> = vec![&r.t, &w.incident, &w.reflected];
        if let Some(tr) = &w.transmitted {
            header.push_str(",transmitted_displacement");
            cols.push(tr);
        }
        extra.extend(time_series("waves.csv", &header, &cols, rows));
    }
    if let Some(sh) = &r.shear {
        extra.extend(shear_csv(r, sh, rows));
    }
    if !r.probes.is_empty() {
        let mut header = String::from("t");
        let mut cols: Vec<&[f64]> = vec![&r.t];
        for p in &r.probes {
            let n = &p.name;
            header.push_str(&format!(
                ",{n}_displacement,{n}_velocity,{n}_acceleration,{n}_stress"
            ));
            cols.extend([
                &p.displacement[..],
                &p.velocity[..],
                &p.acceleration[..],
                &p.stress[..],
            ]);
            if let Some(q) = &p.shear {
                header.push_str(&format!(
                    ",{n}_shear_displacement,{n}_shear_velocity,{n}_shear_stress"
                ));
                cols.extend([&q.displacement[..], &q.velocity[..], &q.stress[..]]);
            }
        }
        extra.extend(time_series("probes.csv", &header, &cols, rows));
    }
    let mut files = vec![OutputFile {
        name: "summary.json".into(),
        contents: summary,
    }];
    if !f.frequency.is_empty() {
        files.push(OutputFile {
            name: "frf.csv".into(),
            contents: frf,
        });
        #[cfg(feature = "plot")]
        files.push(OutputFile {
            name: "frf.svg".into(),
            contents: frf_svg(r)?,
        });
    }
    files.extend(ts);
    files.extend(extra);
    Ok(files)
}

/// `shear.csv`: the shear waves at the ends (with a `[shear_incident]`) and, per
/// interface `i`, the tangential gap `shear_gap_i` (m), the contact shear stress
/// `shear_stress_i` (Pa), the slip `slip_i` (m) and the slider state `slip_state_i` (0
/// stick, +1 / -1 slipping, empty when free).
fn shear_csv(r: &BarStackResult, sh: &super::BarShear, rows: Rows) -> Option<OutputFile> {
    let mut header = String::from("t");
    let mut cols: Vec<&[f64]> = vec![&r.t];
    if let Some(w) = &sh.waves {
        header.push_str(",shear_incident_displacement,shear_reflected_displacement");
        cols.extend([&w.incident[..], &w.reflected[..]]);
        if let Some(tr) = &w.transmitted {
            header.push_str(",shear_transmitted_displacement");
            cols.push(tr);
        }
    }
    for i in 0..sh.gap.len() {
        header.push_str(&format!(
            ",shear_gap_{i},shear_stress_{i},slip_{i},slip_state_{i}"
        ));
        cols.extend([
            &sh.gap[i][..],
            &sh.stress[i][..],
            &sh.slip[i][..],
            &sh.state[i][..],
        ]);
    }
    time_series("shear.csv", &header, &cols, rows)
}

/// `frf.svg`: the accelerance `|A/F|` in dB re 1 (m/s^2)/N and the receptance `|X/F|` in
/// dB re 1 m/N against frequency (the phase, which wraps at every bin, is in frf.csv), a
/// dashed marker at the first mode `f1` (`first_mode_hz`). Only where the force carries
/// energy: bins with the force spectrum below [`super::FRF_FORCE_FLOOR_DB`] of its peak
/// are gaps, and the frequency axis ends at the last bin above it ([`super::Frf::band_limit`]).
#[cfg(feature = "plot")]
pub fn frf_svg(r: &BarStackResult) -> Result<String> {
    use crate::render::svg::{color, decimate_gaps, panel_with, render, scaled, Curve, PanelOpts};
    let f = &r.frf;
    let shown = f.frequency.partition_point(|v| *v <= f.band_limit());
    let (fs, fu) = scaled(&f.frequency[..shown], "Hz");
    let k = match (f.frequency[..shown].last(), fs.last()) {
        (Some(a), Some(b)) if *a > 0.0 => b / a,
        _ => 1.0,
    };
    let db = |v: &[f64]| -> Vec<f64> {
        v[..shown]
            .iter()
            .map(|a| if *a > 0.0 { 20.0 * a.log10() } else { f64::NAN })
            .collect()
    };
    let f1 = r
        .summary
        .iter()
        .find(|(key, _)| *key == "first_mode_hz")
        .map(|(_, v)| v)
        .filter(|v| v.is_finite() && *v > 0.0);
    let markers: Vec<f64> = f1.map(|v| v * k).into_iter().collect();
    let labels = vec!["f1".to_string()];
    let one = |y: &[f64]| {
        vec![Curve {
            label: String::new(),
            points: decimate_gaps(&fs, y),
            color: color(0),
        }]
    };
    let xlabel = format!(
        "frequency, {fu} (gaps: force spectrum below {} dB of its peak)",
        super::FRF_FORCE_FLOOR_DB
    );
    render("frf.svg", (900, 800), |root| {
        let areas = root.split_evenly((2, 1));
        panel_with(
            &areas[0],
            "Frequency response at the excited end (accelerance)",
            &xlabel,
            "|A/F|, dB re 1 (m/s^2)/N",
            &one(&db(&f.accelerance)),
            &markers,
            PanelOpts {
                marker_labels: &labels,
                ..Default::default()
            },
        )?;
        panel_with(
            &areas[1],
            "Receptance at the excited end",
            &xlabel,
            "|X/F|, dB re 1 m/N",
            &one(&db(&f.receptance)),
            &markers,
            PanelOpts {
                marker_labels: &labels,
                ..Default::default()
            },
        )
    })
}
