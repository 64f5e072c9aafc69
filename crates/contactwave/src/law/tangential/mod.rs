//! Tangential branches, one per file (model.md section 13): the shear stress an interface
//! carries as a function of the tangential gap `[u]_T` (slip-positive along +y), the
//! adhesion `beta` shared with the traction branch, and the normal contact pressure `N`
//! through Coulomb friction.
//!
//! Every branch is a reversible spring `k(beta) [u]_T` in parallel with a Coulomb slider
//! (friction coefficient `mu`, possibly falling with the slip path; optional stick
//! stiffness `k_t` in series: rigid stick when infinite); the slider itself (state, phase
//! stresses, return mapping) is in [`coulomb`]. The solvers only ask for these numbers,
//! never for a branch's name.
//!
//! A law is one file: its branch, and its parameters as scenario files give them (a
//! `Spec` implementing [`TangentialLawSpec`]: validation, building, names for `[set]` and
//! sweeps, units); and one line in the table at the end of this file, which makes it a
//! `law = "..."` of [`TangentialSpec`].

pub mod coulomb;
pub mod free;
pub mod linear;
pub mod rccm;
pub mod slip_weakening;

pub use coulomb::Coulomb;
pub use free::Free;
pub use linear::Linear;
pub use rccm::Rccm;
pub use slip_weakening::SlipWeakening;

use super::param::ParamMut;
use super::TangentialBranch;
use crate::error::Result;

/// What a tangential law's parameters (as a scenario file gives them) do.
pub trait TangentialLawSpec {
    /// Validate the parameters and build the branch; errors name `file` and the key
    /// `prefix.<parameter>` (`prefix` the law's dotted key, e.g. `interface.tangential`).
    fn build(&self, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>>;
    /// The parameter `name`, for `[set]` and sweep axes; `None` if the law has none.
    fn param_mut(&mut self, _name: &str) -> Option<ParamMut<'_>> {
        None
    }
    /// The SI unit of a parameter with one (`"Pa/m"`, `"m"`), so that unit strings
    /// (`"0.1 um"`) are read; `None` for a dimensionless or unknown parameter.
    fn unit(_name: &str) -> Option<&'static str>
    where
        Self: Sized,
    {
        None
    }
}

/// The table of tangential laws: each line `Variant(module::Spec)` makes `law = "variant"`
/// (snake case) of a scenario's `tangential` table a law of that file.
macro_rules! tangential_laws {
    ($($(#[$doc:meta])* $variant:ident($spec:ty),)*) => {
        /// Tangential branch of the contact law (model.md section 13), as a scenario gives
        /// it: `{ law = "<name>", <parameters> }`.
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(tag = "law", rename_all = "snake_case")]
        pub enum TangentialSpec {
            $($(#[$doc])* $variant($spec),)*
        }

        impl TangentialSpec {
            /// Validate and build the branch (see [`TangentialLawSpec::build`]).
            pub fn build(&self, file: &str, prefix: &str) -> Result<Box<dyn TangentialBranch>> {
                match self {
                    $(TangentialSpec::$variant(s) => s.build(file, prefix),)*
                }
            }
            /// The parameter `name` of the law (see [`TangentialLawSpec::param_mut`]).
            pub fn param_mut(&mut self, name: &str) -> Option<ParamMut<'_>> {
                match self {
                    $(TangentialSpec::$variant(s) => s.param_mut(name),)*
                }
            }
            /// The SI unit of the parameter `name` in any tangential law that has it.
            pub fn unit(name: &str) -> Option<&'static str> {
                None$(.or_else(|| <$spec as TangentialLawSpec>::unit(name)))*
            }
        }
    };
}

tangential_laws! {
    /// No shear stress (free sliding).
    Free(free::Spec),
    /// `tau - q0 = C_T [u]_T`, open or closed.
    Linear(linear::Spec),
    /// Coulomb friction `|tau| <= mu N`; rigid stick, or elastic stick with `stiffness`.
    Coulomb(coulomb::Spec),
    /// Full RCCM: adhesive spring `beta^2 C_T [u]_T` and Coulomb friction; needs the RCCM
    /// traction branch (its `C_N`, `w`, `b` and adhesion).
    Rccm(rccm::Spec),
    /// Linear slip weakening: Coulomb friction (rigid stick) whose coefficient falls from
    /// `mu_s` to `mu_d` over the slip path `d_c`.
    SlipWeakening(slip_weakening::Spec),
}

impl Default for TangentialSpec {
    fn default() -> Self {
        TangentialSpec::Free(free::Spec {})
    }
}
