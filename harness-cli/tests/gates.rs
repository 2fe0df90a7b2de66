//! Every gate, made to fail through the binary: implementations that fail in
//! known ways (tests/adapters/faulty.py) must fail every command that
//! compares, with the status the verdict table gives (1 beyond policy, 3
//! not compared) and a message that names them.

use crate::binary;

use binary::{assert_says, assert_status, harness_in, text};
use std::path::Path;
use std::process::Output;

const FAULTY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/adapters/faulty.py");

/// A project directory whose harness.toml declares the faulty adapters:
/// `hang` (an f32 port answering hang to everything), `crash` (a Float316
/// ops port that crashes after 100 answers), `no-start`, and `aliased` (a
/// right ops port whose inv_sqrt trace shows a sub that differs), and
/// `unchecked` and `checked` (a port answering values outside the modelled
/// domain, declared without and with a domain check).
fn project() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let entry = |name: &str, numbers: &str, levels: &str, args: &str| {
        format!(
            "[impl.{name}]\nkind = \"pipe\"\nnumbers = \"{numbers}\"\nlevels = [{levels}]\n\
             command = \"python3\"\nargs = [\"{FAULTY}\", {args}]\n\n"
        )
    };
    let toml = [
        entry("hang", "f32", "\"sdf\", \"pixels\"", "\"hang-f32\""),
        entry("crash", "float316", "\"ops\"", "\"crash-after\", \"100\""),
        entry("no-start", "float316", "\"ops\"", "\"no-start\""),
        entry("aliased", "float316", "\"ops\"", "\"aliased-sub\"") + "trace = true\n",
        entry("unchecked", "float316", "\"ops\"", "\"no-domain-check\""),
        entry("checked", "float316", "\"ops\"", "\"no-domain-check\"") + "checks_domain = true\n",
    ]
    .concat();
    std::fs::write(dir.path().join("harness.toml"), toml).unwrap();
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    harness_in(dir, args)
}

#[test]
fn diff_says_what_diverged_and_what_was_not_compared() {
    let p = project();
    let o = run(p.path(), &["diff", "hang", "ref-f64", "--level", "sdf"]);
    assert_status(&o, 1, &["diverged: hang vs ref-f64 on sdf-small"]);
    let o = run(p.path(), &["diff", "ref-f316", "crash", "--level", "ops"]);
    assert_status(&o, 3, &["failed: crash on ops-small", "ZeroDivisionError"]);
    assert_says(&o, "no divergence on 100 vectors");
    let o = run(
        p.path(),
        &["diff", "ref-f316", "no-start", "--level", "ops"],
    );
    assert_status(&o, 3, &["no-start (open)", "nothing was compared"]);
}

/// `diff A B C` runs every implementation that opens, and names the ones
/// that did not.
#[test]
fn diff_with_several_implementations_runs_every_one_that_opens() {
    let p = project();
    let o = run(
        p.path(),
        &["diff", "ref-f316", "no-start", "jack", "--level", "ops"],
    );
    assert_status(&o, 3, &["failed: no-start (open)", "ref-f316 vs jack"]);
    assert_says(&o, "no divergence on 435 vectors");
    let o = run(
        p.path(),
        &[
            "diff",
            "ref-f316",
            "no-start",
            "ref-f316+mul-keep-low",
            "--level",
            "ops",
        ],
    );
    assert_status(
        &o,
        1,
        &[
            "no-start (open)",
            "diverged: ref-f316 vs ref-f316+mul-keep-low",
        ],
    );
}

/// A level asked for that an implementation does not answer is not
/// agreement.
#[test]
fn an_unsupported_level_asked_for_is_not_compared() {
    let p = project();
    let o = run(p.path(), &["diff", "ref-f316", "crash", "--level", "sdf"]);
    assert_status(&o, 3, &["unsupported: crash on sdf-small"]);
}

/// A built-in that cannot run here is skipped, and fails the run unless
/// the user allows it.
#[test]
fn an_unavailable_builtin_fails_unless_allowed() {
    let p = project();
    let no_gpu = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_harness"))
            .args(args)
            .current_dir(p.path())
            .env("WGPU_BACKEND", "dx12")
            .output()
            .unwrap()
    };
    let o = no_gpu(&["diff", "ref-f316", "gpu-f316", "jack", "--level", "ops"]);
    assert_status(&o, 3, &["skipped: gpu-f316 (open)", "lavapipe"]);
    let o = no_gpu(&[
        "diff",
        "ref-f316",
        "gpu-f316",
        "jack",
        "--level",
        "ops",
        "--allow-unavailable",
    ]);
    assert_status(
        &o,
        0,
        &["skipped: gpu-f316 (open)", "allowed by --allow-unavailable"],
    );
}

