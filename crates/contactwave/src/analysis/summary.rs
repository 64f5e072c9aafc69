//! The summary of a run: an ordered list of named scalars (the keys of `summary.json` and
//! the columns of `sweep.csv`).

use serde::ser::{Serialize, SerializeMap, Serializer};
use std::collections::HashMap;

/// Ordered named scalars. Units: see `docs/scenario.md` (outputs).
///
/// Keys are looked up through a hash index, so a run with tens of thousands of keys (a 2D
/// receiver line of 10 000 points writes eight keys a point) sets them in linear time.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    entries: Vec<(String, f64)>,
    /// Position of each key in `entries`.
    index: HashMap<String, usize>,
}

impl PartialEq for Summary {
    fn eq(&self, other: &Self) -> bool {
        self.entries == other.entries
    }
}

impl Summary {
    /// Empty summary.
    pub fn new() -> Self {
        Self::default()
    }
    /// Append or replace a value.
    pub fn set(&mut self, key: &str, value: f64) {
        if let Some(&i) = self.index.get(key) {
            self.entries[i].1 = value;
        } else {
            self.index.insert(key.to_string(), self.entries.len());
            self.entries.push((key.to_string(), value));
        }
    }
    /// Value of a key.
    pub fn get(&self, key: &str) -> Option<f64> {
        self.index.get(key).map(|&i| self.entries[i].1)
    }
    /// Rename `from` to `to` in place (its position kept), its value times `factor`;
    /// nothing if `from` is absent. An existing `to` elsewhere is removed (one value a key).
    pub fn rename(&mut self, from: &str, to: &str, factor: f64) {
        let Some(&i) = self.index.get(from) else {
            return;
        };
        self.entries[i].1 *= factor;
        if from == to {
            return;
        }
        self.entries[i].0 = to.to_string();
        if let Some(&j) = self.index.get(to) {
            self.entries.remove(j);
            self.reindex();
        } else {
            self.index.remove(from);
            self.index.insert(to.to_string(), i);
        }
    }
    /// Remove a key, if present.
    pub fn remove(&mut self, key: &str) {
        if self.index.remove(key).is_some() {
            self.entries.retain(|e| e.0 != key);
            self.reindex();
        }
    }
    fn reindex(&mut self) {
        self.index.clear();
        for (i, e) in self.entries.iter().enumerate() {
            self.index.insert(e.0.clone(), i);
        }
    }
    /// Keys in order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|e| e.0.as_str())
    }
    /// (key, value) pairs in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, f64)> {
        self.entries.iter().map(|e| (e.0.as_str(), e.1))
    }
}

/// A summary value as JSON: a whole number that a double holds exactly (below `2^53` in
/// magnitude: counts such as `nodes`, `steps` and `events`, codes such as
/// `analysis_method`) as an integer, so that `summary.json` writes `15708`, not `15708.0`;
/// other finite values as they are; non-finite ones `null`. The same value either way for
/// any JSON reader.
pub fn json_number(v: f64) -> serde_json::Value {
    match whole_number(v) {
        Some(i) => serde_json::Value::from(i),
        None => serde_json::Number::from_f64(v)
            .map_or(serde_json::Value::Null, serde_json::Value::Number),
    }
}

/// `v` as an integer when it is a whole number that a double holds exactly (below `2^53`
/// in magnitude, not `-0`): how `summary.json` and every CSV file write counts, codes and
/// states.
fn whole_number(v: f64) -> Option<i64> {
    const EXACT: f64 = 9_007_199_254_740_992.0; // 2^53
    let whole = v.fract() == 0.0 && v.abs() < EXACT && !(v == 0.0 && v.is_sign_negative());
    whole.then_some(v as i64)
}

/// Appends `v` to a CSV line the way every table of contactwave writes a number: a whole
/// number below `2^53` in magnitude as an integer (`3`, `-1000000`: a crack node's state, a
/// sweep's `nodes`), any other in its shortest round-trip form (`zmij`: parsing the cell
/// gives the same `f64` back), `NaN`, `inf` and `-inf` as Rust writes them. `buf` is
/// scratch space, reused across calls.
///
/// ```
/// use contactwave::analysis::push_csv_number;
/// let (mut line, mut buf) = (String::new(), zmij::Buffer::new());
/// for v in [2.0, 0.25, -1e6, 1e300, f64::NAN] {
///     push_csv_number(&mut line, &mut buf, v);
///     line.push(',');
/// }
/// assert_eq!(line, "2,0.25,-1000000,1e+300,NaN,");
/// ```
pub fn push_csv_number(line: &mut String, buf: &mut zmij::Buffer, v: f64) {
    match whole_number(v) {
        Some(i) => {
            use std::fmt::Write;
            let _ = write!(line, "{i}");
        }
        None => line.push_str(buf.format(v)),
    }
}

