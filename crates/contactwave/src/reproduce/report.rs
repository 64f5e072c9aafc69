//! The files of `reproduce`: `report.html` (self-contained: inline SVG and CSS, no script,
//! no external resource), `findings.json`, and `figures/<id>.svg` + `figures/<id>.csv`.

use super::{Chapter, ChapterResult, Finding};
use crate::error::Result;
use crate::output::{write_files, OutputFile};
use std::path::{Path, PathBuf};

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The thesis the studies reproduce, cited in full.
pub const THESIS_CITATION: &str = "Dorra Nouira, Nonlinear interactions between US waves and \
     contact interface (Interactions non-linéaires des ondes ultrasonores et interface de \
     contact), PhD thesis, Université de Bordeaux (I2M) jointly with Sapienza University of \
     Rome, 2020 (defended 11 December 2020; theses.fr 2020BORD0262)";

/// `findings.json`: `{ key: value, ... }` over all chapters, plus `_details` with the
/// thesis statement, agreement, verdict (`agrees`, `differs`, `informational`) and the
/// value as the report shows it (`shown`: "below the floor" for round-off amplitudes).
pub fn findings_json(chapters: &[ChapterResult]) -> String {
    let mut values = serde_json::Map::new();
    let mut details = serde_json::Map::new();
    for c in chapters {
        for f in &c.findings {
            let v = if f.value.is_finite() {
                serde_json::json!(f.value)
            } else {
                serde_json::Value::Null
            };
            values.insert(f.key.clone(), v.clone());
            details.insert(
                f.key.clone(),
                serde_json::json!({
                    "value": v,
                    "unit": f.unit,
                    "thesis": f.thesis,
                    "agrees": f.agrees,
                    "note": f.note,
                    "chapter": c.chapter.name(),
                    "verdict": f.verdict(),
                    "informational": f.informational(),
                    "shown": f.shown_value(),
                }),
            );
        }
    }
    values.insert("_details".into(), serde_json::Value::Object(details));
    serde_json::to_string_pretty(&serde_json::Value::Object(values)).unwrap_or_default() + "\n"
}

/// The headline findings of a chapter's summary row: (key, what it is, the thesis' value).
fn headlines(chapter: Chapter) -> &'static [(&'static str, &'static str, &'static str)] {
    match chapter {
        Chapter::Three => &[
            ("uc_xi_opt", "unilateral A2 maximum at xi", "0.35"),
            (
                "ch3_stiffness_range_low_log10",
                "stiffness-sensitive range from C_N",
                "11",
            ),
            ("ch3_stiffness_range_high_log10", "to", "15"),
            ("rccm_beta_end_8_2MPa", "beta_end at A = 8.2 MPa", "0"),
        ],
        Chapter::Four => &[
            ("powerlaw_fit_m", "power-law exponent m", "0.35"),
            ("tribobrake_f1_hz_32N", "first mode at 32 N", "about 800 Hz"),
            (
                "tribobrake_f1_drop_mpl_percent",
                "its drop from 9 to 32 N, modified PL",
                "about 5 %",
            ),
        ],
        Chapter::Five => &[
            (
                "bilinear_max_rel_error",
                "bilinear law, numerical against analytical: largest relative error",
                "they agree",
            ),
            ("ch5_contact_loss_onset_xi", "contact loss from xi", "1"),
            (
                "ch5_unilateral_a2_max_xi",
                "unilateral A2 maximum at xi",
                "0.35",
            ),
        ],
        Chapter::Shear => &[
            (
                "shear_clip_A3_rel_error",
                "A3 of Coulomb clipping against its closed form: relative error",
                "closed form",
            ),
            (
                "shear_dissipation_fraction_max",
                "largest dissipated fraction",
                "closed form 0.4613",
            ),
        ],
        Chapter::FiniteCrack => &[
            (
                "finite_crack_length_within_5pct_signorini",
                "Signorini crack length (wavelengths) from which 2D is within 5 % of 1D",
                "plane interface",
            ),
            (
                "finite_crack_length_within_5pct_rccm",
                "RCCM crack length (wavelengths) from which 2D is within 5 % of 1D",
                "plane interface",
            ),
        ],
    }
}

