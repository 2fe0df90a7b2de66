//! The official Hack font (hack-font.json, from the web IDE): 95 glyphs for
//! codes 32..=126, 11 rows of 8 columns.

use serde::Deserialize;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// Glyph rows, top to bottom; bit j of a row is column j (0 = leftmost).
pub(crate) type Glyph = [u8; GLYPH_ROWS];

pub(crate) const GLYPH_ROWS: usize = 11;
pub(crate) const GLYPH_COLS: usize = 8;
const FIRST: i32 = 32;
const LAST: i32 = 126;

#[derive(Deserialize)]
struct FontFile {
    width: usize,
    height: usize,
    glyphs: BTreeMap<String, Vec<String>>,
}

/// Why the committed font file is unusable (only a corrupted checkout).
#[derive(Debug, thiserror::Error)]
pub(crate) enum FontError {
    #[error("hack-font.json is not valid JSON: {0}")]
    Json(#[from] serde_json::Error),
    #[error("hack-font.json: {0}")]
    Shape(String),
}

fn parse(text: &str) -> Result<Vec<Glyph>, FontError> {
    let file: FontFile = serde_json::from_str(text)?;
    if (file.width, file.height) != (GLYPH_COLS, GLYPH_ROWS) {
        return Err(FontError::Shape(format!(
            "glyphs are {}x{}",
            file.width, file.height
        )));
    }
    (FIRST..=LAST)
        .map(|code| {
            let rows = file
                .glyphs
                .get(&code.to_string())
                .ok_or_else(|| FontError::Shape(format!("no glyph for code {code}")))?;
            let mut glyph = [0u8; GLYPH_ROWS];
            if rows.len() != GLYPH_ROWS {
                return Err(FontError::Shape(format!(
                    "glyph {code} has {} rows",
                    rows.len()
                )));
            }
            for (bits, row) in glyph.iter_mut().zip(rows) {
                if row.len() != GLYPH_COLS || !row.bytes().all(|b| b == b'#' || b == b'.') {
                    return Err(FontError::Shape(format!(
                        "glyph {code} has a bad row {row:?}"
                    )));
                }
                *bits = row
                    .bytes()
                    .enumerate()
                    .fold(0, |acc, (j, b)| acc | (u8::from(b == b'#') << j));
            }
            Ok(glyph)
        })
        .collect()
}

fn font() -> &'static [Glyph] {
    static FONT: OnceLock<Vec<Glyph>> = OnceLock::new();
    FONT.get_or_init(|| {
        // The file is part of the crate; `tests::the_committed_font_parses` guards it.
        parse(include_str!("../hack-font.json")).unwrap_or_else(|e| panic!("{e}"))
    })
}

/// The glyph of character `code`, if the font has one (32..=126).
pub(crate) fn glyph(code: i32) -> Option<&'static Glyph> {
    if (FIRST..=LAST).contains(&code) {
        font().get((code - FIRST) as usize)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_font_parses() {
        let glyphs = parse(include_str!("../hack-font.json")).unwrap();
        assert_eq!(glyphs.len(), 95);
        // Column 7 and row 10 are blank everywhere; 62 glyphs use row 0.
        assert!(glyphs
            .iter()
            .all(|g| g[10] == 0 && g.iter().all(|r| r & 0x80 == 0)));
        assert_eq!(glyphs.iter().filter(|g| g[0] != 0).count(), 62);
        assert!(glyphs[0].iter().all(|r| *r == 0), "space is blank");
        assert!(glyph(31).is_none() && glyph(127).is_none() && glyph(128).is_none());
    }

    #[test]
    fn malformed_fonts_are_errors() {
        assert!(matches!(parse("{"), Err(FontError::Json(_))));
        assert!(matches!(
            parse(r#"{"width":8,"height":11,"glyphs":{}}"#),
            Err(FontError::Shape(_))
        ));
    }
}
