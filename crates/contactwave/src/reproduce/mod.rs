//! `contactwave reproduce`: the studies of thesis chapters 3, 4 and 5, and a chapter beyond
//! the thesis on shear waves and friction, from embedded scenarios, as figures (SVG + CSV),
//! measured findings set beside the thesis' values, and a self-contained HTML report.
//!
//! Each chapter is one module (`chapter3.rs`, `chapter4.rs`, `chapter5/`, `shear.rs`) that
//! turns the embedded base scenarios (`examples/thesis/*.toml`, `examples/shear/*.toml`,
//! compiled into the binary) into a
//! [`ChapterResult`]: figures whose data are [`Panel`]s of curves, and [`Finding`]s with
//! stable keys (written to `findings.json`). Runs go through the same engine as
//! `contactwave run` and `sweep` ([`crate::simulate`], [`crate::simulate_summary`],
//! [`crate::simulate_bar_stack`]), in parallel (rayon). [`write_report`] renders the files.
//!
//! ```no_run
//! use contactwave::reproduce::{run_chapter, write_report, Chapter};
//! let r = run_chapter(Chapter::Four, &|_study: &str, _done: usize, _total: usize| {}).unwrap();
//! write_report(std::path::Path::new("results"), &[r], 1.0).unwrap();
//! ```

mod chapter3;
mod chapter4;
mod chapter5;
mod finite_crack;
mod oblique;
mod report;
mod shear;

pub use report::{findings_json, report_html, write_report, write_report_with, THESIS_CITATION};

use crate::analysis::Summary;
use crate::error::{Error, Result};
use crate::model;
use crate::output::plot::{figure, Panel};
use crate::run::{Executor, Observer};
use crate::scenario::{parse_toml, set_dotted, Scenario};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The base scenarios of the studies, embedded in the binary (also shipped under
/// `examples/thesis/` so that users can start from them).
pub const SCENARIOS: &[(&str, &str)] = &[
    (
        "ch3_rccm.toml",
        include_str!("../../../../examples/thesis/ch3_rccm.toml"),
    ),
    (
        "ch3_unilateral.toml",
        include_str!("../../../../examples/thesis/ch3_unilateral.toml"),
    ),
    (
        "ch4_tribobrake.toml",
        include_str!("../../../../examples/tribobrake.toml"),
    ),
    (
        "ch5_bilinear.toml",
        include_str!("../../../../examples/thesis/ch5_bilinear.toml"),
    ),
    (
        "ch5_modified_pl.toml",
        include_str!("../../../../examples/thesis/ch5_modified_pl.toml"),
    ),
    (
        "shear_clipping.toml",
        include_str!("../../../../examples/shear/clipping.toml"),
    ),
    (
        "shear_rccm.toml",
        include_str!("../../../../examples/shear/rccm_shear.toml"),
    ),
    (
        "oblique_p.toml",
        include_str!("../../../../examples/oblique/p_45deg.toml"),
    ),
];

/// Thesis Table 2 (Al-Al contact stiffness against pressure), embedded.
pub const TABLE2_CSV: &str =
    include_str!("../../../../examples/thesis/table2_contact_stiffness.csv");

/// A thesis chapter whose studies `reproduce` runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Chapter {
    /// RCCM adhesion at 1 MHz in PMMA (half-space, exact solver).
    Three,
    /// The Tribobrake bench (bar stack, FRFs).
    Four,
    /// Nonlinear compression with adhesion at 5 kHz in PMMA (both solvers, analytic).
    Five,
    /// Beyond the thesis: shear waves at frictional and full RCCM interfaces (aluminium,
    /// 1 MHz, exact coupled solver, closed forms of the clipping problem).
    Shear,
    /// Beyond the thesis: finite cracks in 2D (spectral elements), against the plane
    /// interface of the exact 1D solver.
    FiniteCrack,
}

impl Chapter {
    /// All chapters, in order.
    pub const ALL: [Chapter; 5] = [
        Chapter::Three,
        Chapter::Four,
        Chapter::Five,
        Chapter::Shear,
        Chapter::FiniteCrack,
    ];

