//! `gpu-f32` against `ref-f32` and `ref-f64`: error figures of shades and
//! distances, snapshotted (not asserted zero). The figures belong to the
//! adapter: the snapshot is lavapipe's; on other adapters they are printed.

use crate::support::{float_pixels, gpu};
use common::{Outcome, SplitMix64};
use reference::{RefImpl, Reference};
use serde::Serialize;

/// Error of a set of GPU values against one reference.
#[derive(Debug, Serialize)]
struct Figures {
    max_abs: f64,
    mean_abs: f64,
    /// Largest distance in f32 units in the last place (against ref-f32).
    max_ulp: Option<u64>,
}

/// Signed-magnitude bits mapped onto a monotonic integer line.
fn ordered(x: f32) -> i64 {
    let b = x.to_bits() as i32 as i64;
    if b < 0 {
        i64::from(i32::MIN) - b
    } else {
        b
    }
}

fn figures(gpu: &[f32], want: &[f64], ulps: Option<&[f32]>) -> Figures {
    let errs: Vec<f64> = gpu
        .iter()
        .zip(want)
        .map(|(&g, &w)| (g as f64 - w).abs())
        .collect();
    Figures {
        max_abs: errs.iter().cloned().fold(0.0, f64::max),
        mean_abs: errs.iter().sum::<f64>() / errs.len() as f64,
        max_ulp: ulps.map(|r| {
            gpu.iter()
                .zip(r)
                .map(|(&g, &w)| (ordered(g) - ordered(w)).unsigned_abs())
                .max()
                .unwrap_or(0)
        }),
    }
}

#[derive(Debug, Serialize)]
struct Report {
    shade_vs_f32: Figures,
    shade_vs_f64: Figures,
    flips_vs_f32: usize,
    flips_vs_f64: usize,
    sd_vs_f32: Figures,
    sd_vs_f64: Figures,
    col_vs_f32: Figures,
    col_vs_f64: Figures,
}

#[test]
fn f32_error_figures() {
    let Some(gpu) = gpu() else { return };
    let (shade, white): (Vec<f32>, Vec<bool>) =
        gpu.render_f32().expect("render").into_iter().unzip();
    let (ref32, white32) = float_pixels(&Reference::seed(RefImpl::F32));
    let (ref64, white64) = float_pixels(&Reference::seed(RefImpl::F64));
    let ref32_f: Vec<f32> = ref32.iter().map(|&v| v as f32).collect();
    let flips = |w: &[bool]| white.iter().zip(w).filter(|(a, b)| a != b).count();

    let mut rng = SplitMix64::new(32);
    let points: Vec<[common::F316; 3]> = (0..4000)
        .map(|_| {
            std::array::from_fn(|_| {
                common::F316::from_f64_truncating((rng.unit() * 2.0 - 1.0) * 4.0)
                    .expect("encodable")
            })
        })
        .collect();
    let as_f32: Vec<[f32; 3]> = points
        .iter()
        .map(|p| p.map(|c| c.to_f64() as f32))
        .collect();
    let (sd, col): (Vec<f32>, Vec<f32>) = gpu.f32_sdf(&as_f32).expect("sdf").into_iter().unzip();
    let sdf_of = |imp| {
        let r = Reference::seed(imp);
        points
            .iter()
            .map(|&p| match r.sdf(p) {
                Outcome::Value(s) => (s.sd.value, s.col.value),
                other => panic!("a float query trapped: {other:?}"),
            })
            .unzip::<f64, f64, Vec<f64>, Vec<f64>>()
    };
    let (sd32, col32) = sdf_of(RefImpl::F32);
    let (sd64, col64) = sdf_of(RefImpl::F64);
    let sd32_f: Vec<f32> = sd32.iter().map(|&v| v as f32).collect();
    let col32_f: Vec<f32> = col32.iter().map(|&v| v as f32).collect();

    let report = Report {
        shade_vs_f32: figures(&shade, &ref32, Some(&ref32_f)),
        shade_vs_f64: figures(&shade, &ref64, None),
        flips_vs_f32: flips(&white32),
        flips_vs_f64: flips(&white64),
        sd_vs_f32: figures(&sd, &sd32, Some(&sd32_f)),
        sd_vs_f64: figures(&sd, &sd64, None),
        col_vs_f32: figures(&col, &col32, Some(&col32_f)),
        col_vs_f64: figures(&col, &col64, None),
    };
    eprintln!("adapter {}: {report:#?}", gpu.adapter_info());
    assert_within_tolerance(&report);
    if gpu.adapter_info().driver == "llvmpipe" {
        insta::assert_yaml_snapshot!("f32_error_figures_lavapipe", report);
    }
}

/// Bounds every adapter must meet (WGSL lets `sqrt`, division and `pow`
/// be less accurate than IEEE, so a real GPU's figures differ from
/// lavapipe's snapshot): about 50 times lavapipe's shade and distance
/// errors against ref-f64, and at most 0.1 % of the image's pixels flipped.
fn assert_within_tolerance(r: &Report) {
    let bounds = [
        ("shade", &r.shade_vs_f64, 1e-3, 2e-5),
        ("sd", &r.sd_vs_f64, 2e-5, 2e-6),
        ("col", &r.col_vs_f64, 3e-6, 1e-6),
    ];
    for (what, f, max_abs, mean_abs) in bounds {
        assert!(
            f.max_abs <= max_abs,
            "{what}: max |err| {} > {max_abs}",
            f.max_abs
        );
        assert!(
            f.mean_abs <= mean_abs,
            "{what}: mean |err| {} > {mean_abs}",
            f.mean_abs
        );
    }
    let pixels = common::image_consts::WIDTH * common::image_consts::HEIGHT;
    for flips in [r.flips_vs_f32, r.flips_vs_f64] {
        assert!(flips * 1000 <= pixels, "{flips} of {pixels} pixels flipped");
    }
}
