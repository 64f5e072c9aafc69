//! Numbers and durations as the messages a person reads show them (warnings, progress
//! lines, time estimates): short, free of the round-off of unit conversions, and in the
//! unit that reads best. (Sizes in bytes: [`crate::budget::human`]; an error's value is
//! shown as it was given: [`crate::Error::invalid`].)

/// Significant digits [`number`] keeps: more than any value typed into a scenario has,
/// fewer than the round-off of a unit conversion spoils (`"30 us"` is
/// 2.9999999999999997e-5 s).
pub const DIGITS: usize = 12;

/// A number as a message shows it: rounded to [`DIGITS`] significant digits and written as
/// short as it reads back, in exponent form where the decimal one would run to many zeros
/// (below 1e-4 or from 1e16 in magnitude).
///
/// ```
/// use contactwave::human::number;
/// assert_eq!(number(30.0 * 1e-6), "3e-5");            // not 0.000029999999999999997
/// assert_eq!(number(0.1 + 0.2), "0.3");
/// assert_eq!(number(0.082), "0.082");
/// assert_eq!(number(60.0), "60");
/// assert_eq!(number(1e6), "1000000");
/// assert_eq!(number(-2.5e17), "-2.5e17");
/// assert_eq!(number(f64::NAN), "NaN");
/// ```
pub fn number(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return v.to_string();
    }
    let r = format!("{v:.*e}", DIGITS - 1).parse().unwrap_or(v);
    if r.abs() < 1e-4 || r.abs() >= 1e16 {
        format!("{r:e}")
    } else {
        format!("{r}")
    }
}

/// A duration for a person, from `seconds`: `3.1 ms`, `850 ms`, `4.2 s`, `42 s`, `12 minutes`,
/// `3.5 hours`, `6.2 days`, `69 days` (never `100052 minutes`).
///
/// ```
/// use contactwave::human::duration;
/// assert_eq!(duration(0.85), "850 ms");
/// assert_eq!(duration(4.24), "4.2 s");
/// assert_eq!(duration(660.0), "11 minutes");
/// assert_eq!(duration(3.5 * 3600.0), "3.5 hours");
/// assert_eq!(duration(100052.0 * 60.0), "69 days");
/// ```
pub fn duration(seconds: f64) -> String {
    if seconds.is_nan() || seconds == f64::INFINITY {
        return "an unbounded time".to_string();
    }
    let s = seconds.max(0.0);
    let (minute, hour, day) = (60.0, 3600.0, 86400.0);
    if s < 0.01 {
        format!("{:.1} ms", s * 1e3)
    } else if s < 1.0 {
        format!("{:.0} ms", s * 1e3)
    } else if s < 10.0 {
        format!("{s:.1} s")
    } else if s < 1.5 * minute {
        format!("{s:.0} s")
    } else if s < 1.5 * hour {
        format!("{:.0} minutes", s / minute)
    } else if s < 2.0 * day {
        format!("{:.1} hours", s / hour)
    } else if s < 10.0 * day {
        format!("{:.1} days", s / day)
    } else {
        format!("{:.0} days", s / day)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every unit's edges read in the unit above once a value would round to it.
    #[test]
    fn durations_switch_units_where_they_read_best() {
        assert_eq!(duration(0.0), "0.0 ms");
        assert_eq!(duration(-1.0), "0.0 ms");
        assert_eq!(duration(0.0031), "3.1 ms");
        assert_eq!(duration(0.0123), "12 ms");
        assert_eq!(duration(9.96), "10.0 s");
        assert_eq!(duration(89.0), "89 s");
        assert_eq!(duration(90.0), "2 minutes");
        assert_eq!(duration(89.0 * 60.0), "89 minutes");
        assert_eq!(duration(90.0 * 60.0), "1.5 hours");
        assert_eq!(duration(47.0 * 3600.0), "47.0 hours");
        assert_eq!(duration(2.0 * 86400.0), "2.0 days");
        assert_eq!(duration(1e9), "11574 days");
        assert_eq!(duration(f64::INFINITY), "an unbounded time");
    }

    /// A number keeps what was typed and loses only the round-off (the 13th digit on).
    #[test]
    fn numbers_lose_only_the_round_off() {
        assert_eq!(number(0.25e-3 * 0.1), "2.5e-5");
        assert_eq!(number(0.1 * 3.0), "0.3");
        assert_eq!(number(2.9999999999999997e-5), "3e-5");
        assert_eq!(number(1.23456789012e-9), "1.23456789012e-9");
        assert_eq!(number(123456.7), "123456.7");
        assert_eq!(number(1e16), "1e16");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(f64::INFINITY), "inf");
    }
}
