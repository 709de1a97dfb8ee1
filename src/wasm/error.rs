//! The errors the bindings throw: a JavaScript `Error` with the Rust error's message and a
//! `code` property, one of [`ErrorCode`]'s (defined once, in `crate::error`).

use js_sys::{Object, Reflect};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use crate::error_code::ErrorCode;

/// Why a binding refused a call: a stable [`ErrorCode`] and a message. It reaches
/// JavaScript as an `Error` whose `message` is the message and whose own `code` property
/// is the code's string (`"invalid-mesh"`, ...).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BindingError {
    code: ErrorCode,
    message: String,
}

impl BindingError {
    /// An error of this kind with this message.
    pub fn new(code: ErrorCode, message: impl Into<String>) -> Self {
        Self { code, message: message.into() }
    }

    /// An argument of the wrong type, length or value ([`ErrorCode::InvalidArgument`]).
    pub(super) fn argument(message: impl Into<String>) -> Self {
        Self::new(ErrorCode::InvalidArgument, message)
    }

    /// An options object that cannot be used ([`ErrorCode::InvalidOption`]).
    pub(super) fn option(message: impl Into<String>) -> Self {
        Self::new(ErrorCode::InvalidOption, message)
    }

    /// An argument beyond a size limit ([`ErrorCode::Limit`]).
    pub(super) fn limit(message: impl Into<String>) -> Self {
        Self::new(ErrorCode::Limit, message)
    }

    /// The kind of error.
    pub fn code(&self) -> ErrorCode {
        self.code
    }

    /// The message.
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// Any of the crate's errors, with its own code.
impl<E: Into<crate::Error>> From<E> for BindingError {
    fn from(error: E) -> Self {
        let error = error.into();
        Self::new(error.code(), error.to_string())
    }
}

impl From<BindingError> for JsValue {
    /// `new Error(message)` with an own, enumerable, writable `code` property, defined
    /// rather than assigned (so that no setter on `Error.prototype` runs) from a descriptor
    /// without a prototype (so that none of `Object.prototype`'s is read or runs).
    fn from(error: BindingError) -> Self {
        let thrown = js_sys::Error::new(&error.message);
        let descriptor = Object::set_prototype_of(&Object::new(), JsValue::NULL.unchecked_ref());
        let fields = [
            ("value", JsValue::from_str(error.code.as_str())),
            ("writable", JsValue::TRUE),
            ("enumerable", JsValue::TRUE),
            ("configurable", JsValue::TRUE),
        ];
        // Neither can fail on these fresh, ordinary objects; were one to, the Error still
        // carries its message, and nothing here may panic.
        let _ = fields
            .iter()
            .try_for_each(|(key, value)| Reflect::set(&descriptor, &JsValue::from_str(key), value).map(drop))
            .and_then(|()| Reflect::define_property(&thrown, &JsValue::from_str("code"), &descriptor).map(drop));
        thrown.into()
    }
}
