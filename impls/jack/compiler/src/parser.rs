//! Recursive-descent parser reproducing the official grammar (spec §4.1),
//! quirks included: keywords are not reserved, `return(x)`, `a [i]`,
//! `Output . f()` and type names like `intList` are errors, and in an
//! expression a name that starts with true/false/null/this is an error.
//! Nesting is bounded so that no input can overflow the stack.

use crate::ast::*;
use crate::error::{ErrorKind, Pos};
use crate::lexer::{tokenize, Tok, Token};

/// Deepest nesting of statements and terms accepted.
pub const MAX_DEPTH: usize = 200;

/// A syntax error: where and what.
pub type SyntaxError = (Pos, ErrorKind);

/// Parses one class, stopping at the first syntax error.
pub fn parse_class(src: &str) -> Result<Class, SyntaxError> {
    let mut p = Parser {
        toks: tokenize(src),
        i: 0,
        depth: 0,
    };
    let class = p.class()?;
    match &p.peek().tok {
        Tok::Eof => Ok(class),
        _ => Err(p.unexpected("end of file after the class")),
    }
}

struct Parser {
    toks: Vec<Token>,
    i: usize,
    depth: usize,
}

const PRIMITIVE_TYPES: [&str; 3] = ["int", "char", "boolean"];

fn describe(tok: &Tok) -> String {
    match tok {
        Tok::Ident(s) | Tok::Int(s) => format!("'{s}'"),
        Tok::Str(_) => "a string literal".to_string(),
        Tok::Sym(c) => format!("'{c}'"),
        Tok::Bad(msg) => msg.clone(),
        Tok::Eof => "end of file".to_string(),
    }
}

impl Parser {
    fn peek(&self) -> &Token {
        self.peek_at(0)
    }

    fn peek_at(&self, k: usize) -> &Token {
        let last = self.toks.len() - 1;
        &self.toks[(self.i + k).min(last)]
    }

    fn next(&mut self) -> Token {
        let t = self.peek().clone();
        if self.i < self.toks.len() - 1 {
            self.i += 1;
        }
        t
    }

    fn unexpected(&self, expected: &str) -> SyntaxError {
        let t = self.peek();
        let msg = match &t.tok {
            Tok::Bad(msg) => msg.clone(),
            other => format!("Expected {expected}, found {}", describe(other)),
        };
        (t.pos, ErrorKind::Syntax(msg))
    }

    fn at_word(&self, word: &str) -> bool {
        matches!(&self.peek().tok, Tok::Ident(s) if s == word)
    }

    fn at_sym(&self, c: char) -> bool {
        self.peek().tok == Tok::Sym(c)
    }

    fn expect_word(&mut self, word: &str) -> Result<(), SyntaxError> {
        if self.at_word(word) {
            self.next();
            Ok(())
        } else {
            Err(self.unexpected(&format!("'{word}'")))
        }
    }

    fn expect_sym(&mut self, c: char) -> Result<(), SyntaxError> {
        if self.at_sym(c) {
            self.next();
            Ok(())
        } else {
            Err(self.unexpected(&format!("'{c}'")))
        }
    }

    fn ident(&mut self, what: &str) -> Result<Ident, SyntaxError> {
        match &self.peek().tok {
            Tok::Ident(s) => {
                let id = Ident {
                    text: s.clone(),
                    pos: self.peek().pos,
                };
                self.next();
                Ok(id)
            }
            _ => Err(self.unexpected(what)),
        }
    }

