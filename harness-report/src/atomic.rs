//! Atomic writes: a report directory is built in a staging directory next to
//! its final place and swapped in with one rename, so a reader (or a crash)
//! sees either the whole previous report or the whole new one.

use anyhow::{bail, Context, Result};
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A directory being built next to `target`; [`StagingDir::commit`] puts it
/// in place, dropping it without committing removes it.
#[derive(Debug)]
pub struct StagingDir {
    staging: PathBuf,
    target: PathBuf,
    committed: bool,
}

/// `parent/.name.suffix-pid`, a hidden sibling of `target`.
fn sibling(target: &Path, suffix: &str) -> Result<PathBuf> {
    let name = target
        .file_name()
        .with_context(|| format!("{} has no final component", target.display()))?;
    let parent = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    Ok(parent.join(format!(
        ".{}.{suffix}-{}",
        name.to_string_lossy(),
        std::process::id()
    )))
}

/// Whether process `pid` is still running (a staging directory of a live
/// run, a concurrent nightly, must be left alone).
fn process_alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        // No cheap check: keep everything that might be in use.
        true
    }
}

/// Remove `.name.suffix-PID` siblings of `target` whose process is gone
/// (a run killed before its commit or its drop could clean up).
fn remove_stale_siblings(target: &Path, suffix: &str) -> Result<()> {
    let own = sibling(target, suffix)?;
    let (Some(dir), Some(name)) = (own.parent(), target.file_name()) else {
        return Ok(());
    };
    let prefix = format!(".{}.{suffix}-", name.to_string_lossy());
    let Ok(entries) = fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries.filter_map(std::result::Result::ok) {
        let name = entry.file_name();
        let pid = name
            .to_string_lossy()
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok());
        if pid.is_some_and(|pid| pid != std::process::id() && !process_alive(pid)) {
            let path = entry.path();
            let removed = if entry.file_type().is_ok_and(|t| t.is_dir()) {
                fs::remove_dir_all(&path)
            } else {
                fs::remove_file(&path)
            };
            removed.with_context(|| format!("removing stale {}", path.display()))?;
        }
    }
    Ok(())
}

/// What a report folder holds: `report.json` and `repro/` (`harness diff
/// --report`, `harness merge --out`), `index.html` and `images/` besides
/// them (`harness nightly --out`). `history.jsonl` lies beside the folder,
/// not in it.
pub const REPORT_ENTRIES: [&str; 4] = ["report.json", "repro", "index.html", "images"];

/// Refuse a `target` folder that holds anything a report does not write:
/// the commit replaces the folder whole and deletes what it held, so a
/// folder of the user's own files (or one holding the inputs, as `merge
/// --out shards` would) must never be taken for an earlier report.
pub fn check_only_report_entries(target: &Path) -> Result<()> {
    let Ok(entries) = fs::read_dir(target) else {
        return Ok(());
    };
    let mut unexpected: Vec<String> = entries
        .filter_map(std::result::Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| !REPORT_ENTRIES.contains(&name.as_str()))
        .collect();
    unexpected.sort();
    if let Some(first) = unexpected.first() {
        bail!(
            "{} holds {}{}, which no report writes: a report replaces its whole folder \
             (deleting what it held), so give a new or empty folder, or an earlier \
             report's (which holds only {})",
            target.display(),
            target.join(first).display(),
            match unexpected.len() {
                1 => String::new(),
                n => format!(" and {} more", n - 1),
            },
            REPORT_ENTRIES.join(", ")
        );
    }
    Ok(())
}