#[test]
fn the_nightly_fails_on_a_float_port_beyond_policy_and_on_one_that_crashes() {
    let p = project();
    let out = p.path().join("reports/nightly");
    let out = out.to_str().unwrap();
    let o = run(
        p.path(),
        &[
            "nightly", "--out", out, "--impls", "hang", "--steps", "levels",
        ],
    );
    assert_status(&o, 1, &["DIVERGED", "hang vs ref-f64 on sdf-nightly"]);
    // The image alone: a render that traps everywhere fails its pair with
    // the oracle, in the trap colour on the overlay.
    let o = run(
        p.path(),
        &[
            "nightly",
            "--out",
            out,
            "--impls",
            "hang",
            "--steps",
            "renders,pairs",
        ],
    );
    assert_status(
        &o,
        1,
        &["diverged: ref-f64 vs hang image: 131072 pixels trapped on one side"],
    );
    let report = std::fs::read_to_string(Path::new(out).join("report.json")).unwrap();
    let report: serde_json::Value = serde_json::from_str(&report).unwrap();
    let pair = report["image_pairs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["a"] == "ref-f64" && p["b"] == "hang")
        .expect("the pair with the oracle");
    let overlay = image::open(Path::new(out).join(pair["overlay"].as_str().unwrap()))
        .unwrap()
        .to_rgb8();
    assert_eq!(
        overlay.get_pixel(5, 5).0,
        harness_report::images::TRAP_COLOUR
    );
    for (name, why) in [
        ("crash", "ZeroDivisionError"),
        ("no-start", "no-start (open)"),
    ] {
        let o = run(
            p.path(),
            &[
                "nightly", "--out", out, "--impls", name, "--steps", "levels",
            ],
        );
        assert_status(&o, 3, &["INCOMPLETE", why]);
        let report = std::fs::read_to_string(Path::new(out).join("report.json")).unwrap();
        let report: serde_json::Value = serde_json::from_str(&report).unwrap();
        let missing = &report["verdict"]["not_compared"];
        assert!(
            missing.as_array().is_some_and(|m| m
                .iter()
                .any(|n| n["what"].as_str().unwrap().starts_with(name))),
            "{missing}"
        );
        // Also a problem at the report's top, and the step has its time.
        let problems = &report["problems"];
        assert!(
            problems
                .as_array()
                .is_some_and(|p| p.iter().any(|l| l.as_str().unwrap().starts_with(name))),
            "{problems}"
        );
        let steps: Vec<&str> = report["meta"]["steps"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["step"].as_str().unwrap())
            .collect();
        assert!(steps.len() >= 2, "{steps:?}");
        assert_eq!(steps[0], "open implementations", "{steps:?}");
    }
}

/// Two shards of a crashing adapter: each `diff` fails, and so does the
/// merge, which counts only what was compared.
#[test]
fn merge_carries_every_shards_failure_and_counts_what_was_compared() {
    let p = project();
    let mut compared = 0;
    for k in 0..2 {
        let shard = format!("{k}/2");
        let dir = format!("shards/{k}");
        let o = run(
            p.path(),
            &[
                "diff",
                "ref-f316",
                "crash",
                "--vectors",
                &set("ops-nightly"),
                "--shard",
                &shard,
                "--report",
                &dir,
            ],
        );
        assert_status(&o, 3, &["failed: crash"]);
        compared += vectors_compared(&text(&o));
    }
    assert_eq!(compared, 200, "each shard's adapter answers 100");
    let o = run(
        p.path(),
        &["merge", "shards/0", "shards/1", "--out", "merged"],
    );
    assert_status(
        &o,
        3,
        &[
            "crash on ops-nightly (shard 0/2)",
            "crash on ops-nightly (shard 1/2)",
        ],
    );
    assert_says(&o, "on 200 cases");
    let o = run(p.path(), &["merge", "shards/0"]);
    assert_status(&o, 3, &["missing: shard 1/2"]);
    let o = run(
        p.path(),
        &["merge", "shards/0", "shards/1", "--out", "shards/1"],
    );
    assert_status(&o, 2, &["is one of the shard reports being merged"]);
    assert!(p.path().join("shards/1/report.json").exists());
    // A shard of no vector compared nothing.
    let o = run(
        p.path(),
        &[
            "diff",
            "ref-f316",
            "jack",
            "--level",
            "ops",
            "--shard",
            "0/4294967295",
        ],
    );
    assert_status(&o, 3, &["nothing was compared"]);
}

/// The committed set `name`'s file.
fn set(name: &str) -> String {
    format!("{}/../vectors/sets/{name}.json", env!("CARGO_MANIFEST_DIR"))
}

/// The vectors a `diff` compared, from its "no divergence on N vectors".
fn vectors_compared(text: &str) -> usize {
    text.lines()
        .find_map(|l| {
            l.trim()
                .strip_prefix("no divergence on ")?
                .split(' ')
                .next()?
                .parse()
                .ok()
        })
        .unwrap_or_else(|| panic!("no count in {text}"))
}

/// Every pixel trapped: render and bench fail and say how many; check's
/// error bound does not hold.
#[test]
fn traps_are_answers_in_render_bench_and_check() {
    let p = project();
    let o = run(p.path(), &["render", "--impl", "hang", "--out", "hang.png"]);
    assert_status(&o, 1, &["131072 of 131072 pixels trapped (131072 hang)"]);
    let img = image::open(p.path().join("hang.png")).unwrap().to_rgb8();
    assert_eq!(img.get_pixel(0, 0).0, harness_report::images::TRAP_COLOUR);
    let o = run(p.path(), &["bench", "hang"]);
    assert_status(
        &o,
        1,
        &["diverged: hang vs ref-f64 image", "131072 pixels trapped"],
    );
    let o = run(
        p.path(),
        &["check", "--max-error", "hang", "0", "--metric", "max"],
    );
    assert_status(&o, 1, &["bad: hang: 131072 of 131072 pixels trapped"]);
}

/// An implementation that cannot render fails render and bench with 3.
#[test]
fn a_render_that_fails_is_not_compared() {
    let p = project();
    let o = run(
        p.path(),
        &["render", "--impl", "no-start", "--out", "x.png"],
    );
    assert_status(&o, 3, &["no-start", "gave no image"]);
    assert!(!p.path().join("x.png").exists());
    let o = run(p.path(), &["bench", "ref-f32", "no-start"]);
    assert_status(&o, 3, &["failed: no-start", "ref-f32"]);
    let o = run(p.path(), &["bench", "ref-f32"]);
    assert_status(&o, 0, &["verdict: agreed"]);
    let o = run(p.path(), &["bench", "ref-f3"]);
    assert_status(&o, 2, &["unknown implementation `ref-f3`"]);
}

/// A project whose harness.toml declares `name`, the seed shader with
/// `edit` applied to its source.
fn seed_shader_project(name: &str, edit: impl FnOnce(&str) -> String) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let seed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/shaders/seed.glsl"
    ))
    .unwrap();
    std::fs::write(dir.path().join(format!("{name}.glsl")), edit(&seed)).unwrap();
    std::fs::write(
        dir.path().join("harness.toml"),
        format!("[impl.{name}]\nkind = \"shader\"\npath = \"{name}.glsl\"\nshade = \"red\"\n"),
    )
    .unwrap();
    dir
}

