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
    let mut huge = edited(&|r| r.comparisons[0].vectors = usize::MAX);
    huge.push(parts[1].clone());
    assert_eq!(
        merge(&huge).unwrap_err(),
        MergeError::Overflow("compared vectors")
    );
}
