//! Reading JavaScript arguments so that no JavaScript runs inside a Rust frame unguarded.
//!
//! A JavaScript exception that unwinds through wasm frames skips Rust's epilogues: the
//! shadow stack pointer is not restored and a `&mut self` borrow is never released, so an
//! instance dies after a few thousand such calls ("memory access out of bounds",
//! "recursive use of an object"). And wasm-bindgen's own glue for `&[f64]` or `&str`
//! parameters copies whatever it is given, element by element (a string is read as its
//! characters; an element's `valueOf` runs mid-copy). So every export takes `JsValue`s and
//! reads them here: typeof checks and typed-array copies run no user code, and everything
//! that can run user code (a getter, a Proxy trap, an iterator) goes through an import
//! marked `catch` (`Reflect.ownKeys`, `Reflect.get`, `Reflect.construct`), which turns a
//! thrown exception into an `Err`. Sizes are checked against limits before anything is
//! allocated in wasm memory.
//!
//! Options objects are read by one reader, [`Options`]: every key must be one of the
//! object's known names (an unknown key is an [`ErrorCode::InvalidOption`] error naming it
//! and listing the known ones), and each value is read by its type, an error naming the
//! option otherwise.

use js_sys::{Array, Float64Array, Function, Reflect, Uint32Array, Uint8Array, Uint8ClampedArray};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use super::error::BindingError;
use crate::error_code::ErrorCode;

/// An error saying what the caller passed was wrong, naming the argument.
pub(super) fn type_error(what: &str, expected: &str, value: &JsValue) -> BindingError {
    BindingError::argument(format!("{what} must be {expected}, not {}", describe(value)))
}

/// A short description of a JavaScript value's type, for messages (no user code runs).
fn describe(value: &JsValue) -> String {
    if value.is_undefined() {
        "undefined".into()
    } else if value.is_null() {
        "null".into()
    } else if let Some(n) = value.as_f64() {
        format!("the number {n}")
    } else if value.as_bool().is_some() {
        "a boolean".into()
    } else if value.is_string() {
        "a string".into()
    } else if value.is_bigint() {
        "a BigInt".into()
    } else if value.is_symbol() {
        "a symbol".into()
    } else if value.is_function() {
        "a function".into()
    } else if Array::is_array(value) {
        "an array".into()
    } else {
        "an object".into()
    }
}

/// A fresh, genuine typed array made by the engine from `value` (which must already be
/// one, `instanceof` the constructor) of at most `limit` elements (checked first, so that
/// nothing huge is copied): a Proxy or subclass posing as one runs its code here, inside
/// `Reflect.get` and `Reflect.construct`, where an exception becomes an `Err`.
fn own_copy(value: &JsValue, constructor: &str, what: &str, limit: usize, unit: &str) -> Result<JsValue, BindingError> {
    let length = length(value, what)?;
    if length > limit as f64 {
        return Err(BindingError::limit(format!("{what} has {length} {unit}; the limit is {limit}")));
    }
    let make = Reflect::get(&js_sys::global(), &JsValue::from_str(constructor))
        .ok()
        .and_then(|c| c.dyn_into::<Function>().ok())
        .ok_or_else(|| {
            BindingError::new(ErrorCode::Internal, format!("this JavaScript engine has no {constructor}"))
        })?;
    Reflect::construct(&make, &Array::of1(value)).map_err(|e| unreadable(what, &e))
}

/// The `length` an array-like argument claims (0 when it has none), read without copying.
pub(super) fn length(value: &JsValue, what: &str) -> Result<f64, BindingError> {
    if !value.is_object() {
        return Ok(0.0);
    }
    Ok(Reflect::get(value, &JsValue::from_str("length")).map_err(|e| unreadable(what, &e))?.as_f64().unwrap_or(0.0))
}

/// The length of a genuine typed array, checked against `limit` elements.
fn checked_length(length: u32, limit: usize, what: &str, unit: &str) -> Result<usize, BindingError> {
    let length = length as usize;
    if length > limit {
        return Err(BindingError::limit(format!("{what} has {length} {unit}; the limit is {limit}")));
    }
    Ok(length)
}

/// A `Float64Array` argument, copied into Rust; at most `limit` numbers.
pub(super) fn float64s(value: &JsValue, what: &str, limit: usize) -> Result<Vec<f64>, BindingError> {
    if !value.is_instance_of::<Float64Array>() {
        return Err(type_error(what, "a Float64Array", value));
    }
    let copy: Float64Array = own_copy(value, "Float64Array", what, limit, "numbers")?.unchecked_into();
    checked_length(copy.length(), limit, what, "numbers")?;
    Ok(copy.to_vec())
}

