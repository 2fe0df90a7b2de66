//! Jack programs generated from scene descriptions, reached as a user's
//! program is: `harness jack emit` writes one that a `kind = "jack"` entry
//! binds, a `scene = FILE` entry generates one itself, and
//! `harness jack cost` measures one.

use crate::support;

use crate::binary;

use binary::{harness_in, text};
use common::Outcome;
use harness::cast::Cast;
use harness::implementation::{Answer, Num};
use std::path::{Path, PathBuf};
use vectors::{Level, Vector};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../vectors/scenes/{name}.json"))
}

/// `harness diff ref-f316 NAME --level LEVEL` in `dir`: its exit status
/// and output.
fn diff(dir: &Path, name: &str, level: &str) -> (Option<i32>, String) {
    let out = harness_in(dir, &["diff", "ref-f316", name, "--level", level]);
    (out.status.code(), text(&out))
}

#[test]
fn an_emitted_program_is_a_jack_binding_that_agrees_with_ref_f316() {
    let dir = tempfile::tempdir().unwrap();
    let gen = dir.path().join("gen");
    let seed = scene("seed");
    let out = harness_in(
        dir.path(),
        &[
            "jack",
            "emit",
            "--scene",
            seed.to_str().unwrap(),
            "--out",
            "gen",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    for file in ["Float316.jack", "Scene.jack", "Main.jack", "bindings.toml"] {
        assert!(gen.join(file).is_file(), "{file} written");
    }
    std::fs::write(
        dir.path().join("harness.toml"),
        "[impl.gen]\nkind = \"jack\"\nprogram = \"gen\"\nbindings = \"gen/bindings.toml\"\n",
    )
    .unwrap();
    for level in ["sdf", "pixels"] {
        let (code, out) = diff(dir.path(), "gen", level);
        assert_eq!(code, Some(0), "{level}: {out}");
        assert!(out.contains("no divergence"), "{level}: {out}");
    }
    // The binding is used, not ignored: a changed distance in the
    // written program diverges.
    let scene_jack = gen.join("Scene.jack");
    let code = std::fs::read_to_string(&scene_jack).unwrap();
    let changed = code.replacen(".add(", ".sub(", 1);
    assert_ne!(code, changed);
    std::fs::write(&scene_jack, changed).unwrap();
    let (code, out) = diff(dir.path(), "gen", "sdf");
    assert_eq!(code, Some(1), "{out}");
}

#[test]
fn emit_names_the_file_and_the_field_of_a_bad_description() {
    let dir = tempfile::tempdir().unwrap();
    let text_of_seed = std::fs::read_to_string(scene("seed")).unwrap();
    let bad = text_of_seed.replacen("\"radius\": ", "\"radius\": -", 1);
    assert_ne!(bad, text_of_seed);
    std::fs::write(dir.path().join("bad.json"), bad).unwrap();
    let out = harness_in(
        dir.path(),
        &["jack", "emit", "--scene", "bad.json", "--out", "gen"],
    );
    let said = text(&out);
    assert_eq!(out.status.code(), Some(2), "{said}");
    assert!(
        said.contains("bad.json") && said.contains("radius"),
        "{said}"
    );
    assert!(!dir.path().join("gen").exists(), "nothing written");
}

/// A project with `[impl.gen] kind = "jack"` and `extra` fields.
fn cast_with(extra: &str) -> Result<Cast, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let text = format!("[impl.gen]\nkind = \"jack\"\n{extra}\n");
    Cast::with_project(&root.join("harness.toml"), &text).map_err(|e| e.to_string())
}

fn scene_entry(name: &str) -> Cast {
    cast_with(&format!("scene = {:?}", scene(name).display().to_string())).unwrap()
}

#[test]
fn a_scene_entry_generates_the_seed_program_bit_exact_with_ref_f316() {
    let cast = scene_entry("seed");
    let entry = cast.get("gen").unwrap();
    assert_eq!(
        entry.levels,
        [Level::Ops, Level::Sdf, Level::Pixels, Level::Image]
    );
    assert!(entry.about.contains("generated from"), "{}", entry.about);
    let gen = cast.open("gen").unwrap();
    support::assert_agrees_with_ref_f316_on_the_small_sets(gen.as_ref());
    // The kind's fault applies to it as to any bound program: the web
    // IDE's flooring Math.divide is seen at the ops level.
    let web = cast.open("gen+web-divide").unwrap();
    let reference = cast.open("ref-f316").unwrap();
    support::assert_diverges_on_the_small_ops_set(reference.as_ref(), web.as_ref());
}

/// rtdemo's program answers ops and SDF queries, and its image through the
/// whole program's screen (its four levels are not one bit: no pixel
/// statements): its operations are ref-f316's, and its SDF the reference's
/// interpretation of rtdemo.
#[test]
fn a_scene_entry_for_rtdemo_answers_its_own_scene() {
    let cast = scene_entry("rtdemo");
    assert_eq!(
        cast.get("gen").unwrap().levels,
        [Level::Ops, Level::Sdf, Level::Image]
    );
    let gen = cast.open("gen").unwrap();
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let set = vectors::load_named(vectors::named::small_set_name(Level::Ops)).unwrap();
    let report = harness::runner::diff_set(
        &[reference.as_ref(), gen.as_ref()],
        &set,
        harness::runner::RunOptions::default(),
    );
    assert!(
        !report.diverged() && report.failures().next().is_none(),
        "{}",
        harness::text::level_report(&report)
    );
    let checked = scene::load(&scene("rtdemo")).unwrap();
    let described = reference::Described::new(
        reference::RefImpl::F316,
        &checked,
        reference::Settings::default(),
    )
    .unwrap();
    let points = vectors::gen::scene_derived::sdf_set(&checked, 5).unwrap();
    let vectors: Vec<Vector> = points.vectors.into_iter().take(40).collect();
    let answers = gen.eval(&vectors).unwrap();
    let mut compared = 0;
    for (v, a) in vectors.iter().zip(&answers) {
        let Vector::Sdf(s) = v else { continue };
        let want = described
            .sdf(s.p)
            .map(|w| (w.sd.triple.unwrap(), w.col.triple.unwrap()));
        let got = a.clone().map(|a| match a {
            Answer::Sdf {
                sd: Num::F316(sd),
                col: Num::F316(col),
            } => (sd, col),
            other => panic!("{other:?}"),
        });
        assert_eq!(got, want, "{:?}", s.p);
        compared += 1;
    }
    assert!(compared >= 20, "{compared} points");
    assert!(answers.iter().any(|a| matches!(a, Outcome::Value(_))));
}

#[test]
fn a_scene_entry_names_its_field_when_the_scene_is_bad() {
    let err = cast_with("scene = \"no-such-scene.json\"").err().unwrap();
    assert!(
        err.contains("impl.gen.scene") && err.contains("no-such-scene.json"),
        "{err}"
    );
    let both = format!(
        "scene = {:?}\nprogram = \"impls/jack/raymarcher\"",
        scene("seed").display().to_string()
    );
    let err = cast_with(&both).err().unwrap();
    assert!(err.contains("impl.gen.program"), "{err}");
}

#[test]
fn cost_reports_instructions_time_rom_and_a_map() {
    let dir = tempfile::tempdir().unwrap();
    let seed = scene("seed");
    let out = harness_in(
        dir.path(),
        &[
            "jack",
            "cost",
            "--scene",
            seed.to_str().unwrap(),
            "--step",
            "32",
            "--json",
            "--map",
            "map.png",
            "--compare-profiles",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let c: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(c["pixels_measured"], 16 * 8);
    let (mean, max) = (c["mean"].as_f64().unwrap(), c["max"].as_u64().unwrap());
    // The hand-written program's figures are 166 346 and 620 145 over
    // every pixel; the generated one is within a few per cent of them.
    assert!((100_000.0..250_000.0).contains(&mean), "{mean}");
    assert!(max as f64 > mean, "{max}");
    assert!(c["desktop_s"].as_f64().unwrap() > 3600.0);
    assert_eq!(c["fits_shared"], true);
    assert!(c["vm_commands"].as_u64().unwrap() > 1000);
    assert_eq!(c["profile_differences"], serde_json::json!([]));
    let map = image::open(dir.path().join("map.png")).unwrap().to_luma8();
    assert_eq!(map.dimensions(), (512, 256));
    let [wx, wy] = [&c["worst"][0], &c["worst"][1]].map(|v| v.as_u64().unwrap() as u32);
    assert_eq!(map.get_pixel(wx, wy).0, [255], "the worst pixel is white");
}

/// The whole-program capture of a scene entry: `Main.main` of the program
/// generated from the scene with carved shapes draws ref-f316's image on
/// the Hack screen (white where its level is 1, the rest of the screen
/// untouched), about 4.4 G VM instructions.
#[test]
fn a_scene_entrys_whole_program_draws_the_reference_image() {
    let cast = scene_entry("tests/carved");
    let gen = cast.open("gen").unwrap();
    let screen = gen
        .program_screen(None, false)
        .expect("the bindings capture the screen")
        .unwrap();
    let checked = scene::load(&scene("tests/carved")).unwrap();
    let image = reference::Described::new(
        reference::RefImpl::F316,
        &checked,
        reference::Settings::default(),
    )
    .unwrap()
    .render();
    assert_eq!((screen.width, screen.height), (512, 256));
    let differing: Vec<(usize, usize)> = (0..256)
        .flat_map(|y| (0..512).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let want = if x < image.width && y < image.height {
                image.pixels[y * image.width + x].value().unwrap().level == 1
            } else {
                true
            };
            screen.white[y * 512 + x] != want
        })
        .collect();
    assert!(
        differing.is_empty(),
        "{} pixels differ, first {:?}",
        differing.len(),
        differing.first()
    );
}
