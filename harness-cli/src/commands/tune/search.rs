//! The searches over a scene's sites and variants, given a judge that says
//! whether a configuration keeps the constraint and what it costs.
//!
//! [`delta_debug`], as Precimonious searches precisions: each site alone
//! first (a loop's step counts by bisection), which also names the pixel
//! that forbids each site that fails; then every site that passes and
//! saves, all at once, split in halves where the set fails, each half tried
//! on what was accepted before it (the largest passing sets accepted, the
//! largest savings first); then each site left out tried again, greedily,
//! on the accepted set; under a budget (flips or an error), each site that
//! failed alone tried once more on the accepted set, where another site's
//! change may cancel or absorb its own; last, each tuned loop bisected again
//! below its count on the rest. [`exhaustive`] tries every configuration,
//! for spaces small enough to enumerate.

use super::space::{Config, Site};
use scene::sites::Choice;

/// What the search knows of a configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Judged {
    /// Whether it keeps the constraint.
    pub passes: bool,
    /// Its estimated cost.
    pub cost: f64,
}

/// Why a site is left untuned.
#[derive(Clone, Debug, PartialEq)]
pub enum Rejection {
    /// `config`, the site's least aggressive variant alone or on the
    /// accepted set, breaks the constraint.
    Fails { config: Config },
    /// `config` keeps the constraint but costs no less than without the
    /// site.
    NoSaving { config: Config, cost: f64 },
}

/// A rejected site.
#[derive(Clone, Debug, PartialEq)]
pub struct Rejected {
    pub site: String,
    pub why: Rejection,
}

/// A search's answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// The cheapest passing configuration found.
    pub best: Config,
    pub cost: f64,
    /// Every searched site left untuned in `best`, with why
    /// ([`delta_debug`] only).
    pub rejected: Vec<Rejected>,
    /// Configurations judged (the judge may have known some before).
    pub judged: usize,
}

/// The best variant of `site` on `on`, or the configuration that fails.
enum Alone {
    Passes(Choice, f64),
    Fails(Config),
}

/// `on` with `site` at `choice`.
fn with(on: &Config, site: &str, choice: Choice) -> Config {
    let mut c = on.clone();
    c.insert(site.to_string(), choice);
    c
}

struct Search<'a, J> {
    judge: &'a mut J,
    judged: usize,
}

impl<J: FnMut(&Config) -> anyhow::Result<Judged>> Search<'_, J> {
    fn judge(&mut self, c: &Config) -> anyhow::Result<Judged> {
        self.judged += 1;
        (self.judge)(c)
    }

    /// `site`'s cheapest passing option on `on`, among `options` (some of
    /// `site.options`). A loop's options are bisected for the fewest steps
    /// that pass; an operation's are all tried.
    fn alone(&mut self, site: &Site, options: &[Choice], on: &Config) -> anyhow::Result<Alone> {
        let mut best: Option<(Choice, f64)> = None;
        let mut failed = None;
        if site.is_loop {
            // The first passing count, fewest steps first.
            let (mut lo, mut hi) = (0, options.len());
            while lo < hi {
                let mid = (lo + hi) / 2;
                let c = with(on, &site.name, options[mid]);
                let j = self.judge(&c)?;
                if j.passes {
                    best = Some((options[mid], j.cost));
                    hi = mid;
                } else {
                    failed = Some(c);
                    lo = mid + 1;
                }
            }
        } else {
            for &choice in options {
                let c = with(on, &site.name, choice);
                let j = self.judge(&c)?;
                if !j.passes {
                    failed.get_or_insert(c);
                } else if best.is_none_or(|(_, cost)| j.cost < cost) {
                    best = Some((choice, j.cost));
                }
            }
        }
        Ok(match (best, failed) {
            (Some((choice, cost)), _) => Alone::Passes(choice, cost),
            (None, Some(c)) => Alone::Fails(c),
            (None, None) => Alone::Fails(on.clone()),
        })
    }

    /// Accept the largest passing subsets of `set` onto `accepted`;
    /// the sites of subsets that fail alone go to `left`.
    fn split(
        &mut self,
        set: &[(String, Choice)],
        accepted: &mut (Config, f64),
        left: &mut Vec<String>,
    ) -> anyhow::Result<()> {
        if set.is_empty() {
            return Ok(());
        }
        let mut trial = accepted.0.clone();
        trial.extend(set.iter().cloned());
        let j = self.judge(&trial)?;
        if j.passes && j.cost < accepted.1 {
            *accepted = (trial, j.cost);
        } else if let [(site, _)] = set {
            left.push(site.clone());
        } else {
            let (a, b) = set.split_at(set.len() / 2);
            self.split(a, accepted, left)?;
            self.split(b, accepted, left)?;
        }
        Ok(())
    }
}