/// The nightly's levels step on the one implementation `name` of project
/// `p`.
fn nightly_levels(p: &Path, name: &str) -> Output {
    let out = p.join("reports/nightly");
    run(
        p,
        &[
            "nightly",
            "--out",
            out.to_str().unwrap(),
            "--impls",
            name,
            "--steps",
            "levels",
        ],
    )
}

/// A shader with an endless loop: every pixel is a hang, never a white
/// pixel, in every command.
#[test]
fn a_shader_that_loops_for_ever_fails_every_command() {
    let dir = seed_shader_project("loop", |seed| {
        let body = seed.find("void mainImage").unwrap();
        let open = body + seed[body..].find('{').unwrap() + 1;
        format!(
            "{}\n    float spin = 0.0;\n    while (spin >= 0.0) {{ spin += 1.0; }}\n{}",
            &seed[..open],
            &seed[open..]
        )
    });
    let p = dir.path();
    let o = run(p, &["render", "--impl", "loop", "--out", "loop.png"]);
    assert_status(
        &o,
        1,
        &["loop: 131072 of 131072 pixels trapped (131072 hang)"],
    );
    let o = run(p, &["bench", "loop"]);
    assert_status(&o, 1, &["diverged: loop vs ref-f64 image"]);
    let o = run(
        p,
        &["check", "--max-error", "loop", "1", "--metric", "mean"],
    );
    assert_status(&o, 1, &["bad: loop: 131072 of 131072 pixels trapped"]);
    let o = nightly_levels(p, "loop");
    assert_status(&o, 1, &["diverged: loop vs ref-f64 on pixels-nightly"]);
}

