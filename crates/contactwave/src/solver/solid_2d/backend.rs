//! Where a 2D plan's time loop runs: the CPU (always) or, in a build with the feature `gpu`
//! and on a machine with an NVIDIA GPU, the GPU ([`super::gpu`]). Both run the same step
//! (docs/model.md eq. 15.2) with the same crack update on the host; the GPU's sums run in
//! another order, so its results agree with the CPU's to round-off, not bit for bit.

use super::{Plan, Solid2dOutput};
use crate::error::{Error, Result};
use crate::law::{NormalPart, TangentialPart};

/// The machine of a 2D run's time loop (`[model] backend`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// The CPU kernel (parallel over the cores, the same bits for any thread count).
    #[default]
    Cpu,
    /// The GPU kernels (feature `gpu`; CUDA through the driver and NVRTC, loaded at run
    /// time).
    Gpu,
}

impl Backend {
    /// Whether this build has the GPU backend (the feature `gpu`).
    pub const GPU_BUILT: bool = cfg!(feature = "gpu");

    /// `cpu` or `gpu`; `None` for anything else.
    pub fn parse(name: &str) -> Option<Backend> {
        match name {
            "cpu" => Some(Backend::Cpu),
            "gpu" => Some(Backend::Gpu),
            _ => None,
        }
    }
}

impl<L: NormalPart + TangentialPart + Clone> Plan<L> {
    /// Run from rest on `backend`, reporting `(steps done, steps)` to `progress` every 64
    /// steps; `file` names the scenario in errors.
    pub fn run_on(
        &self,
        backend: Backend,
        file: &str,
        progress: Option<&(dyn Fn(usize, usize) + Send + Sync)>,
    ) -> Result<Solid2dOutput> {
        match backend {
            Backend::Cpu => self.run_with(progress),
            Backend::Gpu => {
                if !Backend::GPU_BUILT {
                    return Err(Error::invalid(
                        file,
                        "model.backend",
                        "gpu",
                        "`cpu` (this build has no GPU backend: build with `--features gpu`)",
                    ));
                }
                self.run_gpu(progress)
            }
        }
    }

    #[cfg(not(feature = "gpu"))]
    fn run_gpu(
        &self,
        _progress: Option<&(dyn Fn(usize, usize) + Send + Sync)>,
    ) -> Result<Solid2dOutput> {
        Err(Error::Device {
            message: "this build has no GPU backend (build with `--features gpu`)".into(),
        })
    }
}