impl StagingDir {
    /// Create an empty staging directory beside `target` (creating
    /// `target`'s parent if needed).
    /// Refuses at once a `target` that exists and is not a directory (the
    /// commit could not replace it) or that holds anything but a report's
    /// [`REPORT_ENTRIES`] (the commit would delete it), and removes the
    /// staging directories that killed runs left beside `target`.
    pub fn new(target: &Path) -> Result<Self> {
        if target.exists() && !target.is_dir() {
            bail!("{} exists and is not a directory", target.display());
        }
        check_only_report_entries(target)?;
        let staging = sibling(target, "staging")?;
        if let Some(parent) = staging.parent() {
            fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
        }
        remove_stale_siblings(target, "staging")?;
        if staging.exists() {
            fs::remove_dir_all(&staging)
                .with_context(|| format!("removing stale {}", staging.display()))?;
        }
        fs::create_dir(&staging).with_context(|| format!("creating {}", staging.display()))?;
        Ok(StagingDir {
            staging,
            target: target.to_path_buf(),
            committed: false,
        })
    }

    /// Where to write the files.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The directory the commit replaces.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Replace `target` by the staging directory in one step; the previous
    /// contents of `target` are then removed. A `target` that came to hold
    /// anything but a report's entries since [`StagingDir::new`] is refused
    /// (and kept).
    pub fn commit(mut self) -> Result<PathBuf> {
        if self.target.exists() {
            if !self.target.is_dir() {
                bail!("{} exists and is not a directory", self.target.display());
            }
            check_only_report_entries(&self.target)?;
            exchange(&self.staging, &self.target)?;
            // The staging path now holds the previous report.
            self.committed = true;
            fs::remove_dir_all(&self.staging).with_context(|| {
                format!(
                    "removing the previous report moved to {}",
                    self.staging.display()
                )
            })?;
        } else {
            fs::rename(&self.staging, &self.target).with_context(|| {
                format!(
                    "renaming {} to {}",
                    self.staging.display(),
                    self.target.display()
                )
            })?;
            self.committed = true;
        }
        Ok(self.target.clone())
    }
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: a half-built report must not linger.
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

/// Swap two directories atomically (Linux `renameat2(RENAME_EXCHANGE)`).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> Result<()> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE)
        .with_context(|| format!("exchanging {} and {}", a.display(), b.display()))
}

/// Swap two directories with two renames (no atomic exchange here): a crash
/// between them leaves the previous report under `a`'s name, not lost.
#[cfg(not(target_os = "linux"))]
fn exchange(a: &Path, b: &Path) -> Result<()> {
    let aside = sibling(b, "previous")?;
    fs::rename(b, &aside).with_context(|| format!("moving {} aside", b.display()))?;
    fs::rename(a, b).with_context(|| format!("renaming {} to {}", a.display(), b.display()))?;
    fs::rename(&aside, a).with_context(|| format!("moving {} back", aside.display()))
}

/// Write a file atomically: a temporary sibling, flushed, then renamed over
/// `path`. The temporaries that killed runs left beside `path` are removed.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = sibling(path, "tmp")?;
    remove_stale_siblings(path, "tmp")?;
    let result = (|| {
        let mut f =
            fs::File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        f.write_all(bytes)
            .with_context(|| format!("writing {}", tmp.display()))?;
        f.sync_all()
            .with_context(|| format!("syncing {}", tmp.display()))?;
        fs::rename(&tmp, path)
            .with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Write `img` as a PNG file, atomically ([`write_file`]).
pub fn write_png(path: &Path, img: &image::DynamicImage) -> Result<()> {
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png)
        .with_context(|| format!("encoding {} as PNG", path.display()))?;
    write_file(path, png.get_ref())
}

/// Write `value` as a JSON file, atomically ([`write_file`]).
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let bytes = serde_json::to_vec(value)
        .with_context(|| format!("encoding {} as JSON", path.display()))?;
    write_file(path, &bytes)
}

