//! Plain-text rendering of runner results, as `harness diff` prints them.
//! Deterministic: stable ordering and no timings, so that it can be
//! snapshot-tested.

use crate::compare::{Comparison, Divergence, Policy};
use crate::runner::LevelReport;
use std::fmt::{self, Write};

/// Divergences printed per comparison (all of them are in the JSON report).
pub const PRINTED: usize = 12;

fn divergence(out: &mut String, c: &Comparison, d: &Divergence) -> fmt::Result {
    // A tolerated difference (a flip, a shade) is judged with the others,
    // by the set's flip fraction: within policy only when that holds.
    let tolerated = match (d.tolerated, flip_fraction_beyond(c)) {
        (false, _) => ", beyond policy",
        (true, false) => ", within policy (judged by the flip fraction)",
        (true, true) => ", counted in the flip fraction, which is beyond policy",
    };
    writeln!(
        out,
        "    #{} {} [{}] {}{tolerated}",
        d.index,
        d.input,
        d.input.category(),
        d.kind
    )?;
    writeln!(out, "        {}: {}", c.a, d.a)?;
    writeln!(out, "        {}: {}", c.b, d.b)?;
    if let Some(e) = &d.error {
        let ulps = e
            .ulps_f32
            .map(|u| format!(", {u:.1} ulps f32"))
            .unwrap_or_default();
        writeln!(
            out,
            "        error: abs {:.3e}, rel {:.3e}{ulps}",
            e.abs, e.rel
        )?;
    }
    if let Some(odd) = &d.odd_one_out {
        writeln!(out, "        odd one out: {odd}")?;
    }
    if let Some(cmd) = &d.localize {
        writeln!(out, "        localize: {cmd}")?;
    }
    if let Some(file) = &d.repro {
        writeln!(
            out,
            "        repro: harness diff {} {} --vectors {file}",
            c.a, c.b
        )?;
    }
    Ok(())
}

/// Whether the comparison's dithered pixels flip more than its policy
/// allows.
fn flip_fraction_beyond(c: &Comparison) -> bool {
    match (&c.policy, &c.stats) {
        (Policy::Error { thresholds }, Some(s)) if s.pixels > 0 => {
            s.flips as f64 / s.pixels as f64 > thresholds.max_flip_fraction
        }
        _ => false,
    }
}

/// One comparison, as text.
pub fn comparison(c: &Comparison) -> String {
    let mut out = String::new();
    let _ = (|| -> fmt::Result {
        let policy = match &c.policy {
            Policy::Exact => "exact (bit-exact triples, same outcome kind)".to_string(),
            Policy::Error { thresholds: t } => format!(
                "error figures against {} (abs > {:e} and rel > {:e} diverge; flips over {}%)",
                c.b,
                t.max_abs,
                t.max_rel,
                100.0 * t.max_flip_fraction
            ),
        };
        writeln!(out, "  {} vs {}: policy {policy}", c.a, c.b)?;
        if let Some(s) = &c.stats {
            let values = if s.values == 0 {
                "0 values (error figures n/a)".to_string()
            } else {
                let ulps = s
                    .max_ulps_f32
                    .map(|u| format!(", max {u:.1} ulps f32"))
                    .unwrap_or_default();
                format!(
                    "{} values, max abs {:.3e}, mean abs {:.3e}, max rel {:.3e}{ulps}",
                    s.values, s.max_abs, s.mean_abs, s.max_rel
                )
            };
            let flips = if s.pixels == 0 {
                "no dithered pixels".to_string()
            } else {
                format!("{} of {} pixels flip", s.flips, s.pixels)
            };
            writeln!(out, "    figures: {values}; {flips}")?;
        }
        for finding in &c.findings {
            writeln!(out, "    FINDING: {finding}")?;
        }
        let counts = |per: &std::collections::BTreeMap<String, usize>| {
            let counts: Vec<String> = per.iter().map(|(what, n)| format!("{what} {n}")).collect();
            counts.join(", ")
        };
        if !c.outside_domain.is_empty() {
            writeln!(
                out,
                "    outside the modelled domain, not compared (one side declares no domain \
                 check): {}",
                counts(&c.outside_domain)
            )?;
        }
        if !c.unsupported.is_empty() {
            writeln!(
                out,
                "    unsupported by one side, not compared: {}",
                counts(&c.unsupported)
            )?;
        }
        let total: usize = c.groups.iter().map(|g| g.count).sum();
        let beyond: usize = c
            .groups
            .iter()
            .filter(|g| !g.tolerated)
            .map(|g| g.count)
            .sum();
        if !c.diverged {
            let note = if total > 0 {
                format!(" ({total} differences within policy)")
            } else {
                String::new()
            };
            writeln!(out, "    no divergence on {} vectors{note}", c.vectors)?;
        } else {
            let judged = match total - beyond {
                0 => String::new(),
                n => format!(", {n} judged by the flip fraction"),
            };
            writeln!(
                out,
                "    DIVERGENCE: {beyond} differences beyond policy{judged} on {} vectors",
                c.vectors
            )?;
        }
        if total == 0 {
            return Ok(());
        }
        writeln!(out, "    groups:")?;
        for g in &c.groups {
            let op = g.op.map(|o| format!("{o} / ")).unwrap_or_default();
            let tolerated = if g.tolerated {
                ", judged by the flip fraction"
            } else {
                ""
            };
            writeln!(
                out,
                "      {op}{}: {} x{} (first #{}){tolerated}",
                g.category, g.kind, g.count, g.first
            )?;
        }
        writeln!(out, "    divergences:")?;
        for d in c.divergences.iter().take(PRINTED) {
            divergence(&mut out, c, d)?;
        }
        let more = total.saturating_sub(PRINTED.min(c.divergences.len()));
        if more > 0 {
            writeln!(out, "    ... and {more} more (see the JSON report)")?;
        }
        Ok(())
    })();
    out
}

