//! The set of classes compiled together: what calls and types are checked
//! against.

use std::collections::HashMap;

use crate::ast::Class;
use jack_os::Profile;

/// A class of the program as far as it is known.
#[derive(Debug, Clone, Copy)]
pub enum ProgramClass<'a> {
    /// Parsed: its subroutines are known.
    Parsed(&'a Class),
    /// Its file has a syntax error: the class exists but calls into it are
    /// not checked (to avoid a cascade of errors).
    Unparsed,
}

/// All classes of one compilation and the profile.
#[derive(Debug)]
pub struct Program<'a> {
    /// Which tool's checks apply.
    pub profile: Profile,
    classes: HashMap<String, ProgramClass<'a>>,
}

impl<'a> Program<'a> {
    /// An empty program.
    pub fn new(profile: Profile) -> Self {
        Program {
            profile,
            classes: HashMap::new(),
        }
    }

    /// Adds a class under `name` (the first one added under a name stays).
    pub fn add(&mut self, name: &str, class: ProgramClass<'a>) {
        self.classes.entry(name.to_string()).or_insert(class);
    }

    /// The class called `name`, if the program has one.
    pub fn class(&self, name: &str) -> Option<ProgramClass<'a>> {
        self.classes.get(name).copied()
    }
}
