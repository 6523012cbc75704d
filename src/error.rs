//! The crate's one error type, returned by every checked constructor.

use core::fmt;

/// What was wrong with a value given to a checked constructor (`try_*`).
///
/// Every variant names the field and carries the offending value, so a message such as
/// `material.shininess must be non-negative, got -2` can be shown to a user as it is.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum PhongError {
    /// The value is NaN or infinite.
    NonFinite {
        /// Which field, e.g. `"material.diffuse.x"`.
        field: &'static str,
        /// The offending value.
        value: f32,
    },
    /// The value is negative where only `≥ 0` has a meaning (shininess, colours, coefficients).
    Negative {
        /// Which field.
        field: &'static str,
        /// The offending value.
        value: f32,
    },
    /// A direction whose length is zero (or too small to normalise), so it points nowhere.
    ZeroDirection {
        /// Which field.
        field: &'static str,
    },
    /// A value outside its documented interval `[min, max]`.
    OutOfRange {
        /// Which field.
        field: &'static str,
        /// The offending value.
        value: f32,
        /// The smallest accepted value.
        min: f32,
        /// The largest accepted value.
        max: f32,
    },
}

impl fmt::Display for PhongError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PhongError::NonFinite { field, value } => {
                write!(f, "{field} must be finite, got {value}")
            }
            PhongError::Negative { field, value } => {
                write!(f, "{field} must be non-negative, got {value}")
            }
            PhongError::ZeroDirection { field } => {
                write!(f, "{field} must be a non-zero direction")
            }
            PhongError::OutOfRange {
                field,
                value,
                min,
                max,
            } => write!(f, "{field} must lie in [{min}, {max}], got {value}"),
        }
    }
}

impl core::error::Error for PhongError {}

/// Checks that `value` is finite and `≥ 0`.
pub(crate) fn non_negative(field: &'static str, value: f32) -> Result<f32, PhongError> {
    if !value.is_finite() {
        Err(PhongError::NonFinite { field, value })
    } else if value < 0.0 {
        Err(PhongError::Negative { field, value })
    } else {
        Ok(value)
    }
}

/// Checks a colour: every channel finite and `≥ 0`. `fields` names the x, y, z channels.
pub(crate) fn colour(
    fields: [&'static str; 3],
    value: glam::Vec3,
) -> Result<glam::Vec3, PhongError> {
    non_negative(fields[0], value.x)?;
    non_negative(fields[1], value.y)?;
    non_negative(fields[2], value.z)?;
    Ok(value)
}

/// Checks a direction: finite and long enough to normalise; returns it normalised.
pub(crate) fn direction(field: &'static str, value: glam::Vec3) -> Result<glam::Vec3, PhongError> {
    for c in value.to_array() {
        if !c.is_finite() {
            return Err(PhongError::NonFinite { field, value: c });
        }
    }
    // A vector that is already unit to within rounding is kept bit for bit, so a direction read
    // back from a file (or given as exactly unit) is not nudged by another normalisation.
    if (value.length_squared() - 1.0).abs() <= 4.0 * f32::EPSILON {
        return Ok(value);
    }
    let unit = crate::normalize_or_zero(value);
    if unit == glam::Vec3::ZERO {
        Err(PhongError::ZeroDirection { field })
    } else {
        Ok(unit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::string::ToString;

    #[test]
    fn messages_name_field_and_value() {
        let e = non_negative("material.shininess", -2.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "material.shininess must be non-negative, got -2"
        );
        let e = direction("light.direction", glam::Vec3::ZERO).unwrap_err();
        assert_eq!(
            e,
            PhongError::ZeroDirection {
                field: "light.direction"
            }
        );
    }
}
