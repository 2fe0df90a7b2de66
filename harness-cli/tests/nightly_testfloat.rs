//! `harness nightly --steps testfloat`: TestFloat levels 1 and 2 of every
//! operation through the Float316 implementations, compared bit for bit
//! with ref-f316; the counts per operation and level are in the report
//! (JSON and HTML), and a fault only level 2 catches fails the night.

use crate::binary;

use binary::text;
use std::path::Path;
use std::process::{Command, Output};

/// A clean copy of ref-f316 and one whose division normalises its
/// quotient once (a self-test fault that level 1 misses).
const PROJECT: &str = r#"
[impl.my-port]
kind = "reference"
numbers = "float316"

[impl.my-div]
kind = "reference"
numbers = "float316"
variants = ["div-normalise-once"]
"#;

fn night(dir: &Path, impls: &str) -> (Output, serde_json::Value, String) {
    let out = dir.join("nightly");
    let o = Command::new(env!("CARGO_BIN_EXE_harness"))
        .args([
            "nightly",
            "--impls",
            impls,
            "--steps",
            "testfloat",
            "--out",
            out.to_str().unwrap(),
        ])
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    let report = std::fs::read_to_string(out.join("report.json")).unwrap_or_default();
    let html = std::fs::read_to_string(out.join("index.html")).unwrap_or_default();
    (o, serde_json::from_str(&report).unwrap_or_default(), html)
}

/// The report's count of `op` at `level`.
fn count<'r>(report: &'r serde_json::Value, op: &str, level: u64) -> &'r serde_json::Value {
    report["testfloat"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["op"] == op && c["level"] == level)
        .unwrap_or_else(|| panic!("a count of {op} at level {level}"))
}

#[test]
fn both_levels_of_every_operation_are_compared_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("harness.toml"), PROJECT).unwrap();
    let (o, report, html) = night(dir.path(), "my-port,my-div");
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert_eq!(report["testfloat"].as_array().unwrap().len(), 2 * 12);
    for (op, one, two) in [("add", 46_656, 1_254_528), ("sqrt", 408, 2_448)] {
        for (level, cases) in [(1, one), (2, two)] {
            let c = count(&report, op, level);
            assert_eq!(c["cases"], cases, "{c}");
            assert_eq!(
                c["implementations"],
                serde_json::json!(["ref-f316", "my-port", "my-div"])
            );
            assert_eq!(c["divergences"], 0, "{c}");
        }
    }
    // Level 1 misses the fault, level 2 finds it, and only against my-div.
    assert_eq!(count(&report, "div", 1)["divergences"], 0);
    let found = count(&report, "div", 2)["divergences"].as_u64().unwrap();
    assert!(found > 0);
    let rows: Vec<&serde_json::Value> = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["scope"] == "testfloat-2-div")
        .collect();
    assert_eq!(rows.len(), 2);
    for r in rows {
        assert_eq!(
            (r["level"].as_str(), r["a"].as_str()),
            (Some("testfloat-2"), Some("ref-f316"))
        );
        assert_eq!(r["policy"], "bit-exact");
        let expected = if r["b"] == "my-div" { found } else { 0 };
        assert_eq!(r["divergences"], expected, "{r}");
    }
    assert!(
        html.contains("<td><code>div</code></td><td class=n>46656</td><td class=\"n ok\">0</td><td class=n>1254528</td><td class=\"n bad\">"),
        "{html}"
    );
}

/// `--shard K/N` runs shard K of every set, named so, and the shards of
/// a set together hold each of its vectors once.
#[test]
fn a_sharded_night_runs_its_shard_of_each_set() {
    let dir = tempfile::tempdir().unwrap();
    let cases = |shard: &str| -> u64 {
        let out = dir.path().join(shard.replace('/', "-"));
        let o = Command::new(env!("CARGO_BIN_EXE_harness"))
            .args([
                "nightly", "--impls", "ref-f316", "--steps", "levels", "--shard", shard,
            ])
            .arg("--out")
            .arg(&out)
            .output()
            .expect("the binary runs");
        assert!(o.status.success(), "{}", text(&o));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
                .unwrap();
        let rows = report["comparisons"].as_array().unwrap();
        assert!(!rows.is_empty());
        rows.iter()
            .filter(|r| r["scope"].as_str().unwrap().starts_with("sdf-nightly"))
            .inspect(|r| {
                let set = r["scope"].as_str().unwrap();
                assert!(
                    shard == "0/1" || set.ends_with(&format!("(shard {shard})")),
                    "{set}"
                );
            })
            .map(|r| r["cases"].as_u64().unwrap())
            .max()
            .unwrap()
    };
    let whole = cases("0/1");
    let parts = [cases("0/3"), cases("1/3"), cases("2/3")];
    assert!(
        parts.iter().all(|&p| p > 0 && p < whole),
        "{parts:?} of {whole}"
    );
    assert_eq!(parts.iter().sum::<u64>(), whole);
}
