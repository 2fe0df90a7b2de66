//! `harness jack compile SRC_DIR --out VM_DIR [--profile desktop|web]`:
//! compile every .jack file of a directory to one .vm file per class.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use jack_compiler::{CompileDirError, Profile};

/// Arguments of `harness jack compile`.
#[derive(Debug, clap::Args)]
pub struct CompileArgs {
    /// Directory holding the .jack files.
    pub src_dir: PathBuf,
    /// Directory to write the .vm files to (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Which official tool's checks to follow: desktop or web.
    #[arg(long, default_value_t = Profile::Desktop)]
    pub profile: Profile,
}

/// Compiles; compile errors are printed one per line as `file:line:col: msg`
/// and give exit code 2.
pub fn run(args: CompileArgs) -> anyhow::Result<ExitCode> {
    let classes = match jack_compiler::compile_dir(&args.src_dir, args.profile) {
        Ok(classes) => classes,
        Err(CompileDirError::Compile(errors)) => {
            for e in &errors.0 {
                eprintln!("{e}");
            }
            eprintln!("{} compile error(s)", errors.0.len());
            return Ok(ExitCode::from(2));
        }
        Err(other) => return Err(other.into()),
    };
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    // All classes or none: a path in the way must not leave a partial
    // program behind.
    let files: Vec<(PathBuf, Vec<u8>)> = classes
        .iter()
        .map(|c| (args.out.join(c.file_name()), c.code.clone().into_bytes()))
        .collect();
    for (path, _) in &files {
        crate::output::check_file(path, "--out")?;
    }
    crate::report::atomic::write_files(&files)?;
    println!(
        "compiled {} class(es) to {}",
        classes.len(),
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
