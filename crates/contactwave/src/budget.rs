//! The memory budget: every command estimates what it is about to allocate (time samples x
//! recorded series, mesh nodes, sweep points, file lengths) and refuses, with an
//! [`Error::Invalid`] naming the key to change, the estimate and the limit, **before**
//! allocating. A failed allocation aborts the process (and a Python interpreter with it),
//! so nothing large is allocated unchecked.
//!
//! The budget is the environment variable `CONTACTWAVE_MEMORY_BUDGET` (bytes, with an
//! optional suffix `k`, `M`, `G` or `T`, powers of 1000: `CONTACTWAVE_MEMORY_BUDGET=8G`),
//! read at each check; by default half of the memory the machine has available
//! (`MemAvailable` of `/proc/meminfo`, 4 GB where it cannot be read). Whatever the budget,
//! an estimate above the machine's memory ([`machine_memory`]) is refused: a budget raised
//! beyond it (one copied from a larger machine's job script) names itself and the memory
//! the machine has.
//!
//! ```
//! use contactwave::budget;
//! // 1e3 samples of 4 series fit any budget; 1e15 samples fit none
//! assert!(budget::check("x.toml", "incident.cycles", 10, 1e3 * 4.0 * 8.0, "1e3 samples").is_ok());
//! let e = budget::check("x.toml", "incident.cycles", 1e9, 1e15 * 8.0, "1e15 samples").unwrap_err();
//! let msg = e.to_string();
//! assert!(msg.starts_with("x.toml: field `incident.cycles` = 1000000000: needs about 8 PB"));
//! assert!(msg.contains("CONTACTWAVE_MEMORY_BUDGET"));
//! ```

use crate::error::{Error, Result};
use std::path::Path;
use std::sync::OnceLock;

/// Name of the environment variable that sets the memory budget, bytes.
pub const ENV: &str = "CONTACTWAVE_MEMORY_BUDGET";

/// Budget when the available memory cannot be read, bytes.
pub const FALLBACK: f64 = 4e9;

/// Bytes one recorded sample of one series costs from the solver to the written file:
/// the `f64` itself, the derived series of the analysis and its text in a CSV file.
pub const BYTES_PER_SAMPLE: f64 = 64.0;

/// Half of the memory available now (`MemAvailable`, at most the [`machine_memory`]: a
/// container's limit), bytes; read once.
fn default_budget() -> f64 {
    static AVAILABLE: OnceLock<f64> = OnceLock::new();
    *AVAILABLE.get_or_init(|| {
        std::fs::read_to_string("/proc/meminfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find(|l| l.starts_with("MemAvailable:"))
                    .and_then(|l| l.split_whitespace().nth(1))
                    .and_then(|kb| kb.parse::<f64>().ok())
            })
            .map(|kb| 0.5 * (kb * 1024.0).min(machine_memory().unwrap_or(f64::INFINITY)))
            .filter(|b| *b > 0.0)
            .unwrap_or(FALLBACK)
    })
}

/// The memory of this machine, bytes: `MemTotal` of `/proc/meminfo`, or the limit of the
/// process's control group where it is lower (a container, a batch job's allocation);
/// `None` where neither can be read. Read once.
pub fn machine_memory() -> Option<f64> {
    static TOTAL: OnceLock<Option<f64>> = OnceLock::new();
    *TOTAL.get_or_init(|| {
        let total = std::fs::read_to_string("/proc/meminfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find(|l| l.starts_with("MemTotal:"))
                    .and_then(|l| l.split_whitespace().nth(1))
                    .and_then(|kb| kb.parse::<f64>().ok())
                    .map(|kb| kb * 1024.0)
            });
        // cgroup v2, then v1 ("max", or a v1 value of about 2^63, is no limit)
        let group = [
            "/sys/fs/cgroup/memory.max",
            "/sys/fs/cgroup/memory/memory.limit_in_bytes",
        ]
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .filter_map(|t| t.trim().parse::<f64>().ok())
        .find(|b| *b > 0.0 && *b < 1e18);
        match (total.filter(|b| *b > 0.0), group) {
            (Some(t), Some(g)) => Some(t.min(g)),
            (t, g) => t.or(g),
        }
    })
}

/// Parse a budget: a number of bytes with an optional suffix `k`, `M`, `G`, `T` (powers
/// of 1000), optionally followed by `B`.
///
/// ```
/// use contactwave::budget::parse;
/// assert_eq!(parse("512M"), Some(512e6));
/// assert_eq!(parse("2.5GB"), Some(2.5e9));
/// assert_eq!(parse("1e9"), Some(1e9));
/// assert_eq!(parse("-1"), None);
/// assert_eq!(parse("lots"), None);
/// ```
pub fn parse(text: &str) -> Option<f64> {
    let t = text.trim();
    let t = t.strip_suffix(['B', 'b']).unwrap_or(t);
    let (num, mult) = match t.chars().last()? {
        'k' | 'K' => (&t[..t.len() - 1], 1e3),
        'M' | 'm' => (&t[..t.len() - 1], 1e6),
        'G' | 'g' => (&t[..t.len() - 1], 1e9),
        'T' | 't' => (&t[..t.len() - 1], 1e12),
        _ => (t, 1.0),
    };
    let v = num.trim().parse::<f64>().ok()? * mult;
    (v.is_finite() && v > 0.0).then_some(v)
}

/// The memory budget, bytes: `CONTACTWAVE_MEMORY_BUDGET` if set, else half the available
/// memory. An unreadable value of the variable is an error naming it.
pub fn limit() -> Result<f64> {
    match std::env::var(ENV) {
        Ok(v) => parse(&v).ok_or_else(|| {
            Error::invalid(
                "<environment>",
                ENV,
                &v,
                "must be a number of bytes > 0, with an optional suffix k, M, G or T",
            )
        }),
        Err(_) => Ok(default_budget()),
    }
}

