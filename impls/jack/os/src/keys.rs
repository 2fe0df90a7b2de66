//! Scripted keyboard input: a list of keys, each held for `hold` VM
//! instructions and then released for `hold`, so programs that wait for a
//! press and a release run unattended and deterministically.

use std::sync::Arc;

/// A key list that cannot be parsed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum KeyScriptError {
    /// An entry is neither a key name nor a single printable character.
    #[error("unknown key {0:?} (use a single printable character or a name such as SPACE, ENTER, BACKSPACE, LEFT, F1, COMMA)")]
    UnknownKey(String),
    /// Two commas in a row, or a leading/trailing comma.
    #[error("empty key name at position {0} of the key list")]
    EmptyEntry(usize),
    /// A hold time of zero instructions.
    #[error("the key hold time must be at least one instruction")]
    ZeroHold,
}

/// Named keys and their Hack codes (spec section 1).
const NAMED_KEYS: &[(&str, i16)] = &[
    ("SPACE", 32),
    ("COMMA", 44),
    ("ENTER", 128),
    ("NEWLINE", 128),
    ("BACKSPACE", 129),
    ("LEFT", 130),
    ("UP", 131),
    ("RIGHT", 132),
    ("DOWN", 133),
    ("HOME", 134),
    ("END", 135),
    ("PGUP", 136),
    ("PAGEUP", 136),
    ("PGDN", 137),
    ("PAGEDOWN", 137),
    ("INSERT", 138),
    ("DELETE", 139),
    ("ESC", 140),
    ("ESCAPE", 140),
];

/// Hack code of the function key `F1`..`F12`.
fn function_key(name: &str) -> Option<i16> {
    let n: i16 = name.strip_prefix(['F', 'f'])?.parse().ok()?;
    (1..=12).contains(&n).then_some(140 + n)
}

fn key_code(entry: &str) -> Option<i16> {
    let mut chars = entry.chars();
    if let (Some(c), None) = (chars.next(), chars.next()) {
        return (c.is_ascii_graphic()).then_some(c as i16);
    }
    NAMED_KEYS
        .iter()
        .find(|(name, _)| name.eq_ignore_ascii_case(entry))
        .map(|&(_, code)| code)
        .or_else(|| function_key(entry))
}

/// A deterministic keyboard: key `i` of the list is down during clock
/// `[2i*hold, (2i+1)*hold)` and released during `[(2i+1)*hold, (2i+2)*hold)`;
/// after the list, no key is ever pressed. Cheap to clone.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyScript {
    keys: Arc<[i16]>,
    hold: u64,
}

impl Default for KeyScript {
    fn default() -> Self {
        KeyScript::none()
    }
}

impl KeyScript {
    /// Default hold time, in VM instructions.
    pub const DEFAULT_HOLD: u64 = 1_000_000;

    /// Parse a comma-separated list such as `"SPACE,A,ENTER"`: single
    /// printable characters (case-sensitive) or key names (case-insensitive).
    /// An empty or blank list means no keys.
    pub fn parse(list: &str, hold: u64) -> Result<KeyScript, KeyScriptError> {
        if hold == 0 {
            return Err(KeyScriptError::ZeroHold);
        }
        if list.trim().is_empty() {
            return Ok(KeyScript {
                keys: Arc::from([]),
                hold,
            });
        }
        let keys = list
            .split(',')
            .enumerate()
            .map(|(i, entry)| match entry.trim() {
                "" => Err(KeyScriptError::EmptyEntry(i)),
                e => key_code(e).ok_or_else(|| KeyScriptError::UnknownKey(e.to_string())),
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(KeyScript {
            keys: keys.into(),
            hold,
        })
    }

    /// No key is ever pressed.
    pub fn none() -> KeyScript {
        KeyScript {
            keys: Arc::from([]),
            hold: KeyScript::DEFAULT_HOLD,
        }
    }

    /// The Hack key codes, in order.
    pub fn keys(&self) -> &[i16] {
        &self.keys
    }

    /// The code of the key held at instruction `clock` (0 if none).
    pub fn key_at(&self, clock: u64) -> i16 {
        let slot = clock / self.hold;
        if slot % 2 == 1 {
            return 0;
        }
        usize::try_from(slot / 2)
            .ok()
            .and_then(|i| self.keys.get(i).copied())
            .unwrap_or(0)
    }

    /// The first clock after `clock` at which [`KeyScript::key_at`] changes,
    /// or `None` if it never changes again.
    pub fn next_change(&self, clock: u64) -> Option<u64> {
        let next_slot = clock / self.hold + 1;
        let slots = 2 * self.keys.len() as u64;
        if next_slot >= slots {
            return None;
        }
        next_slot.checked_mul(self.hold)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_names_and_characters() {
        let s = KeyScript::parse("SPACE, A,a,enter,BackSpace,F12,COMMA,LEFT,9,esc", 10).unwrap();
        assert_eq!(s.keys(), &[32, 65, 97, 128, 129, 152, 44, 130, 57, 140]);
        assert_eq!(KeyScript::parse("", 5).unwrap().keys(), &[] as &[i16]);
    }

    #[test]
    fn rejects_bad_lists() {
        assert_eq!(
            KeyScript::parse("A,,B", 5),
            Err(KeyScriptError::EmptyEntry(1))
        );
        assert_eq!(
            KeyScript::parse("SHIFT", 5),
            Err(KeyScriptError::UnknownKey("SHIFT".into()))
        );
        assert_eq!(
            KeyScript::parse("F13", 5),
            Err(KeyScriptError::UnknownKey("F13".into()))
        );
        assert_eq!(
            KeyScript::parse("é", 5),
            Err(KeyScriptError::UnknownKey("é".into()))
        );
        assert_eq!(KeyScript::parse("A", 0), Err(KeyScriptError::ZeroHold));
    }

    #[test]
    fn keys_are_held_then_released() {
        let s = KeyScript::parse("A,B", 3).unwrap();
        let timeline: Vec<i16> = (0..14).map(|c| s.key_at(c)).collect();
        assert_eq!(timeline, [65, 65, 65, 0, 0, 0, 66, 66, 66, 0, 0, 0, 0, 0]);
        assert_eq!(s.next_change(0), Some(3));
        assert_eq!(s.next_change(3), Some(6));
        assert_eq!(s.next_change(8), Some(9));
        assert_eq!(s.next_change(9), None);
        assert_eq!(s.next_change(u64::MAX), None);
        assert_eq!(KeyScript::none().next_change(0), None);
        assert_eq!(KeyScript::none().key_at(0), 0);
    }
}
