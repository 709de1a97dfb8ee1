//! The presentation properties the importer reads, cascaded as CSS does: `fill`,
//! `fill-rule`, `fill-opacity` and `color` inherit; `opacity` does not inherit, but a
//! group's opacity applies to everything inside it, so the importer multiplies it down the
//! tree; `display: none` hides an element and its subtree. Values come from presentation
//! attributes, then from the `style` attribute, which overrides them (later declarations
//! win). Colour values are parsed by svgtypes (named colours, `#rgb`, `#rrggbb`, `rgb()`,
//! `rgba()`, `hsl()`, ...).
//!
//! Folding every opacity into one alpha per element is exact for elements that do not
//! overlap; where elements of a translucent group overlap, a renderer composites the group
//! first, so the overlap is lighter there than one alpha per element draws it.

use roxmltree::Node;
use svgtypes::{Color, Paint as SvgPaint};

use crate::import::vector::FillRule;

/// The fill colour of an imported element: sRGB channels from 0 to 255 and an alpha from 0
/// (transparent) to 1 (opaque). The alpha is the colour's own alpha (`rgba()`,
/// `#rrggbbaa`) times the element's `fill-opacity` times the `opacity` of the element and
/// of each of its ancestors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FillColour {
    /// Red, 0-255.
    pub red: u8,
    /// Green, 0-255.
    pub green: u8,
    /// Blue, 0-255.
    pub blue: u8,
    /// Alpha, 0-1.
    pub alpha: f64,
}

/// A `fill` as specified (`currentColor` stays a keyword until used, as CSS inherits it).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Paint {
    None,
    CurrentColor,
    Colour(Color),
    /// A paint server (`url(#gradient)`), `context-fill`, or a value that does not parse:
    /// filled, in a colour the importer does not know.
    Unknown,
}

/// An element's computed style, as far as the importer needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Style {
    fill: Paint,
    /// The fill rule (inherited).
    pub(super) fill_rule: FillRule,
    fill_opacity: f64,
    color: Color,
    /// The product of `opacity` over the element and its ancestors.
    opacity: f64,
    /// The element's own `opacity` (what a child's `opacity: inherit` takes).
    own_opacity: f64,
}

/// A declaration the importer cannot use: the property and what is wrong.
pub(super) struct StyleError {
    pub(super) property: &'static str,
    pub(super) message: String,
}

/// The properties read, as named in attributes and in `style`.
const PROPERTIES: [&str; 6] = ["fill", "fill-rule", "fill-opacity", "color", "opacity", "display"];

impl Style {
    /// The initial values, the root element's parent style: black fill, nonzero, opaque.
    pub(super) fn initial() -> Self {
        Self {
            fill: Paint::Colour(Color::black()),
            fill_rule: FillRule::NonZero,
            fill_opacity: 1.0,
            color: Color::black(),
            opacity: 1.0,
            own_opacity: 1.0,
        }
    }

    /// Whether shapes with this style are filled (as the outline sees it: any fill but
    /// `none` or `transparent`, even a fully transparent colour).
    pub(super) fn filled(&self) -> bool {
        self.fill != Paint::None
    }

    /// The fill colour, or `None` when unknown (a paint server or an unparsed value) or
    /// when not filled.
    pub(super) fn fill_colour(&self) -> Option<FillColour> {
        let colour = match self.fill {
            Paint::Colour(c) => c,
            Paint::CurrentColor => self.color,
            Paint::None | Paint::Unknown => return None,
        };
        let alpha = f64::from(colour.alpha) / 255.0 * self.fill_opacity * self.opacity;
        Some(FillColour { red: colour.red, green: colour.green, blue: colour.blue, alpha })
    }

