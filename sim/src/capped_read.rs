//! Reading input files with a size cap.
//!
//! Every file a user names (scenario, surrogate, mesh, trajectory cases) is
//! read through here: at most `cap` bytes are read, so a huge file or an
//! endless one (`/dev/zero`) is refused instead of filling memory, and a
//! named pipe or socket is refused before it is opened (opening a pipe
//! with no writer would wait for one forever).
//! Errors describe the file, never its contents.

use std::io::Read;
use std::path::Path;

/// Why a capped read failed.
#[derive(Debug, thiserror::Error)]
pub enum CappedReadError {
    /// The file could not be opened or read.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The file is a directory.
    #[error("is a directory, not a file")]
    Directory,
    /// The file is a named pipe or a socket.
    #[error("is a named pipe or a socket, not a file")]
    Pipe,
    /// The file holds more than the cap.
    #[error("is larger than {cap} bytes, the most this kind of file may hold")]
    TooLarge {
        /// The cap, bytes.
        cap: u64,
    },
    /// The file is not UTF-8 text (for text formats).
    #[error("is not UTF-8 text")]
    NotText,
}

/// Reads at most `cap` bytes of `path`; more is an error.
pub fn read_capped(path: &Path, cap: u64) -> Result<Vec<u8>, CappedReadError> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let kind = std::fs::metadata(path)?.file_type();
        if kind.is_fifo() || kind.is_socket() {
            return Err(CappedReadError::Pipe);
        }
    }
    let file = std::fs::File::open(path)?;
    if file.metadata()?.is_dir() {
        return Err(CappedReadError::Directory);
    }
    let mut bytes = Vec::new();
    file.take(cap.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(CappedReadError::TooLarge { cap });
    }
    Ok(bytes)
}

/// Reads at most `cap` bytes of `path` as UTF-8 text.
pub fn read_capped_text(path: &Path, cap: u64) -> Result<String, CappedReadError> {
    String::from_utf8(read_capped(path, cap)?).map_err(|_| CappedReadError::NotText)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endless_and_oversized_files_are_refused_without_reading_them_whole() {
        // /dev/zero never ends: the cap stops the read after cap + 1 bytes.
        let e = read_capped(Path::new("/dev/zero"), 1000).unwrap_err();
        assert!(matches!(e, CappedReadError::TooLarge { cap: 1000 }), "{e}");
        assert!(matches!(
            read_capped(Path::new("/"), 10).unwrap_err(),
            CappedReadError::Directory
        ));
        let dir = std::env::temp_dir().join(format!("shearcut-capped-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("bytes");
        std::fs::write(&f, [0xff, 0xfe, b'a']).unwrap();
        assert_eq!(read_capped(&f, 3).unwrap().len(), 3);
        assert!(matches!(
            read_capped_text(&f, 3).unwrap_err(),
            CappedReadError::NotText
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A named pipe with no writer is refused at once instead of waiting.
    #[cfg(unix)]
    #[test]
    fn a_named_pipe_is_refused_without_opening_it() {
        let dir = std::env::temp_dir().join(format!("shearcut-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("pipe.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo (coreutils)");
        assert!(matches!(
            read_capped(&fifo, 10).unwrap_err(),
            CappedReadError::Pipe
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
