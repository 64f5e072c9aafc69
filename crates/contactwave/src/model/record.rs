//! A run as plain values: named numbers, texts, arrays and nested maps, in a fixed order.
//! The Python package converts a [`Record`] into a dict of numpy arrays without knowing
//! which kind of model produced it.

/// One value of a [`Record`].
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Nothing (Python `None`).
    None,
    /// A number.
    Number(f64),
    /// A text.
    Text(String),
    /// A short list of numbers (a Python list).
    List(Vec<f64>),
    /// An array (a 1-D numpy array).
    Array(Vec<f64>),
    /// Rows of equal length (a 2-D numpy array, rows x samples).
    Rows(Vec<Vec<f64>>),
    /// A tuple of values.
    Tuple(Vec<Value>),
    /// A nested record (a dict).
    Map(Record),
}

/// Named values in insertion order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Record {
    /// The entries, in order.
    pub entries: Vec<(String, Value)>,
}

impl Record {
    /// An empty record.
    pub fn new() -> Self {
        Record::default()
    }

    /// Append an entry (builder style).
    pub fn with(mut self, key: &str, value: Value) -> Self {
        self.push(key, value);
        self
    }

    /// Append an entry.
    pub fn push(&mut self, key: &str, value: Value) {
        self.entries.push((key.to_string(), value));
    }

    /// The value of `key`, if present.
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
}

impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Number(v)
    }
}

impl From<Vec<f64>> for Value {
    fn from(v: Vec<f64>) -> Self {
        Value::Array(v)
    }
}

impl From<Record> for Value {
    fn from(r: Record) -> Self {
        Value::Map(r)
    }
}

/// A summary as a record (`scenario` first when given, then the keys in order).
pub fn summary_record(file: Option<&str>, s: &crate::analysis::Summary) -> Record {
    let mut r = Record::new();
    if let Some(f) = file {
        r.push("scenario", Value::Text(f.to_string()));
    }
    for (k, v) in s.iter() {
        r.push(k, Value::Number(v));
    }
    r
}
