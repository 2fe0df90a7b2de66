//! Reproducers of hostile runs (issue 20): each once panicked, hung, left a
//! partial file or gave a misleading message.

use crate::binary;

use binary::{assert_says, assert_status, text};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Run the harness with `args`; a run that takes longer than `limit` is
/// killed and fails the test (a FIFO must not block it).
fn harness_within(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            panic!("harness {args:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn harness(args: &[&str]) -> Output {
    harness_within(args, Duration::from_secs(300))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A directory holding `files` (name, contents).
fn dir_with(files: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    dir
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

const HALTS: &[u8] = b"class Main {\n  function void main() {\n    return;\n  }\n}\n";

#[test]
fn a_legal_sdf_point_beyond_the_float_range_is_no_panic() {
    let dir = dir_with(&[(
        "huge.json",
        br#"{"format_version":1,"level":"sdf","name":"x","vectors":[{"category":"c","p":[[0,255,8192],[0,0,0],[0,0,0]]}]}"#,
    )]);
    let set = dir.path().join("huge.json");
    for other in ["ref-f32", "ref-f64"] {
        let o = harness(&["diff", "ref-f316", other, "--vectors", s(&set)]);
        assert!(
            matches!(o.status.code(), Some(0 | 1)),
            "{other}: {}",
            text(&o)
        );
        assert!(!text(&o).contains("panicked"), "{}", text(&o));
    }
}

#[test]
fn jack_run_refuses_a_screen_it_cannot_write_before_running() {
    let src = dir_with(&[("Main.jack", HALTS)]);
    let prev = src.path().join("prev.jpg");
    std::fs::write(&prev, b"an earlier screen").unwrap();
    let o = harness(&["jack", "run", s(src.path()), "--screen", s(&prev)]);
    assert_status(&o, 2, &["does not end in .png"]);
    assert!(!text(&o).contains("instructions:"), "it ran: {}", text(&o));
    assert_eq!(std::fs::read(&prev).unwrap(), b"an earlier screen");
    let png = src.path().join("screen.png");
    let o = harness(&["jack", "run", s(src.path()), "--screen", s(&png)]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(image::open(&png).unwrap().width(), 512);
    assert!(!entries(src.path()).iter().any(|e| e.contains(".tmp")));
}

#[test]
fn jack_compile_writes_every_class_or_none() {
    let class = |n: &str| format!("class {n} {{ function void f() {{ return; }} }}\n");
    let (a, z) = (class("A"), class("Z"));
    let src = dir_with(&[
        ("A.jack", a.as_bytes()),
        ("Main.jack", HALTS),
        ("Z.jack", z.as_bytes()),
    ]);
    let out = tempfile::tempdir().unwrap();
    std::fs::create_dir(out.path().join("Main.vm")).unwrap();
    let o = harness(&["jack", "compile", s(src.path()), "--out", s(out.path())]);
    assert_status(&o, 2, &["Main.vm exists and is not a file"]);
    assert_eq!(entries(out.path()), vec!["Main.vm"], "no partial output");
    std::fs::remove_dir(out.path().join("Main.vm")).unwrap();
    let o = harness(&["jack", "compile", s(src.path()), "--out", s(out.path())]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(entries(out.path()), vec!["A.vm", "Main.vm", "Z.vm"]);
}

#[test]
fn diff_report_leaves_no_stale_repro_files() {
    let report = tempfile::tempdir().unwrap();
    let dir = report.path().join("r");
    let bad = harness(&[
        "diff",
        "ref-f316",
        "ref-f316+sqrt-floor-div",
        "--level",
        "ops",
        "--report",
        s(&dir),
    ]);
    assert_eq!(bad.status.code(), Some(1), "{}", text(&bad));
    assert!(!entries(&dir.join("repro")).is_empty());
    // Every repro the report names is there: report.json and repro/ are
    // replaced together, in one exchange of the directory.
    let json = std::fs::read_to_string(dir.join("report.json")).unwrap();
    let links: Vec<&str> = json
        .lines()
        .filter_map(|l| l.trim().strip_prefix("\"repro\": \""))
        .map(|l| l.trim_end_matches(['"', ',']))
        .collect();
    assert!(!links.is_empty(), "{json}");
    for link in links {
        assert!(Path::new(link).is_file(), "{link} is missing");
    }
    // A staging directory that a killed run left beside it is removed.
    let stale = report.path().join(".r.staging-4000000");
    std::fs::create_dir(&stale).unwrap();
    let good = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--level",
        "ops",
        "--report",
        s(&dir),
    ]);
    assert_eq!(good.status.code(), Some(0), "{}", text(&good));
    assert_eq!(entries(&dir), vec!["report.json", "repro"]);
    assert!(entries(&dir.join("repro")).is_empty(), "stale repro files");
    assert_eq!(entries(report.path()), vec!["r"], "no staging left behind");
    let file = report.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let o = harness(&["diff", "ref-f316", "ref-f316", "--report", s(&file)]);
    assert_status(&o, 2, &["is not a directory"]);
}

#[test]
fn nightly_refuses_an_existing_file_as_out_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("report");
    std::fs::write(&file, "x").unwrap();
    let o = harness_within(&["nightly", "--out", s(&file)], Duration::from_secs(30));
    assert_status(&o, 2, &["exists and is not a directory"]);
    assert!(!text(&o).contains("nightly: "), "a step ran: {}", text(&o));
}

#[test]
fn non_utf8_jack_source_is_located() {
    let src = dir_with(&[(
        "Main.jack",
        b"class Main {\n  // caf\xe9\n  function void main() { return; }\n}\n",
    )]);
    let out = tempfile::tempdir().unwrap();
    let o = harness(&["jack", "compile", s(src.path()), "--out", s(out.path())]);
    assert_status(&o, 2, &["Main.jack:2:9: not valid UTF-8 text"]);
}

#[test]
fn an_error_source_is_printed_once() {
    let dir = dir_with(&[("bad.json", b"{\"format_version\": 1,")]);
    let o = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        s(&dir.path().join("bad.json")),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let t = text(&o);
    let cause = "EOF while parsing";
    assert_eq!(t.matches(cause).count(), 1, "{t}");
}

#[test]
fn an_out_of_range_pixel_is_named() {
    let o = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "99999,99999"]);
    assert_status(
        &o,
        2,
        &["--pixel: (99999,99999) is outside the 512x256 image"],
    );
    let o = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "1,x"]);
    assert_says(&o, "`x` in `1,x` is not a number");
    let o = harness(&[
        "localize",
        "ref-f316",
        "ref-f316",
        "--op",
        "sqrt",
        "--a",
        "0,99999,1",
    ]);
    assert_says(&o, "--a: `99999` is out of range");
}

