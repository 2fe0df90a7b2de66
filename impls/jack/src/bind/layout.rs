//! Object layouts: which field of a class holds which part of a value (a
//! float's sign, exponent and mantissa; a vector's components; an SDF
//! result's distance and colour), how to make an object (a constructor
//! call, or `Memory.alloc` and field writes), and the round-trip check that
//! a made object reads back as what it was made from.

use super::error::BindError;
use super::signatures::Signatures;
use super::spec::Layout;
use super::statement::{compile, Call, Classes, Context, Slot, Ty};
use super::vm::{call_returning, Regs};
use crate::JackError;
use common::F316;
use hack_vm::{Builtin, Machine, Program, Ram};

/// The three kinds of object a binding describes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Float,
    Vec3,
    Hit,
}

impl Kind {
    /// The roles its fields may have, `_` aside.
    fn roles(self) -> &'static [&'static str] {
        match self {
            Kind::Float => &["s", "e", "m"],
            Kind::Vec3 => &["x", "y", "z"],
            Kind::Hit => &["distance", "colour"],
        }
    }

    /// The variables of its constructor statement.
    fn maker_context(self) -> Context {
        let vars = match self {
            Kind::Float => vec![("s", Ty::Int), ("e", Ty::Int), ("m", Ty::Int)],
            Kind::Vec3 => vec![("x", Ty::Float), ("y", Ty::Float), ("z", Ty::Float)],
            Kind::Hit => vec![("distance", Ty::Float), ("colour", Ty::Float)],
        };
        Context { vars, skip: false }
    }
}

/// How objects are made.
#[derive(Clone, Debug)]
enum Maker {
    Alloc,
    Call(Call),
}

/// A checked [`Layout`].
#[derive(Clone, Debug)]
pub(crate) struct ObjectLayout {
    /// The field path, for messages (`float`, `vec3`, `sdf_result`).
    pub field: &'static str,
    pub class: String,
    /// Offset of each role of [`Kind::roles`], in that order.
    offsets: Vec<i32>,
    size: i16,
    maker: Maker,
    /// The roles as written, for messages.
    written: Vec<String>,
}

impl ObjectLayout {
    /// Check `layout` of `kind` against the program.
    pub fn new(
        field: &'static str,
        kind: Kind,
        layout: &Layout,
        classes: &Classes,
        program: &Program,
        signatures: &Signatures,
    ) -> Result<ObjectLayout, BindError> {
        let fields_field = format!("{field}.fields");
        let mut offsets = Vec::new();
        for role in kind.roles() {
            let at: Vec<usize> = (0..layout.fields.len())
                .filter(|&i| layout.fields[i] == *role)
                .collect();
            match at.as_slice() {
                [i] => offsets.push(*i as i32),
                [] => {
                    return Err(BindError::new(
                        &fields_field,
                        format!(
                            "no field has the role `{role}` (a {field} needs {})",
                            kind.roles().join(", ")
                        ),
                    ))
                }
                _ => {
                    return Err(BindError::new(
                        &fields_field,
                        format!("the role `{role}` is given to more than one field"),
                    ))
                }
            }
        }
        if let Some(bad) = layout
            .fields
            .iter()
            .find(|f| *f != "_" && !kind.roles().contains(&f.as_str()))
        {
            return Err(BindError::new(
                &fields_field,
                format!(
                    "unknown role `{bad}` (expected {} or `_`)",
                    kind.roles().join(", ")
                ),
            ));
        }
        if signatures.has_class(&layout.class) == Some(false) {
            return Err(BindError::new(
                &format!("{field}.class"),
                format!("the program has no class {}", layout.class),
            ));
        }
        if let Some(n) = signatures.field_count(&layout.class) {
            if n != layout.fields.len() {
                return Err(BindError::new(
                    &fields_field,
                    format!(
                        "class {} declares {n} field(s), the binding lists {}",
                        layout.class,
                        layout.fields.len()
                    ),
                ));
            }
        }
        let maker = if layout.new.trim() == "alloc" {
            Maker::Alloc
        } else {
            let call = compile(
                &format!("{field}.new"),
                &layout.new,
                &kind.maker_context(),
                classes,
                program,
                signatures,
            )?;
            if call.target.is_some() {
                return Err(BindError::new(
                    &format!("{field}.new"),
                    "a constructor statement has no target: the object it returns is the new one",
                ));
            }
            Maker::Call(call)
        };
        Ok(ObjectLayout {
            field,
            class: layout.class.clone(),
            offsets,
            size: layout.fields.len() as i16,
            maker,
            written: layout.fields.clone(),
        })
    }

