//! A builder for [`Program`]s: register allocation, nested blocks, the
//! constant pool. The lowering (`lower.rs`) speaks only through it.

use crate::ir::{
    BReg, Binary, Constant, Decision, FuncId, Function, Logic, Reg, Stmt, TReg, Taken, Unary, VecOp,
};

/// The function being built.
#[derive(Default)]
struct Open {
    name: String,
    params: Vec<Reg>,
    scalars: u16,
    bools: u16,
    tags: u16,
    /// Innermost block last.
    blocks: Vec<Vec<Stmt>>,
}

/// Builds the functions of one program, one at a time.
#[derive(Default)]
pub struct Builder {
    pub consts: Vec<Constant>,
    pub tables: Vec<Vec<f64>>,
    pub functions: Vec<Function>,
    open: Open,
}

/// A surface: signed distance, colour, material tag.
#[derive(Clone, Copy, Debug)]
pub struct Surf {
    pub sd: Reg,
    pub col: Reg,
    pub tag: TReg,
}

impl Builder {
    /// Start a function with `params` scalar parameters (returned).
    pub fn begin(&mut self, name: &str, params: u16) -> Vec<Reg> {
        self.open = Open {
            name: name.to_string(),
            blocks: vec![Vec::new()],
            ..Open::default()
        };
        let p: Vec<Reg> = (0..params).map(|_| self.reg()).collect();
        self.open.params = p.clone();
        p
    }

    /// Finish the open function with its results; returns its id.
    pub fn end(&mut self, results: Vec<Reg>, tag_results: Vec<TReg>) -> FuncId {
        let open = std::mem::take(&mut self.open);
        let mut blocks = open.blocks;
        let body = blocks.pop().expect("the function's own block");
        debug_assert!(blocks.is_empty(), "a block was left open");
        self.functions.push(Function {
            name: open.name,
            params: open.params,
            results,
            tag_results,
            scalars: open.scalars,
            bools: open.bools,
            tags: open.tags,
            body,
        });
        (self.functions.len() - 1) as FuncId
    }

    /// A fresh scalar register.
    pub fn reg(&mut self) -> Reg {
        self.open.scalars += 1;
        self.open.scalars - 1
    }

    /// Three fresh consecutive scalar registers (a vector).
    pub fn vreg(&mut self) -> Reg {
        self.open.scalars += 3;
        self.open.scalars - 3
    }

    pub fn breg(&mut self) -> BReg {
        self.open.bools += 1;
        self.open.bools - 1
    }

    pub fn treg(&mut self) -> TReg {
        self.open.tags += 1;
        self.open.tags - 1
    }

    /// Append a statement to the innermost open block.
    pub fn push(&mut self, s: Stmt) {
        self.open
            .blocks
            .last_mut()
            .expect("a function is open")
            .push(s);
    }

    /// Start a nested block: statements go there until [`Self::close_block`].
    pub fn open_block(&mut self) {
        self.open.blocks.push(Vec::new());
    }

    /// End the innermost nested block and return its statements.
    pub fn close_block(&mut self) -> Vec<Stmt> {
        self.open.blocks.pop().expect("a block is open")
    }

    /// The statements `f` emits, as a block of their own.
    pub fn block(&mut self, f: impl FnOnce(&mut Self)) -> Vec<Stmt> {
        self.open_block();
        f(self);
        self.close_block()
    }

    /// Emit `f`'s statements inside a trace frame `name`.
    pub fn frame<T>(&mut self, name: &str, f: impl FnOnce(&mut Self) -> T) -> T {
        let mut out = None;
        let body = self.block(|b| out = Some(f(b)));
        self.push(Stmt::Frame {
            name: name.to_string(),
            body,
        });
        out.expect("the frame's body ran")
    }

    /// The pool index of constant `value` (first origin kept).
    fn pool(&mut self, value: f64, origin: &str) -> u16 {
        if let Some(i) = self
            .consts
            .iter()
            .position(|c| c.value.to_bits() == value.to_bits())
        {
            return i as u16;
        }
        self.consts.push(Constant {
            value,
            origin: origin.to_string(),
        });
        (self.consts.len() - 1) as u16
    }

    /// A register holding the constant `value` (from field `origin`).
    pub fn k(&mut self, value: f64, origin: &str) -> Reg {
        let index = self.pool(value, origin);
        let dst = self.reg();
        self.push(Stmt::Const { dst, index });
        dst
    }

    /// A vector register holding a constant vector.
    pub fn kv(&mut self, v: [f64; 3], origin: &str) -> Reg {
        let dst = self.vreg();
        for (i, &c) in v.iter().enumerate() {
            let index = self.pool(c, origin);
            self.push(Stmt::Const {
                dst: dst + i as u16,
                index,
            });
        }
        dst
    }

    /// A vector register made of three scalars.
    pub fn v3(&mut self, x: Reg, y: Reg, z: Reg) -> Reg {
        let dst = self.vreg();
        for (i, src) in [x, y, z].into_iter().enumerate() {
            self.push(Stmt::Copy {
                dst: dst + i as u16,
                src,
            });
        }
        dst
    }

