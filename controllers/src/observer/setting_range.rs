//! The range check every observer setting goes through.

use shearcut_sim::InvalidSetting;

/// Checks that `value` is finite and within [`low`, `high`]; the error names
/// `key`, the value and the range with its `unit` (e.g. "m", "" for none).
pub(crate) fn check_range(
    key: &str,
    value: f64,
    low: f64,
    high: f64,
    unit: &str,
) -> Result<(), InvalidSetting> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(())
    } else {
        let unit = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        Err(InvalidSetting::new(
            key,
            value,
            format!("must be in [{low}, {high}]{unit}"),
        ))
    }
}

/// Checks that the count `value` is within [`low`, `high`], naming `key`.
pub(crate) fn check_count(
    key: &str,
    value: usize,
    low: usize,
    high: usize,
) -> Result<(), InvalidSetting> {
    if (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(InvalidSetting::new(
            key,
            value,
            format!("must be in [{low}, {high}]"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_key_value_and_range() {
        assert!(check_range("clearance", 2e-4, 0.0, 0.01, "m").is_ok());
        let e = check_range("clearance", f64::NAN, 0.0, 0.01, "m").unwrap_err();
        assert_eq!(e.to_string(), "`clearance` = NaN: must be in [0, 0.01] m");
        let e = check_count("consecutive", 0, 1, 8).unwrap_err();
        assert_eq!(e.to_string(), "`consecutive` = 0: must be in [1, 8]");
    }
}
