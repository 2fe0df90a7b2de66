//! An explanation as a few lines of text (`harness explain`).

use super::{Class, DecisionChange, Explanation, RootCause, Summary};
use reference::Decision;
use std::fmt::Write;

/// What taking (or not taking) a decision means.
fn meaning(decision: Decision, taken: bool) -> &'static str {
    match (decision, taken) {
        (Decision::Union, true) => "keeps the first surface",
        (Decision::Union, false) => "takes the second surface",
        (Decision::Checker, true) => "odd square",
        (Decision::Checker, false) => "even square",
        (Decision::MarchHit, true) => "hits",
        (Decision::MarchHit, false) => "does not hit yet",
        (Decision::MarchFar, true) => "is past the far limit",
        (Decision::MarchFar, false) => "is within the far limit",
        (Decision::Miss, true) => "misses (background)",
        (Decision::Miss, false) => "hits a surface",
        (Decision::Shadow, true) => "in shadow",
        (Decision::Shadow, false) => "lit",
        (Decision::Bounce, true) => "meets a sphere and reflects",
        (Decision::Bounce, false) => "meets no sphere",
        (Decision::AngleLow | Decision::ClampLow, true) => "clamped to 0",
        (Decision::AngleHigh | Decision::ClampHigh, true) => "clamped to 1",
        (_, false) if decision != Decision::Dither => "not clamped",
        (_, true) => "white",
        (_, false) => "black",
    }
}

fn number(x: f64) -> String {
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e5) {
        format!("{x:.4e}")
    } else {
        format!("{x:.6}")
    }
}

fn decision_line(low: &str, oracle: &str, d: &DecisionChange) -> String {
    let step = d.step.map(|s| format!(" (step {s})")).unwrap_or_default();
    format!(
        "decision: {} at {}{step}: {low} {} on ({}, {}) [shadows {}, {}]; {oracle} {} on ({}, {})",
        d.decision,
        d.path,
        meaning(d.decision, d.low.taken),
        number(d.low.operands[0]),
        number(d.low.operands[1]),
        number(d.low_shadows[0]),
        number(d.low_shadows[1]),
        meaning(d.decision, d.oracle.taken),
        number(d.oracle.operands[0]),
        number(d.oracle.operands[1]),
    )
}

fn cause_line(rank: usize, c: &RootCause) -> String {
    let operands: Vec<String> = c
        .operands
        .iter()
        .map(|(lo, hi)| format!("{} [{}]", number(*lo), number(*hi)))
        .collect();
    let cancel = if c.cancelled_bits >= 1.0 {
        format!(", {:.0} leading bits cancel", c.cancelled_bits)
    } else {
        String::new()
    };
    format!(
        "{} {} ({} ops), {:.0}% of the error; worst at {}: {}({}) = {} [{}], local error {}, accumulated {}{cancel}",
        if rank == 0 { "root cause:" } else { "      then:" },
        c.site,
        c.count,
        100.0 * c.share,
        c.path,
        c.site.op,
        operands.join(", "),
        number(c.result.0),
        number(c.result.1),
        number(c.local_error),
        number(c.accumulated_error),
    )
}

/// The story of `e` in a few lines: the answers, the class and why, the
/// decision that changed and the root causes (values in brackets are the
/// low-precision run's f64 shadows).
pub fn story(e: &Explanation) -> String {
    let mut s = String::new();
    let (low, oracle) = (e.low.as_str(), e.oracle.as_str());
    if let Some(a) = &e.answers {
        let bit = |w: Option<bool>| match w {
            Some(true) => " white",
            Some(false) => " black",
            None => "",
        };
        let _ = write!(
            s,
            "{}: {low}{} ({} {}, shadow {}), {oracle}{} ({} {})",
            e.input,
            bit(a.low_white),
            a.output,
            number(a.low),
            number(a.low_shadow),
            bit(a.oracle_white),
            a.output,
            number(a.oracle)
        );
        if let Some(t) = a.threshold {
            let _ = write!(s, "; dither threshold {}", number(t));
        }
        s.push('\n');
    } else {
        let _ = writeln!(s, "{}: {low} against {oracle}", e.input);
    }
    let _ = writeln!(s, "class: {}: {}", e.class, e.why);
    if let Some(d) = &e.decision {
        let _ = writeln!(s, "{}", decision_line(low, oracle, d));
    }
    if matches!(e.class, Class::Agree | Class::Unexplained) {
        return s;
    }
    let _ = writeln!(s, "error of {}: {}", e.error_of, number(e.error));
    if e.causes.is_empty() {
        let _ = writeln!(
            s,
            "root cause: none of the {} sites, flipped alone, moves the error towards \
             {oracle}'s ({} of those runs no longer reach what it is of)",
            e.sites, e.unmeasured
        );
    }
    for (i, c) in e.causes.iter().enumerate() {
        let _ = writeln!(s, "{}", cause_line(i, c));
    }
    s
}

/// A summary as text: classes, changed decisions, top root causes.
pub fn summary_text(summary: &Summary) -> String {
    let mut s = String::new();
    for (class, n) in &summary.classes {
        let _ = writeln!(s, "  {n:>6}  {class}");
    }
    for (decision, n) in &summary.decisions {
        let _ = writeln!(s, "  {n:>6}  control flow at {decision}");
    }
    s.push_str(
        "top root causes (pixels whose largest contributor it is, mean share):
",
    );
    for c in summary.causes.iter().take(10) {
        let _ = writeln!(
            s,
            "  {:>6}  {} ({:.0}%)",
            c.pixels,
            c.site,
            100.0 * c.mean_share
        );
    }
    s
}
