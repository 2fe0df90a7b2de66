//! Output paths checked before a long run starts, so that a bad path fails
//! at once instead of after the work (and never truncates an existing file).

use anyhow::{bail, Result};
use std::path::Path;

/// Check that `path` can take a new file: its directory exists and it is
/// not itself a directory (an existing file is replaced atomically later).
/// `what` names the option in the error.
pub fn check_file(path: &Path, what: &str) -> Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if path.file_name().is_none() {
        bail!("{what}: {} is not a file path", path.display());
    }
    if !dir.is_dir() {
        bail!(
            "{what}: the directory {} of {} does not exist",
            dir.display(),
            path.display()
        );
    }
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() => bail!("{what}: {} exists and is not a file", path.display()),
        _ => Ok(()),
    }
}

/// [`check_file`] for a PNG: the name must end in `.png` (the only image
/// format written).
pub fn check_png(path: &Path, what: &str) -> Result<()> {
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        bail!(
            "{what}: {} does not end in .png (only PNG is written)",
            path.display()
        );
    }
    check_file(path, what)
}

/// Check that `path` can take a new report directory: it does not exist,
/// or it is a directory holding nothing but an earlier report's entries
/// (replaced whole later; see [`harness_report::atomic::REPORT_ENTRIES`]).
pub fn check_dir(path: &Path, what: &str) -> Result<()> {
    match std::fs::metadata(path) {
        Ok(m) if !m.is_dir() => bail!("{what}: {} exists and is not a directory", path.display()),
        Ok(_) => harness_report::atomic::check_only_report_entries(path)
            .map_err(|e| anyhow::anyhow!("{what}: {e}")),
        Err(_) => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_targets_are_named() {
        let root = tempfile::tempdir().unwrap();
        let file = root.path().join("prev.png");
        std::fs::write(&file, "x").unwrap();
        check_png(&file, "--screen").unwrap();
        let err = check_png(&root.path().join("prev.jpg"), "--screen").unwrap_err();
        assert!(err.to_string().contains("does not end in .png"), "{err}");
        let err = check_png(&root.path().join("no/such.png"), "--screen").unwrap_err();
        assert!(err.to_string().contains("does not exist"), "{err}");
        let err = check_file(root.path(), "--out").unwrap_err();
        assert!(err.to_string().contains("is not a file"), "{err}");
        let err = check_dir(&file, "--out").unwrap_err();
        assert!(err.to_string().contains("is not a directory"), "{err}");
        // A folder of other files would be deleted by the report's swap.
        let err = check_dir(root.path(), "--out").unwrap_err();
        assert!(
            err.to_string()
                .starts_with(&format!("--out: {}", root.path().display()))
                && err.to_string().contains("prev.png, which no report writes"),
            "{err}"
        );
        let report = root.path().join("report");
        std::fs::create_dir_all(report.join("repro")).unwrap();
        std::fs::write(report.join("report.json"), "[]").unwrap();
        check_dir(&report, "--out").unwrap();
        check_dir(&root.path().join("new"), "--out").unwrap();
    }
}