impl Serialize for Summary {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.entries.len()))?;
        for (k, v) in &self.entries {
            m.serialize_entry(k, &json_number(*v))?;
        }
        m.end()
    }
}

/// The harmonic keys of a shear wave (model.md section 13), `{prefix}A1_over_Ainc` ...
/// `{prefix}A5_over_Ainc`, `{prefix}A2_over_A1`, `{prefix}A3_over_A1` and
/// `{prefix}A3_over_A1_cubed` (s^2/m^2), from its velocity bands (m/s) and the incident
/// velocity amplitude `a_inc` (m/s). A wave that is not there (its A1 below `1e-9 a_inc`,
/// e.g. nothing reflected by a sticking interface between identical media) has ratios 0,
/// not noise over noise.
pub fn set_shear_harmonics(
    s: &mut Summary,
    prefix: &str,
    bands: &super::BandAmplitudes,
    a_inc: f64,
) {
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
    let mut a = bands.harmonic;
    if a[1] <= 1e-9 * a_inc {
        a = [0.0; 6];
    }
    for n in 1..=5 {
        s.set(&format!("{prefix}A{n}_over_Ainc"), ratio(a[n], a_inc));
    }
    s.set(&format!("{prefix}A2_over_A1"), ratio(a[2], a[1]));
    s.set(&format!("{prefix}A3_over_A1"), ratio(a[3], a[1]));
    s.set(
        &format!("{prefix}A3_over_A1_cubed"),
        ratio(a[3], a[1].powi(3)),
    );
}

/// The harmonic keys of one record (a 2D receiver, a measured record), each after
/// `prefix` (e.g. `"top_"`, or `""`): `A1` ... `A5` (the record's unit: m/s for a
/// velocity), `A2_over_A1`, `A3_over_A1` and `beta_star` = A2/A1^2 (the inverse of the
/// record's unit).
pub fn set_record_harmonics(s: &mut Summary, prefix: &str, h: &[f64; 6]) {
    let a1 = h[1];
    let values = [
        h[1],
        h[2],
        h[3],
        h[4],
        h[5],
        h[2] / a1,
        h[3] / a1,
        h[2] / (a1 * a1),
    ];
    for (key, v) in HARMONIC_KEYS.iter().zip(values) {
        s.set(&format!("{prefix}{key}"), v);
    }
}

/// The per-record harmonic keys, in order: what [`set_record_harmonics`] writes after its
/// prefix, and the values of a measured record's analysis (`measured::RecordAnalysis`).
pub const HARMONIC_KEYS: [&str; 8] = [
    "A1",
    "A2",
    "A3",
    "A4",
    "A5",
    "A2_over_A1",
    "A3_over_A1",
    "beta_star",
];

/// The reflected wave's summary keys: `A1_over_Ainc` ... `A5_over_Ainc`, `Asub_over_Ainc`,
/// `A2_over_A1`, `beta_star`, the incident burst's own `incident_A*_over_Ainc` (when its
/// bands are given) and, for a two-tone burst, `Af2_over_Ainc`, `Asum_over_Ainc`,
/// `Adiff_over_Ainc`. `a_inc` is the incident velocity amplitude, m/s.
pub fn set_reflected_harmonics(
    s: &mut Summary,
    refl: &super::BandAmplitudes,
    a_inc: f64,
    two_tone: bool,
    inc: Option<&super::BandAmplitudes>,
) {
    let a = &refl.harmonic;
    for n in 1..=5 {
        s.set(&format!("A{n}_over_Ainc"), a[n] / a_inc);
    }
    s.set("Asub_over_Ainc", refl.subharmonic / a_inc);
    s.set("A2_over_A1", if a[1] > 0.0 { a[2] / a[1] } else { 0.0 });
    s.set(
        "beta_star",
        if a[1] > 0.0 {
            a[2] / (a[1] * a[1])
        } else {
            0.0
        },
    );
    if let Some(inc) = inc {
        for n in 1..=5 {
            s.set(&format!("incident_A{n}_over_Ainc"), inc.harmonic[n] / a_inc);
        }
    }
    if two_tone {
        s.set("Af2_over_Ainc", refl.f2 / a_inc);
        s.set("Asum_over_Ainc", refl.sum / a_inc);
        s.set("Adiff_over_Ainc", refl.difference / a_inc);
    }
}

