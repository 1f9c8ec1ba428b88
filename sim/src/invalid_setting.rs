//! The one error every settings validation in the model returns.

use std::fmt;

/// A setting whose value is outside what the model allows.
///
/// Carries the key (a dotted path such as `material.poisson_ratio` once the
/// application has prefixed it), the offending value as written, and a sentence
/// saying what is allowed, so that the message can be shown as one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct InvalidSetting {
    /// Dotted path of the key, e.g. `poisson_ratio` or `material.poisson_ratio`.
    pub key: String,
    /// The value as the user gave it.
    pub value: String,
    /// What is allowed, e.g. `must be in the open interval (0, 0.5)`.
    pub allowed: String,
}

impl InvalidSetting {
    /// A new error for `key` with `value` and the `allowed` range.
    pub fn new(
        key: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Self {
            key: key.into(),
            value: short_number(value.to_string()),
            allowed: allowed.into(),
        }
    }

    /// The same error with `prefix.` put in front of the key.
    #[must_use]
    pub fn prefixed(mut self, prefix: &str) -> Self {
        if !prefix.is_empty() {
            self.key = format!("{prefix}.{}", self.key);
        }
        self
    }
}

/// A value that is a long plain number (`f64`'s `Display` writes 1e300
/// with 300 digits) as [`number_text`](crate::physical_range::number_text)
/// writes it; any other text, and any integer of up to 24 digits (u64 and
/// i64 values stay exact), as it is.
fn short_number(text: String) -> String {
    if text.len() <= 24 {
        return text;
    }
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => crate::physical_range::number_text(x),
        _ => text,
    }
}

impl fmt::Display for InvalidSetting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` = {}: {}", self.key, self.value, self.allowed)
    }
}

/// Checks that a value is finite and strictly positive.
pub fn positive(key: &str, value: f64) -> Result<(), InvalidSetting> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(InvalidSetting::new(
            key,
            value,
            "must be a finite number > 0",
        ))
    }
}

/// Checks that a value is finite and not negative.
pub fn non_negative(key: &str, value: f64) -> Result<(), InvalidSetting> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(InvalidSetting::new(
            key,
            value,
            "must be a finite number >= 0",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::InvalidSetting;

    #[test]
    fn long_plain_numbers_are_written_short() {
        assert_eq!(InvalidSetting::new("k", 1e300, "").value, "1e300");
        assert_eq!(InvalidSetting::new("k", 1e-300, "").value, "1e-300");
        assert_eq!(InvalidSetting::new("k", 0.25, "").value, "0.25");
        assert_eq!(
            InvalidSetting::new("k", u64::MAX, "").value,
            "18446744073709551615"
        );
        let words = "a value that is not a number at all";
        assert_eq!(InvalidSetting::new("k", words, "").value, words);
    }
}
