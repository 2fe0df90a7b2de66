//! The state file of `harness tune --state FILE`: every configuration
//! evaluated, with its result, appended as it is made, so that a run
//! stopped half way goes on where it stopped and a rerun evaluates nothing
//! twice. JSON Lines: a header (format version, the hash of the
//! description without `variants`), then one evaluated configuration per
//! line; a last line cut short by a kill is dropped. The results hold no
//! constraint and no cost: those are applied when the state is read.

use super::evaluate::Evaluation;
use super::space::{self, Config};
use anyhow::{bail, Context};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

/// The state file's format version.
const VERSION: u32 = 2;

/// The first line.
#[derive(Serialize, Deserialize)]
struct Header {
    version: u32,
    /// FNV-1a of the description without `variants`, in hex.
    scene: String,
}

/// One evaluated configuration.
#[derive(Clone, Serialize, Deserialize)]
pub struct Record {
    pub config: Config,
    pub evaluation: Evaluation,
}

/// The evaluations known, in the order they were made.
pub struct State {
    file: Option<std::fs::File>,
    records: Vec<Record>,
    index: HashMap<String, usize>,
    /// Records read from the file.
    pub loaded: usize,
}

/// The hash a state file records of `description` (without `variants`).
pub fn scene_hash(description: &serde_json::Value) -> String {
    format!(
        "{:016x}",
        common::hash::fnv1a(description.to_string().into_bytes())
    )
}

/// The records of a state file's `text` for the description hashed
/// `scene`; `what` names the file in errors.
fn parse(text: &str, scene: &str, what: &str) -> anyhow::Result<Vec<Record>> {
    let mut lines = text.split_inclusive('\n');
    let header: Header = lines
        .next()
        .and_then(|l| serde_json::from_str(l).ok())
        .with_context(|| format!("{what}: not a tune state file (no header line)"))?;
    if header.version != VERSION {
        bail!(
            "{what}: version {} (this harness reads {VERSION})",
            header.version
        );
    }
    if header.scene != scene {
        bail!(
            "{what}: made for another scene (hash {}, this one {scene}); name a new state file",
            header.scene
        );
    }
    let mut records = Vec::new();
    for (i, line) in lines.enumerate() {
        match serde_json::from_str(line) {
            Ok(r) => records.push(r),
            // Cut short by a kill while it was written.
            Err(_) if !line.ends_with('\n') => break,
            Err(e) => bail!("{what}: line {}: {e}", i + 2),
        }
    }
    Ok(records)
}

impl State {
    /// The state of `path` (created with its header when it does not
    /// exist; kept in memory only without a path) for the description
    /// hashed `scene`.
    pub fn open(path: Option<&Path>, scene: String) -> anyhow::Result<State> {
        let mut state = State {
            file: None,
            records: Vec::new(),
            index: HashMap::new(),
            loaded: 0,
        };
        let Some(path) = path else {
            return Ok(state);
        };
        let what = format!("--state {}", path.display());
        if path.exists() {
            let text = common::input::read_text_limited(path, 1 << 32).context(what.clone())?;
            for r in parse(&text, &scene, &what)? {
                state.remember(r);
            }
            state.loaded = state.records.len();
            if !text.is_empty() && !text.ends_with('\n') {
                // Drop the cut line, so that the next one starts afresh.
                let keep = text.rfind('\n').map_or(0, |i| i + 1);
                std::fs::write(path, &text[..keep]).context(what.clone())?;
            }
        } else {
            let header = serde_json::to_string(&Header {
                version: VERSION,
                scene,
            })?;
            harness_report::atomic::write_file(path, format!("{header}\n").as_bytes())?;
        }
        state.file = Some(
            std::fs::OpenOptions::new()
                .append(true)
                .open(path)
                .context(what)?,
        );
        Ok(state)
    }

    fn remember(&mut self, r: Record) {
        self.index.insert(space::key(&r.config), self.records.len());
        self.records.push(r);
    }

    /// The evaluation of `c`, when known.
    pub fn get(&self, c: &Config) -> Option<&Evaluation> {
        self.index
            .get(&space::key(c))
            .map(|&i| &self.records[i].evaluation)
    }

    /// Remember `c`'s evaluation and append it to the file.
    pub fn insert(&mut self, config: Config, evaluation: Evaluation) -> anyhow::Result<()> {
        let record = Record { config, evaluation };
        if let Some(f) = &mut self.file {
            let line = serde_json::to_string(&record)?;
            f.write_all(format!("{line}\n").as_bytes())
                .context("appending to the --state file")?;
        }
        self.remember(record);
        Ok(())
    }

    /// Every evaluation, in the order made.
    pub fn records(&self) -> &[Record] {
        &self.records
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reference::OpCounts;
    use scene::sites::Choice;

    fn evaluation(flips: u64) -> Evaluation {
        Evaluation {
            flips,
            shades: flips,
            first_flip: None,
            max_error: Some(0.5),
            worst_error: Some((1, 2)),
            counts: OpCounts::default(),
        }
    }

    #[test]
    fn a_state_is_written_read_back_and_refused_for_another_scene() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("state.json");
        let mut s = State::open(Some(&path), "abc".into()).unwrap();
        let mut c = Config::new();
        c.insert("pixel/normalize".into(), Choice::Newton1);
        s.insert(c.clone(), evaluation(3)).unwrap();
        s.insert(Config::new(), evaluation(0)).unwrap();
        let again = State::open(Some(&path), "abc".into()).unwrap();
        assert_eq!(again.loaded, 2);
        assert_eq!(again.get(&c), Some(&evaluation(3)));
        assert_eq!(again.get(&Config::new()), Some(&evaluation(0)));
        let e = State::open(Some(&path), "def".into())
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("made for another scene"), "{e}");
        // A line cut short by a kill is dropped; one broken inside is an
        // error naming it.
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, format!("{text}{{\"config\":")).unwrap();
        let mut cut = State::open(Some(&path), "abc".into()).unwrap();
        assert_eq!(cut.loaded, 2);
        cut.insert(Config::new(), evaluation(1)).unwrap();
        assert_eq!(State::open(Some(&path), "abc".into()).unwrap().loaded, 3);
        std::fs::write(&path, format!("{text}{{\n{text}")).unwrap();
        let e = format!(
            "{:#}",
            State::open(Some(&path), "abc".into()).err().unwrap()
        );
        assert!(e.contains("line 4"), "{e}");
        std::fs::write(&path, "{").unwrap();
        let e = format!(
            "{:#}",
            State::open(Some(&path), "abc".into()).err().unwrap()
        );
        assert!(e.contains("not a tune state file"), "{e}");
    }
}
