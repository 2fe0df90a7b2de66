//! Jack programs bound through `harness.toml` (kind `jack`), verified
//! through their bindings alone: the seed raymarcher and
//! examples/jack-port (another style), faults injected into a bound program
//! localized to the operation and its Jack call path, bad bindings refused
//! with the field named.

use crate::support;

use common::Outcome;
use harness::cast::Cast;
use harness::implementation::{Answer, Implementation};
use harness::localize::{localize, Localization};
use std::path::{Path, PathBuf};

use crate::binary;
use vectors::{Level, PixelVector, Vector};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A cast with `ray` (the raymarcher's folder and bindings file), `port`
/// (examples/jack-port) and `port-bad` (`dir`, a changed copy of the port).
fn cast_with(extra: &str) -> Cast {
    let root = root();
    let text = format!(
        r#"
[impl.ray]
kind = "jack"
program = "{r}/impls/jack/raymarcher"
bindings = "{r}/impls/jack/raymarcher/bindings.toml"

[impl.port]
kind = "jack"
program = "{r}/examples/jack-port"
bindings = "{r}/examples/jack-port/bindings.toml"
{extra}"#,
        r = root.display()
    );
    Cast::with_project(&root.join("harness.toml"), &text).unwrap()
}

fn open(cast: &Cast, label: &str) -> Box<dyn Implementation> {
    cast.open(label).unwrap_or_else(|e| panic!("{label}: {e}"))
}

fn pixel(x: u16, y: u16) -> Vector {
    Vector::Pixel(PixelVector {
        category: "test".into(),
        x,
        y,
    })
}

#[test]
fn both_programs_agree_with_ref_f316_on_the_small_sets_through_bindings() {
    let cast = cast_with("");
    for label in ["ray", "port"] {
        let imp = open(&cast, label);
        support::assert_agrees_with_ref_f316_on_the_small_sets(imp.as_ref());
    }
}

/// The port's image level is its whole program (its pixel function gives
/// the shade alone; its render loop clamps, dithers and draws with
/// Screen.drawPixel inline), and it is ref-f316's image bit for bit: one
/// run of Main.main, about 20 s.
#[test]
fn the_ports_whole_program_image_agrees_with_ref_f316() {
    let cast = cast_with("");
    let port = open(&cast, "port");
    let reference = open(&cast, "ref-f316");
    let set = vectors::load_named(vectors::named::small_set_name(Level::Image)).unwrap();
    let report = harness::runner::diff_set(
        &[reference.as_ref(), port.as_ref()],
        &set,
        harness::runner::RunOptions::default(),
    );
    assert!(report.failures().next().is_none());
    assert!(
        !report.diverged(),
        "{}",
        harness::text::level_report(&report)
    );
    assert_eq!(report.comparisons.len(), 1);
}

/// A copy of the port in `dir`, each `(file, from, to)` replaced.
fn port_copy(dir: &Path, edits: &[(&str, &str, &str)]) {
    let src = root().join("examples/jack-port");
    std::fs::create_dir_all(dir).unwrap();
    for entry in std::fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        let mut text = std::fs::read_to_string(&path).unwrap();
        for (file, from, to) in edits {
            if path.ends_with(file) {
                assert!(text.contains(from), "{from}");
                text = text.replace(from, to);
            }
        }
        std::fs::write(dir.join(path.file_name().unwrap()), text).unwrap();
    }
}

/// The declaration of `name`: the program in `dir` with its bindings file
/// `bindings`.
fn declared(name: &str, dir: &Path, bindings: &str) -> String {
    format!(
        "[impl.{name}]\nkind = \"jack\"\nprogram = \"{d}\"\nbindings = \"{d}/{bindings}\"\n",
        d = dir.display()
    )
}

/// The port with one line of its add changed, in a copy of its folder.
fn bad_port(dir: &Path) -> String {
    port_copy(
        dir,
        &[(
            "Num.jack",
            "            let lm = lm / pow2[d];",
            "            let lm = lm / pow2[d - 1];",
        )],
    );
    declared("port-bad", dir, "bindings.toml")
}

/// The operation at fault and its Jack call path, whichever way it was found.
fn blamed(l: &Localization) -> (common::Op, String) {
    if let Some(o) = &l.origin {
        return (o.op, o.path.join(" > "));
    }
    let r = l
        .replayed
        .as_ref()
        .unwrap_or_else(|| panic!("not localized:\n{l}"));
    (r.record.op, r.record.path.join(" > "))
}

