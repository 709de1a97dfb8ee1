//! A puppet's parts and joints (`crate::deform::puppet`) read from JavaScript and written
//! back: `parts: [{ name, triangles: Uint32Array, depth }]` (other fields, such as an
//! imported part's `paths`, are left alone) and `joints: [{ point: [x, y], parts: [front,
//! back] }]`, as `importPuppet` gives them and the `Deformer` takes them.

use js_sys::{Array, Uint32Array};
use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::read::{self, field};
use super::{max_indices, object};
use crate::deform::{Joint, Part, Puppet, MAX_PART_NAME_BYTES};

/// The parts of a puppet (`parts`, an array) and its joints (`joints`, an array, or
/// `undefined` for none).
pub(super) fn read_puppet(parts: &JsValue, joints: Option<&JsValue>) -> Result<Puppet, BindingError> {
    // The parts hold each triangle once: together at most as many as a mesh may have.
    let mut room = max_indices();
    let parts = read::list(parts, "parts", max_indices())?
        .iter()
        .enumerate()
        .map(|(i, part)| {
            let what = format!("parts[{i}]");
            let name = read::string(&field(part, "name", &what)?, &format!("{what}.name"), MAX_PART_NAME_BYTES)?;
            // The limit left for this part: what the parts before it have not taken.
            let triangles = read::uint32s(&field(part, "triangles", &what)?, &format!("{what}.triangles"), room)?;
            room -= triangles.len();
            let depth = read::number(&field(part, "depth", &what)?, &format!("{what}.depth"))?;
            if !(depth.fract() == 0.0 && depth.abs() <= f64::from(i32::MAX)) {
                return Err(BindingError::argument(format!(
                    "{what}.depth is {}, expected a whole number from -2147483647 to 2147483647",
                    crate::message::Number(depth)
                )));
            }
            Ok(Part { name, triangles, depth: depth as i32 })
        })
        .collect::<Result<Vec<_>, BindingError>>()?;
    let joints = match joints {
        Some(joints) => read_joints(joints)?,
        None => Vec::new(),
    };
    Ok(Puppet { parts, joints })
}

/// The puppet of a mesh to write: `parts` (an array, or `undefined`/`null` for one shape)
/// and `joints` (an array, or `undefined`/`null` for none; refused without parts).
pub(super) fn read_optional_puppet(parts: &JsValue, joints: &JsValue) -> Result<Option<Puppet>, BindingError> {
    let absent = |v: &JsValue| v.is_undefined() || v.is_null();
    match (absent(parts), absent(joints)) {
        (true, true) => Ok(None),
        (true, false) => Err(BindingError::argument("joints were given without parts; joints join parts")),
        (false, _) => Ok(Some(read_puppet(parts, (!absent(joints)).then_some(joints))?)),
    }
}

/// A puppet's `parts` and `joints` as fields of a JavaScript object (none for `None`).
pub(super) fn puppet_fields(puppet: Option<&Puppet>) -> Result<Vec<(&'static str, JsValue)>, BindingError> {
    Ok(match puppet {
        Some(puppet) => {
            vec![("parts", parts_to_js(&puppet.parts)?.into()), ("joints", joints_to_js(&puppet.joints)?.into())]
        }
        None => Vec::new(),
    })
}

/// Joints: `[{ point: [x, y], parts: [front, back] }]`. Part indices are whole numbers
/// (checked against the parts by the deformer); the point two numbers.
pub(super) fn read_joints(joints: &JsValue) -> Result<Vec<Joint>, BindingError> {
    read::list(joints, "joints", max_indices())?
        .iter()
        .enumerate()
        .map(|(i, joint)| {
            let what = format!("joints[{i}]");
            let pair = |key: &str| -> Result<[f64; 2], BindingError> {
                let name = format!("{what}.{key}");
                let items = read::list(&field(joint, key, &what)?, &name, 2)?;
                match items.as_slice() {
                    [a, b] => Ok([read::number(a, &name)?, read::number(b, &name)?]),
                    _ => Err(BindingError::argument(format!("{name} must hold two numbers, not {}", items.len()))),
                }
            };
            let point = pair("point")?;
            let parts = pair("parts")?;
            let index = |x: f64| -> Result<usize, BindingError> {
                if x.fract() == 0.0 && x >= 0.0 && x <= u32::MAX as f64 {
                    Ok(x as usize)
                } else {
                    Err(BindingError::argument(format!(
                        "{what}.parts holds {}, expected part indices (whole numbers from 0)",
                        crate::message::Number(x)
                    )))
                }
            };
            Ok(Joint { point, parts: [index(parts[0])?, index(parts[1])?] })
        })
        .collect()
}

/// Joints as JavaScript reads them.
pub(super) fn joints_to_js(joints: &[Joint]) -> Result<Array, BindingError> {
    let list = Array::new();
    for joint in joints {
        let point = Array::of2(&joint.point[0].into(), &joint.point[1].into());
        let parts = Array::of2(&(joint.parts[0] as u32).into(), &(joint.parts[1] as u32).into());
        list.push(&object(&[("point", point.into()), ("parts", parts.into())])?.into());
    }
    Ok(list)
}

/// Parts as JavaScript reads them (without art).
pub(super) fn parts_to_js(parts: &[Part]) -> Result<Array, BindingError> {
    let list = Array::new();
    for part in parts {
        list.push(
            &object(&[
                ("name", part.name.as_str().into()),
                ("triangles", Uint32Array::from(part.triangles.as_slice()).into()),
                ("depth", part.depth.into()),
            ])?
            .into(),
        );
    }
    Ok(list)
}
