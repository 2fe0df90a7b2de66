//! Reading a user's input file (Jack and VM sources, vector sets, scenes):
//! regular files only, since a FIFO or a device such as `/dev/zero` would
//! block or never end; bounded in size; UTF-8, with the line and column of
//! the first byte that is not.

use std::io::Read;
use std::path::{Path, PathBuf};

/// The largest input file read (the largest committed vector set is under
/// 2 MB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// Why an input file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The operating system refused (missing file, no permission, ...).
    #[error("cannot read {}: {cause}", path.display())]
    Io {
        path: PathBuf,
        cause: std::io::Error,
    },
    /// A directory, FIFO, socket or device.
    #[error("{} is not a regular file (a directory, FIFO or device is not read)", path.display())]
    NotAFile { path: PathBuf },
    /// Larger than [`MAX_INPUT_BYTES`].
    #[error("{} is larger than {limit} bytes", path.display())]
    TooLarge { path: PathBuf, limit: u64 },
    /// Not UTF-8 text; `line` and `column` (1-based, the column in
    /// characters) locate the first bad byte.
    #[error("{}:{line}:{column}: not valid UTF-8 text", path.display())]
    NotUtf8 {
        path: PathBuf,
        line: usize,
        column: usize,
    },
}

/// The text of the regular file `path`, at most [`MAX_INPUT_BYTES`] long.
pub fn read_text(path: &Path) -> Result<String, InputError> {
    read_text_limited(path, MAX_INPUT_BYTES)
}

/// [`read_text`] with another size limit.
pub fn read_text_limited(path: &Path, limit: u64) -> Result<String, InputError> {
    let io = |cause| InputError::Io {
        path: path.to_path_buf(),
        cause,
    };
    // Checked before opening: opening a FIFO for reading blocks.
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(InputError::NotAFile {
            path: path.to_path_buf(),
        });
    }
    let file = std::fs::File::open(path).map_err(io)?;
    if !file.metadata().map_err(io)?.is_file() {
        return Err(InputError::NotAFile {
            path: path.to_path_buf(),
        });
    }
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(InputError::TooLarge {
            path: path.to_path_buf(),
            limit,
        });
    }
    String::from_utf8(bytes).map_err(|e| {
        let (line, column) = position(&e.as_bytes()[..e.utf8_error().valid_up_to()]);
        InputError::NotUtf8 {
            path: path.to_path_buf(),
            line,
            column,
        }
    })
}

/// The 1-based line and column just after `valid`, a valid UTF-8 prefix.
fn position(valid: &[u8]) -> (usize, usize) {
    let text = std::str::from_utf8(valid).expect("the prefix is valid UTF-8");
    let line = text.matches('\n').count() + 1;
    let last = text.rfind('\n').map_or(text, |i| &text[i + 1..]);
    (line, last.chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str, bytes: &[u8]) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("common-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }

    #[test]
    fn non_utf8_is_located() {
        let p = temp("bad.jack", b"class Main {\n  // caf\xe9\n}\n");
        let err = read_text(&p).unwrap_err();
        assert!(
            matches!(
                err,
                InputError::NotUtf8 {
                    line: 2,
                    column: 9,
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .ends_with("bad.jack:2:9: not valid UTF-8 text"),
            "{err}"
        );
        let p = temp("multi.jack", "é\u{e9}x\u{80}".as_bytes());
        assert_eq!(read_text(&p).unwrap(), "ééx\u{80}");
        let p = temp("first.jack", b"\xff");
        assert!(matches!(
            read_text(&p).unwrap_err(),
            InputError::NotUtf8 {
                line: 1,
                column: 1,
                ..
            }
        ));
    }

    #[test]
    fn devices_directories_and_large_files_are_refused() {
        let err = read_text(Path::new("/dev/zero")).unwrap_err();
        assert!(matches!(err, InputError::NotAFile { .. }), "{err:?}");
        let err = read_text(&std::env::temp_dir()).unwrap_err();
        assert!(matches!(err, InputError::NotAFile { .. }), "{err:?}");
        let p = temp("big.json", &[b' '; 11]);
        assert!(matches!(
            read_text_limited(&p, 10).unwrap_err(),
            InputError::TooLarge { limit: 10, .. }
        ));
        assert_eq!(read_text_limited(&p, 11).unwrap().len(), 11);
        let err = read_text(Path::new("/no/such/file")).unwrap_err();
        assert!(
            err.to_string().starts_with("cannot read /no/such/file: "),
            "{err}"
        );
        assert!(
            std::error::Error::source(&err).is_none(),
            "the cause is printed once"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = std::env::temp_dir().join(format!("common-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("set.json");
        let _ = std::fs::remove_file(&fifo);
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let err = read_text(&fifo).unwrap_err();
        assert!(matches!(err, InputError::NotAFile { .. }), "{err:?}");
    }
}
