//! `harness render`: placeholder until the reference renderer lands.

/// Arguments of `harness render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {}

/// Render an image.
pub fn run(_args: RenderArgs) -> anyhow::Result<std::process::ExitCode> {
    anyhow::bail!("render is not built yet")
}
