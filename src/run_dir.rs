//! Result directories: `runs/<scenario>-<UTC time>/`.

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::error::RunError;

/// Creates and returns the result directory: `out` if given, else
/// `runs/<name>-<YYYYmmdd-HHMMSS>` (UTC, plus `-N` if that exists already).
pub fn create(name: &str, out: Option<&Path>) -> Result<PathBuf, RunError> {
    let dir = match out {
        Some(d) => d.to_path_buf(),
        None => {
            // Naming a result directory is the one use of wall time here.
            #[allow(clippy::disallowed_methods)]
            let secs = SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_secs());
            let base = PathBuf::from("runs").join(format!("{name}-{}", utc_stamp(secs)));
            let mut dir = base.clone();
            let mut n = 1;
            while dir.exists() {
                n += 1;
                dir = PathBuf::from(format!("{}-{n}", base.display()));
            }
            dir
        }
    };
    std::fs::create_dir_all(&dir).map_err(|e| RunError::write(&dir, e))?;
    Ok(dir)
}

/// `YYYYmmdd-HHMMSS` for `secs` since the Unix epoch, UTC (civil-from-days,
/// H. Hinnant's algorithm).
pub fn utc_stamp(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}{m:02}{d:02}-{:02}{:02}{:02}",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_stamps() {
        assert_eq!(utc_stamp(0), "19700101-000000");
        // 2000-02-29 12:34:56 UTC = 951827696.
        assert_eq!(utc_stamp(951_827_696), "20000229-123456");
        // 2026-11-22 03:24:05 UTC.
        assert_eq!(utc_stamp(1_795_317_845), "20261122-032405");
    }
}
