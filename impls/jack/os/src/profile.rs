//! Which official tool the OS imitates.

use std::fmt;
use std::str::FromStr;

/// The official tool whose OS behaviour is reproduced (spec section 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Profile {
    /// The desktop VM emulator: `Math.divide` truncates toward zero and the
    /// web IDE's defects listed in section 0 are not copied.
    #[default]
    Desktop,
    /// The web IDE exactly, defects included.
    Web,
}

impl Profile {
    /// Both profiles, default first.
    pub const ALL: [Profile; 2] = [Profile::Desktop, Profile::Web];

    /// The command-line name (`desktop`, `web`).
    pub fn name(self) -> &'static str {
        match self {
            Profile::Desktop => "desktop",
            Profile::Web => "web",
        }
    }
}

impl fmt::Display for Profile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A profile name that is neither `desktop` nor `web`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown OS profile {0:?} (expected \"desktop\" or \"web\")")]
pub struct ProfileParseError(pub String);

impl FromStr for Profile {
    type Err = ProfileParseError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Profile::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| ProfileParseError(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_prints_both_names() {
        for p in Profile::ALL {
            assert_eq!(p.to_string().parse::<Profile>(), Ok(p));
        }
        assert_eq!("WEB".parse::<Profile>(), Ok(Profile::Web));
        assert_eq!(Profile::default(), Profile::Desktop);
        assert!("java".parse::<Profile>().is_err());
    }
}
