//! What `harness tune` found, as one serialisable record (`--json`) and
//! as text.

use super::cost_model::CostModel;
use super::jack_check::JackCheck;
use super::reasons::Forbidding;
use crate::commands::jack::cost::DESKTOP_RATE;
use harness_report::html::duration;
use serde::Serialize;

/// A tuned site.
#[derive(Serialize)]
pub(super) struct Tuned {
    pub(super) site: String,
    pub(super) variant: String,
}

/// A site left untuned, and why.
#[derive(Serialize)]
pub(super) struct RejectedSite {
    pub(super) site: String,
    /// The variant tried there.
    pub(super) variant: String,
    /// The other sites tuned when it was tried (those accepted before it).
    pub(super) on: Option<String>,
    /// `fails` or `no saving`.
    pub(super) reason: &'static str,
    pub(super) flips: u64,
    pub(super) max_error: Option<f64>,
    /// Estimated VM instructions per pixel of what was tried.
    pub(super) per_pixel: f64,
    /// The pixel that forbids it (`fails`).
    pub(super) pixel: Option<Forbidding>,
}

/// Cost figures of one side, VM instructions.
#[derive(Serialize)]
pub(super) struct Saving {
    pub(super) untuned_per_pixel: f64,
    pub(super) tuned_per_pixel: f64,
    pub(super) saved_per_pixel: f64,
    pub(super) saved_percent: f64,
    pub(super) untuned_whole_image: f64,
    pub(super) tuned_whole_image: f64,
    pub(super) saved_whole_image: f64,
    /// On the official desktop VM emulator at its rate.
    pub(super) untuned_desktop_s: f64,
    pub(super) tuned_desktop_s: f64,
}

impl Saving {
    pub(super) fn new(untuned: (f64, f64), tuned: (f64, f64)) -> Saving {
        Saving {
            untuned_per_pixel: untuned.0,
            tuned_per_pixel: tuned.0,
            saved_per_pixel: untuned.0 - tuned.0,
            saved_percent: 100.0 * (untuned.0 - tuned.0) / untuned.0.max(1.0),
            untuned_whole_image: untuned.1,
            tuned_whole_image: tuned.1,
            saved_whole_image: untuned.1 - tuned.1,
            untuned_desktop_s: untuned.1 / DESKTOP_RATE,
            tuned_desktop_s: tuned.1 / DESKTOP_RATE,
        }
    }
}

/// What the Jack check found.
#[derive(Serialize)]
pub(super) struct JackFigures {
    /// Every `step`-th pixel of every `step`-th row was run.
    pub(super) step: u32,
    pub(super) pixels: usize,
    pub(super) measured: Saving,
    /// Measured pixels whose answer differs from the reference's, and the
    /// first few: tuned program against tuned ref-f316, untuned against
    /// untuned.
    pub(super) tuned_mismatches: usize,
    pub(super) untuned_mismatches: usize,
    pub(super) first_mismatches: Vec<String>,
}

/// The results of `harness tune`.
#[derive(Serialize)]
pub(super) struct Report {
    pub(super) scene: String,
    pub(super) name: String,
    pub(super) constraint: String,
    pub(super) search: &'static str,
    pub(super) sites: usize,
    pub(super) configurations: u64,
    pub(super) judged: usize,
    pub(super) rendered: usize,
    /// Judged configurations whose evaluation was known (from the state
    /// file, or judged before in the same search).
    pub(super) known: usize,
    pub(super) search_s: f64,
    pub(super) tuned: Vec<Tuned>,
    pub(super) flips: u64,
    pub(super) shades: u64,
    pub(super) max_error: Option<f64>,
    pub(super) untuned_max_error: Option<f64>,
    pub(super) estimated: Saving,
    pub(super) model: CostModel,
    pub(super) jack: JackFigures,
    pub(super) rejected: Vec<RejectedSite>,
    pub(super) out: String,
    pub(super) plot: String,
}

/// The Jack figures of the two checks (the tuned one is the untuned one
/// when nothing was tuned).
pub(super) fn jack_figures(untuned: &JackCheck, tuned: Option<&JackCheck>) -> JackFigures {
    let figures = |c: &JackCheck| (c.cost.mean, c.cost.whole_image_instructions as f64);
    let t = tuned.unwrap_or(untuned);
    let mut first = untuned.first_mismatches.clone();
    if let Some(t) = tuned {
        first.extend(t.first_mismatches.iter().cloned());
    }
    JackFigures {
        step: untuned.cost.step,
        pixels: untuned.cost.pixels_measured,
        measured: Saving::new(figures(untuned), figures(t)),
        tuned_mismatches: tuned.map_or(0, |t| t.mismatches),
        untuned_mismatches: untuned.mismatches,
        first_mismatches: first,
    }
}

/// A count with thin groups: `21 930 000`.
fn grouped(n: f64) -> String {
    let s = format!("{:.0}", n.abs());
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    if n < -0.5 {
        format!("-{out}")
    } else {
        out
    }
}