/// The one-screen summary: per chapter what was reproduced (headline findings), what
/// differs, and a verdict; the counts of the findings table.
fn summary_html(chapters: &[ChapterResult]) -> String {
    let all: Vec<&Finding> = chapters.iter().flat_map(|c| &c.findings).collect();
    let count = |v: &str| all.iter().filter(|f| f.verdict() == v).count();
    let mut h = String::from("<section id=\"summary\">\n<h2>Summary</h2>\n");
    h.push_str(&format!(
        "<p>{} of {} findings with a thesis value agree, {} differ; {} are informational \
         (no thesis number to compare with). The figures follow; the full \
         <a href=\"#findings\">findings table</a> is at the end.</p>\n",
        count("agrees"),
        count("agrees") + count("differs"),
        count("differs"),
        count("informational")
    ));
    h.push_str(
        "<table class=\"summary\">\n<tr><th>chapter</th><th>reproduced (here, thesis)</th>\
         <th>differs</th><th>verdict</th></tr>\n",
    );
    for c in chapters {
        let find = |k: &str| c.findings.iter().find(|f| f.key == k);
        let reproduced: Vec<String> = headlines(c.chapter)
            .iter()
            .filter_map(|(k, what, thesis)| {
                find(k).map(|f| format!("{what}: {} (thesis: {thesis})", f.shown_value()))
            })
            .collect();
        let differs: Vec<String> = c
            .findings
            .iter()
            .filter(|f| f.agrees == Some(false))
            .map(|f| {
                format!(
                    "<a href=\"#f-{}\"><code>{}</code></a>: {} (thesis {})",
                    esc(&f.key),
                    esc(&f.key),
                    esc(&f.shown_value()),
                    esc(&f.thesis)
                )
            })
            .collect();
        let compared = c.findings.iter().filter(|f| !f.informational()).count();
        let agree = c.findings.iter().filter(|f| f.agrees == Some(true)).count();
        let verdict = if differs.is_empty() {
            format!("reproduced ({agree} of {compared} agree)")
        } else {
            format!(
                "reproduced except {} ({agree} of {compared} agree)",
                differs.len()
            )
        };
        h.push_str(&format!(
            "<tr><td><a href=\"#{}\">{}</a></td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>\n",
            c.chapter.name(),
            esc(&c.title),
            esc(&reproduced.join("; ")),
            if differs.is_empty() {
                "nothing".to_string()
            } else {
                differs.join("<br>")
            },
            if differs.is_empty() { "ok" } else { "differs" },
            esc(&verdict)
        ));
    }
    h.push_str("</table>\n</section>\n");
    h
}

