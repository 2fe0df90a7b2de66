//! The project file, `harness.toml`, through the cast's loader: every
//! declaration is an entry, every error is located and names its field.

use harness::cast::file::FieldError;
use harness::cast::Cast;
use std::path::{Path, PathBuf};

/// Where the fuzzed project file is taken to be: in `examples/`, so that
/// its relative paths reach the repository's example programs, bindings
/// and shaders (`jack-port`, `shaders/seed.glsl`). The file itself is
/// never written: the loader is given the fuzzed text.
pub fn project_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/harness.toml")
}

/// Any text declares implementations or fails with an error that carries
/// FILE:LINE:COL inside the file it names; when the text is valid TOML,
/// the error is about a field and names it (its dotted path starts at a
/// top-level key of the file). A file that loads adds one entry per
/// `[impl.NAME]` table, each found by its name.
pub fn cast_file(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let file = project_file();
    let document = text.parse::<toml::Table>().ok();
    match Cast::with_project(&file, text) {
        Ok(cast) => {
            let document = document.expect("a project file that loads is TOML");
            let declared: Vec<&String> = match document.get("impl") {
                None => Vec::new(),
                Some(tables) => tables
                    .as_table()
                    .expect("`impl` of a file that loads is a table")
                    .keys()
                    .collect(),
            };
            let builtins = Cast::builtin().entries().len();
            assert_eq!(cast.entries().len(), builtins + declared.len());
            for name in declared {
                assert!(cast.get(name).is_some(), "{name} is declared");
            }
        }
        Err(e) => {
            located(&e, &file, text);
            if e.file == file {
                if let Some(document) = &document {
                    let top = e.field.split('.').next().unwrap_or_default();
                    assert!(
                        !e.field.is_empty() && document.contains_key(top),
                        "{e}: the error names no field of the file"
                    );
                }
            }
        }
    }
}

/// `e` is at a line and column of the file it names (the fuzzed text, or a
/// file the text refers to), and says so first.
fn located(e: &FieldError, project: &Path, text: &str) {
    let named;
    let in_file = if e.file == project {
        text
    } else {
        named = std::fs::read_to_string(&e.file)
            .unwrap_or_else(|err| panic!("{e}: names a file that cannot be read: {err}"));
        &named
    };
    let prefix = format!("{}:{}:{}: ", e.file.display(), e.line, e.column);
    assert!(e.to_string().starts_with(&prefix), "{e}");
    let lines: Vec<&str> = in_file.split('\n').collect();
    assert!(
        (1..=lines.len()).contains(&e.line),
        "{e}: line out of the file"
    );
    let width = lines[e.line - 1].chars().count();
    assert!(
        (1..=width + 1).contains(&e.column),
        "{e}: column out of line {} ({width} characters)",
        e.line
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(line: usize, column: usize, field: &str) -> FieldError {
        FieldError {
            file: project_file(),
            line,
            column,
            field: field.into(),
            message: "m".into(),
        }
    }

    fn holds(check: impl FnOnce() + std::panic::UnwindSafe) -> bool {
        std::panic::catch_unwind(check).is_ok()
    }

    /// The location check refuses a line or column outside the text, and
    /// takes the last column plus one (an error at the end of a line).
    #[test]
    fn an_error_outside_the_text_breaks_the_property() {
        let text = "[impl.x]\nkind = 3\n";
        let file = project_file();
        assert!(holds(|| located(&error(2, 8, "impl.x.kind"), &file, text)));
        assert!(holds(|| located(&error(2, 9, "impl.x.kind"), &file, text)));
        assert!(!holds(|| located(
            &error(2, 10, "impl.x.kind"),
            &file,
            text
        )));
        assert!(!holds(|| located(&error(4, 1, "impl.x.kind"), &file, text)));
        assert!(!holds(|| located(&error(0, 1, "impl.x.kind"), &file, text)));
    }

    /// The loader's errors pass the property, in the file and in a
    /// bindings file it names.
    #[test]
    fn the_loader_locates_its_errors() {
        cast_file(b"[impl.x]\nkind = 3\n");
        cast_file(b"[impl.x\n");
        cast_file(b"[impl.p]\nkind = \"jack\"\nprogram = \"jack-port\"\nbindings = \"shaders/seed.glsl\"\n");
        let Err(e) = Cast::with_project(&project_file(), "[impl.x]\nkind = 3\n") else {
            panic!("accepted");
        };
        assert_eq!((e.line, e.column, e.field.as_str()), (2, 8, "impl.x.kind"));
    }
}
