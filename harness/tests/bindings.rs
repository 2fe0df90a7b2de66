//! Jack programs bound through `harness.toml` (kind `jack`), verified
//! through their bindings alone: the seed raymarcher and
//! examples/jack-port (another style), faults injected into a bound program
//! localized to the operation and its Jack call path, bad bindings refused
//! with the field named.

mod support;

use harness::cast::Cast;
use harness::implementation::Implementation;
use harness::localize::{localize, Localization};
use std::path::{Path, PathBuf};
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

/// The port with one line of its add changed, in a copy of its folder.
fn bad_port(dir: &Path) -> String {
    let src = root().join("examples/jack-port");
    std::fs::create_dir_all(dir).unwrap();
    for entry in std::fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let text = if path.ends_with("Num.jack") {
            let line = "            let lm = lm / pow2[d];";
            assert!(text.contains(line));
            text.replace(line, "            let lm = lm / pow2[d - 1];")
        } else {
            text
        };
        std::fs::write(dir.join(path.file_name().unwrap()), text).unwrap();
    }
    format!(
        "[impl.port-bad]\nkind = \"jack\"\nprogram = \"{d}\"\nbindings = \"{d}/bindings.toml\"\n",
        d = dir.display()
    )
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
        "pixel(330,150) > Picture.shade > Light.pixel > Eye.ray > V3.normalize > V3.dot"
    );
    assert!(l.to_string().contains("origin"), "{l}");
}

#[test]
fn the_web_profiles_math_divide_in_a_bound_program_is_localized() {
    let cast = cast_with("");
    let reference = open(&cast, "ref-f316");
    let web = open(&cast, "port+web-divide");
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
    let e = imp.eval(&[op(common::Op::Mul)]).unwrap_err().to_string();
    assert!(e.contains("`ops.mul` is not bound"), "{e}");
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
