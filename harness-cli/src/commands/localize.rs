//! `harness localize A B --pixel X,Y | --point P | --op NAME --a S,E,M
//! [--b S,E,M]`: print the first Float316 operation on which A and B
//! differ for one input, with its operands, both results, the call path
//! and the last matching operation before it. Records are paired by
//! operation and operands, so two ports that order their operations
//! differently are still compared operation with operation.
//! `--point` takes three decimals `x,y,z` (encoded by truncation) or three
//! triples `s,e,m:s,e,m:s,e,m`. Exit 0: the answers agree (a difference
//! of the traces that does not reach the answer is printed as such); 1:
//! they differ (the localization is printed); 2: usage or input error; 3:
//! a side does not answer the input's level (nothing compared).

use anyhow::{bail, Context};
use common::{Op, F316};
use harness::cast::Cast;
use harness::localize::localize;
use std::process::ExitCode;
use vectors::{OpVector, PixelVector, SdfVector, Vector};

/// Arguments of `harness localize`.
#[derive(Debug, clap::Args)]
pub struct LocalizeArgs {
    /// One implementation: a Float316 one of the cast (ref-f316, jack,
    /// gpu-f316, a declared one, or one with a fault:
    /// ref-f316+sqrt-floor-div, jack+web-divide).
    pub a: String,
    /// The other.
    pub b: String,
    /// A pixel `X,Y`.
    #[arg(long, conflicts_with_all = ["point", "op"])]
    pub pixel: Option<String>,
    /// A scene query point: `x,y,z` or `s,e,m:s,e,m:s,e,m`.
    #[arg(long, conflicts_with = "op")]
    pub point: Option<String>,
    /// A Float316 operation (with --a and, for binary ones, --b).
    #[arg(long, requires = "op_a")]
    pub op: Option<Op>,
    /// The first operand `s,e,m`.
    #[arg(long = "a", id = "op_a", value_name = "S,E,M")]
    pub op_a: Option<String>,
    /// The second operand `s,e,m`.
    #[arg(long = "b", id = "op_b", value_name = "S,E,M")]
    pub op_b: Option<String>,
    /// Print the localization as JSON.
    #[arg(long)]
    pub json: bool,
}

fn ints<T: std::str::FromStr>(s: &str, n: usize, what: &str) -> anyhow::Result<Vec<T>> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != n {
        bail!("{what}: `{s}` is not {n} comma-separated numbers");
    }
    parts
        .iter()
        .map(|p| {
            p.parse::<T>().map_err(|_| match p.parse::<f64>() {
                Ok(_) => anyhow::anyhow!("{what}: `{p}` is out of range"),
                Err(_) => anyhow::anyhow!("{what}: `{p}` in `{s}` is not a number"),
            })
        })
        .collect()
}

fn triple(s: &str, what: &str) -> anyhow::Result<F316> {
    let t: Vec<i16> = ints(s, 3, what)?;
    Ok(F316::new(t[0], t[1], t[2]))
}

/// A `--pixel X,Y` argument, inside the image.
pub fn parse_pixel(p: &str) -> anyhow::Result<(usize, usize)> {
    let xy: Vec<u64> = ints(p, 2, "--pixel")?;
    if xy[0] >= common::image_consts::WIDTH as u64 || xy[1] >= common::image_consts::HEIGHT as u64 {
        bail!(
            "--pixel: ({},{}) is outside the 512x256 image",
            xy[0],
            xy[1]
        );
    }
    Ok((xy[0] as usize, xy[1] as usize))
}

/// A `--point` argument: `x,y,z` (encoded by truncation) or three triples
/// `s,e,m:s,e,m:s,e,m`.
pub fn parse_point(p: &str) -> anyhow::Result<[F316; 3]> {
    let coords: Vec<F316> = if p.contains(':') {
        p.split(':')
            .map(|t| triple(t, "--point"))
            .collect::<Result<_, _>>()?
    } else {
        ints::<f64>(p, 3, "--point")?
            .into_iter()
            .map(|x| {
                F316::from_f64_truncating(x).with_context(|| {
                    format!("--point: {} is not a Float316 value", common::shown(x))
                })
            })
            .collect::<Result<_, _>>()?
    };
    if coords.len() != 3 {
        bail!("--point: expected three coordinates");
    }
    Ok([coords[0], coords[1], coords[2]])
}

/// The input the arguments name.
pub fn input_of(args: &LocalizeArgs) -> anyhow::Result<Vector> {
    if let Some(p) = &args.pixel {
        let (x, y) = parse_pixel(p)?;
        return Ok(Vector::Pixel(PixelVector {
            category: "localize".into(),
            x: x as u16,
            y: y as u16,
        }));
    }
    if let Some(p) = &args.point {
        return Ok(Vector::Sdf(SdfVector {
            category: "localize".into(),
            p: parse_point(p)?,
        }));
    }
    if let Some(op) = args.op {
        let a = triple(args.op_a.as_deref().unwrap_or_default(), "--a")?;
        let b = args.op_b.as_deref().map(|b| triple(b, "--b")).transpose()?;
        if b.is_some() != (op.arity() == 2) {
            bail!("`{op}` takes {} operand(s)", op.arity());
        }
        return Ok(Vector::Op(OpVector {
            category: "localize".into(),
            op,
            a,
            b,
        }));
    }
    bail!("say which input: --pixel X,Y, --point x,y,z or --op NAME --a S,E,M [--b S,E,M]")
}

/// Run `harness localize`.
pub fn run(args: LocalizeArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    let input = input_of(&args)?;
    let open = |label: &str| {
        cast.open(label)
            .with_context(|| format!("implementation `{label}`"))
    };
    let (a, b) = (open(&args.a)?, open(&args.b)?);
    // A level a side does not answer is not compared, as in every other
    // command (docs/verdict.md): a Jack program whose image comes from its
    // whole run alone has no pixel to be asked for.
    let level = input.level();
    for imp in [&a, &b] {
        if !imp.supports(level) {
            eprintln!(
                "error: {} does not answer the {level} level: nothing to localize at {input}",
                imp.label()
            );
            return Ok(ExitCode::from(3));
        }
    }
    let tracer = open(&cast.tracer().name)?;
    let found = localize(a.as_ref(), b.as_ref(), tracer.as_ref(), &input)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&found)?);
    } else {
        print!("{found}");
    }
    // Only answers decide: traces that differ on the way to the same
    // answer (an aliased operand whose sign is later dropped) are printed,
    // but they are not a divergence.
    Ok(if found.differs() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
