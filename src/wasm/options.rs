//! Deformer options read from JavaScript: `{ method?, ...settings }` over a method's options,
//! as the constructor (with a puppet's `parts` and `joints`), `setOptions` and the session
//! recorder take them.

use std::sync::OnceLock;

use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::puppet::read_puppet;
use super::read::Options;
use crate::deform::{Method, MethodOptions, Puppet, SettingValue};

/// The deformer options' names: `method`, then every method's settings.
fn names() -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<&'static str>> = OnceLock::new();
    NAMES.get_or_init(|| std::iter::once("method").chain(MethodOptions::all_setting_names()).collect())
}

/// A new deformer's options' names: those of [`names`], and a puppet's `parts` and `joints`.
fn setup_names() -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<&'static str>> = OnceLock::new();
    NAMES.get_or_init(|| names().iter().copied().chain(["parts", "joints"]).collect())
}

/// Reads `{ method?, ...settings }` over `base` as [`MethodOptions::over`] makes them: a
/// different `method` starts from that method's defaults; an unknown key, a setting of
/// another method and a value of the wrong type are refused.
pub(super) fn deformer_options(value: &JsValue, base: MethodOptions) -> Result<MethodOptions, BindingError> {
    method_options(&Options::read(value, "deformer", names())?, base)
}

/// A new deformer's options: `{ method?, ...settings, parts?, joints? }`, the method's
/// options as [`deformer_options`] reads them over the defaults, and the puppet its
/// `parts` and `joints` make (`joints` without `parts` is refused).
pub(super) fn deformer_setup(value: &JsValue) -> Result<(MethodOptions, Option<Puppet>), BindingError> {
    let given = Options::read(value, "deformer", setup_names())?;
    let options = method_options(&given, MethodOptions::default())?;
    let puppet = match (given.get("parts"), given.get("joints")) {
        (None, None) => None,
        (None, Some(_)) => {
            return Err(BindingError::option("option joints needs parts: the parts the joints join".to_owned()))
        }
        (Some(parts), joints) => Some(read_puppet(parts, joints)?),
    };
    Ok((options, puppet))
}

fn method_options(given: &Options, base: MethodOptions) -> Result<MethodOptions, BindingError> {
    let methods: Vec<(&str, Method)> = Method::all().iter().map(|&m| (m.name(), m)).collect();
    let method = given.choice("method", &methods)?;
    let mut values = Vec::new();
    for name in given.names().filter(|&name| !["method", "parts", "joints"].contains(&name)) {
        let value = given.get(name).expect("a name given has a value");
        let value = if let Some(x) = value.as_f64() {
            SettingValue::Number(x)
        } else if let Some(b) = value.as_bool() {
            SettingValue::Bool(b)
        } else if let Some(w) = value.as_string() {
            SettingValue::Word(w)
        } else {
            return Err(given.wrong_type(name, "a number, true, false or a string", value));
        };
        values.push((name, value));
    }
    Ok(MethodOptions::over(base, method, values.iter().map(|(name, value)| (*name, value)))?)
}
