//! The summary of a run: an ordered list of named scalars (the keys of `summary.json` and
//! the columns of `sweep.csv`).

use serde::ser::{Serialize, SerializeMap, Serializer};

/// Ordered named scalars. Units: see `docs/scenario.md` (outputs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Summary {
    entries: Vec<(String, f64)>,
}

impl Summary {
    /// Empty summary.
    pub fn new() -> Self {
        Self::default()
    }
    /// Append or replace a value.
    pub fn set(&mut self, key: &str, value: f64) {
        if let Some(e) = self.entries.iter_mut().find(|e| e.0 == key) {
            e.1 = value;
        } else {
            self.entries.push((key.to_string(), value));
        }
    }
    /// Value of a key.
    pub fn get(&self, key: &str) -> Option<f64> {
        self.entries.iter().find(|e| e.0 == key).map(|e| e.1)
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

impl Serialize for Summary {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.entries.len()))?;
        for (k, v) in &self.entries {
            if v.is_finite() {
                m.serialize_entry(k, v)?;
            } else {
                m.serialize_entry(k, &Option::<f64>::None)?;
            }
        }
        m.end()
    }
}
