//! The run history: one JSON line per nightly run (date, commit, divergence
//! counts, error figures, speeds, duration), so trends show across nights.

use crate::atomic;
use crate::model::Report;
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One line of the history file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct HistoryEntry {
    /// Start time of the run, UTC.
    pub date: String,
    /// Git commit.
    pub commit: String,
    /// Duration of the run, seconds.
    pub duration_s: f64,
    /// Divergences under bit-exact policies, all levels together.
    pub divergences: u64,
    /// Differing dithered pixels per image pair, `A vs B`.
    pub pixel_divergences: BTreeMap<String, u64>,
    /// Error figures against `ref-f64` per implementation or variant.
    pub errors: BTreeMap<String, HistoryError>,
    /// Seconds per pixel per implementation or variant.
    pub seconds_per_pixel: BTreeMap<String, f64>,
    /// Steps that failed or could not run.
    pub problems: usize,
}

/// Error figures of one implementation in one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HistoryError {
    /// Mean absolute shade error.
    pub mean: Option<f64>,
    /// Max absolute shade error.
    pub max: Option<f64>,
    /// Dithered pixel flips.
    pub flips: u64,
}

impl HistoryEntry {
    /// The history line summarising a report.
    pub fn from_report(report: &Report) -> Self {
        HistoryEntry {
            date: report.meta.started_at.clone(),
            commit: report.meta.git_commit.clone(),
            duration_s: report.meta.duration_s,
            divergences: report.bit_exact_divergences(),
            pixel_divergences: report
                .image_pairs
                .iter()
                .map(|p| (format!("{} vs {}", p.a, p.b), p.differing_pixels))
                .collect(),
            errors: report
                .speed_error
                .points
                .iter()
                .map(|p| {
                    let e = HistoryError {
                        mean: p.mean_shade_error,
                        max: p.max_shade_error,
                        flips: p.pixel_flips,
                    };
                    (p.label.clone(), e)
                })
                .collect(),
            seconds_per_pixel: report
                .speed_error
                .points
                .iter()
                .map(|p| (p.label.clone(), p.time_per_pixel_s))
                .collect(),
            problems: report.problems.len(),
        }
    }
}

/// Where the history of a report directory lives: beside it,
/// `DIR/../history.jsonl`.
pub fn path_for(report_dir: &Path) -> PathBuf {
    let parent = report_dir
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    parent.join("history.jsonl")
}

/// The history read back: its entries, oldest first, and how many lines
/// could not be read (kept in the file, left out of trends).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// Readable entries, oldest first.
    pub entries: Vec<HistoryEntry>,
    /// Lines that are not a history entry.
    pub unreadable: usize,
}

/// Read the history file; a missing file is an empty history.
pub fn read(path: &Path) -> Result<History> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(History::default()),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    let mut history = History::default();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        match serde_json::from_str(line) {
            Ok(entry) => history.entries.push(entry),
            Err(_) => history.unreadable += 1,
        }
    }
    Ok(history)
}

/// Append one entry, rewriting the file atomically so a crash never leaves
/// half a line.
pub fn append(path: &Path, entry: &HistoryEntry) -> Result<()> {
    let mut bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    if !bytes.is_empty() && !bytes.ends_with(b"\n") {
        bytes.push(b'\n');
    }
    bytes.extend(serde_json::to_vec(entry)?);
    bytes.push(b'\n');
    atomic::write_file(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Comparison, ImagePair, RunMeta, SpeedPoint};

    fn report() -> Report {
        let mut r = Report::new(RunMeta {
            started_at: "2026-11-21T23:00:00Z".into(),
            git_commit: "abc123".into(),
            duration_s: 321.5,
            ..RunMeta::default()
        });
        r.comparisons = vec![
            Comparison {
                policy: crate::BIT_EXACT.into(),
                divergences: 3,
                ..Comparison::default()
            },
            Comparison {
                policy: crate::ERROR_FIGURES.into(),
                divergences: 40,
                ..Comparison::default()
            },
        ];
        r.image_pairs = vec![ImagePair {
            a: "ref-f316".into(),
            b: "jack".into(),
            differing_pixels: 2,
            ..ImagePair::default()
        }];
        r.speed_error.points = vec![SpeedPoint {
            label: "ref-f32".into(),
            time_per_pixel_s: 1e-6,
            mean_shade_error: Some(1e-7),
            max_shade_error: Some(1e-5),
            pixel_flips: 4,
            ..SpeedPoint::default()
        }];
        r.problems = vec!["gpu: no adapter".into()];
        r
    }

    #[test]
    fn entry_summarises_the_report() {
        let e = HistoryEntry::from_report(&report());
        assert_eq!(e.divergences, 3, "only bit-exact divergences count");
        assert_eq!(e.pixel_divergences["ref-f316 vs jack"], 2);
        assert_eq!(e.errors["ref-f32"].flips, 4);
        assert_eq!(e.seconds_per_pixel["ref-f32"], 1e-6);
        assert_eq!(
            (e.commit.as_str(), e.problems, e.duration_s),
            ("abc123", 1, 321.5)
        );
    }

    #[test]
    fn append_then_read_round_trips_and_skips_bad_lines() {
        let dir = tempfile::tempdir().unwrap();
        let report_dir = dir.path().join("nightly");
        let path = path_for(&report_dir);
        assert_eq!(path, dir.path().join("history.jsonl"));
        assert_eq!(read(&path).unwrap(), History::default());
        let e = HistoryEntry::from_report(&report());
        append(&path, &e).unwrap();
        std::fs::write(
            &path,
            format!("{}not json", std::fs::read_to_string(&path).unwrap()),
        )
        .unwrap();
        append(&path, &e).unwrap();
        let h = read(&path).unwrap();
        assert_eq!(h.entries, vec![e.clone(), e]);
        assert_eq!(h.unreadable, 1);
        assert_eq!(std::fs::read_to_string(&path).unwrap().lines().count(), 3);
    }

    #[test]
    fn old_lines_with_fewer_fields_still_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("history.jsonl");
        std::fs::write(
            &path,
            "{\"date\":\"2026-01-01T00:00:00Z\",\"divergences\":7}\n",
        )
        .unwrap();
        let h = read(&path).unwrap();
        assert_eq!(h.entries[0].divergences, 7);
        assert_eq!(path_for(Path::new("nightly")), Path::new("./history.jsonl"));
    }
}