#[test]
fn a_one_line_change_in_the_ports_add_is_localized_to_add() {
    let dir = tempfile::tempdir().unwrap();
    let cast = cast_with(&bad_port(&dir.path().join("port-bad")));
    let bad = open(&cast, "port-bad");
    let reference = open(&cast, "ref-f316");
    // The pixel of the torus: the port's trace starts at its shade
    // function, not where the reference's does.
    let l = localize(
        bad.as_ref(),
        reference.as_ref(),
        reference.as_ref(),
        &pixel(330, 150),
    )
    .unwrap();
    assert!(l.differs(), "{l}");
    let (op, path) = blamed(&l);
    assert_eq!(op, common::Op::Add, "{l}");
    // The Jack call path of the add at fault: its callers, from the pixel.
    assert_eq!(
        path,
        "pixel(330,150) > Picture.shadeRaw > Light.pixel > Eye.ray > V3.normalize > V3.dot"
    );
    assert!(l.to_string().contains("origin"), "{l}");
}

/// `+web-divide` changes `Math.divide` only: a program that the web IDE's
/// compiler refuses (a field of a class it does not have, which the desktop
/// tools accept) opens with it, and its divisions floor (issue 29 item 5).
#[test]
fn the_web_profiles_math_divide_in_a_bound_program_is_localized() {
    let dir = tempfile::tempdir().unwrap();
    let typo = dir.path().join("typo");
    port_copy(
        &typo,
        &[(
            "Picture.jack",
            "    static Array dither;",
            "    field Vec spare;\n    static Array dither;",
        )],
    );
    let cast = cast_with(&declared("typo", &typo, "bindings.toml"));
    let reference = open(&cast, "ref-f316");
    // The web IDE's compiler refuses it, our desktop profile does not.
    open(&cast, "typo");
    let web_compiler = jack::JackProgram::from_dir(&typo, jack::Profile::Web)
        .expect_err("the web compiler refuses the typo")
        .to_string();
    assert!(web_compiler.contains("Vec"), "{web_compiler}");
    let web = open(&cast, "typo+web-divide");
    let report = support::assert_diverges_on_the_small_ops_set(web.as_ref(), reference.as_ref());
    let input = report.comparisons[0].divergences[0].input.clone();
    let l = localize(web.as_ref(), reference.as_ref(), reference.as_ref(), &input).unwrap();
    // The web IDE's flooring Math.divide changes the port's sqrt (its
    // exponent halving), called from the host: the path is the operation.
    assert_eq!(blamed(&l), (common::Op::Sqrt, "sqrt".to_string()), "{l}");
}

const INLINE: &str = r#"
[impl.inline]
kind = "jack"
program = "{r}/examples/jack-port"
ready = { run = "Main.main", keys = "SPACE", until_call = "Picture.render" }

[impl.inline.float]
class = "Num"
fields = ["m", "e", "s"]
new = "Num.make(m, e, s)"

[impl.inline.ops]
add = "result = Num.add(a, b)"
"#;

#[test]
fn bindings_inline_in_the_project_file_bind_only_what_they_name() {
    let root = root();
    let text = INLINE.replace("{r}", &root.display().to_string());
    let cast = Cast::with_project(&root.join("harness.toml"), &text).unwrap();
    assert_eq!(cast.get("inline").unwrap().levels, [Level::Ops]);
    let imp = open(&cast, "inline");
    let (a, b) = (
        common::F316::new(0, 129, 10240),
        common::F316::new(1, 127, 12288),
    );
    let op = |op| {
        Vector::Op(vectors::OpVector {
            category: "test".into(),
            op,
            a,
            b: Some(b),
        })
    };
    let reference = open(&cast, "ref-f316");
    let add = [op(common::Op::Add)];
    assert_eq!(imp.eval(&add).unwrap(), reference.eval(&add).unwrap());
    // An operation the bindings leave out (the program writes it inline)
    // is answered unsupported, never guessed, and counted apart from the
    // vectors compared (issue 29 item 9).
    let mul = [
        op(common::Op::Mul),
        op(common::Op::Add),
        op(common::Op::Mul),
    ];
    let answers = imp.eval(&mul).unwrap();
    assert_eq!(answers[0], Outcome::Value(Answer::Unsupported));
    assert_eq!(answers[1], reference.eval(&add).unwrap()[0]);
    let set = vectors::VectorSet::new("mixed", Level::Ops, "test", None, mul.to_vec());
    let report = harness::runner::diff_set(
        &[reference.as_ref(), imp.as_ref()],
        &set,
        harness::runner::RunOptions::default(),
    );
    assert!(report.failures().next().is_none());
    let c = &report.comparisons[0];
    assert!(!c.diverged, "{}", harness::text::level_report(&report));
    assert_eq!(c.unsupported.get("mul"), Some(&2), "{c:?}");
    assert_eq!(c.vectors, 1, "{c:?}");
}

