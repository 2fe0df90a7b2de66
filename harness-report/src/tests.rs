//! Tests of the report builder on small hand-made renders.

use super::*;

fn render(label: &str, render_s: f64, pixels: u64) -> Render {
    Render {
        label: label.into(),
        implementation: label.into(),
        render_s,
        pixels,
        ..Render::default()
    }
}

fn images(bits: &[u8], shades: Option<&[f64]>) -> RenderImages {
    RenderImages {
        bits: Grid::new(4, 2, bits.iter().map(|b| *b == 1).collect()).unwrap(),
        shades: shades.map(|s| Grid::new(4, 2, s.to_vec()).unwrap()),
        traps: None,
    }
}

const ORACLE: &str = "ref-f64";
const ORACLE_SHADES: [f64; 8] = [0.1, 0.9, 0.2, 0.8, 0.3, 0.7, 0.4, 0.6];

fn builder(target: &Path) -> ReportBuilder {
    let mut b = ReportBuilder::new(
        target,
        RunMeta {
            started_at: "2026-11-21T00:00:00Z".into(),
            ..RunMeta::default()
        },
        harness::cast::Cast::builtin().role_names(),
    )
    .unwrap();
    b.add_render(
        render(ORACLE, 8e-6, 8),
        images(&[0, 1, 0, 1, 0, 1, 0, 1], Some(&ORACLE_SHADES)),
    )
    .unwrap();
    let mut shades = ORACLE_SHADES;
    shades[2] = 0.6;
    shades[5] = 0.7 + 1e-4;
    b.add_render(
        render("ref-f316", 16e-6, 8),
        images(&[0, 1, 1, 1, 0, 1, 0, 1], Some(&shades)),
    )
    .unwrap();
    b.add_render(
        render("jack", 8.0, 8),
        images(&[0, 1, 1, 1, 0, 1, 0, 0], None),
    )
    .unwrap();
    b
}

fn impossible() -> PixelLocalizer<'static> {
    PixelLocalizer::Impossible("no traces".into())
}

#[test]
fn pairs_list_divergent_pixels_with_localization_and_images() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = builder(&dir.path().join("nightly"));
    let pair = b
        .add_pair(
            ORACLE,
            "ref-f316",
            PairGate::default(),
            PixelLocalizer::Traced {
                method: "by hand".into(),
                first_op: Box::new(|x, y| format!("op at {x},{y}")),
            },
            |x, y| format!("repro {x},{y}"),
        )
        .unwrap()
        .clone();
    assert_eq!(pair.localization, "by hand; 1 listed pixels localized");
    assert_eq!(
        (pair.pixels, pair.differing_pixels, pair.differing_shades),
        (8, 1, Some(2))
    );
    let d = &pair.divergences[0];
    assert_eq!((d.x, d.y, d.a_white, d.b_white), (2, 0, false, true));
    assert_eq!((d.a_shade, d.b_shade), (Some(0.2), Some(0.6)));
    assert_eq!(
        (d.first_op.as_deref(), d.repro.as_str()),
        (Some("op at 2,0"), "repro 2,0")
    );
    let heat = pair.heat.unwrap();
    assert!((heat.max_abs - 0.4).abs() < 1e-12);
    assert!((heat.mean_abs - (0.4 + 1e-4) / 8.0).abs() < 1e-9);
    // Six of the eight pixels agree: p50 is 0; p95 and p99 are the largest.
    assert_eq!(heat.percentiles_abs[0], 0.0);
    assert!((heat.percentiles_abs[1] - 0.4).abs() < 1e-12);
    assert!((heat.percentiles_abs[2] - 0.4).abs() < 1e-12);
    for rel in [&pair.overlay, &heat.image, &heat.legend] {
        assert!(b.stage.path().join(rel).is_file(), "{rel} not written");
    }
    let no_shades = b
        .add_pair(
            "ref-f316",
            "jack",
            PairGate::default(),
            impossible(),
            |_, _| String::new(),
        )
        .unwrap();
    assert_eq!(
        (no_shades.differing_pixels, no_shades.differing_shades),
        (1, None)
    );
    assert_eq!(no_shades.divergences[0].first_op, None);
    assert_eq!(no_shades.localization, "not localizable: no traces");
    assert!(no_shades.heat.is_none());
    assert!(b
        .add_pair(
            "ref-f316",
            "gpu-f32",
            PairGate::default(),
            impossible(),
            |_, _| { String::new() }
        )
        .is_err());
}

#[test]
fn identical_shades_give_no_heat_map() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = builder(&dir.path().join("nightly"));
    b.add_render(
        render("ref-f32", 1e-6, 8),
        images(&[0, 1, 0, 1, 0, 1, 0, 1], Some(&ORACLE_SHADES)),
    )
    .unwrap();
    let pair = b
        .add_pair(
            ORACLE,
            "ref-f32",
            PairGate::default(),
            impossible(),
            |_, _| String::new(),
        )
        .unwrap();
    assert_eq!((pair.differing_pixels, pair.differing_shades), (0, Some(0)));
    assert!(pair.heat.is_none() && pair.divergences.is_empty());
}