/// A level's report, as text.
pub fn level_report(r: &LevelReport) -> String {
    let mut out = format!("level {}: set {} ({} vectors)\n", r.level, r.set, r.vectors);
    for (label, err) in r.failures() {
        out += &format!("  {label}: {err}\n");
    }
    for c in &r.comparisons {
        out += &comparison(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compare::{compare, Sides};
    use crate::implementation::{Answer, Num, Numbers};
    use common::Outcome;
    use vectors::{Level, PixelVector, Vector, VectorSet};

    fn pixels(n: usize) -> VectorSet {
        let vectors = (0..n)
            .map(|x| {
                Vector::Pixel(PixelVector {
                    category: "c".into(),
                    x: x as u16,
                    y: 0,
                })
            })
            .collect();
        VectorSet::new("p", Level::Pixels, "", None, vectors)
    }

    fn pixel(shade: f64, white: bool) -> Outcome<Answer> {
        Outcome::Value(Answer::Pixel {
            shade: Num::F64(shade),
            white,
        })
    }

    fn text_of(subject: &[Outcome<Answer>], oracle: &[Outcome<Answer>]) -> String {
        comparison(&compare(
            &pixels(subject.len()),
            &Sides {
                a_label: "f32-port",
                a_numbers: Numbers::F32,
                a_checks_domain: true,
                a: subject,
                b_label: "ref-f64",
                b_numbers: Numbers::F64,
                b_checks_domain: true,
                b: oracle,
            },
        ))
    }

    #[test]
    fn a_flip_is_within_policy_only_while_the_flip_fraction_is() {
        // 0.1 is no f32 value: the oracle is seen to be f64.
        let oracle: Vec<_> = (0..200).map(|_| pixel(0.1, true)).collect();
        let mut subject = oracle.clone();
        subject[3] = pixel(0.1, false);
        let one = text_of(&subject, &oracle);
        assert!(
            one.contains("within policy (judged by the flip fraction)"),
            "{one}"
        );
        assert!(!one.contains("beyond policy"), "{one}");
        subject[4] = pixel(0.1, false);
        subject[5] = pixel(0.1, false);
        let three = text_of(&subject, &oracle);
        assert!(
            three.contains("counted in the flip fraction, which is beyond policy"),
            "{three}"
        );
        assert!(
            three
                .contains("DIVERGENCE: 0 differences beyond policy, 3 judged by the flip fraction"),
            "{three}"
        );
    }

    #[test]
    fn figures_over_no_values_are_not_zeros() {
        let hang = [Outcome::Hang, Outcome::Hang];
        let t = text_of(&hang, &[pixel(0.1, true), pixel(0.1, true)]);
        assert!(t.contains("figures: 0 values (error figures n/a)"), "{t}");
        assert!(t.contains("hang, beyond policy"), "{t}");
    }
}
