//! Fixed-size arrays in TOML files are read whole or refused.
//!
//! serde reads a `[f64; N]` from the first N elements of a TOML array and
//! the `toml` crate does not complain about the rest, so a 4-element sensor
//! position or a 7-element bias would be accepted silently. A file is
//! therefore compared with what was read from it, written back as TOML:
//! every array of the file must have as many elements as the array read at
//! the same key.

use crate::invalid_setting::InvalidSetting;

/// Compares the arrays of `written` (the file as parsed into a table) with
/// those of `read` (the value deserialised from it, serialised back): the
/// first array whose length differs is an error naming its dotted key, the
/// number of elements given and the number the key takes. Keys present in
/// only one of the two are not compared (defaults, `one or many` keys).
pub fn check_array_lengths(
    written: &toml::Value,
    read: &toml::Value,
) -> Result<(), InvalidSetting> {
    compare(written, read, "")
}

fn compare(written: &toml::Value, read: &toml::Value, key: &str) -> Result<(), InvalidSetting> {
    let at = |k: &str| {
        if key.is_empty() {
            k.to_string()
        } else {
            format!("{key}.{k}")
        }
    };
    match (written, read) {
        (toml::Value::Table(w), toml::Value::Table(r)) => {
            for (k, wv) in w {
                if let Some(rv) = r.get(k) {
                    compare(wv, rv, &at(k))?;
                }
            }
            Ok(())
        }
        (toml::Value::Array(w), toml::Value::Array(r)) => {
            if w.len() != r.len() {
                return Err(InvalidSetting::new(
                    key,
                    format!("{} element(s)", w.len()),
                    format!("must have exactly {} element(s)", r.len()),
                ));
            }
            for (i, (wv, rv)) in w.iter().zip(r).enumerate() {
                compare(wv, rv, &format!("{key}[{i}]"))?;
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize, serde::Deserialize)]
    struct Mount {
        position: [f64; 3],
        rows: Vec<[f64; 2]>,
    }

    fn check(text: &str) -> Result<(), InvalidSetting> {
        let written: toml::Value = toml::from_str(text).unwrap();
        let read: Mount = toml::from_str(text).unwrap();
        check_array_lengths(&written, &toml::Value::try_from(&read).unwrap())
    }

    #[test]
    fn a_longer_array_than_read_is_refused_with_its_key() {
        check("position = [1, 2, 3]\nrows = [[1, 2]]").unwrap();
        let e = check("position = [1, 2, 3, 4]\nrows = []").unwrap_err();
        assert_eq!(
            e.to_string(),
            "`position` = 4 element(s): must have exactly 3 element(s)"
        );
        let e = check("position = [1, 2, 3]\nrows = [[1, 2], [3, 4, 5]]").unwrap_err();
        assert_eq!(e.key, "rows[1]");
    }
}
