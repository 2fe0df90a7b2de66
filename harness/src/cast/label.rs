//! `NAME+VARIANT+...` labels: the one place where an implementation label
//! is split into its cast name and the variants or faults applied to it.
//! Whether the variants apply is the cast's business
//! ([`super::Cast::resolve`]); this is only the syntax.

use std::fmt;
use std::str::FromStr;

/// An implementation label: a cast name and the variants or faults applied
/// to it, in order (`ref-f316+newton-3+dither-threshold`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Label {
    /// The cast name (`ref-f316`).
    pub name: String,
    /// The variants and faults, in the order given.
    pub variants: Vec<String>,
}

impl Label {
    /// The label of `name` with no variant.
    pub fn plain(name: &str) -> Label {
        Label {
            name: name.to_string(),
            variants: Vec::new(),
        }
    }
}

/// A label that is not `NAME[+VARIANT...]`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{label}` is not an implementation label NAME[+VARIANT...]: {why}")]
pub struct BadLabel {
    pub label: String,
    pub why: &'static str,
}

impl FromStr for Label {
    type Err = BadLabel;
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let bad = |why| BadLabel {
            label: text.to_string(),
            why,
        };
        let mut parts = text.split('+');
        let name = parts.next().unwrap_or_default();
        if name.is_empty() {
            return Err(bad("the name is empty"));
        }
        if name.chars().any(char::is_whitespace) {
            return Err(bad("the name contains white space"));
        }
        let variants: Vec<String> = parts.map(str::to_string).collect();
        if variants.iter().any(String::is_empty) {
            return Err(bad("a variant after `+` is empty"));
        }
        Ok(Label {
            name: name.to_string(),
            variants,
        })
    }
}

impl fmt::Display for Label {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)?;
        for v in &self.variants {
            write!(f, "+{v}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_split_at_plus_and_print_back() {
        let l: Label = "ref-f316+newton-3+dither-threshold".parse().unwrap();
        assert_eq!(l.name, "ref-f316");
        assert_eq!(l.variants, ["newton-3", "dither-threshold"]);
        assert_eq!(l.to_string(), "ref-f316+newton-3+dither-threshold");
        assert_eq!("jack".parse::<Label>().unwrap(), Label::plain("jack"));
    }

    #[test]
    fn empty_parts_are_refused() {
        for bad in ["", "+newton-3", "ref-f316+", "ref-f316++newton-3", "a b"] {
            assert!(bad.parse::<Label>().is_err(), "{bad:?}");
        }
    }
}
