//! The syntax tree of one Jack class.

use crate::error::Pos;

/// A name with where it was written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ident {
    /// The name.
    pub text: String,
    /// Its first character.
    pub pos: Pos,
}

/// `class Name { ... }`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Class {
    /// The class name.
    pub name: Ident,
    /// `static` and `field` declarations, in order.
    pub vars: Vec<ClassVarDec>,
    /// Subroutines, in order.
    pub subroutines: Vec<Subroutine>,
}

/// `static` or `field`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClassVarKind {
    /// Class-wide variable (segment static).
    Static,
    /// Per-object variable (segment this).
    Field,
}

/// `static|field type a, b;`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ClassVarDec {
    /// Static or field.
    pub kind: ClassVarKind,
    /// The declared type.
    pub ty: Ident,
    /// The declared names.
    pub names: Vec<Ident>,
}

/// Constructor, function or method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SubroutineKind {
    /// `constructor`.
    Constructor,
    /// `function`.
    Function,
    /// `method`.
    Method,
}

impl SubroutineKind {
    /// The Jack keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            SubroutineKind::Constructor => "constructor",
            SubroutineKind::Function => "function",
            SubroutineKind::Method => "method",
        }
    }
}

/// A subroutine declaration.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Subroutine {
    /// Constructor, function or method.
    pub kind: SubroutineKind,
    /// Return type (`void` included).
    pub ret: Ident,
    /// Name.
    pub name: Ident,
    /// Parameters as (type, name).
    pub params: Vec<(Ident, Ident)>,
    /// `var` declarations.
    pub locals: Vec<VarDec>,
    /// The statements of the body.
    pub body: Vec<Statement>,
}

impl Subroutine {
    /// Whether the declared return type is `void`.
    pub fn is_void(&self) -> bool {
        self.ret.text == "void"
    }
}

/// `var type a, b;`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VarDec {
    /// The declared type.
    pub ty: Ident,
    /// The declared names.
    pub names: Vec<Ident>,
}

/// A statement.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Statement {
    /// `let x = e;` or `let x[i] = e;`.
    Let {
        /// The variable assigned.
        target: Ident,
        /// The index, for an array element.
        index: Option<Expr>,
        /// The value.
        value: Expr,
    },
    /// `if (c) { ... } else { ... }` (an absent else is empty).
    If {
        /// The condition.
        cond: Expr,
        /// Statements run when the condition holds.
        then: Vec<Statement>,
        /// Statements run otherwise.
        els: Vec<Statement>,
    },
    /// `while (c) { ... }`.
    While {
        /// The condition.
        cond: Expr,
        /// The loop body.
        body: Vec<Statement>,
    },
    /// `do call;`.
    Do(Call),
    /// `return;` or `return e;`.
    Return {
        /// Where the `return` keyword is.
        pos: Pos,
        /// The value, if any.
        value: Option<Expr>,
    },
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `&`
    And,
    /// `|`
    Or,
    /// `<`
    Lt,
    /// `>`
    Gt,
    /// `=`
    Eq,
}

impl BinOp {
    /// The operator written as `c`, if it is one.
    pub fn from_char(c: char) -> Option<BinOp> {
        Some(match c {
            '+' => BinOp::Add,
            '-' => BinOp::Sub,
            '*' => BinOp::Mul,
            '/' => BinOp::Div,
            '&' => BinOp::And,
            '|' => BinOp::Or,
            '<' => BinOp::Lt,
            '>' => BinOp::Gt,
            '=' => BinOp::Eq,
            _ => return None,
        })
    }
}

/// A unary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-` (neg)
    Neg,
    /// `~` (not)
    Not,
}

/// `true`, `false`, `null` or `this`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeywordConst {
    /// `true`
    True,
    /// `false`
    False,
    /// `null`
    Null,
    /// `this`
    This,
}

impl KeywordConst {
    /// All four, with their spelling.
    pub const ALL: [(&'static str, KeywordConst); 4] = [
        ("true", KeywordConst::True),
        ("false", KeywordConst::False),
        ("null", KeywordConst::Null),
        ("this", KeywordConst::This),
    ];
}

/// `term (op term)*`, evaluated strictly left to right.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Expr {
    /// The first term.
    pub first: Term,
    /// The following operator/term pairs.
    pub rest: Vec<(BinOp, Term)>,
}

/// A term of an expression.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Term {
    /// A decimal integer literal (leading zeros removed, possibly > 32767)
    /// and where it starts.
    Int(String, Pos),
    /// A string literal.
    Str(String),
    /// A keyword constant.
    Keyword(KeywordConst),
    /// A variable.
    Var(Ident),
    /// `a[e]`.
    Index(Ident, Box<Expr>),
    /// A subroutine call.
    Call(Call),
    /// `(e)`.
    Paren(Box<Expr>),
    /// `-t` or `~t`.
    Unary(UnaryOp, Box<Term>),
}

/// `m(args)`, `v.m(args)` or `C.f(args)`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Call {
    /// The part before the dot, if any (a variable or a class name).
    pub receiver: Option<Ident>,
    /// The subroutine name.
    pub name: Ident,
    /// The arguments.
    pub args: Vec<Expr>,
}

impl Call {
    /// Where the call's name starts (the receiver if there is one).
    pub fn pos(&self) -> Pos {
        self.receiver.as_ref().map_or(self.name.pos, |r| r.pos)
    }
}
