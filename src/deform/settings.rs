//! Method settings by name, read and written the same way by every caller that names them:
//! the JavaScript bindings (`{ method: "arap", iterations: 10 }`), session files and the
//! command line of `examples/pose_obj`. Each method's options type lists its settings once
//! ([`Settings::SETTINGS`], beside the type in `options.rs`); [`MethodOptions::over`] sets
//! named values on a method's options, refusing an unknown name, a setting of another
//! method or a value of the wrong kind, and [`MethodOptions::values`] lists them for
//! writing.

use std::fmt;

use super::error::DeformError;
use super::options::{methods, Access, Method, MethodOptions, Settings};
use crate::message::{one_of, Number};

/// A setting's value as a caller gives it (a JavaScript value, a JSON value, a word on a
/// command line).
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue {
    /// A number (a whole number too).
    Number(f64),
    /// `true` or `false`.
    Bool(bool),
    /// A word, one of a setting's choices.
    Word(String),
}

impl SettingValue {
    /// The value as a short phrase for messages, as the bindings describe JavaScript values.
    fn describe(&self) -> String {
        match self {
            Self::Number(x) => format!("the number {}", Number(*x)),
            Self::Bool(b) => b.to_string(),
            Self::Word(w) if w.len() <= 40 => format!("{w:?}"),
            Self::Word(_) => "a long string".into(),
        }
    }
}

/// The value as written on a command line: `100`, `true`, `spiral`.
impl fmt::Display for SettingValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Number(x) => write!(f, "{}", Number(*x)),
            Self::Bool(b) => write!(f, "{b}"),
            Self::Word(w) => f.write_str(w),
        }
    }
}

/// The largest whole number a setting takes as such (2^53: every whole number up to it is
/// a double, so none is rounded); the method's check bounds it further.
const MAX_WHOLE: f64 = 9_007_199_254_740_992.0;

/// `name` set to `value` on `options` of `method`.
fn set<O: Settings>(options: &mut O, method: Method, name: &str, value: &SettingValue) -> Result<(), DeformError> {
    let Some(setting) = O::SETTINGS.iter().find(|s| s.name == name) else {
        return Err(match Method::all().iter().find(|m| m.setting_names().contains(&name)) {
            Some(&owner) => DeformError::ForeignOption { name: name.into(), method, owner },
            None => DeformError::UnknownOption { name: name.into(), method },
        });
    };
    let wrong = |expected: String| DeformError::OptionValue { name: setting.name, found: value.describe(), expected };
    match (&setting.access, value) {
        (Access::Number(_, set), SettingValue::Number(x)) => set(options, *x),
        (Access::Whole(_, set), SettingValue::Number(x)) if x.fract() == 0.0 && (0.0..=MAX_WHOLE).contains(x) => {
            set(options, *x as usize)
        }
        (Access::Bool(_, set), SettingValue::Bool(b)) => set(options, *b),
        (Access::Word(words, _, set), SettingValue::Word(w)) if words.contains(&w.as_str()) => {
            set(options, words.iter().position(|x| x == w).expect("the word is one of them"))
        }
        (access, _) => return Err(wrong(expected(access))),
    }
    Ok(())
}

/// What a setting accepts, for messages.
fn expected<O>(access: &Access<O>) -> String {
    match access {
        Access::Number(..) => "a number".into(),
        Access::Whole(..) => "a whole number".into(),
        Access::Bool(..) => "true or false".into(),
        Access::Word(words, ..) => one_of(words),
    }
}

/// Every setting of `options` with its value.
fn values<O: Settings>(options: &O) -> Vec<(&'static str, SettingValue)> {
    let value = |access: &Access<O>| match access {
        Access::Number(get, _) => SettingValue::Number(get(options)),
        Access::Whole(get, _) => SettingValue::Number(get(options) as f64),
        Access::Bool(get, _) => SettingValue::Bool(get(options)),
        Access::Word(words, get, _) => SettingValue::Word(words[get(options)].into()),
    };
    O::SETTINGS.iter().map(|s| (s.name, value(&s.access))).collect()
}

