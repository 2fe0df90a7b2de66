//! VM text to commands: the syntax of spec §2.1 and the per-command checks of
//! §2.2 that need no knowledge of the rest of the program (offset ranges,
//! segment limits). Never panics; every error names its line.

use crate::error::LoadError;

/// A memory segment of `push`/`pop`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Segment {
    Argument,
    Local,
    Static,
    Constant,
    This,
    That,
    Pointer,
    Temp,
}

/// An arithmetic or logical command (§2.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Arith {
    Add,
    Sub,
    Neg,
    Eq,
    Gt,
    Lt,
    And,
    Or,
    Not,
}

/// One parsed VM command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Command {
    Push(Segment, u16),
    Pop(Segment, u16),
    Arith(Arith),
    Label(String),
    Goto(String),
    IfGoto(String),
    Function(String, u16),
    Call(String, u16),
    Return,
}

/// A command with the 1-based line it came from.
#[derive(Clone, Debug)]
pub(crate) struct Line {
    pub line: usize,
    pub command: Command,
}

/// Parse one file's text. `file` is used only in error messages.
pub(crate) fn parse(file: &str, text: &str) -> Result<Vec<Line>, LoadError> {
    let stripped = strip_comments(text).map_err(|line| LoadError::Syntax {
        file: file.to_string(),
        line,
        message: "unterminated /* comment".to_string(),
    })?;
    let mut out = Vec::new();
    for (i, raw) in stripped.lines().enumerate() {
        let tokens: Vec<&str> = raw
            .split([' ', '\t', '\r'])
            .filter(|t| !t.is_empty())
            .collect();
        if tokens.is_empty() {
            continue;
        }
        let command = parse_tokens(&tokens).map_err(|message| LoadError::Syntax {
            file: file.to_string(),
            line: i + 1,
            message,
        })?;
        out.push(Line {
            line: i + 1,
            command,
        });
    }
    Ok(out)
}

/// Remove `//` and `/* */` comments, keeping newlines so line numbers stay
/// right. Err(line) for an unterminated block comment.
fn strip_comments(text: &str) -> Result<String, usize> {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut line = 1;
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        line += 1;
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                let start = line;
                chars.next();
                let mut prev = ' ';
                let mut closed = false;
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        line += 1;
                    }
                    if prev == '*' && c == '/' {
                        closed = true;
                        break;
                    }
                    prev = c;
                }
                if !closed {
                    return Err(start);
                }
                // A block comment separates tokens like a space.
                out.push(' ');
            }
            _ => {
                if c == '\n' {
                    line += 1;
                }
                out.push(c);
            }
        }
    }
    Ok(out)
}

fn parse_tokens(t: &[&str]) -> Result<Command, String> {
    let arity = |n: usize| {
        if t.len() == n + 1 {
            Ok(())
        } else {
            Err(format!(
                "'{}' takes {} operand{}, found {}: '{}'",
                t[0],
                n,
                if n == 1 { "" } else { "s" },
                t.len() - 1,
                t.join(" ")
            ))
        }
    };
    let cmd = match t[0] {
        "push" | "pop" => {
            arity(2)?;
            let seg = segment(t[1])?;
            let index = number(t[2], "offset")?;
            check_segment_index(seg, index)?;
            if t[0] == "push" {
                Command::Push(seg, index)
            } else {
                Command::Pop(seg, index)
            }
        }
        "label" | "goto" | "if-goto" => {
            arity(1)?;
            let name = name(t[1])?;
            match t[0] {
                "label" => Command::Label(name),
                "goto" => Command::Goto(name),
                _ => Command::IfGoto(name),
            }
        }
        "function" => {
            arity(2)?;
            Command::Function(name(t[1])?, number(t[2], "nVars")?)
        }
        "call" => {
            arity(2)?;
            Command::Call(name(t[1])?, number(t[2], "nArgs")?)
        }
        "return" => {
            arity(0)?;
            Command::Return
        }
        op => {
            let a = match op {
                "add" => Arith::Add,
                "sub" => Arith::Sub,
                "neg" => Arith::Neg,
                "eq" => Arith::Eq,
                "gt" => Arith::Gt,
                "lt" => Arith::Lt,
                "and" => Arith::And,
                "or" => Arith::Or,
                "not" => Arith::Not,
                _ => return Err(format!("unknown command '{op}'")),
            };
            arity(0)?;
            Command::Arith(a)
        }
    };
    Ok(cmd)
}