/// Jack that the official compiler accepts but the VM refuses to load: the
/// error names the Jack position.
#[test]
fn load_errors_of_compiled_jack_point_at_the_jack_source() {
    let cases: [(&[u8], &str); 2] = [
        (
            b"class Main {\n  function void main() {\n    var int x;\n    let x = 65536;\n    return;\n  }\n}\n",
            "Main.jack:4:13: Main.vm:",
        ),
        (
            b"class Main {\n  function void main() {\n    do Missing.f(1);\n    return;\n  }\n}\n",
            "Main.jack:3:8: Main.vm:",
        ),
    ];
    for (source, expected) in cases {
        let src = dir_with(&[("Main.jack", source)]);
        let o = harness(&["jack", "run", s(src.path())]);
        assert_status(&o, 2, &[expected]);
    }
}

/// A FIFO or a device given as an input file neither blocks nor reads
/// without end.
#[test]
fn fifos_and_devices_are_refused_as_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let fifo: PathBuf = dir.path().join("set.json");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let limit = Duration::from_secs(30);
    for path in [s(&fifo), "/dev/zero"] {
        let o = harness_within(&["diff", "ref-f316", "ref-f316", "--vectors", path], limit);
        assert_status(&o, 2, &["is not a regular file"]);
        let png = dir.path().join("x.png");
        let o = harness_within(
            &[
                "render",
                "--impl",
                "ref-f64",
                "--scene",
                path,
                "--out",
                s(&png),
            ],
            limit,
        );
        assert_status(&o, 2, &["is not a regular file"]);
    }
}

