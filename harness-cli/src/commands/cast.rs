//! `harness cast [--json]`: every implementation of the cast (the
//! built-ins and the project file's) with its kind, number type, levels,
//! traces, variants, roles, where it is declared, whether it can run
//! here (each is opened once, and one that cannot says why) and the GPU
//! adapter of each that runs on one.

use harness::cast::{Cast, Entry, VariantInfo};
use rayon::prelude::*;
use serde::Serialize;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `harness cast`.
#[derive(Debug, clap::Args)]
pub struct CastArgs {
    /// Print the listing as JSON.
    #[arg(long)]
    pub json: bool,
}

/// One implementation as listed.
#[derive(Debug, Serialize)]
pub struct Listed {
    pub name: String,
    pub kind: &'static str,
    pub numbers: String,
    pub levels: Vec<String>,
    pub traces: bool,
    pub variants: Vec<VariantInfo>,
    pub oracle: bool,
    pub tracer: bool,
    pub bit_exact_group: bool,
    pub origin: String,
    pub about: String,
    pub available: bool,
    /// Why it cannot run here.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unavailable: Option<String>,
    /// Seconds it took to open.
    pub open_s: f64,
    /// The GPU adapter it opened on, for one that runs on a GPU.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapter: Option<common::AdapterDescription>,
}

/// Open `entry` and list it.
fn listed(cast: &Cast, entry: &Entry) -> Listed {
    let start = Instant::now();
    let opened = cast.open(&entry.name);
    Listed {
        name: entry.name.clone(),
        kind: entry.kind,
        numbers: entry.numbers.name(),
        levels: entry.levels.iter().map(|l| l.to_string()).collect(),
        traces: entry.traces,
        variants: entry.variants.clone(),
        oracle: entry.roles.oracle,
        tracer: entry.roles.tracer,
        bit_exact_group: entry.bit_exact(),
        origin: entry.origin.to_string(),
        about: entry.about.clone(),
        adapter: opened.as_ref().ok().and_then(|imp| imp.adapter()),
        available: opened.is_ok(),
        unavailable: opened.err().map(|e| e.to_string()),
        open_s: start.elapsed().as_secs_f64(),
    }
}

/// The listing as text: one line per implementation, then the variants
/// and the reason of each unavailable one.
pub fn text(list: &[Listed]) -> String {
    let mut out = format!(
        "{:<20} {:<10} {:<9} {:<21} {:<6} {:<17} {:>6}  {}\n",
        "implementation", "kind", "numbers", "levels", "traces", "roles", "open s", "available"
    );
    for l in list {
        let mut roles = Vec::new();
        if l.oracle {
            roles.push("oracle");
        }
        if l.tracer {
            roles.push("tracer");
        }
        if l.bit_exact_group {
            roles.push("bit-exact");
        }
        out += &format!(
            "{:<20} {:<10} {:<9} {:<21} {:<6} {:<17} {:>6.1}  {}\n",
            l.name,
            l.kind,
            l.numbers,
            l.levels.join(","),
            if l.traces { "yes" } else { "no" },
            roles.join(","),
            l.open_s,
            match &l.unavailable {
                None => "yes".to_string(),
                Some(why) => format!("no: {why}"),
            }
        );
    }
    for l in list {
        let variants: Vec<&str> = l.variants.iter().map(|v| v.name.as_str()).collect();
        if !variants.is_empty() {
            out += &format!("{} +{}\n", l.name, variants.join(" +"));
        }
        if l.origin != "built-in" {
            out += &format!("{}: declared at {}: {}\n", l.name, l.origin, l.about);
        }
        if let Some(adapter) = &l.adapter {
            let software = if adapter.is_software() {
                " [software]"
            } else {
                ""
            };
            out += &format!("{} runs on {adapter}{software}\n", l.name);
        }
    }
    out
}

/// Run `harness cast`.
pub fn run(args: CastArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    // Opening takes seconds for some (a device, a compilation): in
    // parallel.
    let list: Vec<Listed> = cast.entries().par_iter().map(|e| listed(cast, e)).collect();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&list)?);
    } else {
        if let Some(file) = cast.file() {
            println!("project file: {}", file.display());
        }
        print!("{}", text(&list));
    }
    Ok(ExitCode::SUCCESS)
}
