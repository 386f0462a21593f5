//! Enums of named choices: the values of the command-line options that pick one of a
//! few methods (`--norm 2-norm`, `--scheme continuous`, `--cn-variant lambda-ratio`, …).
//!
//! `named_choices!` declares such an enum with one name per variant (used on the
//! command line and in outputs) and optional aliases accepted on input, and derives from
//! that one table: `ALL` and `NAMES` (every variant and its name, in the order of
//! declaration), `name()`, `from_name()`, `Display` (the name) and `FromStr` (the name or
//! an alias, trimmed and in any case; otherwise an [`UnknownChoice`] listing the names).

use thiserror::Error;

/// A value that is neither the name nor an alias of any choice of an option.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown {option} `{value}` (expected one of: {names})")]
pub struct UnknownChoice {
    /// The option, e.g. `norm`.
    pub option: &'static str,
    /// The value given.
    pub value: String,
    /// The names of the choices, separated by `, `.
    pub names: String,
}

/// Declares an enum of named choices (see the [module documentation](crate::choice)):
///
/// ```text
/// named_choices! {
///     option "norm", error ActuationError, default Spectral;
///     /// Matrix norm of κ.
///     pub enum ConditionNorm {
///         /// 2-norm.
///         Spectral = "2-norm" | "2" | "spectral",
///         /// Weighted Frobenius norm.
///         WeightedFrobenius = "weighted-frobenius" | "frobenius",
///     }
/// }
/// ```
///
/// The enum derives `Debug`, `Clone`, `Copy`, `PartialEq` and `Eq`, and with
/// `option "…", error …, serde "kebab-case";` also `Serialize` and `Deserialize` with that
/// `rename_all`; with `default Variant` it implements `Default`. The error type must implement `From<UnknownChoice>`; names and aliases are
/// lowercase.
macro_rules! named_choices {
    (
        option $option:literal, error $error:ty $(, serde $case:literal)? $(, default $default:ident)?;
        $(#[$meta:meta])*
        $vis:vis enum $enum:ident {
            $(
                $(#[$variant_meta:meta])*
                $variant:ident = $name:literal $(| $alias:literal)*,
            )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        $(
            #[derive(::serde::Serialize, ::serde::Deserialize)]
            #[serde(rename_all = $case)]
        )?
        $vis enum $enum {
            $(
                $(#[$variant_meta])*
                $variant,
            )+
        }

        impl $enum {
            /// Every choice, in the order of declaration.
            pub const ALL: [$enum; <[&str]>::len(&[$($name),+])] = [$($enum::$variant),+];

            /// The names of [`Self::ALL`], in the same order.
            pub const NAMES: [&'static str; <[&str]>::len(&[$($name),+])] = [$($name),+];

            /// Name used on the command line and in outputs.
            pub fn name(self) -> &'static str {
                match self {
                    $($enum::$variant => $name,)+
                }
            }

            /// The choice whose name or alias is `s` (exactly), if any.
            pub fn from_name(s: &str) -> Option<$enum> {
                match s {
                    $($name $(| $alias)* => Some($enum::$variant),)+
                    _ => None,
                }
            }
        }

        $(
            impl Default for $enum {
                fn default() -> Self {
                    $enum::$default
                }
            }
        )?

        impl std::fmt::Display for $enum {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $enum {
            type Err = $error;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                $enum::from_name(&s.trim().to_ascii_lowercase()).ok_or_else(|| {
                    $crate::choice::UnknownChoice {
                        option: $option,
                        value: s.to_string(),
                        names: $enum::NAMES.join(", "),
                    }
                    .into()
                })
            }
        }
    };
}