#[test]
fn a_malformed_inline_binding_names_the_file_line_and_field() {
    let root = root();
    let text = INLINE
        .replace("{r}", &root.display().to_string())
        .replace("fields = [\"m\", \"e\", \"s\"]", "fields = \"m\"");
    let e = Cast::with_project(&root.join("harness.toml"), &text)
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("harness.toml:"), "{e}");
    assert!(e.contains("impl.inline.float"), "{e}");
}

fn mod2_vector(a: common::F316) -> Vector {
    Vector::Op(vectors::OpVector {
        category: "test".into(),
        op: common::Op::Mod2,
        a,
        b: None,
    })
}

/// The port's `mod2` counts the integer part down by two, one pass per 2:
/// mod2 of 16383 takes more than the 50 000 instructions the budget once
/// was, answers ref-f316's value under the default budget, and hangs under
/// a budget of 50 000, the hang naming the budget field; a small integer
/// part answers under that budget too (issue 29 item 1 and its example).
#[test]
fn a_slow_operation_answers_under_the_default_budget_and_hangs_below_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let port = root().join("examples/jack-port");
    let bindings = std::fs::read_to_string(port.join("bindings.toml")).unwrap();
    let tight = dir.path().join("tight.toml");
    std::fs::write(&tight, format!("budget = {{ op = 50000 }}\n{bindings}")).unwrap();
    let project = format!(
        "[impl.slow-tight]\nkind = \"jack\"\nprogram = \"{}\"\nbindings = \"{}\"\n",
        port.display(),
        tight.display()
    );
    let cast = cast_with(&project);
    let reference = open(&cast, "ref-f316");
    let slow = [mod2_vector(common::F316::new(0, 140, 16383))];
    let want = reference.eval(&slow).unwrap();
    assert!(matches!(want[0], common::Outcome::Value(_)));
    assert_eq!(open(&cast, "port").eval(&slow).unwrap(), want);
    let tight_port = open(&cast, "slow-tight");
    assert_eq!(tight_port.eval(&slow).unwrap(), [common::Outcome::Hang]);
    let fast = [mod2_vector(common::F316::new(0, 129, 12288))];
    assert_eq!(
        tight_port.eval(&fast).unwrap(),
        reference.eval(&fast).unwrap()
    );

    // On the command line, the hang names the field that sets the budget.
    std::fs::write(dir.path().join("harness.toml"), &project).unwrap();
    let file = dir.path().join("mod2.json");
    std::fs::write(
        &file,
        r#"{"format_version":1,"name":"mod2","level":"ops","vectors":[{"category":"c","op":"mod2","a":[0,140,16383]}]}"#,
    )
    .unwrap();
    let o = binary::harness_in(
        dir.path(),
        &[
            "diff",
            "ref-f316",
            "slow-tight",
            "--vectors",
            file.to_str().unwrap(),
        ],
    );
    let text = binary::text(&o);
    assert_eq!(o.status.code(), Some(1), "{text}");
    assert!(text.contains("hang"), "{text}");
    assert!(
        text.contains("budget `budget.op` (50000 instructions)"),
        "{text}"
    );
}

/// The port's invSqrt calls its `sub` with the result aliased to the second
/// operand, which flips the sign of the result; invSqrt drops that sign
/// later. localize prints the trace difference as one that does not reach
/// the answer and exits 0, and diff finds the answers agree.
#[test]
fn the_ports_aliased_sub_is_a_trace_difference_that_does_not_reach_the_answer() {
    let dir = tempfile::tempdir().unwrap();
    let port = root().join("examples/jack-port");
    std::fs::write(
        dir.path().join("harness.toml"),
        declared("port", &port, "bindings.toml"),
    )
    .unwrap();
    let args = [
        "localize",
        "ref-f316",
        "port",
        "--op",
        "inv_sqrt",
        "--a",
        "0,127,8192",
    ];
    let o = binary::harness_in(dir.path(), &args);
    let text = binary::text(&o);
    assert_eq!(o.status.code(), Some(0), "{text}");
    assert!(
        text.contains("the traces differ, but the difference does not reach the answer"),
        "{text}"
    );
    assert!(
        text.contains("sub((0,127,12288)=1.5, (0,126,8192)=0.5)"),
        "{text}"
    );
    let o = binary::harness_in(dir.path(), &["diff", "ref-f316", "port", "--level", "ops"]);
    let text = binary::text(&o);
    assert_eq!(o.status.code(), Some(0), "{text}");
}