/// A size in bytes for a person: `1.6 TB`, `52 MB`.
pub fn human(bytes: f64) -> String {
    const UNITS: [&str; 7] = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    if !bytes.is_finite() {
        return "an unbounded amount".to_string();
    }
    let mut v = bytes.max(0.0);
    let mut u = 0;
    while v >= 1000.0 && u + 1 < UNITS.len() {
        v /= 1000.0;
        u += 1;
    }
    if u + 1 == UNITS.len() && v >= 1000.0 {
        return format!("{bytes:.1e} B");
    }
    if v >= 10.0 || u == 0 {
        format!("{v:.0} {}", UNITS[u])
    } else {
        format!("{v:.1} {}", UNITS[u]).replace(".0 ", " ")
    }
}

/// Refuse `bytes` (an estimate of what is about to be allocated, `what` says of what)
/// when it exceeds the budget: an [`Error::Invalid`] of `field` = `value` in `file`
/// giving the estimate, the limit and the key to change. A non-finite or negative estimate
/// is refused too.
pub fn check(
    file: &str,
    field: &str,
    value: impl std::fmt::Display,
    bytes: f64,
    what: &str,
) -> Result<()> {
    check_or(file, field, value, bytes, what, &format!("lower `{field}`"))
}

/// [`check`] naming `change` (e.g. `use a shorter file`) as the way out instead of
/// `lower FIELD`.
pub fn check_or(
    file: &str,
    field: &str,
    value: impl std::fmt::Display,
    bytes: f64,
    what: &str,
    change: &str,
) -> Result<()> {
    let limit = limit()?;
    let budget = match std::env::var(ENV) {
        Ok(v) => format!("{ENV}={v}"),
        Err(_) => human(limit),
    };
    refusal(bytes, limit, machine_memory(), &budget, what, change)
        .map_or(Ok(()), |why| Err(Error::invalid(file, field, value, why)))
}

/// Why `bytes` (what `what` needs) is refused under the budget `limit` (shown as `budget`)
/// on a machine of `machine` bytes, naming `change` as the way out; `None` if it is not.
fn refusal(
    bytes: f64,
    limit: f64,
    machine: Option<f64>,
    budget: &str,
    what: &str,
    change: &str,
) -> Option<String> {
    if !(bytes.is_finite() && bytes >= 0.0 && bytes <= limit) {
        return Some(format!(
            "needs about {} of memory ({what}), above the memory budget of {} ({change}, or raise the budget with {ENV}=BYTES)",
            human(bytes),
            human(limit)
        ));
    }
    // within a budget raised above what the machine has: it would swap or be killed
    match machine {
        Some(machine) if bytes > machine => Some(format!(
            "needs about {} of memory ({what}), above this machine's memory of {} (the \
             memory budget, {budget}, is above it): {change}, or run it on a machine with \
             more memory",
            human(bytes),
            human(machine),
        )),
        _ => None,
    }
}

/// Whether `bytes` fits the budget and the machine ([`check`] passes).
pub fn fits(bytes: f64) -> bool {
    check("", "", "", bytes, "").is_ok()
}

/// Refuse to read a file whose size on disk times `factor` (bytes of memory per byte of
/// text while it is parsed) exceeds the budget. A file that cannot be inspected passes
/// (reading it reports the error).
pub fn check_file(path: &Path, field: &str, factor: f64) -> Result<()> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(());
    };
    let len = meta.len() as f64;
    let shown = path.display().to_string();
    check_or(
        &shown,
        field,
        &shown,
        len * factor,
        &format!("a file of {} read into memory", human(len)),
        "use a shorter file",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_for_a_person() {
        assert_eq!(human(512.0), "512 B");
        assert_eq!(human(52e6), "52 MB");
        assert_eq!(human(1.6e12), "1.6 TB");
        assert_eq!(human(2e9), "2 GB");
    }

    /// A budget raised above the machine's memory lets nothing through that the machine
    /// cannot hold: the refusal names the budget as set and the machine's memory.
    #[test]
    fn a_budget_above_the_machine_is_no_licence() {
        let budget = "CONTACTWAVE_MEMORY_BUDGET=100G";
        let (limit, machine) = (100e9, Some(23e9));
        let why = refusal(48e9, limit, machine, budget, "a 2D mesh", "raise `h`").unwrap();
        assert_eq!(
            why,
            "needs about 48 GB of memory (a 2D mesh), above this machine's memory of 23 GB \
             (the memory budget, CONTACTWAVE_MEMORY_BUDGET=100G, is above it): raise `h`, or \
             run it on a machine with more memory"
        );
        // what the machine holds passes, and so does anything where its memory is unknown
        assert_eq!(refusal(20e9, limit, machine, budget, "m", "c"), None);
        assert_eq!(refusal(48e9, limit, None, budget, "m", "c"), None);
        // beyond the budget, the budget is named as before
        let why = refusal(200e9, limit, machine, budget, "m", "c").unwrap();
        assert!(why.contains("above the memory budget of 100 GB"), "{why}");
        // this machine has some memory, and the default budget is at most half of it
        if let Some(m) = machine_memory() {
            assert!(m > 1e6 && default_budget() <= 0.5 * m, "{m}");
        }
    }

    #[test]
    fn estimates_beyond_any_machine_are_refused() {
        assert!(check("f", "k", 1, f64::INFINITY, "x").is_err());
        assert!(check("f", "k", 1, f64::NAN, "x").is_err());
        assert!(check("f", "k", 1, 1e30, "x").is_err());
        assert!(check("f", "k", 1, 1e3, "x").is_ok());
    }
}
