//! `Main.fib(n)`, recursive, in VM code: a small program with many calls,
//! for the tests of this crate (included with `#[macro_use] #[path]`).

/// The VM code of the function `Main.fib` (no `Main.main`), as a string
/// literal for `concat!`.
macro_rules! fib_function {
    () => {
        "
function Main.fib 0
push argument 0
push constant 2
lt
if-goto BASE
push argument 0
push constant 2
sub
call Main.fib 1
push argument 0
push constant 1
sub
call Main.fib 1
add
return
label BASE
push argument 0
return
"
    };
}