    /// A matrix read at the pixel's index; returns its table number.
    pub fn table(&mut self, entries: Vec<f64>) -> u16 {
        self.tables.push(entries);
        (self.tables.len() - 1) as u16
    }

    pub fn un(&mut self, op: Unary, a: Reg) -> Reg {
        let dst = self.reg();
        self.push(Stmt::Unary { dst, op, a });
        dst
    }

    pub fn bin(&mut self, op: Binary, a: Reg, b: Reg) -> Reg {
        let dst = self.reg();
        self.push(Stmt::Binary { dst, op, a, b });
        dst
    }

    pub fn add(&mut self, a: Reg, b: Reg) -> Reg {
        self.bin(Binary::Add, a, b)
    }

    pub fn sub(&mut self, a: Reg, b: Reg) -> Reg {
        self.bin(Binary::Sub, a, b)
    }

    pub fn mul(&mut self, a: Reg, b: Reg) -> Reg {
        self.bin(Binary::Mul, a, b)
    }

    pub fn div(&mut self, a: Reg, b: Reg) -> Reg {
        self.bin(Binary::Div, a, b)
    }

    /// A vector operation (for `Scale`, `b` is a scalar).
    pub fn vec(&mut self, op: VecOp, a: Reg, b: Reg) -> Reg {
        let dst = self.vreg();
        self.push(Stmt::Vector { dst, op, a, b });
        dst
    }

    pub fn normalize(&mut self, a: Reg) -> Reg {
        self.vec(VecOp::Normalize, a, a)
    }

    pub fn dot(&mut self, a: Reg, b: Reg) -> Reg {
        let dst = self.reg();
        self.push(Stmt::Dot { dst, a, b });
        dst
    }

    pub fn length(&mut self, a: Reg) -> Reg {
        let dst = self.reg();
        self.push(Stmt::Length { dst, a });
        dst
    }

    /// `dot(a, b)` clamped as an angle, in a frame `angle`: 0 when its
    /// sign bit is set, else 1 when it is above 1 (the two decisions
    /// reported where the hand-written pipeline reports them).
    pub fn angle(&mut self, a: Reg, b: Reg) -> Reg {
        self.frame("angle", |s| {
            let d = s.dot(a, b);
            let zero = s.k(0.0, "angle");
            let one = s.k(1.0, "angle");
            let out = s.reg();
            let low = s.sign_bit(d);
            s.decide(Decision::AngleLow, low, d, zero);
            s.if_else(
                low,
                |s| s.copy(out, zero),
                |s| {
                    let high = s.gt(d, one);
                    s.decide(Decision::AngleHigh, high, d, one);
                    let v = s.select(high, one, d);
                    s.copy(out, v);
                },
            );
            out
        })
    }

    /// Report the decision `decision`, held in `taken`, on `a` and `b`.
    pub fn decide(&mut self, decision: Decision, taken: BReg, a: Reg, b: Reg) {
        self.push(Stmt::Decide {
            decision,
            taken: Taken::Bool(taken),
            a,
            b,
        });
    }

    pub fn gt(&mut self, a: Reg, b: Reg) -> BReg {
        let dst = self.breg();
        self.push(Stmt::Gt { dst, a, b });
        dst
    }

    pub fn sign_bit(&mut self, a: Reg) -> BReg {
        let dst = self.breg();
        self.push(Stmt::SignBit { dst, a });
        dst
    }

    pub fn logic(&mut self, op: Logic, a: BReg, b: BReg) -> BReg {
        let dst = self.breg();
        self.push(Stmt::Logic { dst, op, a, b });
        dst
    }

    /// A boolean register holding `value`.
    pub fn bool(&mut self, value: bool) -> BReg {
        let dst = self.breg();
        self.push(Stmt::Bool { dst, value });
        dst
    }

    pub fn not(&mut self, a: BReg) -> BReg {
        self.logic(Logic::Not, a, a)
    }

    /// `cond ? a : b` into a fresh register.
    pub fn select(&mut self, cond: BReg, a: Reg, b: Reg) -> Reg {
        let dst = self.reg();
        self.push(Stmt::Select { dst, cond, a, b });
        dst
    }

    /// `cond ? a : b` for whole surfaces.
    pub fn select_surf(&mut self, cond: BReg, a: Surf, b: Surf) -> Surf {
        let sd = self.select(cond, a.sd, b.sd);
        let col = self.select(cond, a.col, b.col);
        let tag = self.treg();
        self.push(Stmt::SelectTag {
            dst: tag,
            cond,
            a: a.tag,
            b: b.tag,
        });
        Surf { sd, col, tag }
    }

    pub fn copy(&mut self, dst: Reg, src: Reg) {
        self.push(Stmt::Copy { dst, src });
    }

    /// Copy a vector.
    pub fn copy3(&mut self, dst: Reg, src: Reg) {
        for i in 0..3 {
            self.copy(dst + i, src + i);
        }
    }

    /// `if cond { then } else { otherwise }`.
    pub fn if_else(
        &mut self,
        cond: BReg,
        then: impl FnOnce(&mut Self),
        otherwise: impl FnOnce(&mut Self),
    ) {
        let then = self.block(then);
        let otherwise = self.block(otherwise);
        self.push(Stmt::If {
            cond,
            then,
            otherwise,
        });
    }
}