/// Delta debugging from `base_cost`, the untuned configuration's cost;
/// `retry_failed`: try the sites that fail alone again on the accepted set
/// (one configuration per operation site, a bisection per loop).
pub fn delta_debug(
    sites: &[Site],
    base_cost: f64,
    retry_failed: bool,
    judge: &mut impl FnMut(&Config) -> anyhow::Result<Judged>,
) -> anyhow::Result<Found> {
    let mut s = Search { judge, judged: 0 };
    let mut rejected = Vec::new();
    let untuned = Config::new();
    // Each site alone.
    let mut viable: Vec<(String, Choice, f64)> = Vec::new();
    for site in sites {
        match s.alone(site, &site.options, &untuned)? {
            Alone::Passes(choice, cost) if cost < base_cost => {
                viable.push((site.name.clone(), choice, cost));
            }
            Alone::Passes(choice, cost) => rejected.push(Rejected {
                site: site.name.clone(),
                why: Rejection::NoSaving {
                    config: with(&untuned, &site.name, choice),
                    cost,
                },
            }),
            Alone::Fails(config) => rejected.push(Rejected {
                site: site.name.clone(),
                why: Rejection::Fails { config },
            }),
        }
    }
    // All at once, split where they fail, the largest savings first.
    viable.sort_by(|a, b| a.2.total_cmp(&b.2).then_with(|| a.0.cmp(&b.0)));
    let set: Vec<(String, Choice)> = viable.iter().map(|(n, c, _)| (n.clone(), *c)).collect();
    let mut accepted = (untuned, base_cost);
    let mut left = Vec::new();
    s.split(&set, &mut accepted, &mut left)?;
    // Each site left out, greedily, on what was accepted.
    for name in left {
        let site = sites
            .iter()
            .find(|x| x.name == name)
            .expect("a searched site");
        let why = match s.alone(site, &site.options, &accepted.0)? {
            Alone::Passes(choice, cost) if cost < accepted.1 => {
                accepted.0.insert(name, choice);
                accepted.1 = cost;
                continue;
            }
            Alone::Passes(choice, cost) => Rejection::NoSaving {
                config: with(&accepted.0, &name, choice),
                cost,
            },
            Alone::Fails(config) => Rejection::Fails { config },
        };
        rejected.push(Rejected { site: name, why });
    }
    // Under a budget, each site that failed alone, on what was accepted;
    // it keeps its first rejection (alone, the clearer reason) if it fails.
    if retry_failed && !accepted.0.is_empty() {
        let failed_alone: Vec<usize> = (0..rejected.len())
            .filter(
                |&i| matches!(&rejected[i].why, Rejection::Fails { config } if config.len() == 1),
            )
            .collect();
        let mut taken = Vec::new();
        for i in failed_alone {
            let site = sites
                .iter()
                .find(|x| x.name == rejected[i].site)
                .expect("a searched site");
            if let Alone::Passes(choice, cost) = s.alone(site, &site.options, &accepted.0)? {
                if cost < accepted.1 {
                    accepted.0.insert(site.name.clone(), choice);
                    accepted.1 = cost;
                    taken.push(i);
                }
            }
        }
        for i in taken.into_iter().rev() {
            rejected.remove(i);
        }
    }
    // Each tuned loop, bisected again below its count on the rest.
    for site in sites.iter().filter(|x| x.is_loop) {
        let Some(&current) = accepted.0.get(&site.name) else {
            continue;
        };
        let fewer = &site.options[..site.options.iter().position(|&o| o == current).unwrap_or(0)];
        if let Alone::Passes(choice, cost) = s.alone(site, fewer, &accepted.0)? {
            if cost < accepted.1 {
                accepted.0.insert(site.name.clone(), choice);
                accepted.1 = cost;
            }
        }
    }
    Ok(Found {
        best: accepted.0,
        cost: accepted.1,
        rejected,
        judged: s.judged,
    })
}

