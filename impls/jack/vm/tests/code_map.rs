//! `HACK_VM_CODE_MAP`: compiling a program writes the map from each
//! function's host code to its VM instructions, which `scripts/profile.sh`
//! joins to perf's samples. (A test binary of its own: it sets the
//! variable for the whole process.)

use hack_vm::{Profile, Program};

#[test]
fn compiling_writes_the_code_map_where_the_variable_names_a_file() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("map.tsv");
    std::env::set_var("HACK_VM_CODE_MAP", &path);
    let source =
        "function Main.main 0\npush constant 2\npush constant 3\ncall Main.add 2\nreturn\n\
                  function Main.add 0\npush argument 0\npush argument 1\nadd\nreturn\n";
    let program = Program::from_sources(&[("Main.vm", source)]).expect("valid VM code");
    program
        .compile_native(Profile::Desktop)
        .expect("compiles on this host");
    let map = std::fs::read_to_string(&path).expect("the map is written");
    let lines: Vec<Vec<&str>> = map.lines().map(|l| l.split('\t').collect()).collect();
    assert!(lines.iter().all(|cols| cols.len() == 6), "{map}");
    for function in ["Main.main", "Main.add"] {
        assert!(lines.iter().any(|cols| cols[0] == function), "{map}");
    }
    assert!(
        lines
            .iter()
            .any(|cols| cols[0] == "Main.add" && cols[4] == "op" && cols[5] == "Add"),
        "{map}"
    );
}
