//! The complete list of built-in OS subroutines (spec section 3), with the
//! signatures the web IDE declares (`builtins.ts`): the compiler validates
//! calls and OS overrides against it, the VM resolves `call` targets with it.

/// How a subroutine is declared in Jack.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SubroutineKind {
    /// `function`: no `this`.
    Function,
    /// `method`: the VM call passes `this` as argument 0.
    Method,
    /// `constructor`: no `this` argument; returns the new object.
    Constructor,
}

/// One built-in OS subroutine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OsSubroutine {
    /// Class name, e.g. `Math`.
    pub class: &'static str,
    /// Subroutine name, e.g. `divide`.
    pub name: &'static str,
    /// `Class.name`, e.g. `Math.divide`.
    pub full_name: &'static str,
    /// Function, method or constructor.
    pub kind: SubroutineKind,
    /// Number of Jack-level parameters, excluding `this`.
    pub params: u8,
    /// Jack types of the parameters, e.g. `["int", "char"]`.
    pub param_types: &'static [&'static str],
    /// Jack return type, e.g. `int`, `String`, `void`.
    pub return_type: &'static str,
    /// Whether the return type is `void` (the VM still pushes 0).
    pub returns_void: bool,
    /// The native implementation to hand to [`crate::Os::call`].
    pub builtin: Builtin,
}

const fn is_void(ty: &str) -> bool {
    let b = ty.as_bytes();
    b.len() == 4 && b[0] == b'v' && b[1] == b'o' && b[2] == b'i' && b[3] == b'd'
}

macro_rules! os_table {
    ($($variant:ident = $class:literal . $name:literal $kind:ident ($($ty:literal),*) -> $ret:literal;)*) => {
        /// One variant per built-in OS subroutine, in table order.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Builtin {
            $(
                #[doc = concat!("`", $class, ".", $name, "`")]
                $variant,
            )*
        }

        static SUBROUTINES: &[OsSubroutine] = &[$(
            OsSubroutine {
                class: $class,
                name: $name,
                full_name: concat!($class, ".", $name),
                kind: SubroutineKind::$kind,
                params: <[&str]>::len(&[$($ty),*]) as u8,
                param_types: &[$($ty),*],
                return_type: $ret,
                returns_void: is_void($ret),
                builtin: Builtin::$variant,
            },
        )*];
    };
}

os_table! {
    MathInit = "Math"."init" Function() -> "void";
    MathMultiply = "Math"."multiply" Function("int", "int") -> "int";
    MathDivide = "Math"."divide" Function("int", "int") -> "int";
    MathMin = "Math"."min" Function("int", "int") -> "int";
    MathMax = "Math"."max" Function("int", "int") -> "int";
    MathSqrt = "Math"."sqrt" Function("int") -> "int";
    MathAbs = "Math"."abs" Function("int") -> "int";
    MemoryInit = "Memory"."init" Function() -> "void";
    MemoryPeek = "Memory"."peek" Function("int") -> "int";
    MemoryPoke = "Memory"."poke" Function("int", "int") -> "void";
    MemoryAlloc = "Memory"."alloc" Function("int") -> "Array";
    MemoryDeAlloc = "Memory"."deAlloc" Function("Array") -> "void";
    ArrayInit = "Array"."init" Function() -> "void";
    ArrayNew = "Array"."new" Constructor("int") -> "Array";
    ArrayDispose = "Array"."dispose" Method() -> "void";
    StringInit = "String"."init" Function() -> "void";
    StringNew = "String"."new" Constructor("int") -> "String";
    StringDispose = "String"."dispose" Method() -> "void";
    StringLength = "String"."length" Method() -> "int";
    StringCharAt = "String"."charAt" Method("int") -> "char";
    StringSetCharAt = "String"."setCharAt" Method("int", "char") -> "void";
    StringAppendChar = "String"."appendChar" Method("char") -> "String";
    StringEraseLastChar = "String"."eraseLastChar" Method() -> "void";
    StringIntValue = "String"."intValue" Method() -> "int";
    StringSetInt = "String"."setInt" Method("int") -> "void";
    StringBackSpace = "String"."backSpace" Function() -> "char";
    StringDoubleQuote = "String"."doubleQuote" Function() -> "char";
    StringNewLine = "String"."newLine" Function() -> "char";
    OutputInit = "Output"."init" Function() -> "void";
    OutputMoveCursor = "Output"."moveCursor" Function("int", "int") -> "void";
    OutputPrintChar = "Output"."printChar" Function("char") -> "void";
    OutputPrintString = "Output"."printString" Function("String") -> "void";
    OutputPrintInt = "Output"."printInt" Function("int") -> "void";
    OutputPrintln = "Output"."println" Function() -> "void";
    OutputBackSpace = "Output"."backSpace" Function() -> "void";
    ScreenInit = "Screen"."init" Function() -> "void";
    ScreenClearScreen = "Screen"."clearScreen" Function() -> "void";
    ScreenSetColor = "Screen"."setColor" Function("boolean") -> "void";
    ScreenDrawPixel = "Screen"."drawPixel" Function("int", "int") -> "void";
    ScreenDrawLine = "Screen"."drawLine" Function("int", "int", "int", "int") -> "void";
    ScreenDrawRectangle = "Screen"."drawRectangle" Function("int", "int", "int", "int") -> "void";
    ScreenDrawCircle = "Screen"."drawCircle" Function("int", "int", "int") -> "void";
    KeyboardInit = "Keyboard"."init" Function() -> "void";
    KeyboardKeyPressed = "Keyboard"."keyPressed" Function() -> "char";
    KeyboardReadChar = "Keyboard"."readChar" Function() -> "char";
    KeyboardReadLine = "Keyboard"."readLine" Function("String") -> "String";
    KeyboardReadInt = "Keyboard"."readInt" Function("String") -> "int";
    SysHalt = "Sys"."halt" Function() -> "void";
    SysError = "Sys"."error" Function("int") -> "void";
    SysWait = "Sys"."wait" Function("int") -> "void";
}