/// Write several files so that either all are replaced or none is: each is
/// written to a temporary sibling first, and only when every one is
/// written are they renamed into place (a failure removes the temporaries).
pub fn write_files(files: &[(PathBuf, Vec<u8>)]) -> Result<()> {
    let mut written: Vec<PathBuf> = Vec::new();
    let result = (|| {
        for (path, bytes) in files {
            let tmp = sibling(path, "tmp")?;
            remove_stale_siblings(path, "tmp")?;
            written.push(tmp.clone());
            fs::write(&tmp, bytes).with_context(|| format!("writing {}", tmp.display()))?;
        }
        for (path, _) in files {
            if fs::metadata(path).is_ok_and(|m| !m.is_file()) {
                bail!("{} exists and is not a file", path.display());
            }
        }
        for ((path, _), tmp) in files.iter().zip(&written) {
            fs::rename(tmp, path)
                .with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))?;
        }
        Ok(())
    })();
    if result.is_err() {
        for tmp in &written {
            let _ = fs::remove_file(tmp);
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn first_commit_creates_the_directory() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("reports/nightly");
        let stage = StagingDir::new(&target).unwrap();
        fs::write(stage.path().join("a.txt"), "new").unwrap();
        stage.commit().unwrap();
        assert_eq!(fs::read_to_string(target.join("a.txt")).unwrap(), "new");
        assert_eq!(entries(&root.path().join("reports")), vec!["nightly"]);
    }

    #[test]
    fn commit_replaces_the_previous_report_whole() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("nightly");
        fs::create_dir_all(target.join("images")).unwrap();
        fs::write(target.join("report.json"), "old").unwrap();
        let stage = StagingDir::new(&target).unwrap();
        fs::write(stage.path().join("report.json"), "new").unwrap();
        stage.commit().unwrap();
        assert_eq!(entries(&target), vec!["report.json"]);
        assert_eq!(
            fs::read_to_string(target.join("report.json")).unwrap(),
            "new"
        );
        assert_eq!(
            entries(root.path()),
            vec!["nightly"],
            "no staging leftovers"
        );
    }

    #[test]
    fn an_abandoned_build_keeps_the_previous_report() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("nightly");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("report.json"), "old").unwrap();
        {
            let stage = StagingDir::new(&target).unwrap();
            fs::write(stage.path().join("report.json"), "half").unwrap();
            // A failure: dropped without commit.
        }
        assert_eq!(entries(&target), vec!["report.json"]);
        assert_eq!(
            fs::read_to_string(target.join("report.json")).unwrap(),
            "old"
        );
        assert_eq!(entries(root.path()), vec!["nightly"]);
    }

    #[test]
    fn a_file_in_the_way_is_refused_before_any_work() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("nightly");
        fs::write(&target, "not a dir").unwrap();
        let err = StagingDir::new(&target).unwrap_err();
        assert!(err.to_string().contains("is not a directory"), "{err}");
        assert_eq!(fs::read_to_string(&target).unwrap(), "not a dir");
        assert_eq!(entries(root.path()), vec!["nightly"]);
    }

    #[test]
    fn staging_directories_of_killed_runs_are_removed() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("nightly");
        // A PID above Linux's maximum (2^22) is never running.
        let dead = root.path().join(".nightly.staging-99999999");
        fs::create_dir(&dead).unwrap();
        fs::write(dead.join("report.json"), "{}").unwrap();
        // A live process's (this one's parent) run is left alone.
        let live = root.path().join(format!(
            ".nightly.staging-{}",
            std::os::unix::process::parent_id()
        ));
        fs::create_dir(&live).unwrap();
        let other = root.path().join(".other.staging-99999999");
        fs::create_dir(&other).unwrap();
        let stage = StagingDir::new(&target).unwrap();
        stage.commit().unwrap();
        assert_eq!(
            entries(root.path()),
            vec![
                live.file_name().unwrap().to_string_lossy().into_owned(),
                ".other.staging-99999999".to_string(),
                "nightly".to_string()
            ]
        );
    }

    /// A folder holding anything a report does not write is refused, by
    /// the entry's name, and kept whole; an earlier report's is replaced.
    #[test]
    fn a_folder_of_other_files_is_refused_and_kept() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("out");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("report.json"), "[]").unwrap();
        fs::create_dir(target.join("repro")).unwrap();
        fs::write(target.join("notes.txt"), "mine").unwrap();
        let err = StagingDir::new(&target).unwrap_err().to_string();
        assert!(err.contains("notes.txt, which no report writes"), "{err}");
        assert_eq!(entries(&target), vec!["notes.txt", "report.json", "repro"]);
        assert_eq!(entries(root.path()), vec!["out"], "no staging left");
        // Something that arrives during the run is found at the commit.
        fs::remove_file(target.join("notes.txt")).unwrap();
        let stage = StagingDir::new(&target).unwrap();
        fs::create_dir(target.join("0")).unwrap();
        let err = stage.commit().unwrap_err().to_string();
        assert!(err.contains("out/0, which no report writes"), "{err}");
        assert_eq!(entries(&target), vec!["0", "report.json", "repro"]);
        fs::remove_dir(target.join("0")).unwrap();
        let stage = StagingDir::new(&target).unwrap();
        fs::write(stage.path().join("report.json"), "[1]").unwrap();
        stage.commit().unwrap();
        assert_eq!(entries(&target), vec!["report.json"]);
    }

    /// `.NAME.tmp-PID` files of dead processes are swept when `NAME` is
    /// written again; a live process's is left alone.
    #[test]
    fn temporaries_of_killed_writes_are_removed() {
        let root = tempfile::tempdir().unwrap();
        let p = root.path().join("history.jsonl");
        let dead = root.path().join(".history.jsonl.tmp-99999999");
        fs::write(&dead, "half").unwrap();
        let live = format!(".history.jsonl.tmp-{}", std::os::unix::process::parent_id());
        fs::write(root.path().join(&live), "busy").unwrap();
        let other = root.path().join(".other.tmp-99999999");
        fs::write(&other, "x").unwrap();
        write_file(&p, b"one\n").unwrap();
        assert_eq!(
            entries(root.path()),
            vec![
                live.clone(),
                ".other.tmp-99999999".into(),
                "history.jsonl".into()
            ]
        );
        let vm = root.path().join("A.vm");
        fs::write(root.path().join(".A.vm.tmp-99999999"), "half").unwrap();
        write_files(&[(vm, b"new".to_vec())]).unwrap();
        assert_eq!(
            entries(root.path()),
            vec![
                live,
                ".other.tmp-99999999".into(),
                "A.vm".into(),
                "history.jsonl".into()
            ]
        );
    }

    #[test]
    fn write_files_writes_all_or_none() {
        let root = tempfile::tempdir().unwrap();
        let a = root.path().join("A.vm");
        let b = root.path().join("B.vm");
        fs::write(&a, "old").unwrap();
        // B.vm is a directory: nothing may change, A.vm included.
        fs::create_dir(&b).unwrap();
        let files = vec![(a.clone(), b"new".to_vec()), (b.clone(), b"new".to_vec())];
        assert!(write_files(&files).is_err());
        assert_eq!(fs::read_to_string(&a).unwrap(), "old");
        assert_eq!(entries(root.path()), vec!["A.vm", "B.vm"]);
        fs::remove_dir(&b).unwrap();
        write_files(&files).unwrap();
        assert_eq!(fs::read_to_string(&b).unwrap(), "new");
        assert_eq!(entries(root.path()), vec!["A.vm", "B.vm"]);
    }

    #[test]
    fn write_file_replaces_contents() {
        let root = tempfile::tempdir().unwrap();
        let p = root.path().join("history.jsonl");
        write_file(&p, b"one\n").unwrap();
        write_file(&p, b"one\ntwo\n").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "one\ntwo\n");
        assert_eq!(entries(root.path()), vec!["history.jsonl"]);
        assert!(write_file(&root.path().join("missing/x"), b"").is_err());
    }
}