    /// `chapter3`, `chapter4`, `chapter5`, `shear`, `finite_crack`.
    pub fn name(self) -> &'static str {
        match self {
            Chapter::Three => "chapter3",
            Chapter::Four => "chapter4",
            Chapter::Five => "chapter5",
            Chapter::Shear => "shear",
            Chapter::FiniteCrack => "finite_crack",
        }
    }

    /// Parse `chapter3` | `chapter4` | `chapter5` | `shear` | `finite_crack` | `all`.
    pub fn parse_list(s: &str) -> Result<Vec<Chapter>> {
        match s {
            "all" => Ok(Chapter::ALL.to_vec()),
            "chapter3" => Ok(vec![Chapter::Three]),
            "chapter4" => Ok(vec![Chapter::Four]),
            "chapter5" => Ok(vec![Chapter::Five]),
            "shear" => Ok(vec![Chapter::Shear]),
            "finite_crack" => Ok(vec![Chapter::FiniteCrack]),
            other => Err(Error::invalid(
                "<command line>",
                "chapter",
                other,
                "chapter3, chapter4, chapter5, shear, finite_crack or all",
            )),
        }
    }
}

/// A figure of the report: panels of curves, a caption stating its parameters, and lines
/// comparing with the thesis.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File stem, unique in the report (`ch3_fig32_a2_vs_xi`): `<id>.svg`, `<id>.csv`.
    pub id: String,
    /// Title, with the thesis figures it reproduces as `... (thesis Figures 23-24)` or
    /// `Figure 81: ...` (the report moves them into the caption: its own number is the
    /// figure's only one).
    pub title: String,
    /// Caption: what is plotted and the parameters.
    pub caption: String,
    /// The data.
    pub panels: Vec<Panel>,
    /// "thesis: ... / here: ..." lines.
    pub comparisons: Vec<String>,
    /// Raster pictures shown after the plot (wavefield snapshots, their GIF, a crack's
    /// state map): written as `figures/<name>` and embedded in the page.
    pub pictures: Vec<Picture>,
}

/// A raster picture of a figure (PNG or GIF).
#[derive(Debug, Clone)]
pub struct Picture {
    /// File name under `figures/` (`<figure id>_<what>.png`).
    pub name: String,
    /// The encoded image.
    pub bytes: Vec<u8>,
    /// What it shows (the page's `alt` text and the picture's caption).
    pub caption: String,
}

impl Figure {
    /// A figure with no comparison lines.
    pub fn new(id: &str, title: &str, caption: String, panels: Vec<Panel>) -> Figure {
        Figure {
            id: id.into(),
            title: title.into(),
            caption,
            panels,
            comparisons: Vec::new(),
            pictures: Vec::new(),
        }
    }

    /// The title without the thesis figure numbers, and these (`Figures 23-24`,
    /// `chapter 1, Figure 5`), from a title `... (thesis Figures 23-24)` or
    /// `Figures 78 and 80: ...`.
    pub fn title_and_thesis(&self) -> (String, Option<String>) {
        let t = self.title.trim();
        if let Some(rest) = t.strip_suffix(')')
            && let Some(i) = rest.rfind(" (thesis ")
        {
            return (rest[..i].to_string(), Some(rest[i + 9..].to_string()));
        }
        if t.starts_with("Figure")
            && let Some((refs, rest)) = t.split_once(": ")
            && refs.chars().any(|c| c.is_ascii_digit())
        {
            let mut c = rest.chars();
            let title = match c.next() {
                Some(f) => f.to_uppercase().chain(c).collect(),
                None => String::new(),
            };
            return (title, Some(refs.to_string()));
        }
        (t.to_string(), None)
    }

    /// Add a "thesis: ... / here: ..." line.
    pub fn compare(mut self, line: String) -> Figure {
        self.comparisons.push(line);
        self
    }

    /// The SVG of the figure.
    pub fn svg(&self) -> Result<String> {
        figure(&format!("{}.svg", self.id), 900, &self.panels)
    }

    /// Its data in long form: `panel,series,x_label,x,y_label,y` (one row per point).
    pub fn csv(&self) -> String {
        let q = |s: &str| format!("\"{}\"", s.replace('"', "'"));
        let mut out = String::from("panel,series,x_label,x,y_label,y\n");
        for p in &self.panels {
            for s in &p.series {
                for (x, y) in &s.points {
                    out.push_str(&format!(
                        "{},{},{},{:e},{},{:e}\n",
                        q(&p.title),
                        q(&s.label),
                        q(&p.xlabel),
                        x,
                        q(&p.ylabel),
                        y
                    ));
                }
            }
        }
        out
    }
}

