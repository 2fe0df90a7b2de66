//! `harness jack run DIR`: load a VM program (or compile a Jack one), run it
//! from its entry on the emulator and report the instruction count, how it
//! ended (with the Jack call stack) and optionally the screen as PNG.

use anyhow::Context;
use hack_vm::{Config, Engine, Exit, KeyScript, Machine, Profile, Program, Ram};
use harness::progress;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

/// Arguments of `harness jack run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// Directory holding the program's .vm files (or .jack files), or one
    /// .vm file.
    pub dir: PathBuf,
    /// Keys pressed one after another, comma-separated (e.g. "SPACE,A,ENTER").
    #[arg(long, default_value = "")]
    pub keys: String,
    /// Instructions each key is held, and then released.
    #[arg(long, default_value_t = KeyScript::DEFAULT_HOLD)]
    pub hold: u64,
    /// Stop after this many VM instructions (reported as a budget end).
    #[arg(long)]
    pub max_instructions: Option<u64>,
    /// OS profile: which official tool to follow.
    #[arg(long, default_value = "desktop")]
    pub profile: Profile,
    /// Write the 512x256 screen to this PNG.
    #[arg(long)]
    pub screen: Option<PathBuf>,
    /// Print the instruction count of each function.
    #[arg(long)]
    pub profile_functions: bool,
    /// Run under both profiles and report whether screens and ends differ.
    #[arg(long)]
    pub compare_profiles: bool,
    /// Print RAM[A] through RAM[B] (inclusive) at the end; repeatable.
    #[arg(long = "ram", value_name = "A..B", value_parser = parse_range)]
    pub ram: Vec<(i32, i32)>,
    /// The load order of the program's files, as comma-separated base
    /// names (e.g. `Main,Ball`): these first, then the others by name. It
    /// decides where each file's statics go; the official tools load in
    /// their directory listing's order, which need not be sorted.
    #[arg(long = "static-order", value_name = "A,B,...", value_delimiter = ',')]
    pub static_order: Vec<String>,
    /// Set RAM[A] to V before the run; repeatable.
    #[arg(long = "set", value_name = "A=V", value_parser = parse_set)]
    pub set: Vec<(i32, i16)>,
    /// The emulator's engine: `auto` (the interpreter, then compiled code
    /// once the run is long), `interp` (the interpreter) or `native` (VM
    /// functions compiled with Cranelift; the interpreter where the host is
    /// not supported). All give the same run. Default: `HACK_VM_ENGINE`,
    /// else `auto`.
    #[arg(long)]
    pub engine: Option<Engine>,
}

/// The last RAM address.
const LAST: i32 = hack_vm::RAM_SIZE as i32 - 1;

fn parse_address(s: &str) -> Result<i32, String> {
    let a: i32 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not an address"))?;
    if (0..=LAST).contains(&a) {
        Ok(a)
    } else {
        Err(format!("address {a} is outside RAM (0..={LAST})"))
    }
}

/// `A..B`, both ends inclusive, A <= B.
fn parse_range(s: &str) -> Result<(i32, i32), String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("{s:?} is not a range A..B"))?;
    let (a, b) = (parse_address(a)?, parse_address(b)?);
    if a > b {
        return Err(format!("{s:?}: the range is empty ({a} > {b})"));
    }
    Ok((a, b))
}

/// `A=V` with V a 16-bit value (-32768..=65535).
fn parse_set(s: &str) -> Result<(i32, i16), String> {
    let (a, v) = s
        .split_once('=')
        .ok_or_else(|| format!("{s:?} is not A=V"))?;
    let v: i32 = v
        .trim()
        .parse()
        .map_err(|_| format!("{v:?} is not a number"))?;
    if !(-32768..=65535).contains(&v) {
        return Err(format!("{v} is not a 16-bit value"));
    }
    Ok((parse_address(a)?, v as i16))
}

/// Words printed per line of a `--ram` range.
const WORDS_PER_LINE: i32 = 16;

/// The `--ram` ranges, 16 words a line: `RAM[256..271]: 0 0 ...`.
fn print_ram(ram: &Ram, ranges: &[(i32, i32)]) {
    for &(a, b) in ranges {
        let mut from = a;
        while from <= b {
            let to = (from + WORDS_PER_LINE - 1).min(b);
            let words: Vec<String> = (from..=to).map(|i| ram.read(i).to_string()).collect();
            println!("RAM[{from}..{to}]: {}", words.join(" "));
            from = to + 1;
        }
    }
}

/// A machine for `args` under `profile`, with the `--set` words written.
fn machine(args: &RunArgs, profile: Profile, config: Config) -> anyhow::Result<Machine> {
    let program = load(&args.dir, profile, &args.static_order)?;
    // The checks only one profile's tool makes at load (a web static index
    // past 239).
    program
        .check_profile(profile)
        .with_context(|| format!("loading {} under --profile {profile}", args.dir.display()))?;
    let mut m = Machine::new(program, config);
    for &(a, v) in &args.set {
        m.ram_mut().write(a, v);
    }
    Ok(m)
}

