//! Tokens of Jack (spec §4.1). Identifiers include the keywords, which are not
//! reserved; the parser gives them meaning by position. Each token records
//! whether whitespace or a comment came before it, because the grammar makes
//! spacing significant in places (`a [i]` and `return(x)` are errors).

use crate::error::Pos;

/// What a token is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Tok {
    /// A letter followed by letters, digits and `_` (keywords included).
    Ident(String),
    /// Decimal digits, as written.
    Int(String),
    /// A string literal's contents (no escapes).
    Str(String),
    /// One of `{}()[].,;+-*/&|<>=~`.
    Sym(char),
    /// Text that is no token; the sentence says why. Lexing stops here.
    Bad(String),
    /// End of input.
    Eof,
}

/// A token with its position.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Token {
    /// The token.
    pub tok: Tok,
    /// Where it starts.
    pub pos: Pos,
    /// Whether whitespace or a comment separates it from the token before.
    pub spaced: bool,
}

const SYMBOLS: &str = "{}()[].,;+-*/&|<>=~";

/// Splits a source into tokens. The last token is `Eof`, or `Bad` at the
/// first place where no token can start.
pub fn tokenize(src: &str) -> Vec<Token> {
    let mut lx = Lexer {
        chars: src.chars().collect(),
        i: 0,
        line: 1,
        col: 1,
    };
    let mut out = Vec::new();
    loop {
        let spaced = match lx.skip_trivia() {
            Ok(spaced) => spaced,
            Err((pos, msg)) => {
                out.push(Token {
                    tok: Tok::Bad(msg),
                    pos,
                    spaced: true,
                });
                return out;
            }
        };
        let pos = lx.pos();
        let tok = lx.token();
        let done = matches!(tok, Tok::Eof | Tok::Bad(_));
        out.push(Token { tok, pos, spaced });
        if done {
            return out;
        }
    }
}

struct Lexer {
    chars: Vec<char>,
    i: usize,
    line: u32,
    col: u32,
}

/// Whitespace as the official grammar defines it: any code up to ' '.
fn is_space(c: char) -> bool {
    c <= ' '
}

fn is_ident_start(c: char) -> bool {
    c.is_alphabetic()
}

fn is_ident_char(c: char) -> bool {
    c.is_alphabetic() || c.is_ascii_digit() || c == '_'
}

impl Lexer {
    fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            col: self.col,
        }
    }

    fn peek(&self, k: usize) -> Option<char> {
        self.chars.get(self.i + k).copied()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek(0)?;
        self.i += 1;
        if c == '\n' {
            self.line = self.line.saturating_add(1);
            self.col = 1;
        } else {
            self.col = self.col.saturating_add(1);
        }
        Some(c)
    }

    /// Skips whitespace and comments; tells whether there were any.
    fn skip_trivia(&mut self) -> Result<bool, (Pos, String)> {
        let start = self.i;
        loop {
            match (self.peek(0), self.peek(1)) {
                (Some(c), _) if is_space(c) => {
                    self.bump();
                }
                (Some('/'), Some('/')) => {
                    while let Some(c) = self.peek(0) {
                        if c == '\n' {
                            break;
                        }
                        self.bump();
                    }
                }
                (Some('/'), Some('*')) => {
                    let pos = self.pos();
                    self.bump();
                    self.bump();
                    loop {
                        match (self.peek(0), self.peek(1)) {
                            (Some('*'), Some('/')) => {
                                self.bump();
                                self.bump();
                                break;
                            }
                            (Some(_), _) => {
                                self.bump();
                            }
                            (None, _) => {
                                return Err((pos, "Unterminated comment".to_string()));
                            }
                        }
                    }
                }
                _ => return Ok(self.i > start),
            }
        }
    }

    fn token(&mut self) -> Tok {
        let Some(c) = self.peek(0) else {
            return Tok::Eof;
        };
        if is_ident_start(c) {
            let mut s = String::new();
            while let Some(c) = self.peek(0).filter(|&c| is_ident_char(c)) {
                s.push(c);
                self.bump();
            }
            Tok::Ident(s)
        } else if c.is_ascii_digit() {
            let mut s = String::new();
            while let Some(c) = self.peek(0).filter(char::is_ascii_digit) {
                s.push(c);
                self.bump();
            }
            Tok::Int(s)
        } else if c == '"' {
            self.bump();
            let mut s = String::new();
            loop {
                match (self.peek(0), self.peek(1)) {
                    (Some('"'), _) => {
                        self.bump();
                        return Tok::Str(s);
                    }
                    (Some('\n'), _) | (Some('\r'), Some('\n')) | (None, _) => {
                        return Tok::Bad("Unterminated string literal".to_string());
                    }
                    (Some(c), _) => {
                        s.push(c);
                        self.bump();
                    }
                }
            }
        } else if SYMBOLS.contains(c) {
            self.bump();
            Tok::Sym(c)
        } else if c == '_' {
            Tok::Bad("An identifier cannot start with '_'".to_string())
        } else {
            Tok::Bad(format!("Unexpected character '{}'", c.escape_default()))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(src: &str) -> Vec<(Tok, bool)> {
        tokenize(src)
            .into_iter()
            .map(|t| (t.tok, t.spaced))
            .collect()
    }

    #[test]
    fn spacing_and_comments_are_recorded() {
        assert_eq!(
            toks("a[i] b /*c*/ [ x//y\n"),
            vec![
                (Tok::Ident("a".into()), false),
                (Tok::Sym('['), false),
                (Tok::Ident("i".into()), false),
                (Tok::Sym(']'), false),
                (Tok::Ident("b".into()), true),
                (Tok::Sym('['), true),
                (Tok::Ident("x".into()), true),
                (Tok::Eof, true),
            ]
        );
    }

    #[test]
    fn positions_count_lines_and_characters() {
        let t = tokenize("x\n  é2 \"ab\"");
        let pos: Vec<(u32, u32)> = t.iter().map(|t| (t.pos.line, t.pos.col)).collect();
        assert_eq!(pos, vec![(1, 1), (2, 3), (2, 6), (2, 10)]);
        assert_eq!(t[1].tok, Tok::Ident("é2".into()));
    }

    #[test]
    fn bad_input_stops_with_a_sentence() {
        let last = |s: &str| tokenize(s).pop().unwrap().tok;
        assert_eq!(
            last("x _y"),
            Tok::Bad("An identifier cannot start with '_'".into())
        );
        assert_eq!(
            last("\"ab\ncd\""),
            Tok::Bad("Unterminated string literal".into())
        );
        assert_eq!(last("/* open"), Tok::Bad("Unterminated comment".into()));
        assert_eq!(last("a # b"), Tok::Bad("Unexpected character '#'".into()));
    }

    #[test]
    fn integers_stop_at_letters() {
        assert_eq!(
            toks("12ab"),
            vec![
                (Tok::Int("12".into()), false),
                (Tok::Ident("ab".into()), false),
                (Tok::Eof, false)
            ]
        );
    }
}
