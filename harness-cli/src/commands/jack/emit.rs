//! `harness jack emit --scene FILE --out DIR`: the Jack program generated
//! from a scene description (crate `scene-jack`), its classes and its
//! `bindings.toml`, written into DIR, where a `kind = "jack"` entry with
//! `program = "DIR"` and `bindings = "DIR/bindings.toml"` reaches it.

use anyhow::Context;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `harness jack emit`.
#[derive(Debug, clap::Args)]
pub struct EmitArgs {
    /// The scene description (docs/scenes.md).
    #[arg(long)]
    pub scene: PathBuf,
    /// Directory to write the .jack files and bindings.toml to (created if
    /// missing; files of the same names are replaced).
    #[arg(long)]
    pub out: PathBuf,
}

/// Generate and write; a description that cannot be read or generated is
/// an error naming the file and the field (exit 2).
pub fn run(args: EmitArgs) -> anyhow::Result<ExitCode> {
    let sources = scene_jack::emit_file(&args.scene)?.sources;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("--out: cannot create {}", args.out.display()))?;
    let files: Vec<(PathBuf, Vec<u8>)> = sources
        .classes
        .iter()
        .map(|c| (args.out.join(&c.name), c.text.clone().into_bytes()))
        .chain([(
            args.out.join("bindings.toml"),
            sources.bindings.clone().into_bytes(),
        )])
        .collect();
    for (path, _) in &files {
        crate::output::check_file(path, "--out")?;
    }
    // All files or none: a path in the way leaves no half program.
    harness_report::atomic::write_files(&files)?;
    println!(
        "wrote {} classes and bindings.toml ({} static words of {}) to {}",
        sources.classes.len(),
        sources.statics,
        scene_jack::STATIC_WORDS,
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
