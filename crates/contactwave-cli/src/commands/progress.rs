//! Progress of the long computations (`run`, `convergence`, `sweep`, `reproduce`), told
//! three ways:
//!
//! - on a terminal, a bar on stderr redrawn at most [`REDRAWS_PER_SECOND`] times a second
//!   (however often the work reports);
//! - in a log (stderr not a terminal: a file, a batch job), once the work has lasted
//!   [`LOG_AFTER`] (or `CONTACTWAVE_PROGRESS_AFTER` seconds), one line at each tenth,
//!   `progress: 40 % (838 of 2095 steps, 12 s elapsed, about 18 s left)`;
//! - on both, once, the time the whole work will take, from the rate measured over its
//!   first [`MEASURE`] (`time estimate: about 11 minutes in all, ...`), when that is over
//!   [`ANNOUNCE`]: no assumed machine speed, the machine's own under its load.
//!
//! What is said ([`Log`]) is computed from the times of the reports alone, the clock being
//! the caller's; [`Reporter`] holds the clock and the bar.

use contactwave::human;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Progress-bar template of the step-by-step computations (`run` of a bar stack or a 2D
/// scenario, `convergence`).
pub const STEPS_TEMPLATE: &str = "{bar:40} {pos}/{len}  {elapsed_precise} elapsed, eta {eta}";

/// Most redraws of a progress bar per second (a bar redrawn at every report of a fast
/// 2D run wrote 220 kB into a terminal's log in 24 s).
pub const REDRAWS_PER_SECOND: u8 = 10;

/// How long the work goes on before, without a terminal, it reports its progress in lines.
pub const LOG_AFTER: Duration = Duration::from_secs(10);

/// The environment variable that sets [`LOG_AFTER`], seconds (`0`: from the first tenth).
pub const LOG_AFTER_ENV: &str = "CONTACTWAVE_PROGRESS_AFTER";

/// Over how long the rate of the first steps (points, runs) is measured for the estimate.
pub const MEASURE: Duration = Duration::from_secs(2);

/// Work estimated shorter than this is not announced (the bar's or the lines' time left
/// says enough).
pub const ANNOUNCE: Duration = Duration::from_secs(60);

/// A progress bar of length `len` with the given template on stderr when it is a terminal,
/// redrawn at most [`REDRAWS_PER_SECOND`] times a second (hidden otherwise).
pub fn progress_bar(template: &str, len: u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let target = ProgressDrawTarget::stderr_with_hz(REDRAWS_PER_SECOND);
    let b = ProgressBar::with_draw_target(Some(len), target);
    if let Ok(style) = ProgressStyle::with_template(template) {
        b.set_style(style);
    }
    b
}

/// [`LOG_AFTER`], or the seconds of `CONTACTWAVE_PROGRESS_AFTER` (a number >= 0).
fn log_after() -> Duration {
    std::env::var(LOG_AFTER_ENV)
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map_or(LOG_AFTER, Duration::from_secs_f64)
}

/// A rate for a person: `36 steps/s`, `2.5 points/s`, under one a second the time each
/// takes (`25 s per run`).
fn rate(per_second: f64, unit: &str) -> String {
    if per_second >= 10.0 {
        format!("{per_second:.0} {unit}/s")
    } else if per_second >= 1.0 {
        format!("{per_second:.1} {unit}/s")
    } else {
        let one = unit.strip_suffix('s').unwrap_or(unit);
        format!("{} per {one}", human::duration(1.0 / per_second))
    }
}

/// What is said of one computation's progress: the lines to print, from the times and
/// counts of its reports.
#[derive(Debug, Clone)]
pub struct Log {
    /// What is counted (`steps`, `points`, `runs`).
    unit: &'static str,
    /// The current stage's name (`reproduce`'s study), empty for none.
    label: String,
    /// From when progress lines are written (in a log).
    after: Duration,
    /// The first report of the current stage: its time and count.
    first: Option<(Duration, usize)>,
    /// The last tenth a line was written for.
    tenth: usize,
    /// Whether the stage's estimate was made.
    estimated: bool,
}

impl Log {
    /// A log of `unit` whose progress lines start once the work has lasted `after`.
    pub fn new(unit: &'static str, after: Duration) -> Self {
        Log {
            unit,
            label: String::new(),
            after,
            first: None,
            tenth: 0,
            estimated: false,
        }
    }

    /// A new stage named `label` (`reproduce`'s next study): its own rate, tenths and
    /// estimate, its lines named.
    pub fn restart(&mut self, label: &str) {
        self.label = label.to_string();
        self.first = None;
        self.tenth = 0;
        self.estimated = false;
    }

    /// The lines to print for the report of `done` of `total` at `now` (since the work
    /// began): the time estimate, once, after [`MEASURE`] of the stage; and, `in_log`, a
    /// progress line at each new tenth once `now` is past `after`.
    pub fn lines(&mut self, now: Duration, done: usize, total: usize, in_log: bool) -> Vec<String> {
        let mut out = Vec::new();
        if total == 0 {
            return out;
        }
        let done = done.min(total);
        let (t0, d0) = *self.first.get_or_insert((now, done));
        let measured = now.saturating_sub(t0);
        // units per second since the stage's first report
        let per_second = if done > d0 && !measured.is_zero() {
            (done - d0) as f64 / measured.as_secs_f64()
        } else {
            f64::NAN
        };
        let left = (total - done) as f64 / per_second;
        let label = if self.label.is_empty() {
            String::new()
        } else {
            format!("{}: ", self.label)
        };
        if !self.estimated && measured >= MEASURE && per_second > 0.0 {
            self.estimated = true;
            let whole = now.as_secs_f64() + left;
            if done < total && whole >= ANNOUNCE.as_secs_f64() {
                out.push(format!(
                    "time estimate: {label}about {} in all, {} left ({total} {} at {}, the \
                     rate of the first {})",
                    human::duration(whole),
                    human::duration(left),
                    self.unit,
                    rate(per_second, self.unit),
                    human::duration(measured.as_secs_f64()),
                ));
            }
        }
        let tenth = (done * 10 / total).min(9);
        if in_log && tenth > self.tenth && now >= self.after {
            self.tenth = tenth;
            let eta = if left.is_finite() {
                format!(", about {} left", human::duration(left))
            } else {
                String::new()
            };
            out.push(format!(
                "progress: {label}{} % ({done} of {total} {}, {} elapsed{eta})",
                tenth * 10,
                self.unit,
                human::duration(now.as_secs_f64()),
            ));
        }
        out
    }
}

/// What a computation reports its progress `(done, total)` to: the bar of
/// [`progress_bar`] (moved at most [`REDRAWS_PER_SECOND`] times a second), the lines of a
/// [`Log`] on stderr (above the bar on a terminal).
#[derive(Debug)]
pub struct Reporter {
    bar: ProgressBar,
    /// Whether the bar is hidden (stderr is no terminal): the progress lines are written.
    in_log: bool,
    start: Instant,
    state: Mutex<State>,
}

#[derive(Debug)]
struct State {
    log: Log,
    /// When the bar was last moved.
    drawn: Option<Instant>,
    /// The bar's length as last set.
    len: Option<u64>,
}

impl Reporter {
    /// A reporter of `unit` (`steps`, `points`, `runs`) to `bar`, its clock started now.
    pub fn new(bar: &ProgressBar, unit: &'static str) -> Arc<Self> {
        Arc::new(Reporter {
            bar: bar.clone(),
            in_log: bar.is_hidden(),
            start: Instant::now(),
            state: Mutex::new(State {
                log: Log::new(unit, log_after()),
                drawn: None,
                len: None,
            }),
        })
    }

    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// `done` of `total` are done.
    pub fn report(&self, done: usize, total: usize) {
        let now = Instant::now();
        let mut s = self.state();
        for line in s.log.lines(now - self.start, done, total, self.in_log) {
            self.say(&line);
        }
        if self.in_log {
            return;
        }
        let redraw = Duration::from_secs(1) / u32::from(REDRAWS_PER_SECOND);
        let due = s.drawn.is_none_or(|t| now - t >= redraw) || done >= total;
        if due {
            if s.len != Some(total as u64) {
                s.len = Some(total as u64);
                self.bar.set_length(total as u64);
            }
            self.bar.set_position(done as u64);
            s.drawn = Some(now);
        }
    }

    /// A new stage named `label` (`reproduce`'s next study): the bar shows it from the
    /// start, the log measures it afresh.
    pub fn stage(&self, label: &str) {
        let mut s = self.state();
        s.log.restart(label);
        s.len = None;
        s.drawn = None;
        self.bar.set_message(label.to_string());
        self.bar.reset_elapsed();
    }

    /// Write `line` on stderr: above the bar on a terminal.
    pub fn say(&self, line: &str) {
        if self.in_log {
            eprintln!("{line}");
        } else {
            self.bar.println(line);
        }
    }
}

/// [`Reporter::report`] of `steps` to `bar`, as the closure the solvers call.
pub fn step_reporter(bar: &ProgressBar) -> impl Fn(usize, usize) + Send + Sync + 'static {
    let r = Reporter::new(bar, "steps");
    move |done: usize, total: usize| r.report(done, total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    fn secs(s: f64) -> Duration {
        Duration::from_secs_f64(s)
    }

    /// The estimate comes from the rate the work keeps, measured over its first seconds:
    /// 24000 steps at 36 steps/s (a loaded machine, not the 1e8 node-updates/s a nominal
    /// rate assumes) take about 11 minutes, said once, in minutes.
    #[test]
    fn the_estimate_is_the_measured_rate_of_the_first_steps() {
        let mut log = Log::new("steps", LOG_AFTER);
        let (total, per_second) = (24_000, 36.0);
        let mut said = Vec::new();
        // the first report at 0.5 s (the plan built), then one every 64 steps
        for k in 0..total / 64 {
            let done = k * 64;
            let now = secs(0.5 + done as f64 / per_second);
            said.extend(log.lines(now, done, total, false));
        }
        assert_eq!(said.len(), 1, "{said:?}");
        let s = &said[0];
        assert!(
            s.starts_with("time estimate: about 11 minutes in all, 11 minutes left"),
            "{s}"
        );
        assert!(
            s.contains("(24000 steps at 36 steps/s, the rate of the first 3.6 s)"),
            "{s}"
        );
        assert_eq!(rate(0.04, "runs"), "25 s per run");
        // a run estimated under a minute is not announced
        let mut log = Log::new("steps", LOG_AFTER);
        let quick: Vec<String> = (0..40)
            .flat_map(|k| log.lines(secs(k as f64), k * 10, 400, false))
            .collect();
        assert!(quick.is_empty(), "{quick:?}");
    }

    /// In a log, each tenth past `after` has a line with the time left (none on a
    /// terminal, where the bar shows it); long times read in hours or days.
    #[test]
    fn log_lines_give_the_time_left() {
        let mut log = Log::new("points", Duration::ZERO);
        let lines: Vec<String> = (0..=20)
            .flat_map(|k| log.lines(secs(30.0 * k as f64), k, 20, true))
            .collect();
        let progress: Vec<&String> = lines
            .iter()
            .filter(|l| l.starts_with("progress:"))
            .collect();
        assert_eq!(progress.len(), 9, "{lines:?}");
        assert_eq!(
            progress[3],
            "progress: 40 % (8 of 20 points, 4 minutes elapsed, about 6 minutes left)"
        );
        // 30 s a point over a thousand points: hours, then the last tenth
        let mut log = Log::new("points", Duration::ZERO);
        let l = log.lines(secs(0.0), 0, 10_000, true);
        assert!(l.is_empty(), "{l:?}");
        let l = log.lines(secs(30.0 * 1000.0), 1000, 10_000, true);
        let line = "progress: 10 % (1000 of 10000 points, 8.3 hours elapsed, about 3.1 days left)";
        assert!(l.iter().any(|x| x == line), "{l:?}");
        // a stage's lines are named, its rate measured afresh
        log.restart("fig 3.4");
        let l = log.lines(secs(40_000.0), 0, 4, true);
        assert!(l.is_empty(), "{l:?}");
        let l = log.lines(secs(40_010.0), 2, 4, true);
        assert!(
            l.iter().any(|x| x
                == "progress: fig 3.4: 50 % (2 of 4 points, 11.1 hours elapsed, about 10 s left)"),
            "{l:?}"
        );
        // on a terminal: no progress line
        let mut log = Log::new("steps", Duration::ZERO);
        assert!((0..=10).all(|k| log.lines(secs(k as f64), k, 10, false).is_empty()));
        // not before `after`
        let mut log = Log::new("steps", secs(10.0));
        assert!(log.lines(secs(1.0), 0, 10, true).is_empty());
        assert!(log.lines(secs(2.0), 5, 10, true).is_empty());
        assert_eq!(log.lines(secs(11.0), 6, 10, true).len(), 1);
    }

    /// A terminal that counts what the bar draws.
    #[derive(Debug, Default)]
    struct Counting(Arc<AtomicUsize>);

    impl indicatif::TermLike for Counting {
        fn width(&self) -> u16 {
            80
        }
        fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
            Ok(())
        }
        fn write_line(&self, _: &str) -> std::io::Result<()> {
            Ok(())
        }
        fn write_str(&self, _: &str) -> std::io::Result<()> {
            Ok(())
        }
        fn clear_line(&self) -> std::io::Result<()> {
            Ok(())
        }
        fn flush(&self) -> std::io::Result<()> {
            self.0.fetch_add(1, Ordering::SeqCst);
            Ok(())
        }
    }

    /// However often a run reports (here as fast as it can, for 0.3 s), its bar is
    /// redrawn at most ten times a second.
    #[test]
    fn the_bar_is_redrawn_at_most_ten_times_a_second() {
        let draws = Arc::new(AtomicUsize::new(0));
        let target = ProgressDrawTarget::term_like(Box::new(Counting(draws.clone())));
        let bar = ProgressBar::with_draw_target(Some(0), target);
        let report = step_reporter(&bar);
        let start = Instant::now();
        let (mut done, total) = (0, 1 << 40);
        while start.elapsed() < Duration::from_millis(300) {
            report(done, total);
            done += 64;
        }
        let seconds = start.elapsed().as_secs_f64();
        let n = draws.load(Ordering::SeqCst);
        assert!(done > 10_000, "{done} reports");
        assert!(
            n as f64 <= 3.0 + seconds * f64::from(REDRAWS_PER_SECOND),
            "{n} draws in {seconds} s"
        );
    }
}