    /// Runs `f` one nesting level deeper, failing past [`MAX_DEPTH`].
    fn nested<T>(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<T, SyntaxError>,
    ) -> Result<T, SyntaxError> {
        if self.depth >= MAX_DEPTH {
            return Err((self.peek().pos, ErrorKind::TooDeep(MAX_DEPTH)));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn class(&mut self) -> Result<Class, SyntaxError> {
        self.expect_word("class")?;
        let name = self.ident("a class name")?;
        self.expect_sym('{')?;
        let mut vars = Vec::new();
        while self.at_word("static") || self.at_word("field") {
            let kind = if self.at_word("static") {
                ClassVarKind::Static
            } else {
                ClassVarKind::Field
            };
            self.next();
            let ty = self.ty()?;
            let names = self.names()?;
            vars.push(ClassVarDec { kind, ty, names });
        }
        let mut subroutines = Vec::new();
        loop {
            let kind = match &self.peek().tok {
                Tok::Ident(s) if s == "constructor" => SubroutineKind::Constructor,
                Tok::Ident(s) if s == "function" => SubroutineKind::Function,
                Tok::Ident(s) if s == "method" => SubroutineKind::Method,
                _ => break,
            };
            self.next();
            subroutines.push(self.subroutine(kind)?);
        }
        if !self.at_sym('}') {
            return Err(self.unexpected("a class variable, a subroutine or '}'"));
        }
        self.next();
        Ok(Class {
            name,
            vars,
            subroutines,
        })
    }

    /// A type: `int`, `char`, `boolean` or a class name. As in the official
    /// grammar, a name that starts with a primitive type (e.g. `intList`) is
    /// an error: the keyword matches and a space must follow it.
    fn ty(&mut self) -> Result<Ident, SyntaxError> {
        let id = self.ident("a type")?;
        for prim in PRIMITIVE_TYPES {
            if id.text.len() > prim.len() && id.text.starts_with(prim) {
                let pos = Pos {
                    line: id.pos.line,
                    col: id.pos.col.saturating_add(prim.len() as u32),
                };
                let msg = format!("Expected whitespace after the type '{prim}'");
                return Err((pos, ErrorKind::Syntax(msg)));
            }
        }
        Ok(id)
    }

    /// `name (, name)* ;`
    fn names(&mut self) -> Result<Vec<Ident>, SyntaxError> {
        let mut names = vec![self.ident("a variable name")?];
        while self.at_sym(',') {
            self.next();
            names.push(self.ident("a variable name")?);
        }
        self.expect_sym(';')?;
        Ok(names)
    }

    fn subroutine(&mut self, kind: SubroutineKind) -> Result<Subroutine, SyntaxError> {
        let ret = self.ty()?;
        let name = self.ident("a subroutine name")?;
        self.expect_sym('(')?;
        let mut params = Vec::new();
        if !self.at_sym(')') {
            loop {
                let ty = self.ty()?;
                let pname = self.ident("a parameter name")?;
                params.push((ty, pname));
                if !self.at_sym(',') {
                    break;
                }
                self.next();
            }
        }
        self.expect_sym(')')?;
        self.expect_sym('{')?;
        let mut locals = Vec::new();
        while self.at_word("var") {
            self.next();
            let ty = self.ty()?;
            let names = self.names()?;
            locals.push(VarDec { ty, names });
        }
        let body = self.statements()?;
        if !self.at_sym('}') {
            return Err(self.unexpected("a statement or '}'"));
        }
        self.next();
        Ok(Subroutine {
            kind,
            ret,
            name,
            params,
            locals,
            body,
        })
    }

    /// Statements up to (not including) the closing brace.
    fn statements(&mut self) -> Result<Vec<Statement>, SyntaxError> {
        let mut out = Vec::new();
        loop {
            let word = match &self.peek().tok {
                Tok::Ident(s) => s.clone(),
                _ => return Ok(out),
            };
            let stmt = match word.as_str() {
                "let" => self.let_statement()?,
                "if" => self.nested(Self::if_statement)?,
                "while" => self.nested(Self::while_statement)?,
                "do" => {
                    self.next();
                    let call = self.call()?;
                    self.expect_sym(';')?;
                    Statement::Do(call)
                }
                "return" => self.return_statement()?,
                _ => return Ok(out),
            };
            out.push(stmt);
        }
    }

    fn block(&mut self) -> Result<Vec<Statement>, SyntaxError> {
        self.expect_sym('{')?;
        let body = self.statements()?;
        if !self.at_sym('}') {
            return Err(self.unexpected("a statement or '}'"));
        }
        self.next();
        Ok(body)
    }

    fn condition(&mut self) -> Result<Expr, SyntaxError> {
        self.expect_sym('(')?;
        let cond = self.expr()?;
        self.expect_sym(')')?;
        Ok(cond)
    }

    fn let_statement(&mut self) -> Result<Statement, SyntaxError> {
        self.next();
        let target = self.ident("a variable name")?;
        let index = if self.at_sym('[') && !self.peek().spaced {
            self.next();
            let e = self.expr()?;
            self.expect_sym(']')?;
            Some(e)
        } else {
            None
        };
        self.expect_sym('=')?;
        let value = self.expr()?;
        self.expect_sym(';')?;
        Ok(Statement::Let {
            target,
            index,
            value,
        })
    }

    fn if_statement(&mut self) -> Result<Statement, SyntaxError> {
        self.next();
        let cond = self.condition()?;
        let then = self.block()?;
        let els = if self.at_word("else") {
            self.next();
            self.block()?
        } else {
            Vec::new()
        };
        Ok(Statement::If { cond, then, els })
    }

    fn while_statement(&mut self) -> Result<Statement, SyntaxError> {
        self.next();
        let cond = self.condition()?;
        let body = self.block()?;
        Ok(Statement::While { cond, body })
    }

    /// `return;` or `return e;`, where a space must separate `return` from
    /// the value (`return(x);` and `return-1;` are errors).
    fn return_statement(&mut self) -> Result<Statement, SyntaxError> {
        let pos = self.next().pos;
        if self.at_sym(';') {
            self.next();
            return Ok(Statement::Return { pos, value: None });
        }
        if !self.peek().spaced {
            return Err(self.unexpected("';' or whitespace after 'return'"));
        }
        let value = self.expr()?;
        self.expect_sym(';')?;
        Ok(Statement::Return {
            pos,
            value: Some(value),
        })
    }

    /// `name(args)` or `a.name(args)`, with no space around the dot.
    fn call(&mut self) -> Result<Call, SyntaxError> {
        let first = self.ident("a subroutine name")?;
        let (receiver, name) = if self.at_sym('.') && !self.peek().spaced {
            self.next();
            if self.peek().spaced {
                return Err(self.unexpected("a subroutine name right after '.'"));
            }
            (Some(first), self.ident("a subroutine name")?)
        } else {
            (None, first)
        };
        self.expect_sym('(')?;
        let mut args = Vec::new();
        if !self.at_sym(')') {
            loop {
                args.push(self.expr()?);
                if !self.at_sym(',') {
                    break;
                }
                self.next();
            }
        }
        self.expect_sym(')')?;
        Ok(Call {
            receiver,
            name,
            args,
        })
    }

    fn expr(&mut self) -> Result<Expr, SyntaxError> {
        self.nested(|p| {
            let first = p.term()?;
            let mut rest = Vec::new();
            while let Tok::Sym(c) = p.peek().tok {
                let Some(op) = BinOp::from_char(c) else { break };
                p.next();
                rest.push((op, p.term()?));
            }
            Ok(Expr { first, rest })
        })
    }

    fn term(&mut self) -> Result<Term, SyntaxError> {
        let t = self.peek().clone();
        match t.tok {
            Tok::Int(digits) => {
                self.next();
                let trimmed = digits.trim_start_matches('0');
                Ok(Term::Int(
                    if trimmed.is_empty() { "0" } else { trimmed }.to_string(),
                    t.pos,
                ))
            }
            Tok::Str(s) => {
                self.next();
                Ok(Term::Str(s))
            }
            Tok::Ident(name) => self.name_term(&name, t.pos),
            Tok::Sym('(') => {
                self.next();
                let e = self.expr()?;
                self.expect_sym(')')?;
                Ok(Term::Paren(Box::new(e)))
            }
            Tok::Sym(c @ ('-' | '~')) => {
                self.next();
                let op = if c == '-' { UnaryOp::Neg } else { UnaryOp::Not };
                let inner = self.nested(Self::term)?;
                Ok(Term::Unary(op, Box::new(inner)))
            }
            _ => Err(self.unexpected("an expression")),
        }
    }

    /// A term that starts with a name: keyword constant, call, array element
    /// or variable, tried in the official grammar's order.
    fn name_term(&mut self, name: &str, pos: Pos) -> Result<Term, SyntaxError> {
        for (word, k) in KeywordConst::ALL {
            if name == word {
                self.next();
                return Ok(Term::Keyword(k));
            }
            if name.starts_with(word) {
                let msg = format!(
                    "A name that starts with '{word}' cannot be used in an expression ({name})"
                );
                return Err((pos, ErrorKind::Syntax(msg)));
            }
        }
        let next = self.peek_at(1);
        let is_call = (next.tok == Tok::Sym('.') && !next.spaced) || next.tok == Tok::Sym('(');
        if is_call {
            return Ok(Term::Call(self.call()?));
        }
        let id = self.ident("a name")?;
        if self.at_sym('[') && !self.peek().spaced {
            self.next();
            let index = self.expr()?;
            self.expect_sym(']')?;
            return Ok(Term::Index(id, Box::new(index)));
        }
        Ok(Term::Var(id))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(src: &str) -> (u32, u32, String) {
        let (pos, kind) = parse_class(src).unwrap_err();
        (pos.line, pos.col, kind.to_string())
    }

    fn body(stmts: &str) -> String {
        format!("class Main {{ function void main() {{ var int a, x; {stmts} return; }} }}")
    }

    #[test]
    fn parses_a_class() {
        let c = parse_class(
            "class P { field int x, y; static P origin;
               constructor P new(int ax, int ay) { let x = ax; let y = ay; return this; }
               method int sum() { return x + y; } }",
        )
        .unwrap();
        assert_eq!(c.name.text, "P");
        assert_eq!(c.vars.len(), 2);
        assert_eq!(c.subroutines.len(), 2);
        assert_eq!(c.subroutines[0].params.len(), 2);
    }

    #[test]
    fn keywords_are_not_reserved() {
        assert!(parse_class(
            "class Main { function void main() { var int while; let while = 1; return; } }"
        )
        .is_ok());
    }

    #[test]
    fn spacing_quirks_are_errors() {
        let e = err(&body("return(x);"));
        assert!(e.2.contains("whitespace after 'return'"), "{e:?}");
        assert!(parse_class(&body("let x = a [1];")).is_err());
        assert!(parse_class(&body("do Output . printInt(1);")).is_err());
        assert!(parse_class(&body("do Output. printInt(1);")).is_err());
        assert!(parse_class(&body("do Output .printInt(1);")).is_err());
        assert!(parse_class(&body("do Output.printInt (1);")).is_ok());
        assert!(parse_class(&body("let a [1] = 2;")).is_err());
        assert!(parse_class(&body("let a[1] = 2;")).is_ok());
    }

    #[test]
    fn primitive_prefixed_type_names_are_errors() {
        assert_eq!(
            err("class Main { field intList l; }"),
            (
                1,
                23,
                "Expected whitespace after the type 'int'".to_string()
            )
        );
        assert!(parse_class("class Main { field IntList l; }").is_ok());
    }

    #[test]
    fn keyword_prefixed_names_fail_in_expressions_only() {
        let e = err(&body("let x = thisX;"));
        assert_eq!(
            e.2,
            "A name that starts with 'this' cannot be used in an expression (thisX)"
        );
        assert!(parse_class("class Main { function void main() { var int nullable; let nullable = 1; do nullify(); return; } }").is_ok());
    }

    #[test]
    fn else_if_is_an_error() {
        assert!(parse_class(&body("if (x) { } else if (x) { }")).is_err());
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let deep = format!("let x = {}1{};", "(".repeat(100_000), ")".repeat(100_000));
        assert!(matches!(
            parse_class(&body(&deep)).unwrap_err().1,
            ErrorKind::TooDeep(_)
        ));
        let neg = format!("let x = {}1;", "-".repeat(100_000));
        assert!(matches!(
            parse_class(&body(&neg)).unwrap_err().1,
            ErrorKind::TooDeep(_)
        ));
        let ifs = format!("{}{}", "if (x) {".repeat(100_000), "}".repeat(100_000));
        assert!(matches!(
            parse_class(&body(&ifs)).unwrap_err().1,
            ErrorKind::TooDeep(_)
        ));
    }

    #[test]
    fn error_positions_point_at_the_offending_token() {
        assert_eq!(
            err("class Main {\n  function void main() {\n    let x = 1\n  }\n}"),
            (4, 3, "Expected ';', found '}'".to_string())
        );
        assert_eq!(
            err("class Main { } x"),
            (
                1,
                16,
                "Expected end of file after the class, found 'x'".to_string()
            )
        );
    }
}