/// The line and column (1-based) where `needle` starts in `text`.
fn line_col(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).unwrap_or_else(|| panic!("{needle}"));
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    (line, at - before.rfind('\n').map_or(0, |i| i + 1) + 1)
}

fn open_err(cast: &Cast, label: &str) -> String {
    match cast.open(label) {
        Ok(_) => panic!("{label} opened"),
        Err(e) => e.to_string(),
    }
}

/// A binding error found at open names the file, the line and the column
/// of the field's value, inline and in a bindings file (issue 29 item 6).
#[test]
fn a_binding_error_at_open_names_the_file_line_and_column() {
    let root = root();
    let text = INLINE
        .replace("{r}", &root.display().to_string())
        .replace("Num.add(a, b)", "Num.plus(a, b)");
    let cast = Cast::with_project(&root.join("harness.toml"), &text).unwrap();
    let (line, col) = line_col(&text, "\"result = Num.plus");
    let e = open_err(&cast, "inline");
    let at = format!("harness.toml:{line}:{col}: impl.inline.ops.add: bad binding: ");
    assert!(e.contains(&at), "{at}\n{e}");
    assert!(e.contains("no function `Num.plus`"), "{e}");

    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad");
    port_copy(
        &bad,
        &[(
            "bindings.toml",
            "\"Num.make(m, e, s)\"",
            "\"Num.make(m, e)\"",
        )],
    );
    let cast = cast_with(&declared("bad", &bad, "bindings.toml"));
    let file = std::fs::read_to_string(bad.join("bindings.toml")).unwrap();
    let (line, col) = line_col(&file, "\"Num.make(m, e)\"");
    let e = open_err(&cast, "bad");
    let at = format!("bindings.toml:{line}:{col}: float.new: bad binding: ");
    assert!(e.contains(&at), "{at}\n{e}");
}

/// An inline entry without `ready` is refused when declared, naming it
/// (issue 29 item 6).
#[test]
fn an_inline_entry_without_ready_is_refused_naming_ready() {
    let root = root();
    let text = INLINE.replace("{r}", &root.display().to_string()).replace(
        "ready = { run = \"Main.main\", keys = \"SPACE\", until_call = \"Picture.render\" }\n",
        "",
    );
    let e = Cast::with_project(&root.join("harness.toml"), &text)
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("impl.inline.ready: missing"), "{e}");
}

/// `sdf_result.fields` swapped, with a `new` that never receives the parts,
/// round-trips; the roles check at open refuses it (issue 29 item 6).
#[test]
fn swapped_sdf_result_fields_are_refused_at_open() {
    let dir = tempfile::tempdir().unwrap();
    let swapped = dir.path().join("swapped");
    port_copy(
        &swapped,
        &[(
            "bindings.toml",
            "fields = [\"colour\", \"distance\"]",
            "fields = [\"distance\", \"colour\"]",
        )],
    );
    let cast = cast_with(&declared("swapped", &swapped, "bindings.toml"));
    let e = open_err(&cast, "swapped");
    assert!(e.contains("sdf_result.fields: bad binding: "), "{e}");
    assert!(e.contains("each other's roles"), "{e}");
}

/// The port bound at the pixel level with the shade alone (issue 29 item
/// 3): `Light.pixel` leaves the shade before the clamp in `shade`. Declared
/// `pixel_shade = "unclamped"`, the harness clamps it and computes the
/// white bit with ref-f316's own operations, and the pixels agree with
/// ref-f316's; declared clamped (the default), the same shade is compared
/// unclamped, and the pixels whose shade lies outside [0, 1] diverge.
#[test]
fn a_pixel_binding_that_gives_the_shade_alone_agrees_with_ref_f316() {
    let dir = tempfile::tempdir().unwrap();
    let raw = dir.path().join("raw");
    port_copy(
        &raw,
        &[(
            "bindings.toml",
            "pixel = \"shade = Picture.shadeRaw(u, v)\"",
            "pixel = \"Light.pixel(u, v, shade)\"",
        )],
    );
    let bindings = std::fs::read_to_string(raw.join("bindings.toml")).unwrap();
    std::fs::write(
        raw.join("as-clamped.toml"),
        bindings.replace("pixel_shade = \"unclamped\"\n", ""),
    )
    .unwrap();
    let cast = cast_with(&format!(
        "{}{}",
        declared("raw", &raw, "bindings.toml"),
        declared("raw-as-clamped", &raw, "as-clamped.toml")
    ));
    let reference = open(&cast, "ref-f316");
    let set = vectors::load_named(vectors::named::small_set_name(Level::Pixels)).unwrap();
    let options = harness::runner::RunOptions::default();
    let subject = open(&cast, "raw");
    assert!(subject.supports(Level::Pixels));
    let report = harness::runner::diff_set(&[reference.as_ref(), subject.as_ref()], &set, options);
    assert!(report.failures().next().is_none());
    assert!(
        !report.diverged(),
        "{}",
        harness::text::level_report(&report)
    );
    assert_eq!(report.comparisons[0].vectors, set.vectors.len());

    let wrong = open(&cast, "raw-as-clamped");
    let report = harness::runner::diff_set(&[reference.as_ref(), wrong.as_ref()], &set, options);
    assert!(
        report.diverged(),
        "{}",
        harness::text::level_report(&report)
    );
}