/// The analysis keys, appended after the others: `analysis_method` (code of
/// [`super::AnalysisMethod::code`]), the floors `A2_floor_over_Ainc` ...
/// `A5_floor_over_Ainc` (what the method gives on the linear response, over `a_inc`) and
/// `harmonic_floor_warning` (1 when a harmonic 2..5 is within a factor 10 of its floor).
pub fn set_analysis_keys(
    s: &mut Summary,
    method: super::AnalysisMethod,
    refl: &super::BandAmplitudes,
    floor: &super::BandAmplitudes,
    a_inc: f64,
) {
    s.set("analysis_method", method.code());
    for n in 2..=5 {
        s.set(&format!("A{n}_floor_over_Ainc"), floor.harmonic[n] / a_inc);
    }
    let near = super::methods::near_floor(refl, floor);
    s.set(
        "harmonic_floor_warning",
        if near.is_empty() { 0.0 } else { 1.0 },
    );
}

/// Harmonics 2..5 of a summary within a factor 10 of their floor (from the keys of
/// [`set_analysis_keys`] and `A*_over_Ainc`, each after `prefix`: `""`, or
/// `"reflected_normal_"` at oblique incidence).
pub fn harmonics_near_floor(s: &Summary, prefix: &str) -> Vec<usize> {
    (2..=5)
        .filter(|n| {
            let a = s
                .get(&format!("{prefix}A{n}_over_Ainc"))
                .unwrap_or(f64::NAN);
            let f = s
                .get(&format!("{prefix}A{n}_floor_over_Ainc"))
                .unwrap_or(f64::NAN);
            f > 0.0 && a < 10.0 * f
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts are written as integers, fractions and non-finite values as before, and
    /// every value reads back as the same number.
    #[test]
    fn whole_numbers_are_written_as_integers() {
        let mut s = Summary::new();
        for (k, v) in [
            ("steps", 15708.0),
            ("zero", 0.0),
            ("negative_zero", -0.0),
            ("dt", 1.2732395447351628e-9),
            ("half", -2.5),
            ("huge", 1e300),
            ("nan", f64::NAN),
        ] {
            s.set(k, v);
        }
        let text = serde_json::to_string(&s).unwrap();
        assert_eq!(
            text,
            r#"{"steps":15708,"zero":0,"negative_zero":-0.0,"dt":1.2732395447351628e-9,"half":-2.5,"huge":1e+300,"nan":null}"#
        );
        let back: serde_json::Map<String, serde_json::Value> = serde_json::from_str(&text).unwrap();
        // (serde_json's default reader may round the last bit of a long fraction)
        for (k, v) in s.iter().filter(|(_, v)| v.is_finite()) {
            let read = back[k].as_f64().unwrap();
            assert!((read - v).abs() <= 2.0 * f64::EPSILON * v.abs(), "{k}");
        }
        assert_eq!(back["steps"].as_i64(), Some(15708));
        assert!(back["half"].is_f64() && back["negative_zero"].is_f64());
    }

    /// Setting, renaming and removing keep one value a key, in order, found by the index.
    #[test]
    fn keys_stay_unique_and_ordered() {
        let mut s = Summary::new();
        for (i, k) in ["a", "b", "c", "d"].iter().enumerate() {
            s.set(k, i as f64);
        }
        s.set("b", 10.0);
        s.rename("a", "c", 2.0); // "c" exists: the renamed one, at a's place, stays
        s.remove("d");
        s.rename("b", "e", 0.5);
        let pairs: Vec<(&str, f64)> = s.iter().collect();
        assert_eq!(pairs, vec![("c", 0.0), ("e", 5.0)]);
        assert_eq!((s.get("c"), s.get("e")), (Some(0.0), Some(5.0)));
        assert_eq!((s.get("a"), s.get("b"), s.get("d")), (None, None, None));
        s.set("a", 1.0);
        assert_eq!(s.keys().collect::<Vec<_>>(), vec!["c", "e", "a"]);
    }

    /// A record's harmonics are the keys of `HARMONIC_KEYS` after its prefix (what the 2D
    /// receivers' names are checked against: `tests/all/solid_2d.rs`, colliding names).
    #[test]
    fn records_write_the_harmonic_keys_after_their_prefix() {
        let mut s = Summary::new();
        set_record_harmonics(&mut s, "p_", &[0.0, 2.0, 1.0, 0.5, 0.25, 0.125]);
        let keys: Vec<&str> = s.keys().collect();
        assert_eq!(keys.len(), HARMONIC_KEYS.len());
        assert_eq!(s.get("p_A2_over_A1"), Some(0.5));
        assert_eq!(s.get("p_beta_star"), Some(0.25));
    }
}