/// A measured value set beside the thesis' statement.
#[derive(Debug, Clone)]
pub struct Finding {
    /// Stable key of `findings.json`.
    pub key: String,
    /// Measured value (SI units, or as named in `unit`).
    pub value: f64,
    /// Unit of the value (`Hz`, `%`, `Pa^(1-m)/m`, `` for dimensionless).
    pub unit: String,
    /// What the thesis states.
    pub thesis: String,
    /// Whether the value lies within the tolerance the report states (`None`: the thesis
    /// gives no number to compare with).
    pub agrees: Option<bool>,
    /// Where it differs: by how much and why.
    pub note: String,
    /// For an amplitude (or an amplitude above a floor): the resolution of the analysis.
    /// A value below it (round-off, or a negative difference to the floor) is reported as
    /// "below the floor", never as a number.
    pub floor: Option<f64>,
}

/// The resolution of harmonic amplitude ratios (`A_n/A_inc`, `A_n/A_1`, and these above the
/// incident burst's own content): values below it are round-off of the analysis.
pub const AMPLITUDE_FLOOR: f64 = 1e-6;

impl Finding {
    /// Mark the value as an amplitude with resolution `floor` (see [`Finding::floor`]).
    pub fn with_floor(mut self, floor: f64) -> Finding {
        self.floor = Some(floor);
        self
    }

    /// Informational: the thesis gives no number to compare with (no verdict).
    pub fn informational(&self) -> bool {
        self.agrees.is_none()
    }

    /// `agrees`, `differs` or `informational`.
    pub fn verdict(&self) -> &'static str {
        match self.agrees {
            Some(true) => "agrees",
            Some(false) => "differs",
            None => "informational",
        }
    }

    /// Why an informational finding has no verdict (empty for the others).
    pub fn why_informational(&self) -> &'static str {
        if !self.informational() {
            ""
        } else if self.thesis.starts_with("(not in the thesis)") {
            "beyond the thesis: shown for context, no thesis value to compare with"
        } else if self.thesis.starts_with("(no thesis value)") {
            "a property of the analysis (no thesis value), used by other findings"
        } else {
            "the thesis states a trend without a number; the value is shown for context"
        }
    }

    /// The value as the report shows it: 4 significant digits and the unit, or "below the
    /// floor (< f)" for an amplitude under its resolution.
    pub fn shown_value(&self) -> String {
        match self.floor {
            Some(fl) if self.value.is_finite() && self.value < fl => {
                format!("below the floor (< {fl:.0e})")
            }
            _ if self.unit.is_empty() => fmt_value(self.value),
            _ => format!("{} {}", fmt_value(self.value), self.unit),
        }
    }

    /// The "thesis: ... / here: ..." line of the report.
    pub fn line(&self) -> String {
        let mut s = format!("thesis: {} / here: {}", self.thesis, self.shown_value());
        match self.agrees {
            Some(true) => s.push_str(" (agrees)"),
            Some(false) => s.push_str(" (differs)"),
            None => s.push_str(" (informational)"),
        }
        if !self.note.is_empty() {
            s.push_str(" — ");
            s.push_str(&self.note);
        }
        s
    }
}