    /// The word of role `i` of the object at `addr`.
    #[inline]
    pub fn get(&self, ram: &Ram, addr: i16, i: usize) -> i16 {
        ram.read(i32::from(addr) + self.offsets[i])
    }

    #[inline]
    fn set(&self, ram: &mut Ram, addr: i16, i: usize, v: i16) {
        ram.write(i32::from(addr) + self.offsets[i], v);
    }

    /// The float at `addr` (a float layout).
    #[inline]
    pub fn read_float(&self, ram: &Ram, addr: i16) -> F316 {
        F316::new(
            self.get(ram, addr, 0),
            self.get(ram, addr, 1),
            self.get(ram, addr, 2),
        )
    }

    /// Write `v` into the float at `addr` (a float layout).
    #[inline]
    pub fn write_float(&self, ram: &mut Ram, addr: i16, v: F316) {
        self.set(ram, addr, 0, v.s);
        self.set(ram, addr, 1, v.e);
        self.set(ram, addr, 2, v.m);
    }

    fn alloc(&self, m: &mut Machine) -> Result<i16, JackError> {
        let done = m.call_builtin(Builtin::MemoryAlloc, &[self.size]);
        match done.stop {
            None => Ok(done.value),
            Some(stop) => Err(JackError::BadArgument(format!(
                "{}: Memory.alloc({}) failed: {stop:?}",
                self.field, self.size
            ))),
        }
    }

    /// Run the constructor statement with `regs` (its context's
    /// variables); the new object.
    fn construct(&self, m: &mut Machine, call: &Call, regs: &[i16]) -> Result<i16, JackError> {
        let mut regs = Regs::from(regs);
        call_returning(m, call, &mut regs, &format!("{}.new", self.field))
    }

    /// A new float object holding `v` (a float layout).
    pub fn make_float(&self, m: &mut Machine, v: F316) -> Result<i16, JackError> {
        match &self.maker {
            Maker::Alloc => {
                let p = self.alloc(m)?;
                self.write_float(m.ram_mut(), p, v);
                Ok(p)
            }
            Maker::Call(call) => self.construct(m, call, &[v.s, v.e, v.m]),
        }
    }

    /// A new object with `parts` (float objects) in its roles: a vector of
    /// three components or an SDF result. A constructor without arguments
    /// makes its own parts; `values` are then written into them.
    pub fn make_compound(
        &self,
        m: &mut Machine,
        float: &ObjectLayout,
        values: &[F316],
    ) -> Result<i16, JackError> {
        let mut parts = Vec::new();
        let takes_parts = match &self.maker {
            Maker::Alloc => true,
            Maker::Call(call) => call.args.iter().any(|s| matches!(s, Slot::Var(_))),
        };
        if takes_parts {
            for &v in values {
                parts.push(float.make_float(m, v)?);
            }
        }
        let p = match &self.maker {
            Maker::Alloc => {
                let p = self.alloc(m)?;
                for (i, &part) in parts.iter().enumerate() {
                    self.set(m.ram_mut(), p, i, part);
                }
                p
            }
            Maker::Call(call) => self.construct(m, call, &parts)?,
        };
        if !takes_parts {
            for (i, &v) in values.iter().enumerate() {
                let part = self.get(m.ram(), p, i);
                float.write_float(m.ram_mut(), part, v);
            }
        }
        Ok(p)
    }

    /// The values of the parts of the compound object at `p`.
    pub fn read_compound(&self, ram: &Ram, float: &ObjectLayout, p: i16) -> Vec<F316> {
        (0..self.offsets.len())
            .map(|i| float.read_float(ram, self.get(ram, p, i)))
            .collect()
    }

    /// A round-trip error: `made` was made, `read` read back.
    pub fn round_trip_error(&self, made: String, read: String) -> BindError {
        BindError::new(
            &format!("{}.fields", self.field),
            format!(
                "round trip failed: made {made} and read back {read} through fields [{}] of {}: \
                 the field order does not match the class (or `{}.new` does not store what it is given)",
                self.written.join(", "),
                self.class,
                self.field
            ),
        )
    }
}