    /// The style of `node` given its parent's, or `Ok(None)` when it is not displayed.
    pub(super) fn of(node: Node, parent: &Style) -> Result<Option<Style>, StyleError> {
        let mut declarations: Vec<(&str, &str)> = Vec::new();
        for name in PROPERTIES {
            if let Some(value) = node.attribute(name) {
                declarations.push((name, value));
            }
        }
        // The style attribute overrides presentation attributes.
        if let Some(text) = node.attribute("style") {
            for declaration in text.split(';') {
                if let Some((name, value)) = declaration.split_once(':') {
                    let value = value.trim();
                    let value = value.strip_suffix("!important").map_or(value, str::trim_end);
                    declarations.push((name.trim(), value));
                }
            }
        }
        let mut style = Style { own_opacity: 1.0, ..*parent };
        for (name, value) in declarations {
            let value = value.trim();
            // CSS-wide keywords: `unset` inherits the inherited properties and resets
            // `opacity`, as `initial` resets every one.
            let initial = Style::initial();
            let keyword = ["inherit", "initial", "unset"].into_iter().find(|k| value.eq_ignore_ascii_case(k));
            match (name, keyword) {
                ("opacity", Some("inherit")) => style.own_opacity = parent.own_opacity,
                ("opacity", Some(_)) => style.own_opacity = 1.0,
                ("display", Some("initial" | "unset")) | (_, Some("inherit")) => {}
                ("fill", Some("initial")) => style.fill = initial.fill,
                ("fill-rule", Some("initial")) => style.fill_rule = initial.fill_rule,
                ("fill-opacity", Some("initial")) => style.fill_opacity = initial.fill_opacity,
                ("color", Some("initial")) => style.color = initial.color,
                (_, Some(_)) => {}
                ("display", None) if value == "none" => return Ok(None),
                ("fill", None) => style.fill = parse_paint(value),
                ("fill-rule", None) => {
                    style.fill_rule = match value {
                        "nonzero" => FillRule::NonZero,
                        "evenodd" => FillRule::EvenOdd,
                        other => {
                            return Err(StyleError {
                                property: "fill-rule",
                                message: format!("`{other}` is not nonzero or evenodd"),
                            })
                        }
                    }
                }
                // Invalid values are ignored, as CSS ignores an invalid declaration.
                ("fill-opacity", None) => style.fill_opacity = alpha_value(value).unwrap_or(style.fill_opacity),
                ("opacity", None) => style.own_opacity = alpha_value(value).unwrap_or(style.own_opacity),
                // `color: currentColor` is the inherited colour.
                ("color", None) if !value.eq_ignore_ascii_case("currentcolor") => {
                    if let Ok(colour) = value.parse::<Color>() {
                        style.color = colour;
                    }
                }
                _ => {}
            }
        }
        style.opacity = parent.opacity * style.own_opacity;
        Ok(Some(style))
    }
}

/// A `fill` value. `transparent` counts as `none`, as the outline always has.
fn parse_paint(value: &str) -> Paint {
    if value.eq_ignore_ascii_case("currentcolor") {
        return Paint::CurrentColor;
    }
    if value.eq_ignore_ascii_case("transparent") {
        return Paint::None;
    }
    match SvgPaint::from_str(value) {
        Ok(SvgPaint::None) => Paint::None,
        Ok(SvgPaint::CurrentColor) => Paint::CurrentColor,
        Ok(SvgPaint::Color(colour)) => Paint::Colour(colour),
        // Paint servers, context paint, and values that do not parse.
        Ok(SvgPaint::Inherit | SvgPaint::FuncIRI(..) | SvgPaint::ContextFill | SvgPaint::ContextStroke) | Err(_) => {
            Paint::Unknown
        }
    }
}

/// An `<alpha-value>` (`opacity`, `fill-opacity`): a number or a percentage, clamped to 0-1.
fn alpha_value(text: &str) -> Option<f64> {
    let (number, scale) = match text.strip_suffix('%') {
        Some(number) => (number, 0.01),
        None => (text, 1.0),
    };
    let svgtypes::Number(value) = number.parse().ok()?;
    let value = value * scale;
    (!value.is_nan()).then(|| value.clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_values_are_numbers_or_percentages_clamped() {
        assert_eq!(alpha_value("0.5"), Some(0.5));
        assert_eq!(alpha_value("50%"), Some(0.5));
        assert_eq!(alpha_value("2"), Some(1.0));
        assert_eq!(alpha_value("-1"), Some(0.0));
        assert_eq!(alpha_value("half"), None);
        assert_eq!(alpha_value(""), None);
    }

    #[test]
    fn paints() {
        assert_eq!(parse_paint("none"), Paint::None);
        assert_eq!(parse_paint("transparent"), Paint::None);
        assert_eq!(parse_paint("currentcolor"), Paint::CurrentColor);
        assert_eq!(parse_paint("#f00"), Paint::Colour(Color::new_rgb(255, 0, 0)));
        assert_eq!(parse_paint("url(#g) red"), Paint::Unknown);
        assert_eq!(parse_paint("context-fill"), Paint::Unknown);
        assert_eq!(parse_paint("glitter"), Paint::Unknown);
    }
}