/// A shader with a sign error that moves the torus onto the sphere: no
/// pixel traps, but more of the nightly's pixels change level than f32's
/// flip fraction allows, and `diff` on the image says so too.
#[test]
fn a_shader_with_a_sign_error_fails_the_nightly_by_its_flip_fraction() {
    let dir = seed_shader_project("torus", |seed| {
        let torus = "sdTorus(p - vec3(1.5";
        assert!(seed.contains(torus), "the seed shader places its torus");
        seed.replace(torus, "sdTorus(p + vec3(1.5")
    });
    let p = dir.path();
    let o = nightly_levels(p, "torus");
    assert_status(
        &o,
        1,
        &[
            "diverged: torus vs ref-f64 on pixels-nightly",
            "pixels flip",
        ],
    );
    let o = run(p, &["diff", "ref-f64", "torus", "--level", "image"]);
    assert_status(&o, 1, &["FINDING"]);
}

/// `examples/jack-port` copied into a project, with `while (true) { }`
/// put first in the body of `function Num NAME` of Num.jack.
fn jack_port_looping_in(name: &str) -> tempfile::TempDir {
    jack_port_with("Num", name, "while (true) { }")
}

/// `examples/jack-port` copied into a project, with `statement` put first
/// in the body of the function `name` of class `class` (after its `var`
/// declarations).
fn jack_port_with(class: &str, name: &str, statement: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let port = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/jack-port");
    for entry in std::fs::read_dir(&port).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, dir.path().join(path.file_name().unwrap())).unwrap();
    }
    let file = dir.path().join(format!("{class}.jack"));
    let text = std::fs::read_to_string(&file).unwrap();
    let head = text.find(&format!(" {name}(")).unwrap();
    let body = head
        + ["let ", "do ", "while ", "if ", "return"]
            .iter()
            .filter_map(|k| text[head..].find(k))
            .min()
            .unwrap();
    let changed = format!("{}{statement}\n        {}", &text[..body], &text[body..]);
    std::fs::write(&file, changed).unwrap();
    std::fs::write(
        dir.path().join("harness.toml"),
        "[impl.port]\nkind = \"jack\"\nprogram = \".\"\nbindings = \"bindings.toml\"\n",
    )
    .unwrap();
    dir
}

/// A Jack port whose `Num.mod2` never returns: each call is a hang at its
/// budget, an answer that diverges; one whose `Num.add` never returns
/// cannot reach its bindings' ready point, and is a failure of the port
/// (never an unavailable one, which --allow-unavailable would pass).
#[test]
fn a_jack_port_that_loops_fails_with_its_call_stack() {
    let p = jack_port_looping_in("mod2");
    let o = run(p.path(), &["diff", "ref-f316", "port", "--level", "ops"]);
    assert_status(&o, 1, &["diverged: ref-f316 vs port on ops-small"]);
    assert_says(&o, "port: hang");
    let p = jack_port_looping_in("add");
    for args in [
        &[
            "diff",
            "ref-f316",
            "port",
            "--level",
            "ops",
            "--allow-unavailable",
        ][..],
        &["render", "--impl", "port", "--out", "x.png"],
        &["bench", "port", "--allow-unavailable"],
    ] {
        let o = run(p.path(), args);
        assert_status(&o, 3, &["port", "Num.add", "budget"]);
    }
    let out = p.path().join("reports/nightly");
    let o = run(
        p.path(),
        &[
            "nightly",
            "--out",
            out.to_str().unwrap(),
            "--impls",
            "port",
            "--steps",
            "levels",
            "--allow-unavailable",
        ],
    );
    assert_status(&o, 3, &["failed: port (open)", "Num.add"]);
}

/// `explain` judges a pixel by its dithered bit: at (0,0) both bits are
/// black and only the shade differs (by 3.9e-5), at (106,93) the bit flips.
#[test]
fn explain_exits_1_only_where_the_dithered_bit_differs() {
    let p = project();
    let o = run(p.path(), &["explain", "ref-f316", "--pixel", "0,0"]);
    assert_status(&o, 0, &["ref-f316 black", "ref-f64 black"]);
    let o = run(p.path(), &["explain", "ref-f316", "--pixel", "106,93"]);
    assert_status(&o, 1, &["pixel(106,93)"]);
}