fn segment(s: &str) -> Result<Segment, String> {
    Ok(match s {
        "argument" => Segment::Argument,
        "local" => Segment::Local,
        "static" => Segment::Static,
        "constant" => Segment::Constant,
        "this" => Segment::This,
        "that" => Segment::That,
        "pointer" => Segment::Pointer,
        "temp" => Segment::Temp,
        _ => return Err(format!("unknown segment '{s}'")),
    })
}

/// A decimal number in 0..=32767; `-n` parses but is refused (§2.1, §2.2).
fn number(s: &str, what: &str) -> Result<u16, String> {
    let digits = s.strip_prefix('-').unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("expected a decimal {what}, found '{s}'"));
    }
    match s.parse::<i64>() {
        Ok(v) if (0..=32767).contains(&v) => Ok(v as u16),
        _ => {
            let label = if what == "offset" { "offset" } else { what };
            Err(format!(
                "Illegal {label} value {s} (must be between 0 and 32767)"
            ))
        }
    }
}

fn check_segment_index(seg: Segment, i: u16) -> Result<(), String> {
    let limit = match seg {
        Segment::Temp => 7,
        // A static index past the web IDE's 239 is refused for the web
        // profile only (`Program::check_profile`): the desktop runs it.
        Segment::Pointer => 1,
        _ => return Ok(()),
    };
    if i > limit {
        let name = match seg {
            Segment::Temp => "temp",
            _ => "pointer",
        };
        return Err(format!(
            "Illegal {name} index {i} (must be between 0 and {limit})"
        ));
    }
    Ok(())
}

/// A name `[letter _ . $][letter digit _ . $]*` (§2.1).
fn name(s: &str) -> Result<String, String> {
    let ok_first = |c: char| c.is_ascii_alphabetic() || matches!(c, '_' | '.' | '$');
    let mut chars = s.chars();
    let valid =
        chars.next().is_some_and(ok_first) && chars.all(|c| ok_first(c) || c.is_ascii_digit());
    if valid {
        Ok(s.to_string())
    } else {
        Err(format!("illegal name '{s}'"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(text: &str) -> Result<Command, LoadError> {
        parse("T.vm", text).map(|v| v.into_iter().next().unwrap().command)
    }

    #[test]
    fn comments_crlf_and_blank_lines() {
        let lines = parse(
            "T.vm",
            "// hi\r\n\r\npush constant 7 // c\r\n/* a\nb */ add\npop temp 0",
        )
        .unwrap();
        let got: Vec<(usize, Command)> = lines.into_iter().map(|l| (l.line, l.command)).collect();
        assert_eq!(
            got,
            vec![
                (3, Command::Push(Segment::Constant, 7)),
                (5, Command::Arith(Arith::Add)),
                (6, Command::Pop(Segment::Temp, 0)),
            ]
        );
    }

    #[test]
    fn rejects_bad_syntax_with_line() {
        for bad in [
            "Push constant 1",
            "push constant",
            "push constant 1 2",
            "push nowhere 1",
            "push constant x",
            "label 1abc",
            "label a:b",
            "function f",
            "return 1",
            "add 1",
            "frobnicate",
            "push constant 32768",
            "push constant -1",
            "push temp 8",
            "push pointer 2",
            "call f 99999999999999999999999",
            "/* never closed",
        ] {
            let err = parse("T.vm", &format!("\n{bad}")).unwrap_err();
            let msg = err.to_string();
            assert!(msg.contains("T.vm"), "{bad}: {msg}");
        }
        let msg = one("push constant 32768").unwrap_err().to_string();
        assert!(
            msg.contains("Illegal offset value 32768 (must be between 0 and 32767)"),
            "{msg}"
        );
    }

    #[test]
    fn accepts_names_and_limits() {
        assert_eq!(
            one("label $a.b_c9").unwrap(),
            Command::Label("$a.b_c9".into())
        );
        assert_eq!(
            one("push constant 32767").unwrap(),
            Command::Push(Segment::Constant, 32767)
        );
        assert_eq!(
            one("pop static 239").unwrap(),
            Command::Pop(Segment::Static, 239)
        );
        assert_eq!(
            one("pop static 240").unwrap(),
            Command::Pop(Segment::Static, 240)
        );
        assert_eq!(one("if-goto\tL").unwrap(), Command::IfGoto("L".into()));
    }
}