#[test]
fn speed_points_measure_against_the_oracle() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = builder(&dir.path().join("nightly"));
    b.report_mut().renders[2].vm_instructions = Some(8_000);
    let p = b.speed_point("ref-f316").unwrap();
    assert_eq!((p.time_per_pixel_s, p.pixel_flips), (2e-6, 1));
    assert!((p.max_shade_error.unwrap() - 0.4).abs() < 1e-12);
    let jack = b.speed_point("jack").unwrap();
    assert_eq!(
        (
            jack.pixel_flips,
            jack.mean_shade_error,
            jack.vm_instructions_per_pixel
        ),
        (2, None, Some(1000.0))
    );
    let oracle = b.speed_point(ORACLE).unwrap();
    assert_eq!((oracle.pixel_flips, oracle.max_shade_error), (0, None));
    assert!(b.speed_point("gpu-f32").is_err());
}

#[test]
fn renders_must_be_unique_and_match_their_shades() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = builder(&dir.path().join("nightly"));
    assert!(b
        .add_render(render("jack", 1.0, 8), images(&[0; 8], None))
        .is_err());
    let bad = RenderImages {
        bits: Grid::new(4, 2, vec![false; 8]).unwrap(),
        shades: Some(Grid::new(2, 4, vec![0.0; 8]).unwrap()),
        traps: None,
    };
    assert!(b.add_render(render("x", 1.0, 8), bad).is_err());
}

#[test]
fn cheapest_variant_is_the_fastest_identical_float316_reference() {
    let p = |label: &str, s: f64, same: Option<bool>| SpeedPoint {
        label: label.into(),
        time_per_pixel_s: s,
        identical_to_spec: same,
        ..SpeedPoint::default()
    };
    let points = [
        p("ref-f316", 3e-6, Some(true)),
        p("ref-f316+newton-1", 1e-6, Some(false)),
        p("ref-f316+mul-low-product", 2e-6, Some(true)),
        p("gpu-f316", 1e-9, Some(true)),
        p("ref-f64", 1e-8, Some(true)),
    ];
    assert_eq!(
        cheapest_spec_identical(&points, "ref-f316").as_deref(),
        Some("ref-f316+mul-low-product (2.0 µs per pixel)")
    );
    // The labels are those the nightly renders its variants under.
    assert!(harness::cast::Cast::builtin()
        .open("ref-f316+mul-low-product")
        .is_ok());
    assert_eq!(cheapest_spec_identical(&points[1..2], "ref-f316"), None);
}

#[test]
fn finish_writes_everything_then_swaps_and_appends_history() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("nightly");
    let history = history::path_for(&target);
    for run in 0..2 {
        let mut b = builder(&target);
        b.add_pair(
            ORACLE,
            "ref-f316",
            PairGate::default(),
            impossible(),
            |x, y| format!("harness diff ref-f64 ref-f316 --vectors repro/pixel-{x}-{y}.json"),
        )
        .unwrap();
        b.set_cost_map(&Grid::new(4, 2, vec![10, 20, 30, 40, 50, 60, 70, 80 + run]).unwrap())
            .unwrap();
        let points: Vec<SpeedPoint> = ["ref-f316", "jack"]
            .iter()
            .map(|l| b.speed_point(l).unwrap())
            .collect();
        b.report_mut().speed_error.points = points;
        assert_eq!(b.finish(&history).unwrap(), target);
    }
    let report =
        Report::from_json(&std::fs::read_to_string(target.join("report.json")).unwrap()).unwrap();
    assert_eq!(report.schema_version, SCHEMA_VERSION);
    assert_eq!(report.cost_map.as_ref().unwrap().max, 81);
    assert_eq!(report.cost_map.as_ref().unwrap().mean, 45.125);
    assert_eq!(report.speed_error.plot, "images/speed-error.svg");
    let page = std::fs::read_to_string(target.join("index.html")).unwrap();
    // Every file the page references exists beside it.
    for src in page
        .split("src=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
    {
        assert!(target.join(src).is_file(), "{src} referenced but missing");
    }
    assert_eq!(
        page.matches("src=\"").count(),
        3 + 1 + 2 + 2 + 1,
        "renders, overlay, heat+bar, cost+bar, plot"
    );
    let h = history::read(&history).unwrap();
    assert_eq!(h.entries.len(), 2);
    assert_eq!(h.entries[1].pixel_divergences["ref-f64 vs ref-f316"], 1);
    // The staging directory is gone; only the report and the history remain.
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(names, ["history.jsonl", "nightly"]);
}