/// A `Uint32Array` argument, copied into Rust; at most `limit` numbers.
pub(super) fn uint32s(value: &JsValue, what: &str, limit: usize) -> Result<Vec<u32>, BindingError> {
    if !value.is_instance_of::<Uint32Array>() {
        return Err(type_error(what, "a Uint32Array", value));
    }
    let copy: Uint32Array = own_copy(value, "Uint32Array", what, limit, "numbers")?.unchecked_into();
    checked_length(copy.length(), limit, what, "numbers")?;
    Ok(copy.to_vec())
}

/// A `Uint8Array` or `Uint8ClampedArray` argument (image pixels), copied; at most `limit` bytes.
pub(super) fn bytes(value: &JsValue, what: &str, limit: usize) -> Result<Vec<u8>, BindingError> {
    let constructor = if value.is_instance_of::<Uint8ClampedArray>() {
        "Uint8ClampedArray"
    } else if value.is_instance_of::<Uint8Array>() {
        "Uint8Array"
    } else {
        return Err(type_error(what, "a Uint8Array or Uint8ClampedArray", value));
    };
    let copy = own_copy(value, constructor, what, limit, "bytes")?;
    let copy = Uint8Array::new(&copy.unchecked_into::<Uint8ClampedArray>().buffer());
    checked_length(copy.length(), limit, what, "bytes")?;
    Ok(copy.to_vec())
}

/// A string argument of at most `limit` bytes (UTF-8).
pub(super) fn string(value: &JsValue, what: &str, limit: usize) -> Result<String, BindingError> {
    let Some(text) = value.as_string() else {
        return Err(type_error(what, "a string", value));
    };
    if text.len() > limit {
        return Err(BindingError::limit(format!("{what} is {} bytes; the limit is {limit}", text.len())));
    }
    Ok(text)
}

/// A number argument.
pub(super) fn number(value: &JsValue, what: &str) -> Result<f64, BindingError> {
    value.as_f64().ok_or_else(|| type_error(what, "a number", value))
}

/// A whole number argument from 0 to `limit`.
pub(super) fn count(value: &JsValue, what: &str, limit: usize) -> Result<usize, BindingError> {
    let n = number(value, what)?;
    if !(n.fract() == 0.0 && n >= 0.0 && n <= limit as f64) {
        return Err(BindingError::argument(format!("{what} is {n}, expected a whole number from 0 to {limit}")));
    }
    Ok(n as usize)
}

/// The elements of an array argument (`undefined` and `null` read as empty), at most `limit`.
pub(super) fn list(value: &JsValue, what: &str, limit: usize) -> Result<Vec<JsValue>, BindingError> {
    if value.is_undefined() || value.is_null() {
        return Ok(Vec::new());
    }
    if !Array::is_array(value) {
        return Err(type_error(what, "an array", value));
    }
    let get = |key: JsValue| Reflect::get(value, &key).map_err(|e| unreadable(what, &e));
    let length = count(&get(JsValue::from_str("length"))?, &format!("{what}.length"), limit)?;
    (0..length).map(|i| get(JsValue::from(i as u32))).collect()
}

/// An options object, read once: its own string-keyed properties (`undefined` and `null`
/// read as none; properties whose value is `undefined` are left out), each checked against
/// the known names. The one reader of every options object the bindings take.
pub(super) struct Options {
    /// The object's name in messages, e.g. "triangulation".
    what: &'static str,
    /// The known names.
    names: &'static [&'static str],
    /// The properties given, in the object's key order.
    given: Vec<(String, JsValue)>,
}