/// A port whose `mod2` runs `statement` first: `diff` names the input it
/// crashed on (with `diff_names`) and keeps the answers before it, and
/// `check` says bad (with `why`), never skip, so `git bisect run` blames
/// the commit.
fn assert_mod2_crashes_on_its_input(statement: &str, diff_names: &[&str], why: &str) {
    let p = jack_port_with("Num", "mod2", statement);
    let o = run(p.path(), &["diff", "ref-f316", "port", "--level", "ops"]);
    assert_status(&o, 3, diff_names);
    assert!(
        vectors_compared(&text(&o)) > 0,
        "the answers before it are compared: {}",
        text(&o)
    );
    let check = [
        "check",
        "--no-divergence",
        "ref-f316",
        "port",
        "--level",
        "ops",
    ];
    let o = run(p.path(), &check);
    assert_status(&o, 1, &["bad: ", why]);
}

/// A bound operation that halts the program crashes on its input.
#[test]
fn a_jack_operation_that_halts_is_a_crash_on_its_input() {
    assert_mod2_crashes_on_its_input(
        "do Sys.halt();",
        &["failed: port on ops-small", "crashed", "mod2(", "halted"],
        "halted",
    );
}

/// A bound operation that recurses for ever overflows the Jack stack: a
/// crash on its input like `Sys.halt`, never a failure of the whole batch
/// (which `check` skipped with 125 and `diff` reported without its input,
/// dropping the answers before it).
#[test]
fn a_jack_operation_that_recurses_for_ever_is_a_crash_on_its_input() {
    assert_mod2_crashes_on_its_input(
        "do Num.mod2(a);",
        &[
            "failed: port on ops-small",
            "crashed on input #",
            "mod2(",
            "Stack overflow",
        ],
        "Stack overflow",
    );
}

/// A port whose whole program stops with `Sys.error` as it starts to draw
/// (its entry points all answer): the nightly's screens step reports that
/// screen as not compared, never skips it.
#[test]
fn a_whole_program_that_stops_fails_the_screens_step() {
    let p = jack_port_with("Picture", "render", "do Sys.error(7);");
    let out = p.path().join("reports/nightly");
    let o = run(
        p.path(),
        &[
            "nightly",
            "--out",
            out.to_str().unwrap(),
            "--impls",
            "port",
            "--steps",
            "screens",
        ],
    );
    assert_status(
        &o,
        3,
        &["port-main", "the whole program did not finish", "7"],
    );
}

/// localize compares the answers first: a trace that differs inside an
/// operation whose answer agrees (a sub that writes its result over an
/// operand, its sign dropped later) is shown as a difference that does not
/// reach the answer, and localize exits 0 as diff does.
#[test]
fn localize_exits_0_when_the_answers_agree_and_the_traces_do_not() {
    let p = project();
    let args = ["--op", "inv_sqrt", "--a", "0,127,8192"];
    let o = run(
        p.path(),
        &[&["localize", "ref-f316", "aliased"][..], &args].concat(),
    );
    assert_status(
        &o,
        0,
        &[
            "the answers agree: the traces differ, but the difference does not reach the answer",
            "origin: sub((0,127,12288)=1.5, (0,126,8192)=0.5) at record 3 [inv_sqrt]",
        ],
    );
    let o = run(p.path(), &["diff", "ref-f316", "aliased", "--level", "ops"]);
    assert_status(&o, 0, &["no divergence"]);
    // A divergence that reaches the answer still exits 1.
    let faulty = [
        "localize",
        "ref-f316+sqrt-floor-div",
        "aliased",
        "--op",
        "sqrt",
    ];
    let o = run(p.path(), &[&faulty[..], &["--a", "0,120,15576"]].concat());
    assert_status(&o, 1, &["origin: sqrt((0,120,15576)"]);
}

/// An input outside the reference's modelled domain (floor of 2^14 or more)
/// says nothing about a port that has no domain check: it is counted per
/// operation and not compared, unless the entry declares a check of its
/// own, and then it is a divergence as before.
#[test]
fn inputs_outside_the_domain_are_counted_for_a_port_without_a_domain_check() {
    let p = project();
    let o = run(
        p.path(),
        &["diff", "ref-f316", "unchecked", "--level", "ops"],
    );
    assert_status(
        &o,
        0,
        &["outside the modelled domain, not compared (one side declares no domain check): floor "],
    );
    let o = run(
        p.path(),
        &["check", "--no-divergence", "ref-f316", "unchecked"],
    );
    assert_status(&o, 0, &[]);
    let o = run(p.path(), &["diff", "ref-f316", "checked", "--level", "ops"]);
    assert_status(&o, 1, &["floor / ", "outcome kind"]);
}