/// Every configuration of `sites`; the cheapest passing one (the untuned
/// one, at `base_cost`, when none saves).
pub fn exhaustive(
    sites: &[Site],
    base_cost: f64,
    judge: &mut impl FnMut(&Config) -> anyhow::Result<Judged>,
) -> anyhow::Result<Found> {
    let mut best = (Config::new(), base_cost);
    let mut judged = 0;
    // An odometer over each site's index: 0 untuned, i the option i - 1.
    let mut at = vec![0usize; sites.len()];
    loop {
        let c: Config = sites
            .iter()
            .zip(&at)
            .filter(|(_, &i)| i > 0)
            .map(|(s, &i)| (s.name.clone(), s.options[i - 1]))
            .collect();
        if !c.is_empty() {
            judged += 1;
            let j = judge(&c)?;
            if j.passes && j.cost < best.1 {
                best = (c, j.cost);
            }
        }
        let Some(k) = (0..sites.len()).find(|&k| at[k] < sites[k].options.len()) else {
            break;
        };
        at[k] += 1;
        at[..k].iter_mut().for_each(|i| *i = 0);
    }
    Ok(Found {
        best: best.0,
        cost: best.1,
        rejected: Vec::new(),
        judged,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(name: &str) -> Site {
        Site {
            name: name.into(),
            options: vec![Choice::Newton1],
            is_loop: false,
        }
    }

    /// A made-up scene: each tuned operation site saves its amount, a loop
    /// saves 64 - steps, and the constraint fails on `bad`, on `a` and `b`
    /// together, and on fewer than 40 steps.
    fn judge_of<'a>(
        saving: &'a [(&'a str, f64)],
    ) -> impl FnMut(&Config) -> anyhow::Result<Judged> + 'a {
        move |c: &Config| {
            let mut cost = 1000.0;
            for (site, choice) in c {
                cost -= match choice {
                    Choice::Steps(n) => f64::from(64 - n),
                    _ => saving.iter().find(|s| s.0 == site).unwrap().1,
                };
            }
            let steps_ok = c
                .values()
                .all(|ch| !matches!(ch, Choice::Steps(n) if *n < 40));
            let conflict = c.contains_key("a") && c.contains_key("b");
            let passes = !c.contains_key("bad") && !conflict && steps_ok;
            Ok(Judged { passes, cost })
        }
    }

    fn sites() -> Vec<Site> {
        let mut s = vec![op("a"), op("b"), op("c"), op("bad"), op("dear")];
        s.push(Site {
            name: "march".into(),
            options: (1..64).map(Choice::Steps).collect(),
            is_loop: true,
        });
        s
    }

    const SAVINGS: [(&str, f64); 5] = [
        ("a", 30.0),
        ("b", 20.0),
        ("c", 5.0),
        ("bad", 50.0),
        ("dear", -3.0),
    ];

    #[test]
    fn delta_debugging_finds_the_optimum_and_says_why_each_site_is_left_out() {
        let found = delta_debug(&sites(), 1000.0, false, &mut judge_of(&SAVINGS)).unwrap();
        let names: Vec<&str> = found.best.keys().map(String::as_str).collect();
        assert_eq!(names, ["a", "c", "march"]);
        assert_eq!(found.best["march"], Choice::Steps(40));
        assert_eq!(found.cost, 1000.0 - 30.0 - 5.0 - 24.0);
        let why = |site: &str| &found.rejected.iter().find(|r| r.site == site).unwrap().why;
        assert!(matches!(why("bad"), Rejection::Fails { config } if config.len() == 1));
        assert!(matches!(why("dear"), Rejection::NoSaving { cost, .. } if *cost == 1003.0));
        // `b` passes alone and fails on the accepted `a`.
        assert!(matches!(why("b"), Rejection::Fails { config } if config.contains_key("a")));
        assert_eq!(found.rejected.len(), 3);

        let all = exhaustive(&sites(), 1000.0, &mut judge_of(&SAVINGS)).unwrap();
        assert_eq!((all.best, all.cost), (found.best, found.cost));
        assert_eq!(all.judged, 2 * 2 * 2 * 2 * 2 * 64 - 1);
        assert!(found.judged < all.judged / 10, "{}", found.judged);
    }

    /// A site that fails alone and passes on another (`late` needs `a`) is
    /// found only when the failed sites are tried again, at one more
    /// configuration each.
    #[test]
    fn a_site_that_fails_alone_is_tried_again_on_the_accepted_set_under_a_budget() {
        let savings = [("a", 30.0), ("late", 10.0), ("bad", 50.0)];
        let sites = vec![op("a"), op("late"), op("bad")];
        let mut judge = |c: &Config| -> anyhow::Result<Judged> {
            let cost = 1000.0
                - c.keys()
                    .map(|k| savings.iter().find(|s| s.0 == k).unwrap().1)
                    .sum::<f64>();
            let passes = !c.contains_key("bad") && (!c.contains_key("late") || c.contains_key("a"));
            Ok(Judged { passes, cost })
        };
        let strict = delta_debug(&sites, 1000.0, false, &mut judge).unwrap();
        assert_eq!(strict.best.keys().collect::<Vec<_>>(), ["a"]);
        let retried = delta_debug(&sites, 1000.0, true, &mut judge).unwrap();
        assert_eq!(retried.best.keys().collect::<Vec<_>>(), ["a", "late"]);
        assert_eq!(retried.cost, 960.0);
        assert_eq!(
            retried.judged,
            strict.judged + 2,
            "`late` and `bad` once more"
        );
        let left: Vec<&str> = retried.rejected.iter().map(|r| r.site.as_str()).collect();
        assert_eq!(left, ["bad"]);
    }
}