/// Every command agrees about a Jack entry whose only image is its
/// whole-program capture (issue 29 item 4): the port bound without `pixel`,
/// its render loop cut to the first two rows so that a whole run is short.
/// diff judges the image and gives no localize command and no repro file
/// for its pixels, a pixels level asked for is not compared (3), check
/// judges the image (1: the rows left white diverge) and cannot decide a
/// shade metric (125), render writes the captured bits (exit 0; 3 with
/// --values), bench has its row, and localize at a pixel exits 3.
#[test]
fn every_command_agrees_about_a_capture_only_jack_entry() {
    let dir = tempfile::tempdir().unwrap();
    let cap = dir.path().join("cap");
    port_copy(
        &cap,
        &[
            (
                "bindings.toml",
                "pixel = \"shade = Picture.shadeRaw(u, v)\"\npixel_shade = \"unclamped\"\n",
                "",
            ),
            ("Picture.jack", "while (yi < 256) {", "while (yi < 2) {"),
        ],
    );
    let project = declared("cap", &cap, "bindings.toml");
    std::fs::write(dir.path().join("harness.toml"), &project).unwrap();
    let run = |args: &[&str]| {
        let o = binary::harness_in(dir.path(), args);
        (o.status.code(), binary::text(&o))
    };

    let report = dir.path().join("report");
    let report_arg = report.to_str().unwrap();
    let (code, text) = run(&[
        "diff", "ref-f316", "cap", "--level", "image", "--report", report_arg,
    ]);
    assert_eq!(code, Some(1), "{text}");
    assert!(!text.contains("harness localize"), "{text}");
    let repro: Vec<_> = std::fs::read_dir(report.join("repro")).unwrap().collect();
    assert!(repro.is_empty(), "{repro:?}");

    let (code, text) = run(&["diff", "ref-f316", "cap", "--level", "pixels"]);
    assert_eq!(code, Some(3), "{text}");

    let (code, text) = run(&[
        "check",
        "--no-divergence",
        "ref-f316",
        "cap",
        "--level",
        "image",
    ]);
    assert_eq!(code, Some(1), "{text}");
    let (code, text) = run(&["check", "--max-error", "cap", "0.5", "--metric", "max"]);
    assert_eq!(code, Some(125), "{text}");
    assert!(text.contains("--metric flips"), "{text}");

    let png = dir.path().join("cap.png");
    let (code, text) = run(&["render", "--impl", "cap", "--out", png.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{text}");
    // The two rows the program drew are ref-f316's; the rest stayed white.
    let bits = image::open(&png).unwrap().to_luma8();
    let reference = reference::Reference::seed(reference::RefImpl::F316);
    for y in 0..256u32 {
        for x in (0..512u32).step_by(7) {
            let want = y >= 2
                || reference
                    .pixel(x as usize, y as usize)
                    .value()
                    .unwrap()
                    .white;
            assert_eq!(bits.get_pixel(x, y).0[0] == 255, want, "({x},{y})");
        }
    }
    let values = dir.path().join("values.json");
    let (code, text) = run(&[
        "render",
        "--impl",
        "cap",
        "--out",
        png.to_str().unwrap(),
        "--values",
        values.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(3), "{text}");
    assert!(!values.exists());

    // Judged against the oracle (the rows left white are flips beyond
    // policy), not skipped.
    let (code, text) = run(&["bench", "cap"]);
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.lines().any(|l| l.starts_with("cap ")),
        "{code:?}\n{text}"
    );
    assert!(!text.contains("skipped"), "{text}");

    let (code, text) = run(&["localize", "ref-f316", "cap", "--pixel", "3,1"]);
    assert_eq!(code, Some(3), "{text}");
    assert!(text.contains("does not answer the pixels level"), "{text}");
}
