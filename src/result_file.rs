//! Result files written whole or not at all: each under a temporary name
//! beside its final one, renamed into place when complete.

use std::fs::File;
use std::path::Path;

use serde::Serialize;

use crate::error::RunError;

/// Writes the file `path` through `write`, which is given a temporary name
/// beside it (`.partial-<file name>`, the same extension), and renames it
/// into place: readers see the whole file or none. A failed write (a full
/// device) or rename removes the temporary file; one left by a killed
/// process is overwritten by the next write of the same file. Callers
/// keep other processes out of the directory while they write it (`tune`
/// and `tune merge` lock theirs: [`crate::tune::result_dir::DirectoryLock`];
/// a run's directory is its own from its claim).
///
/// # Errors
/// `write`'s error, or the rename's.
pub fn publish(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), RunError>,
) -> Result<(), RunError> {
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let partial = path.with_file_name(format!("{PARTIAL_PREFIX}{file_name}"));
    let remove_partial = |_: &RunError| {
        let _ = std::fs::remove_file(&partial);
    };
    write(&partial).inspect_err(remove_partial)?;
    // Make the contents durable before the name points at them.
    if let Ok(f) = File::open(&partial) {
        let _ = f.sync_all();
    }
    std::fs::rename(&partial, path)
        .map_err(|e| RunError::write(path, e))
        .inspect_err(remove_partial)
}

/// How the name of a file [`publish`] has not finished begins.
pub const PARTIAL_PREFIX: &str = ".partial-";

/// Writes `rows` to `path` as CSV with a header of the field names
/// ([`publish`]ed).
pub fn write_csv<T: Serialize>(
    path: &Path,
    rows: impl IntoIterator<Item = T>,
) -> Result<(), RunError> {
    publish(path, |tmp| {
        let mut w = csv::Writer::from_path(tmp).map_err(|e| RunError::write(path, e))?;
        for r in rows {
            w.serialize(r).map_err(|e| RunError::write(path, e))?;
        }
        w.flush().map_err(|e| RunError::write(path, e))
    })
}

/// Writes the CSV table `path`: the header `columns`, then `rows`
/// ([`publish`]ed).
pub fn write_table<C: AsRef<[u8]>>(
    path: &Path,
    columns: impl IntoIterator<Item = C>,
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<(), RunError> {
    publish(path, |tmp| {
        let mut w = csv::Writer::from_path(tmp).map_err(|e| RunError::write(path, e))?;
        w.write_record(columns)
            .map_err(|e| RunError::write(path, e))?;
        for cells in rows {
            w.write_record(cells)
                .map_err(|e| RunError::write(path, e))?;
        }
        w.flush().map_err(|e| RunError::write(path, e))
    })
}

/// Writes any serialisable value to `path` as pretty JSON ([`publish`]ed).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), RunError> {
    let text = serde_json::to_string_pretty(value).map_err(|e| RunError::write(path, e))?;
    write_text(path, &(text + "\n"))
}

/// Writes `text` to `path` ([`publish`]ed).
pub fn write_text(path: &Path, text: &str) -> Result<(), RunError> {
    publish(path, |tmp| {
        std::fs::write(tmp, text).map_err(|e| RunError::write(path, e))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_published_file_is_whole_or_absent() {
        let d = std::env::temp_dir().join(format!("shearcut-result-file-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("summary.json");
        let e = publish(&p, |tmp| {
            std::fs::write(tmp, "{\"sum").unwrap();
            Err(RunError::write(tmp, "device full"))
        });
        assert!(e.is_err());
        assert!(!p.exists());
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0);
        publish(&p, |tmp| {
            std::fs::write(tmp, "{}").map_err(|e| RunError::write(tmp, e))
        })
        .unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "{}");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        // A rename that fails (onto a non-empty directory) leaves no
        // partial file either.
        let in_the_way = d.join("in-the-way");
        std::fs::create_dir_all(in_the_way.join("x")).unwrap();
        let e = publish(&in_the_way, |tmp| {
            std::fs::write(tmp, "{}").map_err(|e| RunError::write(tmp, e))
        });
        assert!(e.is_err());
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 2);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
