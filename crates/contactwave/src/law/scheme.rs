//! How the interface force of a contact point enters a time step: the choice shared by the
//! contact update (`law/contact/`) and the slider's return mapping
//! (`law/tangential/coulomb.rs`).

/// How the interface force enters the step (the law itself holds exactly at the new time
/// level in both).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum InterfaceScheme {
    /// The interface stress of the new time level acts over the whole step (backward,
    /// as thesis eqs. 2.27-2.31): first order, and it dissipates energy (a linear spring
    /// interface loses a fraction of order `K chi` of its vibration energy per step).
    Backward,
    /// The mean of the interface stresses at the new and the previous-but-one level
    /// replaces the stress at the current level in the centred scheme (trapezoidal /
    /// average acceleration): second order, no numerical dissipation for a linear spring,
    /// unconditionally stable. Rigid (Signorini, bonded) branches keep the backward
    /// projection, which enforces the constraint at the new level, and so do open
    /// traction-free faces (their stress is the new level's, none: the mean with an
    /// earlier contact stress would do work on faces that carry nothing).
    #[default]
    Average,
}