/// A number with 4 significant digits.
pub fn fmt_value(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    // the decimal exponent of the value rounded to 4 digits (0.99999 rounds to 1.000, not
    // to the five digits of 1.0000 that the exponent of 0.99999 itself would give)
    let rounded = format!("{:.3e}", v.abs());
    let exponent: i32 = rounded
        .split_once('e')
        .and_then(|(_, e)| e.parse().ok())
        .unwrap_or(0);
    if (-3..5).contains(&exponent) {
        let digits = (3 - exponent).clamp(0, 6) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// The result of a chapter.
#[derive(Debug, Clone)]
pub struct ChapterResult {
    /// Which chapter.
    pub chapter: Chapter,
    /// Section title.
    pub title: String,
    /// A paragraph on the setting (material, frequency, laws).
    pub intro: String,
    /// Figures, in order.
    pub figures: Vec<Figure>,
    /// Findings, in order.
    pub findings: Vec<Finding>,
    /// Wall time, s.
    pub seconds: f64,
    /// Simulations run.
    pub runs: usize,
}

/// Progress callback: `(study, done, total)`.
pub type Progress<'a> = &'a (dyn Fn(&str, usize, usize) + Sync);

/// Run one chapter's studies at the default resolution.
pub fn run_chapter(chapter: Chapter, progress: Progress) -> Result<ChapterResult> {
    run_chapter_at(chapter, false, progress)
}

/// Run one chapter's studies; `quick`: the coarser resolution and fewer points of the
/// chapters that have one (`finite_crack`: `contactwave reproduce --quick`, the one CI
/// runs); the other chapters run alike either way.
pub fn run_chapter_at(chapter: Chapter, quick: bool, progress: Progress) -> Result<ChapterResult> {
    let t0 = std::time::Instant::now();
    let ctx = Ctx {
        progress,
        runs: AtomicUsize::new(0),
    };
    let mut r = match chapter {
        Chapter::Three => chapter3::run(&ctx)?,
        Chapter::Four => chapter4::run(&ctx)?,
        Chapter::Five => chapter5::run(&ctx)?,
        Chapter::Shear => shear::run(&ctx)?,
        Chapter::FiniteCrack => finite_crack::run(&ctx, finite_crack::Resolution { quick })?,
    };
    r.seconds = t0.elapsed().as_secs_f64();
    r.runs = ctx.runs.load(Ordering::SeqCst);
    Ok(r)
}

/// Shared state of a chapter's run.
pub(crate) struct Ctx<'a> {
    progress: Progress<'a>,
    runs: AtomicUsize,
}

/// A variant of a base scenario: dotted keys and their values.
pub(crate) type Edits = Vec<(&'static str, toml::Value)>;

/// A float TOML value.
pub(crate) fn f(v: f64) -> toml::Value {
    toml::Value::Float(v)
}

/// A TOML inline table from `key = value` text (e.g. a contact law).
pub(crate) fn tv(text: &str) -> toml::Value {
    // callers pass literal, valid TOML; an invalid literal is a programming error caught
    // by the tests, reported as an empty table rather than a panic
    toml::from_str::<toml::Table>(&format!("v = {text}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::Table(toml::Table::new()))
}

impl Ctx<'_> {
    /// The embedded base scenario `name`.
    pub(crate) fn base(&self, name: &str) -> Result<toml::Table> {
        let text = SCENARIOS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
            .ok_or_else(|| {
                Error::invalid("<embedded>", "scenario", name, "an embedded scenario")
            })?;
        parse_toml(text, &format!("examples/thesis/{name}"))
    }

    /// Apply the edits to a copy of the base table.
    pub(crate) fn table(&self, base: &toml::Table, edits: &Edits) -> Result<toml::Table> {
        let mut t = base.clone();
        for (k, v) in edits {
            set_dotted(&mut t, k, v.clone())?;
        }
        Ok(t)
    }

    /// A half-space scenario from a base and edits.
    pub(crate) fn scenario(&self, base: &toml::Table, edits: &Edits) -> Result<Scenario> {
        Scenario::from_table(self.table(base, edits)?, Path::new("<reproduce>"))
    }

    /// Run `f` over `items` in parallel with progress under `study`; the first error wins.
    pub(crate) fn map<T: Sync, R: Send>(
        &self,
        study: &str,
        items: &[T],
        f: impl Fn(&T) -> Result<R> + Sync,
    ) -> Result<Vec<R>> {
        let observer = StudyProgress { ctx: self, study };
        Executor::new()
            .map(items, f, &observer)?
            .into_iter()
            .map(|r| r.unwrap_or(Err(Error::Interrupted)))
            .collect()
    }

    /// Summaries of the variants of `base` (half-space or bar stack), in parallel.
    pub(crate) fn summaries(
        &self,
        study: &str,
        base: &toml::Table,
        variants: &[Edits],
    ) -> Result<Vec<Summary>> {
        self.map(study, variants, |e| {
            model::plan(self.table(base, e)?, Path::new("<reproduce>"))
                .base()?
                .summary()
        })
    }
}

/// Reports a study's progress and counts its runs (the executor's observer).
struct StudyProgress<'a, 'b> {
    ctx: &'a Ctx<'b>,
    study: &'a str,
}

impl<R> Observer<R> for StudyProgress<'_, '_> {
    fn point(&self, _index: usize, _result: &Result<R>) -> Result<()> {
        self.ctx.runs.fetch_add(1, Ordering::SeqCst);
        Ok(())
    }

    fn progress(&self, done: usize, total: usize) {
        (self.ctx.progress)(self.study, done, total)
    }
}

/// The value of `key` in each summary (NaN where missing).
pub(crate) fn column(s: &[Summary], key: &str) -> Vec<f64> {
    s.iter().map(|x| x.get(key).unwrap_or(f64::NAN)).collect()
}

/// `n` evenly spaced values from `a` to `b`.
pub(crate) fn lin(a: f64, b: f64, n: usize) -> Vec<f64> {
    crate::study::linspace(a, b, n)
}

/// x of the maximum of a sampled curve, refined by a parabola through the largest sample
/// and its neighbours.
pub(crate) fn argmax_refined(x: &[f64], y: &[f64]) -> f64 {
    let Some(i) = (0..y.len())
        .filter(|&i| y[i].is_finite())
        .max_by(|&a, &b| y[a].total_cmp(&y[b]))
    else {
        return f64::NAN;
    };
    if i == 0 || i + 1 >= y.len() {
        return x[i];
    }
    let (x0, x1, x2) = (x[i - 1], x[i], x[i + 1]);
    let (y0, y1, y2) = (y[i - 1], y[i], y[i + 1]);
    let d = (x0 - x1) * (x0 - x2) * (x1 - x2);
    if d == 0.0 {
        return x1;
    }
    let a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / d;
    let b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / d;
    if a >= 0.0 {
        return x1;
    }
    (-b / (2.0 * a)).clamp(x0.min(x2), x0.max(x2))
}

/// A finding without a note: `key`, measured `value` (in `unit`), the thesis' statement and
/// whether they agree (`None`: no statement to compare with).
fn finding(key: &str, value: f64, unit: &str, thesis: &str, agrees: Option<bool>) -> Finding {
    Finding {
        key: key.into(),
        value,
        unit: unit.into(),
        thesis: thesis.into(),
        agrees,
        note: String::new(),
        floor: None,
    }
}

/// A figure panel without markers.
fn panel(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: Vec<crate::output::plot::Series>,
) -> crate::output::plot::Panel {
    crate::output::plot::Panel {
        title: title.into(),
        xlabel: xlabel.into(),
        ylabel: ylabel.into(),
        series,
        markers: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_scenarios_parse_and_argmax_refines() {
        let ctx = Ctx {
            progress: &|_, _, _| {},
            runs: AtomicUsize::new(0),
        };
        for (name, _) in SCENARIOS {
            let t = ctx.base(name).unwrap();
            model::plan(t, Path::new(name)).base().unwrap();
        }
        let x: Vec<f64> = (0..11).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = x.iter().map(|v| -(v - 0.37f64).powi(2)).collect();
        assert!((argmax_refined(&x, &y) - 0.37).abs() < 1e-12);
        assert!(matches!(tv("{ law = \"free\" }"), toml::Value::Table(_)));
    }

    /// Four significant digits on both sides of a power of ten, whatever the round-off:
    /// a value a hair below 1 and a hair above show alike.
    #[test]
    fn four_significant_digits_across_powers_of_ten() {
        for (v, s) in [
            (1.0000000000000022, "1.000"),
            (0.9999999999999998, "1.000"),
            (0.99996, "1.000"),
            (0.99994, "0.9999"),
            (-9.99996, "-10.00"),
            (12.345, "12.35"),
            (1234.4, "1234"),
            (99999.7, "1.000e5"),
            (0.001, "0.001000"),
            (0.00099999, "0.001000"),
            (0.0009994, "9.994e-4"),
            (0.0, "0"),
        ] {
            assert_eq!(fmt_value(v), s, "{v}");
        }
    }
}