/// Run `harness jack run`. Exit 0 when the program halted (or, with
/// `--compare-profiles`, when both profiles agree), 1 otherwise.
pub fn run(args: RunArgs) -> anyhow::Result<ExitCode> {
    let keys = KeyScript::parse(&args.keys, args.hold).context("--keys")?;
    let config = |profile| Config {
        profile,
        keys: keys.clone(),
        profile_functions: args.profile_functions,
        engine: args.engine.unwrap_or_default(),
        ..Config::default()
    };
    if let Some(path) = &args.screen {
        for p in screen_paths(path, args.compare_profiles) {
            crate::output::check_png(&p, "--screen")?;
        }
    }
    if args.compare_profiles {
        return compare_profiles(&args, config);
    }
    let mut machine = machine(&args, args.profile, config(args.profile))?;
    let exit = finish(&mut machine, args.max_instructions, args.profile);
    println!("instructions: {}", machine.steps());
    let compiled = machine.compiled_steps();
    println!(
        "compiled: {compiled} ({:.2}%)",
        100.0 * compiled as f64 / machine.steps().max(1) as f64
    );
    println!("end: {exit}");
    print_ram(machine.ram(), &args.ram);
    if args.profile_functions {
        let total = machine.steps().max(1) as f64;
        for (name, count) in machine.function_profile() {
            println!("{count:>14} {:>6.2}%  {name}", 100.0 * count as f64 / total);
        }
    }
    if let Some(path) = &args.screen {
        write_screen(machine.ram(), path)?;
    }
    Ok(if exit == Exit::Halted {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// Run the program under both profiles side by side: the first call or
/// return where their call traces part, then each run to its end, its
/// end state and screen. Exit 0 when nothing differs.
fn compare_profiles(
    args: &RunArgs,
    config: impl Fn(Profile) -> Config,
) -> anyhow::Result<ExitCode> {
    let [pa, pb] = Profile::ALL;
    let mut a = machine(args, pa, config(pa))?;
    let mut b = machine(args, pb, config(pb))?;
    let bar = progress::show(
        progress::instructions(args.max_instructions, "traces"),
        progress::wanted(),
    );
    let traces = hack_vm::compare_call_traces(&mut a, &mut b, args.max_instructions, &mut |n| {
        bar.set_position(n)
    });
    bar.finish_and_clear();
    let mut ends = Vec::new();
    for (p, machine) in [(pa, &mut a), (pb, &mut b)] {
        let left = args
            .max_instructions
            .map(|max| max.saturating_sub(machine.steps()));
        ends.push(finish(machine, left, p));
    }
    for ((p, m), e) in [(pa, &a), (pb, &b)].into_iter().zip(&ends) {
        println!("{p}: {} instructions, {e}", m.steps());
        if !args.ram.is_empty() {
            println!("{p}:");
            print_ram(m.ram(), &args.ram);
        }
    }
    let same_end = ends[0] == ends[1];
    println!("end states: {}", if same_end { "same" } else { "differ" });
    // The desktop draws text one pixel row lower (spec section 6): a screen
    // that is the other's shifted by that row is the same picture.
    let diff = screen_diff(a.ram(), b.ram()).filter(|_| !one_row_lower(a.ram(), b.ram()));
    match diff {
        None if screen_diff(a.ram(), b.ram()).is_some() => {
            println!("screens: same, the desktop's one pixel row lower (its text origin)")
        }
        None => println!("screens: same"),
        Some((count, (x, y))) => println!("screens: {count} pixels differ, first at ({x},{y})"),
    }
    let show = |e: &Option<hack_vm::CallEvent>| {
        e.as_ref()
            .map_or("(the run had ended)".to_string(), ToString::to_string)
    };
    match &traces.divergence {
        None => println!("call traces: same ({} calls and returns)", traces.matching),
        Some(d) => {
            println!(
                "call traces: differ after {} matching calls and returns, in {}",
                traces.matching,
                d.stack.join(" > ")
            );
            println!("  {pa}: {}", show(&d.a));
            println!("  {pb}: {}", show(&d.b));
        }
    }
    if let Some(path) = &args.screen {
        for (out, m) in screen_paths(path, true).into_iter().zip([&a, &b]) {
            write_screen(m.ram(), &out)?;
        }
    }
    Ok(
        if same_end && diff.is_none() && traces.divergence.is_none() {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        },
    )
}

/// Where `--screen PATH` writes: PATH, or with both profiles compared
/// `STEM-PROFILE.EXT` beside it, one per profile.
fn screen_paths(path: &Path, per_profile: bool) -> Vec<PathBuf> {
    if !per_profile {
        return vec![path.to_path_buf()];
    }
    Profile::ALL
        .iter()
        .map(|p| {
            path.with_file_name(format!(
                "{}-{p}.{}",
                path.file_stem().unwrap_or_default().to_string_lossy(),
                path.extension().unwrap_or_default().to_string_lossy()
            ))
        })
        .collect()
}

/// The program of `dir`: its .jack files compiled under `profile` if it has
/// any, else its .vm files.
fn load(dir: &Path, profile: Profile, order: &[String]) -> anyhow::Result<Arc<Program>> {
    if dir.is_file() {
        // One .vm file, as the official tools load it.
        let text =
            common::input::read_text(dir).with_context(|| format!("reading {}", dir.display()))?;
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !name.ends_with(".vm") {
            anyhow::bail!("{} is neither a folder nor a .vm file", dir.display());
        }
        return Program::from_sources(&[(name, text)])
            .with_context(|| format!("loading {}", dir.display()));
    }
    let has_jack = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(Result::ok)
        .any(|e| e.path().extension().is_some_and(|x| x == "jack"));
    if !has_jack {
        return Program::load_dir_in_order(dir, order)
            .with_context(|| format!("loading {}", dir.display()));
    }
    let compiler_profile: jack_compiler::Profile = profile.name().parse()?;
    let classes = jack_compiler::compile_dir(dir, compiler_profile)
        .with_context(|| format!("compiling {}", dir.display()))?;
    let mut sources: Vec<(String, String)> = classes
        .iter()
        .map(|c| (c.file_name(), c.code.clone()))
        .collect();
    hack_vm::in_load_order(&mut sources, order)?;
    Program::from_sources(&sources).map_err(|e| {
        let context = format!("loading the VM code compiled from {}", dir.display());
        match jack_position(&classes, &e) {
            Some(at) => anyhow::anyhow!("{at}: {e}").context(context),
            None => anyhow::Error::new(e).context(context),
        }
    })
}

/// The Jack source position (`File.jack:line:col`) a load error of
/// compiled code points at (a literal above 32767, a call into a class
/// that is not there), when the error has a line.
fn jack_position(classes: &[jack_compiler::VmClass], e: &hack_vm::LoadError) -> Option<String> {
    let hack_vm::LoadError::Syntax { file, line, .. } = e else {
        return None;
    };
    let class = classes.iter().find(|c| &c.file_name() == file)?;
    let pos = class.jack_pos(*line)?;
    Some(format!("{}.jack:{pos}", class.class_name))
}

/// Instructions between two updates of the progress counter.
const PROGRESS_EVERY: u64 = 50_000_000;

/// Run `machine` on for at most `budget` more instructions, counting them
/// on a progress line when standard error is a terminal.
///
/// Without a budget, the run is checked every [`IDLE_CHECK_EVERY`]
/// instructions for an idle loop (`Machine::idle`: a `goto` to its own
/// label, the OS's `while (true) {}` in `Sys.halt`), where the official
/// tools spin for ever: the run stops at the first check that finds one,
/// says so, and counts as halted.
fn finish(machine: &mut Machine, budget: Option<u64>, label: Profile) -> Exit {
    let bar = progress::show(
        progress::instructions(budget.map(|b| machine.steps() + b), label.name()),
        progress::wanted(),
    );
    let exit = if budget.is_some() {
        machine.run_observed(budget, PROGRESS_EVERY, &mut |n| bar.set_position(n))
    } else {
        loop {
            let exit = machine.run_observed(Some(IDLE_CHECK_EVERY), PROGRESS_EVERY, &mut |n| {
                bar.set_position(n)
            });
            match exit {
                Exit::Budget { stack } if machine.idle() => {
                    bar.finish_and_clear();
                    println!(
                        "idle: {label} stopped at instruction {} in an idle loop in {stack} \
                         (the official tools spin there for ever)",
                        machine.steps()
                    );
                    return Exit::Halted;
                }
                Exit::Budget { .. } => {}
                other => break other,
            }
        }
    };
    bar.finish_and_clear();
    exit
}

/// Instructions between two checks for an idle loop in a run without a
/// budget.
const IDLE_CHECK_EVERY: u64 = 1_000_000;

/// Whether screen `desktop` is screen `web` one pixel row lower.
fn one_row_lower(desktop: &Ram, web: &Ram) -> bool {
    (0..512).all(|x| !desktop.pixel(x, 0) && !web.pixel(x, 255))
        && (0..255).all(|y| (0..512).all(|x| web.pixel(x, y) == desktop.pixel(x, y + 1)))
}

/// Number of differing pixels and the first (row-major), if any differ.
fn screen_diff(a: &Ram, b: &Ram) -> Option<(usize, (usize, usize))> {
    let mut count = 0;
    let mut first = None;
    for y in 0..256 {
        for x in 0..512 {
            if a.pixel(x, y) != b.pixel(x, y) {
                count += 1;
                first.get_or_insert((x, y));
            }
        }
    }
    first.map(|f| (count, f))
}

/// The screen as a greyscale PNG (white 255, black, a 1 bit, 0), written
/// atomically: a failure leaves an existing file as it was.
fn write_screen(ram: &Ram, path: &Path) -> anyhow::Result<()> {
    let img = image::GrayImage::from_fn(512, 256, |x, y| {
        image::Luma([if ram.pixel(x as usize, y as usize) {
            0
        } else {
            255
        }])
    });
    harness_report::atomic::write_png(path, &image::DynamicImage::ImageLuma8(img))
}
