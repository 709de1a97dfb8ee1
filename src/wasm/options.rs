//! Deformer options read from JavaScript: `{ method?, ...settings }` over a method's options,
//! as the constructor, `setOptions` and the session recorder take them.

use std::sync::OnceLock;

use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::read::Options;
use crate::deform::{Method, MethodOptions, SettingValue};

/// The deformer options' names: `method`, then every method's settings.
fn names() -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<&'static str>> = OnceLock::new();
    NAMES.get_or_init(|| std::iter::once("method").chain(MethodOptions::all_setting_names()).collect())
}

/// Reads `{ method?, ...settings }` over `base` as [`MethodOptions::over`] makes them: a
/// different `method` starts from that method's defaults; an unknown key, a setting of
/// another method and a value of the wrong type are refused.
pub(super) fn deformer_options(value: &JsValue, base: MethodOptions) -> Result<MethodOptions, BindingError> {
    let given = Options::read(value, "deformer", names())?;
    let methods: Vec<(&str, Method)> = Method::all().iter().map(|&m| (m.name(), m)).collect();
    let method = given.choice("method", &methods)?;
    let mut values = Vec::new();
    for name in given.names().filter(|&name| name != "method") {
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
