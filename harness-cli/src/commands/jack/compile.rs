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
    if let Some(error) = unloadable(&args.src_dir, &classes) {
        eprintln!("{error}");
        eprintln!("1 compile error(s)");
        return Ok(ExitCode::from(2));
    }
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
    harness_report::atomic::write_files(&files)?;
    println!(
        "compiled {} class(es) to {}",
        classes.len(),
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// A line of the compiled code that the VM refuses to load, as an error at
/// the Jack position it comes from (`let x = 40000;` compiles, as the
/// official compilers compile it, to a `push constant` the VM refuses). A
/// call to a class outside the directory is no error here: the directory
/// may be part of a program.
fn unloadable(src_dir: &std::path::Path, classes: &[jack_compiler::VmClass]) -> Option<String> {
    let files: Vec<(String, String)> = classes
        .iter()
        .map(|c| (c.file_name(), c.code.clone()))
        .collect();
    let Err(hack_vm::LoadError::Syntax {
        file,
        line,
        message,
    }) = hack_vm::Program::from_sources(&files)
    else {
        return None;
    };
    if message.starts_with("Undefined function") {
        return None;
    }
    let class = classes.iter().find(|c| c.file_name() == file)?;
    let pos = class.jack_pos(line)?;
    Some(format!(
        "{}:{}:{}: {message} (the VM code it compiles to, {file} line {line}, would not load)",
        src_dir.join(format!("{}.jack", class.class_name)).display(),
        pos.line,
        pos.col
    ))
}