/// The report page. `svgs[i][j]` is the SVG of figure j of chapter i: the summary first,
/// then the chapters' figures, then the full findings table.
pub fn report_html(chapters: &[ChapterResult], svgs: &[Vec<String>], total_seconds: f64) -> String {
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>contactwave: reproduction of the thesis studies</title>\n<style>\n\
         body{font-family:sans-serif;max-width:980px;margin:0 auto;padding:.5em 1.5em;color:#222;line-height:1.4}\n\
         h1{font-size:1.5em;margin:.4em 0}h2{border-bottom:2px solid #ccc;padding-bottom:.2em;margin-top:1.5em}\n\
         #summary h2{margin-top:.6em}\n\
         figure{margin:1.5em 0;padding:.5em;border:1px solid #ddd;border-radius:4px}\n\
         figure svg{width:100%;height:auto;display:block}\n\
         .pictures{display:flex;flex-wrap:wrap;gap:.6em;margin-top:.5em}\n\
         .picture{flex:1 1 45%;min-width:280px}.picture img{width:100%;height:auto;display:block}\n\
         .picture .small{font-size:.85em;color:#333}\n\
         figcaption{font-size:.92em;color:#333}\n\
         .cmp{font-family:monospace;font-size:.88em;background:#f4f6f8;padding:.3em .5em;margin:.3em 0}\n\
         .differs{background:#fff3e0}.informational{color:#555}\n\
         table{border-collapse:collapse;font-size:.9em;margin:1em 0}\n\
         table.summary{font-size:.85em}\n\
         td,th{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top}\n\
         p.small{font-size:.85em;margin:.3em 0}\n\
         nav a{margin-right:1em}\n</style>\n</head>\n<body>\n",
    );
    h.push_str("<h1>contactwave: the studies of thesis chapters 3, 4 and 5, and beyond</h1>\n");
    h.push_str(&format!(
        "<p class=\"small\">Reproduces {}. Generated by <code>contactwave reproduce</code> \
         version {} in {:.1} s ({} simulations); each figure's data is in \
         <code>figures/&lt;id&gt;.csv</code>, the findings in <code>findings.json</code>; SI \
         units unless an axis says otherwise. A is the incident wave's stress amplitude, \
         sigma_i^max = 2 Z2/(Z1 + Z2) A its blocked stress peak (2A at a wall) and xi the load \
         ratio (p0 / sigma_i^max for rigid compression; docs/model.md section 1).</p>\n",
        esc(THESIS_CITATION),
        env!("CARGO_PKG_VERSION"),
        total_seconds,
        chapters.iter().map(|c| c.runs).sum::<usize>()
    ));
    h.push_str(&summary_html(chapters));
    h.push_str("<nav>");
    for c in chapters {
        h.push_str(&format!(
            "<a href=\"#{}\">{}</a>",
            c.chapter.name(),
            esc(&c.title)
        ));
    }
    h.push_str("<a href=\"#findings\">Findings</a></nav>\n");
    let mut n = 0;
    for (c, svg) in chapters.iter().zip(svgs) {
        h.push_str(&format!(
            "<h2 id=\"{}\">{}</h2>\n<p>{}</p>\n<p><small>{} figures, {} simulations, {:.1} s.</small></p>\n",
            c.chapter.name(),
            esc(&c.title),
            esc(&c.intro),
            c.figures.len(),
            c.runs,
            c.seconds
        ));
        for f in c.findings.iter().filter(|f| f.agrees == Some(false)) {
            h.push_str(&format!(
                "<div class=\"cmp differs\"><b>{}</b>: {}</div>\n",
                esc(&f.key),
                esc(&f.line())
            ));
        }
        for (fig, s) in c.figures.iter().zip(svg) {
            n += 1;
            let (title, thesis) = fig.title_and_thesis();
            h.push_str(&format!(
                "<figure id=\"{}\">\n{}\n<figcaption><b>Figure {n}. {}.</b> {}{} \
                 <small>(data: <code>figures/{}.csv</code>)</small>",
                esc(&fig.id),
                strip_xml_declaration(s),
                esc(&title),
                thesis
                    .map(|t| format!("Thesis {}. ", esc(&t)))
                    .unwrap_or_default(),
                esc(&fig.caption),
                esc(&fig.id)
            ));
            for line in &fig.comparisons {
                h.push_str(&format!("<div class=\"cmp\">{}</div>", esc(line)));
            }
            h.push_str("</figcaption>\n");
            if !fig.pictures.is_empty() {
                h.push_str("<div class=\"pictures\">\n");
                for p in &fig.pictures {
                    h.push_str(&picture_html(p));
                }
                h.push_str("</div>\n");
            }
            h.push_str("</figure>\n");
        }
    }
    h.push_str(&findings_table(chapters));
    h.push_str("</body>\n</html>\n");
    h
}

/// The full findings table (end of the report): one row per finding with its verdict;
/// informational rows say why they have none.
fn findings_table(chapters: &[ChapterResult]) -> String {
    let mut h = String::from(
        "<h2 id=\"findings\">Findings</h2>\n<p>Every measured value beside the thesis' \
         statement. Verdict: <b>agrees</b> or <b>differs</b> within the tolerance the thesis \
         row states; <b>informational</b> rows have no thesis number to compare with (values \
         beyond the thesis, properties of the analysis, or trends the thesis states without a \
         number): they are shown for context, the note says which. Amplitudes below the \
         analysis' resolution read \"below the floor\".</p>\n<table>\n<tr><th>key</th>\
         <th>thesis</th><th>here</th><th>verdict</th><th>note</th></tr>\n",
    );
    for c in chapters {
        for f in &c.findings {
            let note = match (f.why_informational(), f.note.as_str()) {
                ("", n) => n.to_string(),
                (w, "") => format!("informational: {w}"),
                (w, n) => format!("informational: {w}. {n}"),
            };
            h.push_str(&format!(
                "<tr id=\"f-{}\" class=\"{}\"><td><code>{}</code></td><td>{}</td><td>{}</td>\
                 <td>{}</td><td>{}</td></tr>\n",
                esc(&f.key),
                f.verdict(),
                esc(&f.key),
                esc(&f.thesis),
                esc(&f.shown_value()),
                f.verdict(),
                esc(&note)
            ));
        }
    }
    h.push_str("</table>\n");
    h
}

/// A picture as an inline image (a data URI: the page stays self-contained) with its
/// caption and file name.
fn picture_html(p: &super::Picture) -> String {
    use base64::Engine;
    let mime = if p.name.ends_with(".gif") {
        "image/gif"
    } else {
        "image/png"
    };
    format!(
        "<div class=\"picture\"><img alt=\"{}\" src=\"data:{mime};base64,{}\">\
         <div class=\"small\">{} <small>(<code>figures/{}</code>)</small></div></div>\n",
        esc(&p.caption),
        base64::engine::general_purpose::STANDARD.encode(&p.bytes),
        esc(&p.caption),
        esc(&p.name)
    )
}

fn strip_xml_declaration(svg: &str) -> &str {
    let s = svg.trim_start();
    if s.starts_with("<?xml") {
        s.find("?>").map(|i| &s[i + 2..]).unwrap_or(s)
    } else {
        s
    }
}

/// Write `report.html`, `findings.json` and `figures/*` into `dir`. Returns the paths.
pub fn write_report(
    dir: &Path,
    chapters: &[ChapterResult],
    total_seconds: f64,
) -> Result<Vec<PathBuf>> {
    write_report_with(dir, chapters, total_seconds, None)
}

/// [`write_report`] with `findings.json` carrying the `"provenance"` object of
/// `provenance` ([`crate::output::provenance`]) when given.
pub fn write_report_with(
    dir: &Path,
    chapters: &[ChapterResult],
    total_seconds: f64,
    provenance: Option<&crate::output::provenance::Provenance>,
) -> Result<Vec<PathBuf>> {
    let mut svgs = Vec::with_capacity(chapters.len());
    let mut fig_files = Vec::new();
    for c in chapters {
        let mut v = Vec::with_capacity(c.figures.len());
        for f in &c.figures {
            let svg = f.svg()?;
            fig_files.push(OutputFile {
                name: format!("{}.svg", f.id),
                contents: svg.clone(),
            });
            fig_files.push(OutputFile {
                name: format!("{}.csv", f.id),
                contents: f.csv(),
            });
            v.push(svg);
        }
        svgs.push(v);
    }
    let mut written = write_files(&dir.join("figures"), &fig_files)?;
    let pictures: Vec<crate::render::BinaryFile> = chapters
        .iter()
        .flat_map(|c| &c.figures)
        .flat_map(|f| &f.pictures)
        .map(|p| crate::render::BinaryFile {
            name: p.name.clone(),
            bytes: p.bytes.clone(),
        })
        .collect();
    written.extend(crate::output::write_binary_files(
        &dir.join("figures"),
        &pictures,
    )?);
    written.extend(write_files(
        dir,
        &[
            OutputFile {
                name: "report.html".into(),
                contents: report_html(chapters, &svgs, total_seconds),
            },
            OutputFile {
                name: "findings.json".into(),
                contents: match provenance {
                    Some(p) => p.stamp_json(&findings_json(chapters)),
                    None => findings_json(chapters),
                },
            },
        ],
    )?);
    Ok(written)
}
