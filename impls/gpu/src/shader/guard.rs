//! The loop guard: a shader that loops for ever must not hang the harness,
//! and a GPU dispatch cannot be interrupted (lavapipe runs it on CPU
//! threads to its end). So before compilation every loop of the module gets
//! a counter at the top of its body:
//!
//! ```text
//! harness_iterations += 1;
//! if harness_iterations > LIMIT { harness_runaway = true; break; }
//! ```
//!
//! The counter is one per invocation, shared by all loops, so nested loops
//! are bounded too: once past the limit every loop breaks at its next
//! iteration. The wrapper reports `harness_runaway` as a hang. The two
//! private variables are declared by the wrapper (`wrappers/io.*`).

use naga::{
    BinaryOperator, Block, Expression, Function, Handle, Literal, Module, Range, Span, Statement,
};

/// Add the guard to every loop of every function of `module`, breaking
/// after `limit` iterations in all. The wrapper's two variables must be
/// declared; a module without them is left as it is (`false`).
pub(crate) fn install(module: &mut Module, limit: u32) -> bool {
    let find = |name: &str| {
        module
            .global_variables
            .iter()
            .find(|(_, g)| g.name.as_deref() == Some(name))
            .map(|(h, _)| h)
    };
    let (Some(counter), Some(flag)) = (find("harness_iterations"), find("harness_runaway")) else {
        return false;
    };
    let guard = Guard {
        counter,
        flag,
        limit,
    };
    for (_, function) in module.functions.iter_mut() {
        guard.function(function);
    }
    for entry in module.entry_points.iter_mut() {
        guard.function(&mut entry.function);
    }
    true
}

struct Guard {
    counter: Handle<naga::GlobalVariable>,
    flag: Handle<naga::GlobalVariable>,
    limit: u32,
}

impl Guard {
    fn function(&self, function: &mut Function) {
        let mut body = std::mem::take(&mut function.body);
        self.block(function, &mut body);
        function.body = body;
    }

    /// Guard the loops in `block` and in every block nested in it.
    fn block(&self, function: &mut Function, block: &mut Block) {
        for (statement, _) in block.span_iter_mut() {
            match statement {
                Statement::Block(inner) => self.block(function, inner),
                Statement::If { accept, reject, .. } => {
                    self.block(function, accept);
                    self.block(function, reject);
                }
                Statement::Switch { cases, .. } => {
                    for case in cases {
                        self.block(function, &mut case.body);
                    }
                }
                Statement::Loop {
                    body, continuing, ..
                } => {
                    self.block(function, body);
                    self.block(function, continuing);
                    let mut guarded = self.check(function);
                    guarded.append(body);
                    *body = guarded;
                }
                _ => {}
            }
        }
    }

    /// The statements that count one iteration and break past the limit.
    fn check(&self, function: &mut Function) -> Block {
        let undefined = Span::UNDEFINED;
        let mut add = |e: Expression| function.expressions.append(e, undefined);
        // Expressions that need no emitting: pointers to globals, literals.
        let counter = add(Expression::GlobalVariable(self.counter));
        let flag = add(Expression::GlobalVariable(self.flag));
        let one = add(Expression::Literal(Literal::U32(1)));
        let limit = add(Expression::Literal(Literal::U32(self.limit)));
        let yes = add(Expression::Literal(Literal::Bool(true)));
        // Emitted, in one range.
        let count = add(Expression::Load { pointer: counter });
        let next = add(Expression::Binary {
            op: BinaryOperator::Add,
            left: count,
            right: one,
        });
        let over = add(Expression::Binary {
            op: BinaryOperator::Greater,
            left: next,
            right: limit,
        });
        let mut stop = Block::new();
        stop.push(
            Statement::Store {
                pointer: flag,
                value: yes,
            },
            undefined,
        );
        stop.push(Statement::Break, undefined);
        let mut check = Block::new();
        check.push(
            Statement::Emit(Range::new_from_bounds(count, over)),
            undefined,
        );
        check.push(
            Statement::Store {
                pointer: counter,
                value: next,
            },
            undefined,
        );
        check.push(
            Statement::If {
                condition: over,
                accept: stop,
                reject: Block::new(),
            },
            undefined,
        );
        check
    }
}