/// Whether `name` is a whole-number setting of some method (JSON writes it without a
/// fraction).
pub(crate) fn is_whole(name: &str) -> bool {
    fn whole<O: Settings>(name: &str) -> bool {
        O::SETTINGS.iter().any(|s| s.name == name && matches!(s.access, Access::Whole(..)))
    }
    macro_rules! any_whole {
        ($($(#[$doc:meta])* $variant:ident($word:literal, $options:ident),)*) => {
            false $(|| whole::<super::options::$options>(name))*
        };
    }
    methods!(any_whole)
}

/// Writes the by-name functions of [`Method`] and [`MethodOptions`] from the list of methods.
macro_rules! by_name {
    ($($(#[$doc:meta])* $variant:ident($word:literal, $options:ident),)*) => {
        use super::options::{$($options),*};

        impl Method {
            /// Every method, in the list's order.
            pub fn all() -> &'static [Method] {
                &[$(Self::$variant),*]
            }

            /// The method of this name (see [`Method::name`]).
            pub fn from_name(name: &str) -> Result<Method, DeformError> {
                Self::all().iter().copied().find(|m| m.name() == name)
                    .ok_or_else(|| DeformError::UnknownMethod { name: name.into() })
            }

            /// The method's default options.
            pub fn defaults(self) -> MethodOptions {
                match self {
                    $(Self::$variant => MethodOptions::$variant($options::default()),)*
                }
            }

            /// The names of the method's settings.
            pub fn setting_names(self) -> Vec<&'static str> {
                match self {
                    $(Self::$variant => $options::SETTINGS.iter().map(|s| s.name).collect(),)*
                }
            }
        }

        impl MethodOptions {
            /// Sets one setting by name: refuses a name that is not one of this method's
            /// settings (another method's, or none) and a value of the wrong kind. Ranges
            /// are [`MethodOptions::check`]'s.
            pub fn set(&mut self, name: &str, value: &SettingValue) -> Result<(), DeformError> {
                match self {
                    $(Self::$variant(o) => set(o, Method::$variant, name, value),)*
                }
            }

            /// Every setting of the method with its value, in the method's order.
            pub fn values(&self) -> Vec<(&'static str, SettingValue)> {
                match self {
                    $(Self::$variant(o) => values(o),)*
                }
            }
        }
    };
}

methods!(by_name);

impl MethodOptions {
    /// The options that a method name and named values make over `base`, as every reader
    /// of options makes them (the JavaScript API, sessions, the command line): a `method`
    /// other than `base`'s starts from that method's defaults, `base` otherwise; each value
    /// then sets one of its settings ([`MethodOptions::set`]); ranges are checked.
    pub fn over<'a>(
        base: MethodOptions,
        method: Option<Method>,
        values: impl IntoIterator<Item = (&'a str, &'a SettingValue)>,
    ) -> Result<MethodOptions, DeformError> {
        let mut options = match method {
            Some(method) if method != base.method() => method.defaults(),
            _ => base,
        };
        for (name, value) in values {
            options.set(name, value)?;
        }
        options.check()?;
        Ok(options)
    }

    /// The names of every method's settings, each once, in the list's order.
    pub fn all_setting_names() -> Vec<&'static str> {
        let mut names: Vec<&'static str> = Vec::new();
        for name in Method::all().iter().flat_map(|m| m.setting_names()) {
            if !names.contains(&name) {
                names.push(name);
            }
        }
        names
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deform::{AkapOptions, ArapOptions, Integrator};

    #[test]
    fn values_written_read_back_to_the_same_options() {
        let akap = MethodOptions::Akap(AkapOptions::default().with_lambda(0.25).with_integrator(Integrator::Linear));
        let arap = MethodOptions::Arap(ArapOptions::default().with_iterations(7));
        for options in [akap, arap] {
            let values = options.values();
            let base = if options.method() == Method::Akap { arap } else { akap };
            let read = MethodOptions::over(base, Some(options.method()), values.iter().map(|(n, v)| (*n, v)));
            assert_eq!(read, Ok(options));
        }
    }

    #[test]
    fn names_kinds_and_methods_are_checked() {
        let akap = MethodOptions::default();
        let over = |method, name, value| MethodOptions::over(akap, method, [(name, &value)]);
        assert_eq!(
            over(None, "iterations", SettingValue::Number(3.0)),
            Err(DeformError::ForeignOption { name: "iterations".into(), method: Method::Akap, owner: Method::Arap })
        );
        assert_eq!(
            over(None, "lamda", SettingValue::Number(3.0)),
            Err(DeformError::UnknownOption { name: "lamda".into(), method: Method::Akap })
        );
        let wrong = over(None, "lambda", SettingValue::Word("big".into())).unwrap_err();
        assert_eq!(wrong.to_string(), "option lambda must be a number, not \"big\"");
        let wrong = over(None, "integrator", SettingValue::Word("euler".into())).unwrap_err();
        assert_eq!(wrong.to_string(), "option integrator must be \"spiral\" or \"linear\", not \"euler\"");
        let wrong = over(Some(Method::Arap), "iterations", SettingValue::Number(1e300)).unwrap_err();
        assert_eq!(wrong.to_string(), "option iterations must be a whole number, not the number 1e300");
        let wrong = over(Some(Method::Arap), "iterations", SettingValue::Number(2.5)).unwrap_err();
        assert_eq!(wrong.to_string(), "option iterations must be a whole number, not the number 2.5");
        // Ranges beyond the kind are the method's check.
        assert!(matches!(
            over(None, "lambda", SettingValue::Number(-1.0)),
            Err(DeformError::InvalidOption { name: "lambda", .. })
        ));
        assert!(matches!(
            over(Some(Method::Arap), "iterations", SettingValue::Number(1001.0)),
            Err(DeformError::InvalidOption { name: "iterations", .. })
        ));
        assert_eq!(Method::from_name("bogus"), Err(DeformError::UnknownMethod { name: "bogus".into() }));
        assert_eq!(Method::from_name("mls"), Ok(Method::Mls));
        assert_eq!(Method::from_name("cauchy-green"), Ok(Method::CauchyGreen));
        assert_eq!(
            MethodOptions::all_setting_names(),
            ["lambda", "dirichlet", "integrator", "iterations", "variant", "alpha", "cage", "smoothness"],
            "AKAP's settings, then ARAP's, MLS's and Cauchy-Green's"
        );
    }
}
