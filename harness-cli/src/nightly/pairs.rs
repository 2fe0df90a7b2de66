//! Which renders the nightly compares, which of those pairs gate the
//! night, and how their divergent pixels are localized and reproduced.

use super::Rendered;
use harness::implementation::Implementation;
use harness::localize::{localizable, localize};
use harness_report::{PairGate, PixelLocalizer};
use vectors::{PixelVector, Vector};

/// Two renders to compare.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedPair {
    pub a: String,
    pub b: String,
    /// What fails the night: any differing pixel of two bit-exact renders,
    /// or more flips against the oracle than the render's policy allows.
    pub gate: PairGate,
}

/// The pairs of the renders: each program screen against its entry points'
/// image, then every render against the tracer's and the oracle's.
pub fn plan(rendered: &[Rendered], tracer: &str, oracle: &str) -> Vec<PlannedPair> {
    let find = |label: &str| rendered.iter().find(|r| r.label == label);
    let mut pairs = Vec::new();
    for screen in rendered {
        if let Some(own) = screen.screen_of.as_deref().and_then(find) {
            pairs.push(PlannedPair {
                a: own.label.clone(),
                b: screen.label.clone(),
                gate: PairGate {
                    bit_exact: own.bit_exact && screen.bit_exact,
                    flip_limit: None,
                },
            });
        }
    }
    for r in rendered {
        for base in [tracer, oracle] {
            if let Some(base) = find(base).filter(|b| b.label != r.label) {
                let bit_exact = base.label == tracer && base.bit_exact && r.bit_exact;
                let against_oracle = base.label == oracle;
                pairs.push(PlannedPair {
                    a: base.label.clone(),
                    b: r.label.clone(),
                    gate: PairGate {
                        bit_exact,
                        flip_limit: r.flip_limit.filter(|_| against_oracle),
                    },
                });
            }
        }
    }
    pairs
}

/// The pixel vector of `(x, y)`.
pub fn pixel(x: usize, y: usize) -> Vector {
    Vector::Pixel(PixelVector {
        category: "image".into(),
        x: x as u16,
        y: y as u16,
    })
}

/// How the listed pixels of a pair are localized: op traces when both
/// sides are Float316 implementations open here (`sides`), else why not.
/// `labels` are the pair's labels, each with the implementation whose
/// screen it is, if it is one.
pub fn pixel_localizer<'a>(
    sides: [Option<&'a dyn Implementation>; 2],
    tracer: Option<&'a dyn Implementation>,
    labels: [(&str, Option<&str>); 2],
) -> PixelLocalizer<'a> {
    let missing = |(label, screen_of): (&str, Option<&str>)| match screen_of {
        Some(own) => format!(
            "{label} is the screen after {own}'s whole program ran: it has no per-pixel \
             trace (the repro command localizes the pixel through {own}'s entry point)"
        ),
        None => format!("{label} is not open here"),
    };
    // A float side is the first reason, whatever the other side is.
    for imp in sides.into_iter().flatten() {
        if let Err(why) = localizable(imp, imp) {
            return PixelLocalizer::Impossible(why.to_string());
        }
    }
    let (a, b, tracer) = match (sides, tracer) {
        ([None, _], _) => return PixelLocalizer::Impossible(missing(labels[0])),
        ([_, None], _) => return PixelLocalizer::Impossible(missing(labels[1])),
        (_, None) => return PixelLocalizer::Impossible("the tracer is not open here".into()),
        ([Some(a), Some(b)], Some(t)) => (a, b, t),
    };
    PixelLocalizer::Traced {
        method: format!(
            "first divergent Float316 operation from the op traces of both sides \
             (a side that cannot trace replays {}'s trace op by op)",
            tracer.label()
        ),
        first_op: Box::new(move |x, y| match localize(a, b, tracer, &pixel(x, y)) {
            Ok(found) => found.one_line(),
            Err(e) => format!("not localized: {e}"),
        }),
    }
}