fn error_text(e: Option<f64>) -> String {
    e.map_or("unbounded (a pixel trapped)".into(), |e| format!("{e:.4}"))
}

/// The results as text.
pub(super) fn text(r: &Report) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "scene {} ({}): {} sites searched, {} configurations",
        r.name, r.scene, r.sites, r.configurations
    );
    let _ = writeln!(s, "constraint: {}", r.constraint);
    let _ = writeln!(
        s,
        "search: {}, {} configurations judged ({} rendered, {} known already) in {}",
        r.search,
        r.judged,
        r.rendered,
        r.known,
        duration(r.search_s)
    );
    if r.tuned.is_empty() {
        let _ = writeln!(s, "tuned sites: none saves under the constraint");
    } else {
        let _ = writeln!(s, "tuned sites ({}):", r.tuned.len());
        for t in &r.tuned {
            let _ = writeln!(s, "  {}: {}", t.site, t.variant);
        }
    }
    let _ = writeln!(
        s,
        "tuned image: {} levels and {} shades differ from the untuned image; \
         max |shade - ref-f64| {} (untuned {})",
        r.flips,
        r.shades,
        error_text(r.max_error),
        error_text(r.untuned_max_error)
    );
    let saving = |s: &mut String, what: &str, v: &Saving| {
        let _ = writeln!(
            s,
            "{what}: untuned {} VM instructions per pixel, tuned {}: {} saved per pixel ({:.2}%), \
             {} over the whole image ({} -> {}); official desktop VM emulator at {:.1} M/s: \
             {} -> {}",
            grouped(v.untuned_per_pixel),
            grouped(v.tuned_per_pixel),
            grouped(v.saved_per_pixel),
            v.saved_percent,
            grouped(v.saved_whole_image),
            grouped(v.untuned_whole_image),
            grouped(v.tuned_whole_image),
            DESKTOP_RATE / 1e6,
            duration(v.untuned_desktop_s),
            duration(v.tuned_desktop_s)
        );
    };
    saving(&mut s, "estimated (per-operation costs)", &r.estimated);
    let j = &r.jack;
    saving(
        &mut s,
        &format!(
            "measured on the generated Jack programs ({})",
            crate::commands::jack::cost::every_nth(j.step)
        ),
        &j.measured,
    );
    let _ = writeln!(
        s,
        "bit for bit: the tuned program differs from the tuned ref-f316 at {} of {} pixels, \
         the untuned one from ref-f316 at {}",
        j.tuned_mismatches, j.pixels, j.untuned_mismatches
    );
    for m in &j.first_mismatches {
        let _ = writeln!(s, "  {m}");
    }
    let against = |estimate: f64, measured: f64| {
        format!(
            "{}, measured {} ({:+.2}%)",
            grouped(estimate),
            grouped(measured),
            100.0 * (estimate - measured) / measured.max(1.0)
        )
    };
    let (e, m) = (&r.estimated, &j.measured);
    let _ = write!(
        s,
        "cost model: costs measured on {} pixels of the untuned program and of the one with \
         every operation site tuned; VM instructions per pixel estimated for the untuned image {}",
        r.model.sample,
        against(e.untuned_per_pixel, m.untuned_per_pixel)
    );
    if !r.tuned.is_empty() {
        let _ = write!(
            s,
            ", for the tuned one {}; saving estimated {:.2}%, measured {:.2}%",
            against(e.tuned_per_pixel, m.tuned_per_pixel),
            e.saved_percent,
            m.saved_percent
        );
    }
    s.push('\n');
    if !r.rejected.is_empty() {
        let _ = writeln!(s, "sites left untuned ({}):", r.rejected.len());
    }
    for x in &r.rejected {
        let tried = match &x.on {
            Some(on) => format!("{}: {} (on {on})", x.site, x.variant),
            None => format!("{}: {}", x.site, x.variant),
        };
        match &x.pixel {
            Some(p) => {
                let _ = writeln!(
                    s,
                    "  {tried} fails ({} levels differ, max error {}); at ({},{}): untuned {}, \
                     tuned {}",
                    x.flips,
                    error_text(x.max_error),
                    p.x,
                    p.y,
                    p.untuned,
                    p.tuned
                );
                if let Some(d) = &p.changed_decision {
                    let _ = writeln!(s, "      first changed decision: {d}");
                }
                let _ = writeln!(s, "      against ref-f64: {}", p.explanation);
            }
            None => {
                let _ = writeln!(
                    s,
                    "  {tried} {} ({} VM instructions per pixel, {} levels differ)",
                    if x.reason == "fails" {
                        "fails"
                    } else {
                        "keeps the constraint but saves nothing"
                    },
                    grouped(x.per_pixel),
                    x.flips
                );
            }
        }
    }
    let _ = writeln!(s, "wrote {} and {}", r.out, r.plot);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_grouped_by_thousands() {
        assert_eq!(grouped(21_930_000_000.0), "21 930 000 000");
        assert_eq!(grouped(166.4), "166");
        assert_eq!(grouped(-1234.0), "-1 234");
        assert_eq!(grouped(0.0), "0");
    }
}