/// Every built-in OS subroutine of spec section 3, in a fixed order.
pub fn subroutines() -> &'static [OsSubroutine] {
    SUBROUTINES
}

/// The built-in called `full_name` (`"Math.divide"`), if there is one.
/// Names are case-sensitive, as in Jack.
pub fn lookup(full_name: &str) -> Option<&'static OsSubroutine> {
    let (class, name) = full_name.split_once('.')?;
    SUBROUTINES
        .iter()
        .find(|s| s.class == class && s.name == name)
}

impl Builtin {
    /// The table entry of this built-in.
    pub fn info(self) -> &'static OsSubroutine {
        &SUBROUTINES[self as usize]
    }

    /// Arguments the VM passes: the Jack parameters plus `this` for methods.
    pub fn vm_arity(self) -> usize {
        let info = self.info();
        info.params as usize + usize::from(info.kind == SubroutineKind::Method)
    }

    /// `Class.name`, e.g. `Math.divide`.
    pub fn full_name(self) -> &'static str {
        self.info().full_name
    }

    /// Whether the web IDE blocks in this built-in (`Sys.wait` and the
    /// Keyboard reads), which costs an extra VM step to deliver the result
    /// (spec 2.7). Only the Keyboard reads advance the clock here.
    pub fn blocks(self) -> bool {
        matches!(
            self,
            Builtin::SysWait
                | Builtin::KeyboardReadChar
                | Builtin::KeyboardReadLine
                | Builtin::KeyboardReadInt
        )
    }
}

impl std::fmt::Display for Builtin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.full_name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_complete_and_indexed_by_variant() {
        assert_eq!(subroutines().len(), 50);
        for (i, s) in subroutines().iter().enumerate() {
            assert_eq!(s.builtin as usize, i);
            assert_eq!(s.full_name, format!("{}.{}", s.class, s.name));
            assert_eq!(s.params as usize, s.param_types.len());
            assert_eq!(s.returns_void, s.return_type == "void");
            assert_eq!(lookup(s.full_name), Some(s));
        }
        let count = |class: &str| subroutines().iter().filter(|s| s.class == class).count();
        let per_class = [
            ("Math", 7),
            ("Memory", 5),
            ("Array", 3),
            ("String", 13),
            ("Output", 7),
            ("Screen", 7),
            ("Keyboard", 5),
            ("Sys", 3),
        ];
        for (class, n) in per_class {
            assert_eq!(count(class), n, "{class}");
        }
    }

    #[test]
    fn functions_missing_from_the_web_ide_are_not_built_in() {
        for name in [
            "Sys.init",
            "Math.bit",
            "Math.twoToThe",
            "math.divide",
            "Math",
            "Math.",
        ] {
            assert_eq!(lookup(name), None, "{name}");
        }
    }

    #[test]
    fn vm_arity_counts_this_for_methods() {
        assert_eq!(Builtin::MathDivide.vm_arity(), 2);
        assert_eq!(Builtin::StringSetCharAt.vm_arity(), 3);
        assert_eq!(Builtin::StringLength.vm_arity(), 1);
        assert_eq!(Builtin::ArrayNew.vm_arity(), 1);
        assert_eq!(Builtin::StringNew.info().kind, SubroutineKind::Constructor);
        assert_eq!(Builtin::ScreenDrawLine.vm_arity(), 4);
        assert_eq!(Builtin::SysHalt.vm_arity(), 0);
        assert_eq!(Builtin::MemoryAlloc.info().return_type, "Array");
        assert_eq!(Builtin::KeyboardReadLine.to_string(), "Keyboard.readLine");
    }
}
