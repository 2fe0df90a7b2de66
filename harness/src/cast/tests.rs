//! The cast: built-in entries, labels, the project file's errors.

use super::*;
use crate::implementation::Numbers;
use std::path::Path;
use vectors::Level;

fn project(text: &str) -> Result<Cast, FieldError> {
    Cast::with_project(Path::new("dir/harness.toml"), text)
}

fn error(text: &str) -> String {
    match project(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_six_built_ins_are_entries_with_their_roles() {
    let cast = Cast::builtin();
    assert_eq!(
        cast.names(),
        ["ref-f64", "ref-f32", "ref-f316", "jack", "gpu-f32", "gpu-f316"]
    );
    assert_eq!(cast.oracle().name, "ref-f64");
    assert_eq!(cast.tracer().name, "ref-f316");
    let group: Vec<&str> = cast
        .bit_exact_group()
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    assert_eq!(group, ["ref-f316", "jack", "gpu-f316"]);
    assert!(!cast.get("gpu-f32").unwrap().answers(Level::Ops));
    let kinds: Vec<&str> = crate::impls::KINDS.iter().map(|k| k.name()).collect();
    let mut unique = kinds.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(
        kinds.len(),
        unique.len(),
        "kind names are unique: {kinds:?}"
    );
}

#[test]
fn a_variant_that_does_not_apply_is_an_error() {
    let cast = Cast::builtin();
    for (label, message) in [
        (
            "ref-f64+sqrt-floor-div",
            "ref-f64 has no variant or fault `sqrt-floor-div` (it has dither-threshold, fma, f32-oracle)",
        ),
        (
            "ref-f64+newton-1",
            "ref-f64 has no variant or fault `newton-1` (it has dither-threshold, fma, f32-oracle)",
        ),
        (
            "ref-f32+mul-keep-low",
            "ref-f32 has no variant or fault `mul-keep-low` (it has dither-threshold, fma)",
        ),
        (
            "ref-f316+fma",
            "ref-f316 has no variant or fault `fma` (it has mul-low-product,",
        ),
        (
            "gpu-f316+newton-3",
            "gpu-f316 has no variant or fault `newton-3` (it has none)",
        ),
        ("jack+sqrt-floor-div", "jack has no variant or fault"),
    ] {
        let e = cast.resolve(label).err().unwrap().to_string();
        assert!(e.starts_with(message), "{label}: {e}");
    }
    for label in [
        "ref-f316+sqrt-floor-div",
        "ref-f316+newton-3+dither-threshold",
        "ref-f64+dither-threshold",
        "ref-f64+f32-oracle",
        "ref-f32+fma",
        "ref-f64+fma",
        "jack+web-divide",
    ] {
        assert!(cast.resolve(label).is_ok(), "{label}");
    }
    let e = cast.resolve("ref-f99").err().unwrap().to_string();
    assert!(
        e.starts_with("unknown implementation `ref-f99` (expected one of ref-f64,"),
        "{e}"
    );
}

#[test]
fn a_declared_entry_opens_under_its_own_name() {
    let cast = project(
        r#"
[impl.slow-sqrt]
kind = "reference"
numbers = "float316"
variants = ["newton-3"]
"#,
    )
    .unwrap();
    let e = cast.get("slow-sqrt").unwrap();
    assert_eq!(e.kind, "reference");
    assert_eq!(e.numbers, Numbers::Float316);
    assert!(e.bit_exact() && e.traces && !e.roles.tracer);
    assert_eq!(
        e.origin,
        Origin::Declared {
            file: "dir/harness.toml".into(),
            line: 2
        }
    );
    let imp = cast.open("slow-sqrt+dither-threshold").unwrap();
    assert_eq!(imp.label(), "slow-sqrt+dither-threshold");
    assert_eq!(imp.numbers(), Numbers::Float316);
    assert!(cast.bit_exact_group().iter().any(|e| e.name == "slow-sqrt"));
}

#[test]
fn roles_can_be_given_to_declared_entries() {
    let cast = project(
        r#"
[impl.my-f64]
kind = "reference"
numbers = "f64"

[roles]
oracle = "my-f64"
"#,
    )
    .unwrap();
    assert_eq!(cast.oracle().name, "my-f64");
    assert!(!cast.get("ref-f64").unwrap().roles.oracle);
    let e = error("[roles]\noracle = \"ref-f32\"\n");
    assert_eq!(
        e,
        "dir/harness.toml:2:10: roles.oracle: the oracle must compute with f64; ref-f32 computes with f32"
    );
    let e = error("[roles]\ntracer = \"gpu-f316\"\n");
    assert!(
        e.starts_with("dir/harness.toml:2:10: roles.tracer: the tracer must"),
        "{e}"
    );
}

#[test]
fn a_malformed_project_file_names_the_file_line_and_field() {
    for (text, message) in [
        (
            "[impl.x]\nkind = \"reference\"\nnumbers = \"f31\"\n",
            "dir/harness.toml:3:11: impl.x.numbers: the reference computes with float316, f64 or f32, not `f31`",
        ),
        (
            "[impl.x]\nkind = \"pythn\"\n",
            "dir/harness.toml:2:8: impl.x.kind: unknown kind `pythn` (expected one of reference, jack, shader, pipe)",
        ),
        (
            "[impl.x]\nnumbers = \"f64\"\n",
            "dir/harness.toml:1:1: impl.x.kind: missing (required)",
        ),
        (
            "[impl.x]\nkind = \"reference\"\nnumbers = \"f64\"\nvariant = [\"newton-1\"]\n",
            "dir/harness.toml:4:1: impl.x.variant: unknown field (expected the fields of kind `reference`)",
        ),
        (
            "[impl.x]\nkind = \"reference\"\nnumbers = \"f64\"\nvariants = [\"newton-1\"]\n",
            "dir/harness.toml:4:12: impl.x.variants: `newton-1` does not apply to the ref-f64 formulation",
        ),
        (
            "[impl.x]\nkind = \"reference\"\nnumbers = \"f64\"\nvariants = [\"newton-1\", 3]\n",
            "dir/harness.toml:4:25: impl.x.variants: item 1: expected a string, found integer",
        ),
        (
            "[impl.x]\nkind = 3\n",
            "dir/harness.toml:2:8: impl.x.kind: expected a string, found integer",
        ),
        (
            "[impl.ref-f316]\nkind = \"reference\"\nnumbers = \"f64\"\n",
            "dir/harness.toml:1:1: impl.ref-f316: `ref-f316` is already an implementation (built-in)",
        ),
        (
            "[impl.\"a+b\"]\nkind = \"reference\"\n",
            "dir/harness.toml:1:1: impl.a+b: a name cannot contain `+`",
        ),
        ("[impls.x]\n", "dir/harness.toml:1:2: impls: unknown field (expected `impl` or `roles`)"),
        ("[impl.x\nkind = 1\n", "dir/harness.toml:1:8: "),
        (
            "[impl.x]\nkind = \"shader\"\npath = \"x.wgsl\"\nnumbers = \"f64\"\n",
            "dir/harness.toml:4:11: impl.x.numbers: unknown number type `f64` (expected f32 or float316)",
        ),
        (
            "[impl.x]\nkind = \"jack\"\nprofile = \"phone\"\n",
            "dir/harness.toml:3:11: impl.x.profile: ",
        ),
    ] {
        let e = error(text);
        assert!(e.starts_with(message), "{text}\n{e}");
    }
}
