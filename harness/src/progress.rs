//! Progress bars of the long steps (indicatif), in one style: drawn on
//! standard error when it is a terminal, hidden otherwise (logs and tests
//! get none of their escape codes).

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Whether bars are wanted here: standard error is a terminal.
pub fn wanted() -> bool {
    std::io::stderr().is_terminal()
}

/// Where bars draw: standard error when `shown`, nowhere otherwise.
fn target(shown: bool) -> ProgressDrawTarget {
    if shown {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    }
}

/// Bars drawn together, one line each, on [`target`].
pub fn multi(shown: bool) -> MultiProgress {
    MultiProgress::with_draw_target(target(shown))
}

fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template).expect("the template is valid")
}

/// A bar over `len` items (vectors, pixels, pairs) labelled `prefix`, the
/// message saying what they are.
pub fn items(len: u64, prefix: &str, what: &str) -> ProgressBar {
    let bar = ProgressBar::hidden();
    bar.set_style(style("{prefix:>10} {bar:40} {pos}/{len} {msg} ({eta})"));
    bar.set_length(len);
    bar.set_prefix(prefix.to_string());
    bar.set_message(what.to_string());
    bar
}

/// A bar over emulated VM instructions, with their rate: a bar when about
/// `expected` are due, a counter when nobody knows how many.
pub fn instructions(expected: Option<u64>, prefix: &str) -> ProgressBar {
    let bar = ProgressBar::hidden();
    match expected {
        Some(len) => {
            bar.set_style(style(
                "{prefix:>10} {bar:40} {human_pos}/{human_len} VM instructions, {per_sec:0} ({eta})",
            ));
            bar.set_length(len);
        }
        None => bar.set_style(style(
            "{prefix:>10} {spinner} {human_pos} VM instructions, {per_sec:0} ({elapsed})",
        )),
    }
    bar.set_prefix(prefix.to_string());
    bar
}

/// Show `bar` on its own (not in a [`multi`]) when `shown`.
pub fn show(bar: ProgressBar, shown: bool) -> ProgressBar {
    bar.set_draw_target(target(shown));
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_count_what_they_are_told_and_a_hidden_one_draws_nothing() {
        let bar = show(items(3, "jack", "pixels"), false);
        assert!(bar.is_hidden());
        bar.inc(2);
        assert_eq!((bar.position(), bar.length()), (2, Some(3)));
        let count = show(instructions(None, "Main.main"), false);
        count.set_position(21_000_000_000);
        assert_eq!((count.position(), count.length()), (21_000_000_000, None));
        let known = instructions(Some(100), "Main.main");
        assert_eq!(known.length(), Some(100));
    }
}
