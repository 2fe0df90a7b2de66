//! `harness nightly`: everything in one run, over the whole cast: every
//! level on the committed nightly sets (with the stability rows of their
//! categories), the unary checks over every normalised input, the
//! self-test, full-image renders (with the tracer's precision variants),
//! the program screens, the pairs of renders with the divergent pixels of
//! Float316 pairs localized, and their speed and error, written as one
//! report directory (`report.json`, `index.html`, images) that replaces the
//! previous one atomically, plus a line in the history file. The cast is
//! the project's with the seed scene's Shadertoy port added. The steps are
//! [`crate::nightly::steps`]. The exit status is the night's verdict
//! ([`harness::verdict`]): 0 passed, 1 a comparison beyond its policy (any
//! level, bit-exact or error figures, an image pair, the self-test), 3
//! something not compared (an implementation that did not open or failed
//! on a set, a failed render; an unavailable one unless
//! `--allow-unavailable`).

use crate::nightly::{self, steps};
use anyhow::{bail, Result};
use harness::cast::Cast;
use harness::impls::shader;
use std::path::PathBuf;
use std::process::ExitCode;
use vectors::Shard;

/// Arguments of `harness nightly`.
#[derive(Debug, clap::Args)]
pub struct NightlyArgs {
    /// Report directory (replaced atomically when the run completes).
    #[arg(long, default_value = "reports/nightly")]
    pub out: PathBuf,
    /// The unary checks against a slow implementation (the Jack emulator)
    /// take every N-th input (the others always take every input); the
    /// default is every input.
    #[arg(long, default_value_t = 1)]
    pub jack_unary_step: usize,
    /// Run only these steps (comma-separated: levels, unary, testfloat,
    /// selftest, renders, screens, pairs, explain, scenes, tuned, speed); default
    /// all.
    #[arg(long, value_delimiter = ',', value_name = "STEP,...")]
    pub steps: Option<Vec<String>>,
    /// Open only these implementations of the cast (comma-separated), with
    /// the oracle and the tracer; default all.
    #[arg(long = "impls", value_delimiter = ',', value_name = "NAME,...")]
    pub implementations: Option<Vec<String>>,
    /// A described scene for the scenes step: a shipped scene's name
    /// (`rtdemo`) or a file (repeatable; default every shipped scene, the
    /// test scene tests/carved.json and every scene of examples/scenes).
    #[arg(long = "scene", value_name = "NAME")]
    pub scenes: Vec<String>,
    /// Run only shard K/N of the committed and TestFloat sets (K counts
    /// from 0; a vector's shard is a stable hash of its identity).
    #[arg(long)]
    pub shard: Option<Shard>,
    /// An implementation that cannot run on this machine (no Vulkan
    /// adapter) is reported as skipped without failing the
    /// night.
    #[arg(long)]
    pub allow_unavailable: bool,
}

/// Run the nightly job over `cast` and the seed scene's Shadertoy port
/// ([`shader::seed_shadertoy`], unless the project file declares an entry
/// of that name).
pub fn run(args: NightlyArgs, mut cast: Cast) -> Result<ExitCode> {
    cast.add_unless_declared(shader::seed_shadertoy());
    let cast = &cast;
    let keys = steps::keys();
    if let Some(bad) = args
        .steps
        .iter()
        .flatten()
        .find(|s| !keys.contains(&s.as_str()))
    {
        bail!(
            "--steps: unknown step `{bad}` (expected {})",
            keys.join(", ")
        );
    }
    if let Some(bad) = args
        .implementations
        .iter()
        .flatten()
        .find(|n| cast.get(n).is_none())
    {
        bail!(
            "--impls: unknown implementation `{bad}` (expected one of {})",
            cast.names().join(", ")
        );
    }
    crate::output::check_dir(&args.out, "--out")?;
    let options = nightly::Options {
        out: args.out,
        slow_unary_step: args.jack_unary_step,
        steps: args.steps,
        implementations: args.implementations,
        progress: harness::progress::wanted(),
        shard: args.shard.unwrap_or(Shard::WHOLE),
        allow_unavailable: args.allow_unavailable,
        scenes: if args.scenes.is_empty() {
            nightly::scenes::nightly_default()?
        } else {
            args.scenes
                .iter()
                .map(|n| nightly::scenes::resolve(n))
                .collect::<Result<_>>()?
        },
    };
    let (summary, dir) = nightly::run(cast, &options)?;
    println!(
        "nightly: {}; report {}",
        summary.line(),
        dir.join("index.html").display()
    );
    Ok(summary.verdict.report())
}
