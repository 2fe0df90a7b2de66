use super::*;
use crate::cast::Cast;

fn explain_image(label: &str) -> (Vec<(usize, usize)>, bool, Vec<Explanation>) {
    let explainer = Explainer::new(label).unwrap();
    let (pixels, divergent) = explainer.image_pixels(10).unwrap();
    let explanations = explainer.pixels(&pixels);
    (pixels, divergent, explanations)
}

/// Every one of the 613 pixels where ref-f316's dithered bit differs from
/// ref-f64's is classified, none is left unexplained, and every one whose
/// shade is off by more than 0.25 names the decision that changed.
#[test]
fn every_divergent_seed_pixel_of_ref_f316_is_explained() {
    let (pixels, divergent, explanations) = explain_image("ref-f316");
    assert!(divergent);
    assert_eq!(pixels.len(), 613);
    let summary = Summary::of(&explanations);
    eprintln!("{}", summary_text(&summary));
    assert_eq!(summary.count(Class::Unexplained), 0, "{summary:?}");
    assert_eq!(summary.count(Class::Agree), 0);
    for class in [Class::ThresholdFlip, Class::ControlFlow, Class::Accumulated] {
        assert!(summary.count(class) > 0, "no {class}: {summary:?}");
    }
    let mut large = 0;
    for e in &explanations {
        let a = e.answers.as_ref().expect("both sides answer");
        assert_ne!(a.low_white, a.oracle_white, "{}", e.input);
        let d = e.decision.as_ref().expect("a dithered bit differs");
        match e.class {
            Class::ThresholdFlip => {
                assert_eq!(d.decision, Decision::Dither);
                assert!(e.output_error().unwrap() <= THRESHOLD_MARGIN);
                let t = a.threshold.unwrap();
                assert!((a.low - t).abs().min((a.oracle - t).abs()) <= THRESHOLD_MARGIN);
            }
            Class::Accumulated => {
                assert_eq!(d.decision, Decision::Dither);
                assert!(e.output_error().unwrap() > THRESHOLD_MARGIN);
            }
            Class::ControlFlow => assert_ne!(d.decision, Decision::Dither),
            other => panic!("{}: {other}", e.input),
        }
        if e.output_error().unwrap() > 0.25 {
            large += 1;
            assert_eq!(e.class, Class::ControlFlow, "{}", story(e));
            assert!(story(e).contains("decision: "), "{}", story(e));
        }
        // Every pixel has a root cause, with its operation, operands and
        // shadows, and every flipped run reached what its error is of.
        let cause = e.causes.first().unwrap_or_else(|| panic!("{}", story(e)));
        assert!(
            cause.share > 0.0 && !cause.operands.is_empty(),
            "{}",
            story(e)
        );
        assert_eq!(e.unmeasured, 0, "{}", story(e));
    }
    assert!(large > 0, "the seed has pixels off by more than 0.25");
}

/// ref-f32 differs from ref-f64 in no dithered bit: its largest shade
/// differences are explained instead.
#[test]
fn ref_f32_largest_shade_differences_are_explained() {
    let (pixels, divergent, explanations) = explain_image("ref-f32");
    assert!(!divergent, "ref-f32 flips no pixel today");
    assert_eq!(pixels.len(), 10);
    let mut previous = f64::INFINITY;
    for e in &explanations {
        let error = e.output_error().unwrap();
        eprintln!("{}", story(e));
        assert!(error > 0.0 && error <= previous, "{}", e.input);
        previous = error;
        assert!(
            matches!(e.class, Class::Accumulated | Class::ControlFlow),
            "{}",
            story(e)
        );
        assert!(!e.causes.is_empty(), "{}", story(e));
    }
}

/// Under the precision variant newton-1 (one Newton step in invSqrt), the
/// pixels it flips that ref-f316 does not are blamed on inv_sqrt in
/// normalize.
#[test]
fn newton_1_is_blamed_on_inv_sqrt_in_normalize() {
    let newton = Explainer::new("ref-f316+newton-1").unwrap();
    let spec = Reference::seed(RefImpl::F316).render();
    let oracle = Reference::seed(RefImpl::F64).render();
    let super::Subject::Seed(low) = &newton.low else {
        panic!("the seed scene's explainer")
    };
    let variant = low.render();
    let only_newton: Vec<(usize, usize)> = differing_pixels(&variant, &oracle)
        .into_iter()
        .filter(|&(x, y)| spec.is_white(x, y) == oracle.is_white(x, y))
        .step_by(50)
        .collect();
    assert!(only_newton.len() > 10);
    let explanations = newton.pixels(&only_newton);
    let blamed = explanations
        .iter()
        .filter(|e| {
            e.causes
                .first()
                .is_some_and(|c| c.site.op == "inv_sqrt" && c.site.path.ends_with("normalize"))
        })
        .count();
    eprintln!("{blamed} of {}", explanations.len());
    assert!(
        blamed * 4 >= explanations.len() * 3,
        "{blamed} of {} blamed on inv_sqrt in normalize: {}",
        explanations.len(),
        story(&explanations[0])
    );
}

#[test]
fn the_story_names_class_decision_and_root_cause() {
    let e = Explainer::new("ref-f316").unwrap().pixel(106, 93);
    let text = story(&e);
    assert_eq!(e.class, Class::ControlFlow);
    let d = e.decision.as_ref().unwrap();
    assert_eq!((d.decision, d.step), (Decision::MarchHit, Some(19)));
    assert!(text.contains("class: control-flow divergence"), "{text}");
    assert!(
        text.contains("decision: march-hit at pixel(106,93) > march step 19"),
        "{text}"
    );
    assert!(text.contains("root cause: "), "{text}");
    assert!(e
        .one_line()
        .starts_with("control-flow divergence at march-hit"));
}

/// The explanation of a Float316 implementation is ref-f316's, and holds
/// exactly where it agrees with ref-f316 bit for bit.
#[test]
fn an_explanation_holds_only_where_the_implementation_agrees() {
    let cast = Cast::builtin();
    let spec = cast.open("ref-f316").unwrap();
    let faulty = cast.open("ref-f316+mul-keep-low").unwrap();
    assert_eq!(
        reference_label(faulty.as_ref()).unwrap(),
        "ref-f316+mul-keep-low"
    );
    let f64 = cast.open("ref-f64").unwrap();
    assert!(reference_label(f64.as_ref()).is_err());
    let pixel = |x, y| {
        vectors::Vector::Pixel(vectors::PixelVector {
            category: "t".into(),
            x,
            y,
        })
    };
    // Row 87 has pixels the fault flips.
    let row: Vec<vectors::Vector> = (0..512).map(|x| pixel(x, 87)).collect();
    let why = holds_for(faulty.as_ref(), spec.as_ref(), &row)
        .unwrap()
        .unwrap();
    assert!(why.contains("does not agree with ref-f316"), "{why}");
    assert_eq!(holds_for(spec.as_ref(), spec.as_ref(), &row).unwrap(), None);
}

#[test]
fn an_sdf_query_is_explained() {
    let p = [1.5, 0.3, 1.0].map(|x| F316::from_f64_truncating(x).unwrap());
    let e = Explainer::new("ref-f316").unwrap().point(p);
    assert_eq!(e.class, Class::Accumulated, "{}", story(&e));
    assert_eq!(
        e.causes[0].site.path,
        "sdf > scene > torus",
        "{}",
        story(&e)
    );
}
