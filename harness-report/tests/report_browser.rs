//! The HTML report opens in a real browser: a report built from real
//! renders (ref-f316 and ref-f64, a pair and speed points) and the
//! stability rows of the reference's answers to ops-small is loaded in
//! headless Chromium, and the DOM it produces must show the main sections
//! and every image decoded. Chromium comes from Debian (`scripts/setup.sh`
//! installs it); without it the test fails and says so.

use harness::cast::Cast;
use harness::implementation::Implementation;
use harness::runner::{self, RunOptions};
use harness_report::measure;
use harness_report::model::{Render, RunMeta};
use harness_report::stability;
use harness_report::{PairGate, PixelLocalizer, ReportBuilder};
use std::process::Command;

const CHROMIUM: &str = "/usr/bin/chromium";

fn build_report(dir: &std::path::Path) -> std::path::PathBuf {
    let cast = Cast::builtin();
    let mut builder =
        ReportBuilder::new(&dir.join("report"), RunMeta::collect(), cast.role_names()).unwrap();
    for label in ["ref-f316", "ref-f64"] {
        let (full, _) = measure::render(&cast, label, false).unwrap();
        builder
            .add_render(
                Render {
                    label: label.into(),
                    implementation: label.into(),
                    setup_s: full.setup_s,
                    render_s: full.render_s,
                    pixels: full.pixels(),
                    ..Render::default()
                },
                full.images,
            )
            .unwrap();
    }
    builder
        .add_pair(
            "ref-f316",
            "ref-f64",
            PairGate::default(),
            PixelLocalizer::Impossible("ref-f64 computes with f64".into()),
            |x, y| format!("harness diff ref-f316 ref-f64 --vectors repro/pixel-{x}-{y}.json"),
        )
        .unwrap();
    for label in ["ref-f316", "ref-f64"] {
        let point = builder.speed_point(label).unwrap();
        builder.report_mut().speed_error.points.push(point);
    }
    let set = vectors::load_named("ops-small").unwrap();
    let opened: Vec<Box<dyn Implementation>> = ["ref-f316", "ref-f64", "ref-f32"]
        .into_iter()
        .map(|n| Cast::builtin().open(n).unwrap())
        .collect();
    let refs: Vec<&dyn Implementation> = opened.iter().map(|b| b.as_ref()).collect();
    let runs = runner::run(&refs, &set, RunOptions::default());
    let bases = stability::Bases {
        oracle: "ref-f64",
        bit_exact: "ref-f316",
    };
    let rows = stability::rows(&set, &runs, &[], bases, |imp, v| {
        Some(format!(
            "harness diff {imp} ref-f64 --vectors repro/{}.json",
            v.slug()
        ))
    });
    builder.report_mut().stability = rows;
    builder.finish(&dir.join("history.jsonl")).unwrap()
}

#[test]
fn the_report_opens_in_headless_chromium_with_its_sections_and_images() {
    assert!(
        std::path::Path::new(CHROMIUM).exists(),
        "{CHROMIUM} is missing: run scripts/setup.sh (Debian package chromium)"
    );
    let tmp = tempfile::tempdir().unwrap();
    let report = build_report(tmp.path());
    let page = format!("file://{}", report.join("index.html").display());
    let dom = dump_dom(tmp.path(), &page);
    for section in [
        "summary",
        "levels",
        "renders",
        "pairs",
        "speed",
        "stability",
        "trend",
    ] {
        assert!(
            dom.contains(&format!("<section id=\"{section}\">")),
            "section {section} missing from the DOM"
        );
    }
    let attr = |name: &str| -> usize {
        let key = format!("{name}=\"");
        let start = dom
            .find(&key)
            .unwrap_or_else(|| panic!("no {name} on <body>"))
            + key.len();
        dom[start..].split('"').next().unwrap().parse().unwrap()
    };
    for category in ["div-by-zero", "underflow", "hang"] {
        assert!(
            dom.contains(&format!("<td>ops-small</td><td>{category}</td>")),
            "no stability row for {category}"
        );
    }
    assert!(dom.contains("First divergent operation: not localizable: ref-f64 computes with f64"));
    let (loaded, total) = (attr("data-images-loaded"), attr("data-images-total"));
    assert!(total >= 4, "only {total} images on the page");
    assert_eq!(loaded, total, "{loaded} of {total} images decoded");
    // The pair's pixel table starts folded; a link to one of its rows (the
    // target of a box on the overlay) unfolds it.
    assert!(dom.contains("<details class=\"pixels\"><summary>"));
    let row = dom
        .split("<tr id=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .expect("a divergent pixel's row");
    let dom = dump_dom(tmp.path(), &format!("{page}#{row}"));
    assert!(
        dom.contains("<details class=\"pixels\" open=\"\"><summary>"),
        "following #{row} left its table folded"
    );
}

/// The DOM headless Chromium builds from `url` (scripts run).
fn dump_dom(tmp: &std::path::Path, url: &str) -> String {
    let profile = tmp.join("chromium-profile");
    let out = Command::new(CHROMIUM)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--allow-file-access-from-files",
            &format!("--user-data-dir={}", profile.display()),
            "--dump-dom",
            url,
        ])
        .output()
        .expect("chromium runs");
    assert!(
        out.status.success(),
        "chromium failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}
