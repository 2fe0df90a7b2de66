//! `load,` with no file name, from a script run as `NAME.tst` in its own
//! folder (the process's current directory): the folder's .vm files. A
//! test binary of its own, since it changes the current directory.

use hack_vm::{run_script, Profile};
use std::path::Path;

#[test]
fn a_bare_load_in_a_script_named_without_a_folder_loads_the_current_folder() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("Add.vm"),
        "push constant 7\npush constant 8\nadd\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("AddVME.tst"),
        "load,\noutput-file Add.out,\noutput-list RAM[256]%D1.6.1;\nset sp 256,\nrepeat 3 { vmstep; }\noutput;\n",
    )
    .unwrap();
    std::env::set_current_dir(dir.path()).unwrap();
    for profile in Profile::ALL {
        let report = run_script(Path::new("AddVME.tst"), profile)
            .unwrap_or_else(|e| panic!("{profile}: {e}"));
        assert_eq!(report.lines, 2);
        assert_eq!(
            std::fs::read_to_string("Add.out").unwrap(),
            "|RAM[256]|\n|     15 |\n"
        );
    }
}