/// The command that reproduces a divergent pixel of the implementations
/// `a` and `b`: `harness localize` when both are Float316 (`by_localize`),
/// else `harness diff` on the pixel's repro file (written in the report).
pub fn pixel_repro(a: &str, b: &str, by_localize: bool, x: usize, y: usize) -> String {
    if by_localize {
        format!("harness localize {a} {b} --pixel {x},{y}")
    } else {
        format!(
            "harness diff {a} {b} --vectors repro/{}.json",
            pixel(x, y).slug()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::image_consts::{HEIGHT, WIDTH};
    use harness::cast::Cast;
    use harness::implementation::Answer;
    use harness_report::images::Grid;
    use harness_report::model::{Render, RunMeta};
    use harness_report::{RenderImages, ReportBuilder};

    fn rendered(label: &str, bit_exact: bool, screen_of: Option<&str>) -> Rendered {
        let float_entry = !bit_exact && !label.contains('+');
        Rendered {
            label: label.into(),
            bit_exact,
            screen_of: screen_of.map(String::from),
            flip_limit: float_entry.then_some(0.01),
        }
    }

    #[test]
    fn pairs_of_bit_exact_renders_gate_the_night_and_variants_do_not() {
        let renders = [
            rendered("ref-f64", false, None),
            rendered("ref-f316", true, None),
            rendered("jack", true, None),
            rendered("my-port", true, None),
            rendered("gpu-f32", false, None),
            rendered("ref-f316+newton-3", false, None),
            rendered("jack-main", true, Some("jack")),
        ];
        let planned = plan(&renders, "ref-f316", "ref-f64");
        let gated: Vec<(&str, &str)> = planned
            .iter()
            .filter(|p| p.gate.bit_exact)
            .map(|p| (p.a.as_str(), p.b.as_str()))
            .collect();
        let flip_gated: Vec<(&str, &str)> = planned
            .iter()
            .filter(|p| p.gate.flip_limit.is_some())
            .map(|p| (p.a.as_str(), p.b.as_str()))
            .collect();
        assert_eq!(
            flip_gated,
            [("ref-f64", "gpu-f32")],
            "a float entry's render against the oracle, never a variant's, a screen's \
             or a Float316 render's (those are judged against the tracer)"
        );
        assert_eq!(
            gated,
            [
                ("jack", "jack-main"),
                ("ref-f316", "jack"),
                ("ref-f316", "my-port"),
                ("ref-f316", "jack-main"),
            ]
        );
        let all: Vec<(&str, &str)> = planned
            .iter()
            .map(|p| (p.a.as_str(), p.b.as_str()))
            .collect();
        for pair in [
            ("ref-f316", "ref-f64"),
            ("ref-f64", "ref-f316"),
            ("ref-f316", "ref-f316+newton-3"),
            ("ref-f64", "jack-main"),
        ] {
            assert!(all.contains(&pair), "{pair:?} in {all:?}");
        }
    }

    /// A render of one row of `imp` (the other rows black).
    fn row_render(imp: &dyn Implementation, y: usize) -> RenderImages {
        let row: Vec<Vector> = (0..WIDTH).map(|x| pixel(x, y)).collect();
        let mut bits = vec![false; WIDTH * HEIGHT];
        for (x, answer) in imp.eval(&row).unwrap().into_iter().enumerate() {
            let common::Outcome::Value(Answer::Pixel { white, .. }) = answer else {
                panic!("pixel ({x},{y}): {answer}");
            };
            bits[y * WIDTH + x] = white;
        }
        RenderImages {
            bits: Grid::new(WIDTH, HEIGHT, bits).unwrap(),
            shades: None,
            traps: None,
        }
    }

    #[test]
    fn pixels_a_fault_flips_are_localized_to_the_faulty_operation() {
        let cast = Cast::builtin();
        let clean = cast.open("ref-f316").unwrap();
        let faulty = cast.open("ref-f316+mul-keep-low").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let mut builder =
            ReportBuilder::new(&dir.path().join("r"), RunMeta::default(), cast.role_names())
                .unwrap();
        // Row 87 has pixels whose dithered bit the fault flips.
        for imp in [&clean, &faulty] {
            let render = Render {
                label: imp.label(),
                ..Render::default()
            };
            builder
                .add_render(render, row_render(imp.as_ref(), 87))
                .unwrap();
        }
        let (a, b) = (clean.label(), faulty.label());
        let localizer = pixel_localizer(
            [Some(clean.as_ref()), Some(faulty.as_ref())],
            Some(clean.as_ref()),
            [(&a, None), (&b, None)],
        );
        let pair = builder
            .add_pair(&a, &b, PairGate::default(), localizer, |x, y| {
                pixel_repro(&a, &b, true, x, y)
            })
            .unwrap();
        assert!(!pair.divergences.is_empty());
        assert!(pair
            .localization
            .starts_with("first divergent Float316 operation"));
        let reference = reference::Reference::seed(reference::RefImpl::F316);
        let keep_low = reference::Variant::MulKeepLow
            .apply(reference::Settings::default())
            .arith;
        for d in &pair.divergences {
            let op = d.first_op.as_deref().unwrap();
            // The true origin: the first mul of the clean trace whose result
            // the fault changes (every operation before it is the same).
            let trace = reference.trace_pixel(d.x as usize, d.y as usize).unwrap();
            let (index, origin) = trace
                .records
                .iter()
                .enumerate()
                .find(|(_, r)| {
                    r.op == common::Op::Mul
                        && reference::op(common::Op::Mul, &r.args, keep_low).unwrap() != r.result
                })
                .expect("the fault changes a mul of a flipped pixel");
            let expected = format!("mul({}, {}) = ", origin.args[0], origin.args[1]);
            assert!(
                op.starts_with(&expected),
                "pixel ({}, {}): {op}, expected {expected}",
                d.x,
                d.y
            );
            assert!(
                op.contains(&format!(", record {index} [")),
                "{op}: record {index}"
            );
            assert!(op.contains("(ref-f316+mul-keep-low)"), "{op}");
            assert_eq!(
                d.repro,
                format!(
                    "harness localize ref-f316 ref-f316+mul-keep-low --pixel {},{}",
                    d.x, d.y
                )
            );
        }
    }

    #[test]
    fn pairs_with_a_float_side_or_a_screen_say_why_they_are_not_localized() {
        let cast = Cast::builtin();
        let f316 = cast.open("ref-f316").unwrap();
        let f64 = cast.open("ref-f64").unwrap();
        let why = |l: PixelLocalizer| match l {
            PixelLocalizer::Impossible(why) => why,
            PixelLocalizer::Traced { .. } => panic!("traced"),
        };
        let (a, b) = (("ref-f316", None), ("ref-f64", None));
        let tracer = Some(f316.as_ref());
        let float = pixel_localizer([Some(f316.as_ref()), Some(f64.as_ref())], tracer, [a, b]);
        assert!(why(float).starts_with("ref-f64 computes with f64"));
        let main = ("jack-main", Some("jack"));
        let screen = pixel_localizer([Some(f316.as_ref()), None], tracer, [a, main]);
        assert!(why(screen).contains("no per-pixel trace"));
        let float_screen = pixel_localizer([Some(f64.as_ref()), None], tracer, [b, main]);
        assert!(why(float_screen).starts_with("ref-f64 computes with f64"));
        assert_eq!(
            pixel_repro("ref-f316", "ref-f64", false, 3, 4),
            "harness diff ref-f316 ref-f64 --vectors repro/pixel-3-4.json"
        );
    }
}
