//! The search space: each call site of a scene's Float316 program with the
//! variants the search tries there, and a configuration (a variant for some
//! of the sites).

use scene::sites::{self, Choice, Kind};
use std::collections::BTreeMap;

/// A variant for each tuned site, by site name; a site not named computes
/// as the description says.
pub type Config = BTreeMap<String, Choice>;

/// A site and the variants tried there, the most aggressive first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Site {
    pub name: String,
    pub options: Vec<Choice>,
    /// A march loop: its options are every step count below its own, and
    /// fewer steps are assumed to change at least the pixels that more
    /// steps change.
    pub is_loop: bool,
}

/// The sites of `program` (a Float316 program) with their options: those
/// of every pixel and those of the set-up (the camera, once per image,
/// whose operations change every pixel's ray).
pub fn searched(program: &scene::Program) -> Vec<Site> {
    sites::sites(program)
        .into_iter()
        .filter_map(|(name, kind)| {
            let (options, is_loop) = match kind {
                Kind::Op(variant) => (vec![Choice::from(variant)], false),
                Kind::Loop(count) => ((1..count).map(Choice::Steps).collect(), true),
            };
            (!options.is_empty()).then_some(Site {
                name,
                options,
                is_loop,
            })
        })
        .collect()
}

/// How many configurations `sites` make (each site untuned or one of its
/// options), saturating.
pub fn size(sites: &[Site]) -> u64 {
    sites
        .iter()
        .fold(1u64, |n, s| n.saturating_mul(s.options.len() as u64 + 1))
}

/// A configuration in one line: `site: variant` joined by `, `, or
/// `untuned`; the key of the state file too.
pub fn key(c: &Config) -> String {
    if c.is_empty() {
        return "untuned".into();
    }
    c.iter()
        .map(|(site, choice)| format!("{site}: {choice}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The description's `variants` field for `c`.
pub fn variants_field(c: &Config) -> serde_json::Value {
    c.iter()
        .map(|(site, choice)| serde_json::json!({"site": site, "variant": choice}))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_seeds_sites_take_in_the_set_up_and_count_the_space() {
        let seed = scene::parse(scene::SEED).unwrap();
        let p = scene::lower(&seed, scene::Formulation::Float316);
        let s = searched(&p);
        assert!(s
            .iter()
            .any(|s| s.name == "setup/camera/normalize" && s.options == [Choice::Newton1]));
        assert!(s
            .iter()
            .any(|s| s.name == "sdf/scene/floor/floor" && s.options == [Choice::FloorDirect]));
        assert!(s
            .iter()
            .any(|s| s.name == "pixel/light/mul" && s.options == [Choice::TruncatedProduct]));
        let march = s.iter().find(|s| s.name == "pixel/march step").unwrap();
        assert!(march.is_loop);
        assert_eq!(march.options.len(), 63);
        assert_eq!(march.options[0], Choice::Steps(1));
        assert!(s
            .iter()
            .any(|s| s.name == "pixel/shadow/normalize" && s.options == [Choice::Newton1]));
        assert!(size(&s) > 1000);
    }

    #[test]
    fn a_configuration_is_written_as_a_description_reads_it() {
        let mut c = Config::new();
        assert_eq!(key(&c), "untuned");
        c.insert("pixel/normalize".into(), Choice::Newton1);
        c.insert("pixel/march step".into(), Choice::Steps(16));
        assert_eq!(
            key(&c),
            "pixel/march step: 16 steps, pixel/normalize: newton-1"
        );
        let mut v: serde_json::Value = serde_json::from_str(scene::SEED).unwrap();
        v["variants"] = variants_field(&c);
        let checked = scene::parse(&v.to_string()).unwrap();
        assert_eq!(checked.description.variants.len(), 2);
    }
}