impl Options {
    /// Reads `value`, refusing a value that is not an object, an unknown key, and a getter or
    /// Proxy trap that throws, all as [`ErrorCode::InvalidOption`] errors.
    pub(super) fn read(
        value: &JsValue,
        what: &'static str,
        names: &'static [&'static str],
    ) -> Result<Self, BindingError> {
        let mut options = Self { what, names, given: Vec::new() };
        if value.is_undefined() || value.is_null() {
            return Ok(options);
        }
        if !value.is_object() || value.is_function() || Array::is_array(value) {
            return Err(BindingError::option(format!("{what} options must be an object, not {}", describe(value))));
        }
        let unreadable =
            |e: JsValue| BindingError::option(format!("{what} options could not be read: {}", message(&e)));
        let keys = Reflect::own_keys(value).map_err(unreadable)?;
        for key in keys.iter() {
            let Some(name) = key.as_string() else { continue };
            if !names.contains(&name.as_str()) {
                return Err(BindingError::option(format!(
                    "unknown {what} option `{name}`; the options are {}",
                    names.join(", ")
                )));
            }
            let field = Reflect::get(value, &key).map_err(unreadable)?;
            if !field.is_undefined() {
                options.given.push((name, field));
            }
        }
        Ok(options)
    }

    /// The names of the options given, in the object's order.
    pub(super) fn names(&self) -> impl Iterator<Item = &str> {
        self.given.iter().map(|(name, _)| name.as_str())
    }

    /// The value of option `name`, if given.
    pub(super) fn get(&self, name: &str) -> Option<&JsValue> {
        debug_assert!(self.names.contains(&name), "{name} is not a {} option", self.what);
        self.given.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// Option `name` as a number, if given.
    pub(super) fn number(&self, name: &str) -> Result<Option<f64>, BindingError> {
        self.get(name).map(|v| v.as_f64().ok_or_else(|| self.wrong_type(name, "a number", v))).transpose()
    }

    /// Option `name` as a whole number from 0 to `limit`, if given.
    pub(super) fn count(&self, name: &str, limit: usize) -> Result<Option<usize>, BindingError> {
        let Some(n) = self.number(name)? else { return Ok(None) };
        if !(n.fract() == 0.0 && n >= 0.0 && n <= limit as f64) {
            return Err(BindingError::option(format!(
                "option {name} is {}, expected a whole number from 0 to {limit}",
                crate::message::Number(n)
            )));
        }
        Ok(Some(n as usize))
    }

    /// Option `name` as one of the strings of `choices`, if given.
    pub(super) fn choice<T: Copy>(&self, name: &str, choices: &[(&str, T)]) -> Result<Option<T>, BindingError> {
        let Some(value) = self.get(name) else { return Ok(None) };
        let text = value.as_string();
        if let Some(&(_, chosen)) = choices.iter().find(|(word, _)| text.as_deref() == Some(*word)) {
            return Ok(Some(chosen));
        }
        let words: Vec<&str> = choices.iter().map(|(word, _)| *word).collect();
        let expected = crate::message::one_of(&words);
        Err(match text {
            Some(text) if text.len() <= 40 => {
                BindingError::option(format!("option {name} is {text:?}, expected {expected}"))
            }
            _ => self.wrong_type(name, &expected, value),
        })
    }

    /// Option `name` as true or false, if given.
    pub(super) fn boolean(&self, name: &str) -> Result<Option<bool>, BindingError> {
        self.get(name)
            .map(|value| value.as_bool().ok_or_else(|| self.wrong_type(name, "true or false", value)))
            .transpose()
    }

    /// Option `name` has a value of the wrong type.
    pub(super) fn wrong_type(&self, name: &str, expected: &str, value: &JsValue) -> BindingError {
        BindingError::option(format!("option {name} must be {expected}, not {}", describe(value)))
    }
}

/// Field `key` of `value`, which must be an object (`what` names it in messages).
pub(super) fn field(value: &JsValue, key: &str, what: &str) -> Result<JsValue, BindingError> {
    if !value.is_object() || value.is_function() {
        return Err(type_error(what, "an object", value));
    }
    Reflect::get(value, &JsValue::from_str(key)).map_err(|e| unreadable(&format!("{what}.{key}"), &e))
}

/// Field `key` of `value`, `None` when it is `undefined` or `null`.
pub(super) fn optional(value: &JsValue, key: &str, what: &str) -> Result<Option<JsValue>, BindingError> {
    let v = field(value, key, what)?;
    Ok((!(v.is_undefined() || v.is_null())).then_some(v))
}

/// An argument whose reading threw: the exception's message.
pub(super) fn unreadable(what: &str, thrown: &JsValue) -> BindingError {
    BindingError::argument(format!("{what} could not be read: {}", message(thrown)))
}

/// The message of a thrown JavaScript value, read without running more of its code.
fn message(thrown: &JsValue) -> String {
    if let Some(text) = thrown.as_string() {
        return text;
    }
    Reflect::get(thrown, &JsValue::from_str("message"))
        .ok()
        .and_then(|m| m.as_string())
        .unwrap_or_else(|| "an exception was thrown".into())
}
