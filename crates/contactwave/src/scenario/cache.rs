//! What validating a scenario builds or reads that does not change from one sweep point
//! to the next: contact laws (a tabulated or modified-power law tabulates its curve) and
//! waveform files. A template keeps one [`BuildCache`]; every point built from it reuses
//! the entries whose inputs are equal.

use crate::error::Result;
use crate::excitation::{ToneBurst, Window};
use crate::law::spec::{CompressionSpec, TractionSpec};
use crate::law::{registry, ContactLaw};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Most laws kept (a sweep over a law parameter builds a new law per point: those are not
/// worth keeping past this many).
const MAX_LAWS: usize = 16;

/// A file's columns (time s, value).
pub type Columns = Arc<(Vec<f64>, Vec<f64>)>;

type LawKey = (u64, CompressionSpec, TractionSpec, String);

/// Frequency and cycles (bits) and window of a tone burst.
type BurstKey = (u64, u64, Window);

/// Most tone bursts kept (a sweep over the frequency or the cycles builds one per point).
const MAX_BURSTS: usize = 16;

/// Laws and files shared by the points of one template.
#[derive(Debug, Default)]
pub struct BuildCache {
    laws: Mutex<Vec<(LawKey, Arc<ContactLaw>)>>,
    files: Mutex<Vec<(PathBuf, String, Columns)>>,
    bursts: Mutex<Vec<(BurstKey, ToneBurst)>>,
}

impl BuildCache {
    /// An empty cache.
    pub fn new() -> Self {
        BuildCache::default()
    }

    /// The law for static pressure `p0` (Pa) and these branches, built and validated
    /// once ([`registry::build_law`]; `file` and `prefix` name the keys in errors).
    pub fn law(
        &self,
        p0: f64,
        compression: &CompressionSpec,
        traction: &TractionSpec,
        file: &str,
        prefix: &str,
    ) -> Result<Arc<ContactLaw>> {
        let key: LawKey = (
            p0.to_bits(),
            compression.clone(),
            traction.clone(),
            format!("{file}\u{0}{prefix}"),
        );
        let laws = self.laws.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, law)) = laws.iter().find(|(k, _)| *k == key) {
            return Ok(law.clone());
        }
        drop(laws);
        let law = Arc::new(registry::build_law(
            p0,
            compression,
            traction,
            file,
            prefix,
        )?);
        let mut laws = self.laws.lock().unwrap_or_else(|p| p.into_inner());
        if laws.len() < MAX_LAWS {
            laws.push((key, law.clone()));
        }
        Ok(law)
    }

    /// A tone burst of `cycles` cycles at `frequency` (Hz) in `window` with peak
    /// `amplitude` (Pa), its window normalisation computed once per frequency, cycles and
    /// window ([`ToneBurst::with_amplitude`]: the same burst as [`ToneBurst::new`]).
    pub fn tone_burst(
        &self,
        amplitude: f64,
        frequency: f64,
        cycles: f64,
        window: Window,
    ) -> ToneBurst {
        let key: BurstKey = (frequency.to_bits(), cycles.to_bits(), window);
        let bursts = self.bursts.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, b)) = bursts.iter().find(|(k, _)| *k == key) {
            return b.with_amplitude(amplitude);
        }
        drop(bursts);
        let b = ToneBurst::new(amplitude, frequency, cycles, window);
        let mut bursts = self.bursts.lock().unwrap_or_else(|p| p.into_inner());
        if bursts.len() < MAX_BURSTS {
            bursts.push((key, b.clone()));
        }
        b
    }

    /// The two columns of a CSV file read by `read` once (`field` names the key in
    /// errors and is part of the key, as readers differ by field).
    pub fn columns(
        &self,
        path: &Path,
        field: &str,
        read: impl FnOnce(&Path, &str) -> Result<(Vec<f64>, Vec<f64>)>,
    ) -> Result<Columns> {
        let files = self.files.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((_, _, c)) = files.iter().find(|(p, f, _)| p == path && f == field) {
            return Ok(c.clone());
        }
        drop(files);
        let c: Columns = Arc::new(read(path, field)?);
        let mut files = self.files.lock().unwrap_or_else(|p| p.into_inner());
        files.push((path.to_path_buf(), field.to_string(), c.clone()));
        Ok(c)
    }
}