/// The same for the project file and the files it names: `--cast`, a jack
/// entry's `bindings` and a shader entry's `path` (each once blocked on a
/// FIFO and read /dev/zero without end).
#[test]
fn fifos_and_devices_are_refused_as_project_files_and_the_files_they_name() {
    let dir = tempfile::tempdir().unwrap();
    let fifo: PathBuf = dir.path().join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let limit = Duration::from_secs(30);
    for path in [s(&fifo), "/dev/zero"] {
        let o = harness_within(&["cast", "--cast", path], limit);
        assert_status(&o, 2, &["is not a regular file"]);
        let bindings =
            format!("[impl.port]\nkind = \"jack\"\nprogram = \".\"\nbindings = \"{path}\"\n");
        let shader =
            format!("[impl.glow]\nkind = \"shader\"\npath = \"{path}\"\nlanguage = \"wgsl\"\n");
        for (name, project) in [("bindings.toml", bindings), ("shader.toml", shader)] {
            let file = dir.path().join(name);
            std::fs::write(&file, project).unwrap();
            let o = harness_within(&["cast", "--cast", s(&file)], limit);
            assert_says(&o, "is not a regular file");
        }
    }
}

/// Every test marked ignore is run by the nightly job: `scripts/nightly.sh`
/// runs `cargo test --release -p CRATE -- --ignored` for each crate that
/// has one (two such tests once ran nowhere).
#[test]
fn the_nightly_runs_every_ignored_test() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let nightly = std::fs::read_to_string(root.join("scripts/nightly.sh")).unwrap();
    let mut crates = Vec::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path.is_dir() && !name.starts_with('.') && name != "target" {
                stack.push(path);
            } else if name.ends_with(".rs")
                && std::fs::read_to_string(&path)
                    .unwrap_or_default()
                    .contains(concat!("#[", "ignore"))
            {
                let manifest = path
                    .ancestors()
                    .find(|a| a.join("Cargo.toml").exists())
                    .unwrap()
                    .join("Cargo.toml");
                let text = std::fs::read_to_string(&manifest).unwrap();
                let package = text
                    .lines()
                    .find_map(|l| l.strip_prefix("name = \""))
                    .map(|n| n.trim_end_matches('"').to_string())
                    .unwrap();
                crates.push((package, path));
            }
        }
    }
    assert!(
        !crates.is_empty(),
        "the jack crate has ignored whole-image tests"
    );
    for (package, file) in crates {
        let run = format!("cargo test --release --locked -p {package} -- --ignored");
        assert!(
            nightly.contains(&run),
            "{}: `{run}` is not in scripts/nightly.sh",
            file.display()
        );
    }
}

/// A report replaces its whole folder: `merge --out` a folder that holds
/// the shards being merged, or `diff --report` a folder of other files,
/// would delete them. Both are refused, naming what is in the way, and
/// nothing is deleted (issue 35, item 8).
#[test]
fn a_report_never_replaces_a_folder_of_other_files_or_of_its_inputs() {
    let root = tempfile::tempdir().unwrap();
    let shards = root.path().join("shards");
    let set = format!(
        "{}/../vectors/sets/ops-small.json",
        env!("CARGO_MANIFEST_DIR")
    );
    for k in 0..2 {
        let o = harness(&[
            "diff",
            "ref-f316",
            "ref-f316",
            "--vectors",
            &set,
            "--shard",
            &format!("{k}/2"),
            "--report",
            s(&shards.join(k.to_string())),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    }
    let zero = shards.join("0");
    let one = shards.join("1");
    for out in [&shards, &root.path().to_path_buf()] {
        let o = harness(&["merge", s(&zero), s(&one), "--out", s(out)]);
        assert_status(
            &o,
            2,
            &[&format!("--out {} holds the shard report", s(out))],
        );
        assert_eq!(entries(&shards), vec!["0", "1"]);
        assert_eq!(entries(&zero), vec!["report.json", "repro"]);
    }
    let merged = root.path().join("merged");
    let o = harness(&["merge", s(&zero), s(&one), "--out", s(&merged)]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // A folder of the user's own files is no report's.
    let mine = dir_with(&[("notes.txt", b"mine")]);
    let o = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        &set,
        "--report",
        s(mine.path()),
    ]);
    assert_status(&o, 2, &["notes.txt, which no report writes"]);
    assert_eq!(entries(mine.path()), vec!["notes.txt"]);
    // An earlier report's folder is replaced as before.
    let o = harness(&["merge", s(&zero), s(&one), "--out", s(&merged)]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

/// A `--point` coordinate beyond Float316's range is named as the user
/// wrote it, `1e-300`, not as 300 digits (issue 35 item 11).
#[test]
fn a_point_beyond_the_float316_range_is_shown_compactly() {
    let o = harness(&["localize", "ref-f316", "ref-f64", "--point", "1e-300,0,0"]);
    assert_status(&o, 2, &["--point: 1e-300 is not a Float316 value"]);
    assert!(!text(&o).contains("000000"), "{}", text(&o));
}