#[test]
fn report_json_refuses_other_schemas() {
    let mut r = Report::new(RunMeta::default());
    assert!(Report::from_json(&r.to_json().unwrap()).is_ok());
    r.schema_version = 99;
    let err = Report::from_json(&r.to_json().unwrap()).unwrap_err();
    assert!(err.to_string().contains("schema_version"), "{err}");
}

#[test]
fn percentiles_are_nearest_rank_values() {
    let values: Vec<f64> = (1..=100).rev().map(f64::from).collect();
    assert_eq!(
        percentiles(&values, [0.5, 0.95, 0.99, 1.0]),
        [50.0, 95.0, 99.0, 100.0]
    );
    assert_eq!(percentiles(&[7.0], [0.01, 0.5]), [7.0, 7.0]);
    assert_eq!(percentiles(&[], [0.5]), [0.0]);
    // 131072 pixels, 613 of them differing by 0.25: p95 is 0, p99.9 not.
    let mut shades = vec![0.0; 131_072];
    shades[..613].fill(0.25);
    assert_eq!(percentiles(&shades, [0.95, 0.999]), [0.0, 0.25]);
}

#[test]
fn a_trap_differs_from_every_value_and_is_drawn_in_its_own_colour() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = builder(&dir.path().join("nightly"));
    let mut trapped = images(&[0, 1, 0, 1, 0, 1, 0, 1], Some(&ORACLE_SHADES));
    // Pixel 2 traps: its placeholder bit and shade equal the oracle's.
    trapped.traps = Some(Grid::new(4, 2, (0..8).map(|i| i == 2).collect()).unwrap());
    b.add_render(render("hang", 1.0, 8), trapped.clone())
        .unwrap();
    assert_eq!(b.report().renders.last().unwrap().trapped, 1);
    let oracle = b.render_images(ORACLE).unwrap().clone();
    assert_eq!(trapped.differing(&oracle).unwrap(), [(2, 0)]);
    assert_eq!(trapped.trap_mismatches(&oracle), 1);
    assert_eq!(trapped.trap_mismatches(&trapped), 0);
    assert!(trapped.differing(&trapped).unwrap().is_empty());
    assert_eq!(
        trapped.shade_error(&oracle).unwrap(),
        Some((0.0, 0.0)),
        "the trapped pixel's placeholder is no error figure"
    );
    let gate = PairGate {
        bit_exact: false,
        flip_limit: Some(0.5),
    };
    let pair = b
        .add_pair(ORACLE, "hang", gate, impossible(), |_, _| String::new())
        .unwrap()
        .clone();
    assert_eq!(pair.differing_pixels, 1);
    assert_eq!(
        pair.beyond_policy.as_deref(),
        Some("1 pixels trapped on one side and answered on the other")
    );
}

#[test]
fn the_pair_gate_judges_bit_exact_pairs_flip_fractions_and_traps() {
    let exact = PairGate {
        bit_exact: true,
        flip_limit: None,
    };
    assert_eq!(exact.judge(100, 0, Some(0), 0), None);
    assert_eq!(
        exact.judge(100, 0, Some(3), 0).as_deref(),
        Some("3 pixels differ between two bit-exact renders")
    );
    let float = PairGate {
        bit_exact: false,
        flip_limit: Some(0.01),
    };
    assert_eq!(float.judge(100, 1, Some(50), 0), None, "1% is within 1%");
    assert_eq!(
        float.judge(100, 2, None, 0).as_deref(),
        Some("2 of 100 dithered pixels flip (2.000%), over the policy's 1.000%")
    );
    assert!(
        float.judge(100, 1, None, 1).is_some(),
        "a trap is never within policy"
    );
    assert_eq!(
        PairGate::default().judge(100, 100, Some(100), 100),
        None,
        "measured only"
    );
}

/// A run killed after its report was swapped in, before its history line
/// was appended: the next run appends the missing line before its own.
#[test]
fn a_report_the_history_lacks_gets_its_line_at_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("nightly");
    let history = history::path_for(&target);
    let run = |started_at: &str| {
        let mut b = builder(&target);
        b.report_mut().meta.started_at = started_at.into();
        b.finish(&history).unwrap();
    };
    run("2026-11-21T01:00:00Z");
    run("2026-11-22T01:00:00Z");
    // The kill: the second run's line never reached the history.
    let text = std::fs::read_to_string(&history).unwrap();
    let first_line = text.lines().next().unwrap();
    std::fs::write(&history, format!("{first_line}\n")).unwrap();
    run("2026-11-23T01:00:00Z");
    let dates: Vec<String> = history::read(&history)
        .unwrap()
        .entries
        .into_iter()
        .map(|e| e.date)
        .collect();
    assert_eq!(
        dates,
        [
            "2026-11-21T01:00:00Z",
            "2026-11-22T01:00:00Z",
            "2026-11-23T01:00:00Z"
        ]
    );
}
