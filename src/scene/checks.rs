//! The range checks every part of a scene uses: a value finite and > 0, or ≥ 0, else an
//! error naming its key and unit.

use crate::error::SceneError;

/// Check that `value` is finite and > 0; the error names `field` and the unit.
pub(crate) fn positive(field: &str, value: f64, unit: &str) -> Result<(), SceneError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SceneError::invalid(
            field,
            value,
            format!("must be finite and > 0 ({unit})"),
        ))
    }
}

/// Check that `value` is finite and ≥ 0; the error names `field` and the unit.
pub(crate) fn non_negative(field: &str, value: f64, unit: &str) -> Result<(), SceneError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(SceneError::invalid(
            field,
            value,
            format!("must be finite and ≥ 0 ({unit})"),
        ))
    }
}
