//! `merge` of shard reports equals the unsharded report, timings apart:
//! the level-2 add campaign in 4 shards, against a fault that diverges on
//! thousands of its cases (so truncation, omitted counts and groups are
//! all exercised).

use harness::implementation::Implementation;
use harness::merge::{merge, run_shard, MergeError};
use harness::runner::{LevelReport, RunOptions};
use vectors::gen::testfloat::{self, CaseLevel};
use vectors::Shard;

fn without_timings(mut r: LevelReport) -> LevelReport {
    for s in &mut r.runs {
        s.seconds = 0.0;
    }
    r
}

#[test]
fn four_shards_merge_into_the_unsharded_report() {
    let set = testfloat::set(&[common::Op::Add], CaseLevel::Two, testfloat::DEFAULT_SEED);
    let cast = harness::cast::Cast::builtin();
    let clean = cast.open("ref-f316").unwrap();
    let faulty = cast.open("ref-f316+add-align-off-by-one").unwrap();
    let impls: Vec<&dyn Implementation> = vec![clean.as_ref(), faulty.as_ref()];
    let options = RunOptions::default();
    let whole = run_shard(&impls, &set, Shard::WHOLE, options);
    let c = &whole.comparisons[0];
    assert!(
        c.omitted > 0,
        "the fault diverges on more cases than are kept"
    );
    let parts: Vec<Vec<LevelReport>> = (0..4)
        .map(|k| {
            vec![run_shard(
                &impls,
                &set,
                Shard { index: k, count: 4 },
                options,
            )]
        })
        .collect();
    let merged = merge(&parts).unwrap();
    assert!(merged.missing.is_empty());
    assert_eq!(
        without_timings(merged.reports[0].clone()),
        without_timings(whole.clone())
    );

    let three = merge(&parts[..3]).unwrap();
    assert_eq!(three.missing, vec![3]);
    assert!(three.reports[0].vectors < whole.vectors);
    let twice = [parts[1].clone(), parts[1].clone()];
    assert_eq!(
        merge(&twice).unwrap_err(),
        MergeError::Duplicate(Shard { index: 1, count: 4 })
    );
    assert_eq!(
        merge(&[vec![whole]]).unwrap_err(),
        MergeError::NotSharded(0)
    );
    // Hand-edited reports: a campaign of no shard, a shard past the end,
    // and counts that would wrap are refused, never merged.
    let edited = |f: &dyn Fn(&mut LevelReport)| {
        let mut part = parts[0].clone();
        f(&mut part[0]);
        vec![part]
    };
    for shard in [Shard { index: 0, count: 0 }, Shard { index: 4, count: 4 }] {
        assert_eq!(
            merge(&edited(&|r| r.shard = Some(shard))).unwrap_err(),
            MergeError::BadShard(0, shard)
        );
    }
    // Shards of two campaigns (0/4 beside 1/3) are refused.
    let mut other = parts[1].clone();
    other[0].shard = Some(Shard { index: 1, count: 3 });
    assert_eq!(
        merge(&[parts[0].clone(), other]).unwrap_err(),
        MergeError::Counts(4, 3)
    );
    let mut huge = edited(&|r| r.comparisons[0].vectors = usize::MAX);
    huge.push(parts[1].clone());
    assert_eq!(
        merge(&huge).unwrap_err(),
        MergeError::Overflow("compared vectors")
    );
}

/// The error policy's figures merged: counts summed, maxima kept, and the
/// mean error weighted by each shard's values (1.0 over 10 values and 3.0
/// over 30 give 2.5, not the mean of the means).
#[test]
fn merged_error_figures_weigh_each_shards_mean_by_its_values() {
    let set = testfloat::set(&[common::Op::Add], CaseLevel::One, testfloat::DEFAULT_SEED);
    let cast = harness::cast::Cast::builtin();
    let a = cast.open("ref-f316").unwrap();
    let b = cast.open("ref-f316+add-align-off-by-one").unwrap();
    let impls: Vec<&dyn Implementation> = vec![a.as_ref(), b.as_ref()];
    let stats =
        |values: usize, mean_abs: f64, max_abs: f64, flips: usize| harness::compare::ErrorStats {
            values,
            max_abs,
            mean_abs,
            max_rel: max_abs / 10.0,
            max_ulps_f32: None,
            pixels: 2 * values,
            flips,
        };
    let parts: Vec<Vec<LevelReport>> = [(0, stats(10, 1.0, 4.0, 1)), (1, stats(30, 3.0, 2.0, 2))]
        .into_iter()
        .map(|(k, st)| {
            let mut r = run_shard(
                &impls,
                &set,
                Shard { index: k, count: 2 },
                RunOptions::default(),
            );
            r.comparisons[0].stats = Some(st);
            vec![r]
        })
        .collect();
    let merged = merge(&parts).unwrap();
    let s = merged.reports[0].comparisons[0].stats.clone().unwrap();
    assert_eq!((s.values, s.pixels, s.flips), (40, 80, 3));
    assert_eq!((s.max_abs, s.max_rel), (4.0, 0.4));
    assert_eq!(s.mean_abs, 2.5);
    // No value compared: a mean of 0, not 0/0.
    let empty: Vec<Vec<LevelReport>> = parts
        .iter()
        .map(|p| {
            let mut p = p.clone();
            p[0].comparisons[0].stats = Some(stats(0, 0.0, 0.0, 0));
            p
        })
        .collect();
    let s = merge(&empty).unwrap().reports[0].comparisons[0]
        .stats
        .clone()
        .unwrap();
    assert_eq!(s.mean_abs, 0.0);
}
