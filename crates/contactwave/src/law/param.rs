//! A law's scenario parameters: what each law file's `Spec` does ([`LawSpec`]: validate,
//! build, name its parameters and their units), the table that registers the laws of one
//! kind (`law_table!`), the handle `[set]` and sweep axes change a parameter through, and
//! the range checks every law's builder uses (errors name file, field, value and the
//! allowed range).

use crate::error::{Error, Result};

/// A law parameter that `[set]` and sweep axes may change.
#[derive(Debug)]
pub enum ParamMut<'a> {
    /// A required number.
    F64(&'a mut f64),
    /// An optional number (setting it gives it a value).
    OptF64(&'a mut Option<f64>),
}

/// What a law's parameters, as a scenario file gives them, do: each law file's `Spec`
/// implements it, and one line of its kind's `law_table!` registers it.
pub trait LawSpec {
    /// The branch it builds: `dyn CompressionBranch`, `dyn TractionBranch` or
    /// `dyn TangentialBranch`.
    type Branch: ?Sized;
    /// Validate the parameters and build the branch for the interface's static pressure
    /// `p0` (Pa: where a compression branch starts; the other kinds do not read it);
    /// errors name `file` and the key `prefix.<parameter>` (`prefix` the law's dotted key,
    /// e.g. `interface.compression`), the value and the allowed range.
    fn build(&self, p0: f64, file: &str, prefix: &str) -> Result<Box<Self::Branch>>;
    /// The parameter `name`, for `[set]` and sweep axes; `None` if the law has none of
    /// that name (the default: no parameter can be set).
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

/// The table of the laws of one kind: `law_table! { (docs) Name: Branch { (docs)
/// Variant(module::Spec), ... } }` makes the scenario's `{ law = "variant", ... }` (snake
/// case) of that kind a law of that file: it generates the enum `Name` (serde, tagged by
/// `law`) and its `build`, `param_mut` and `unit`, each dispatching to the file's
/// [`LawSpec`].
macro_rules! law_table {
    (
        $(#[$edoc:meta])*
        $name:ident: $branch:ty {
            $($(#[$doc:meta])* $variant:ident($spec:ty),)*
        }
    ) => {
        $(#[$edoc])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize)]
        #[serde(tag = "law", rename_all = "snake_case")]
        pub enum $name {
            $($(#[$doc])* $variant($spec),)*
        }

        /// `{ law = "name", parameters... }`: the law's name, then its parameters read
        /// as its file's `Spec`; a parameter's error names its key ([`law_error`]).
        impl<'de> serde::Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                /// The law names (snake case, as serde spells the variants).
                #[derive(serde::Deserialize)]
                #[serde(rename_all = "snake_case")]
                enum Law {
                    $($variant,)*
                }
                let mut table = match <toml::Value as serde::Deserialize>::deserialize(d)? {
                    toml::Value::Table(t) => t,
                    other => {
                        return Err(<D::Error as serde::de::Error>::custom(format!(
                            "invalid type: {} `{other}`, expected a table naming its law, \
                             e.g. {{ law = \"rigid\" }}",
                            other.type_str()
                        )))
                    }
                };
                let law: Law = match table.remove("law") {
                    Some(name) => serde_path_to_error::deserialize(name)
                        .map_err(|e| $crate::law::param::law_error::<D::Error>(e, "law"))?,
                    None => return Err(<D::Error as serde::de::Error>::missing_field("law")),
                };
                let rest = toml::Value::Table(table);
                Ok(match law {
                    $(Law::$variant => $name::$variant(
                        serde_path_to_error::deserialize(rest)
                            .map_err(|e| $crate::law::param::law_error::<D::Error>(e, ""))?,
                    ),)*
                })
            }
        }

        impl $name {
            /// Validate and build the branch for static pressure `p0` (Pa), errors naming
            /// `file` and `prefix.<parameter>` (see [`crate::law::param::LawSpec::build`]).
            pub fn build(
                &self,
                p0: f64,
                file: &str,
                prefix: &str,
            ) -> $crate::error::Result<Box<$branch>> {
                match self {
                    $($name::$variant(s) => $crate::law::param::LawSpec::build(s, p0, file, prefix),)*
                }
            }
            /// The parameter `name` of the law (see
            /// [`crate::law::param::LawSpec::param_mut`]).
            pub fn param_mut(&mut self, name: &str) -> Option<$crate::law::param::ParamMut<'_>> {
                match self {
                    $($name::$variant(s) => $crate::law::param::LawSpec::param_mut(s, name),)*
                }
            }
            /// The SI unit of the parameter `name` in any law of the table that has it.
            pub fn unit(name: &str) -> Option<&'static str> {
                None$(.or_else(|| <$spec as $crate::law::param::LawSpec>::unit(name)))*
            }
        }
    };
}
pub(crate) use law_table;

/// A law table's error at its key `inner` (a parameter's path, or `at` where the path is
/// empty) as `in `key`: message`: the scenario reader ([`crate::scenario`]'s field errors)
/// appends the key to the law's own, so that the message names `crack.0.tangential.friction`
/// and not the table.
#[doc(hidden)]
pub fn law_error<E: serde::de::Error>(
    e: serde_path_to_error::Error<toml::de::Error>,
    at: &str,
) -> E {
    let path = e.path().to_string();
    let key = if path == "." { at.to_string() } else { path };
    let message = e.into_inner().to_string();
    if key.is_empty() {
        E::custom(message)
    } else {
        E::custom(format!("{LAW_KEY_PREFIX}{key}`: {message}"))
    }
}

/// How [`law_error`] begins a message that names a key inside a law table.
pub const LAW_KEY_PREFIX: &str = "in law key `";

/// `v` finite and > 0, else an error naming `file`, `field` and the value.
pub(crate) fn positive(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            file,
            field,
            v,
            "must be a finite number > 0",
        ))
    }
}

/// The stiffest interface a law takes, Pa/m: it carries 1e12 Pa, beyond any solid's
/// modulus, at a gap of 1 pm, so a stiffer one is rigid (the `rigid` compression law, a
/// bonded crack). Far stiffer ones (about 1e119 Pa/m, gaps of 1e-113 m) would lose the gap
/// equations' precision.
pub const STIFFEST: f64 = 1e24;

/// A stiffness `v` (Pa/m) at most [`STIFFEST`], else an error naming `file`, `field` and
/// the value (its sign and finiteness are the caller's checks).
pub(crate) fn stiffness_at_most(file: &str, field: &str, v: f64) -> Result<()> {
    if v <= STIFFEST {
        Ok(())
    } else {
        Err(Error::invalid(
            file,
            field,
            v,
            "must be at most 1e24 Pa/m (1e12 Pa at a gap of 1 pm: a stiffer interface is \
             rigid; use the rigid law)",
        ))
    }
}

/// `v` finite and >= 0, else an error naming `file`, `field` and the value.
pub(crate) fn non_negative(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            file,
            field,
            v,
            "must be a finite number >= 0",
        ))
    }
}

/// `v` finite and in (0, 1) (an exponent or a fraction), else an error naming `file`,
/// `field` and the value.
pub(crate) fn exponent(file: &str, field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 && v < 1.0 {
        Ok(())
    } else {
        Err(Error::invalid(file, field, v, "must lie in (0, 1)"))
    }
}
