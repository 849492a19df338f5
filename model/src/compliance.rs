//! The clauses of each protocol's standard, written once as data, for the
//! compliance matrices (`docs/compliance/<protocol>.md`).
//!
//! A clause is one numbered rule of the specification a protocol follows:
//! its id (the matrix's row, the name a test cites), its section and the
//! standard's own words. Tests and scenarios name the clauses they exercise
//! by id (`tbgen`'s compliance suite); the matrix is generated from those
//! declarations, a clause no test names is a gap row, and an id a test names
//! that is not here fails the suite. Where the rule book
//! ([`crate::rules`]) already quotes a clause for the monitors, the clause
//! takes its words from the rule, so the words are written once.

use crate::rules::Rule;

/// Which roles of a node a clause is held against, one matrix row each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Roles {
    /// One row: the clause does not depend on the node's role.
    Any,
    /// A row for the node as transmitter and one as receiver (the fault
    /// confinement rules: a rule naming one role is shown, with the other,
    /// not to move that role's counter).
    TransmitterAndReceiver,
}

/// A node's role in an exercise of a clause.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Role {
    /// The row of a [`Roles::Any`] clause.
    Any,
    /// The node sends the frame ("A unit originating a message").
    Transmitter,
    /// The node receives it.
    Receiver,
}

impl Role {
    /// The role as the matrix prints it.
    pub fn name(self) -> &'static str {
        match self {
            Role::Any => "",
            Role::Transmitter => "transmitter",
            Role::Receiver => "receiver",
        }
    }
}

/// Where a clause's words come from.
#[derive(Debug)]
pub enum Text {
    /// Quoted here: the section and the standard's words.
    Quoted {
        /// The section (`part B §8, rule 3`).
        section: &'static str,
        /// The standard's words.
        words: &'static str,
    },
    /// The rule book's rule quotes them (its section and words).
    Rule(&'static Rule),
}

/// One numbered rule of a standard.
#[derive(Debug)]
pub struct Clause {
    /// The id tests cite (`fc-3`).
    pub id: &'static str,
    /// A few words saying what the clause is about (`TEC + 8 for a transmitter's error flag`).
    pub short: &'static str,
    /// The roles it is held against.
    pub roles: Roles,
    /// The section and the words.
    pub text: Text,
}

impl Clause {
    /// A clause whose words are quoted here.
    pub const fn quoted(
        id: &'static str,
        short: &'static str,
        roles: Roles,
        section: &'static str,
        words: &'static str,
    ) -> Clause {
        Clause {
            id,
            short,
            roles,
            text: Text::Quoted { section, words },
        }
    }

    /// The section the words are from.
    pub fn section(&self) -> &'static str {
        match &self.text {
            Text::Quoted { section, .. } => section,
            Text::Rule(r) => r.section,
        }
    }

    /// The standard's words.
    pub fn words(&self) -> &'static str {
        match &self.text {
            Text::Quoted { words, .. } => words,
            Text::Rule(r) => r.seed_words,
        }
    }

    /// The rule book's rule that quotes this clause, if any.
    pub fn rule(&self) -> Option<&'static Rule> {
        match &self.text {
            Text::Quoted { .. } => None,
            Text::Rule(r) => Some(r),
        }
    }

    /// The rows of the matrix: one per role held.
    pub fn rows(&self) -> &'static [Role] {
        match self.roles {
            Roles::Any => &[Role::Any],
            Roles::TransmitterAndReceiver => &[Role::Transmitter, Role::Receiver],
        }
    }
}

/// A standard and its clauses, in the order the matrix lists them.
#[derive(Debug)]
pub struct Standard {
    /// The protocol's stem (`can`), the matrix's file name.
    pub protocol: &'static str,
    /// The document (`Robert Bosch GmbH, CAN Specification Version 2.0, 1991`).
    pub title: &'static str,
    /// Its clauses, grouped as the matrix prints them: `(group, clauses)`.
    pub groups: &'static [(&'static str, &'static [Clause])],
}

impl Standard {
    /// Every clause, in order.
    pub fn clauses(&self) -> impl Iterator<Item = &'static Clause> + '_ {
        self.groups.iter().flat_map(|(_, c)| c.iter())
    }

    /// The clause called `id`.
    pub fn clause(&self, id: &str) -> Option<&'static Clause> {
        self.clauses().find(|c| c.id == id)
    }
}

/// Every standard with a compliance matrix.
pub fn standards() -> [&'static Standard; 2] {
    [
        &crate::can::clauses::STANDARD,
        &crate::canopen::clauses::STANDARD,
    ]
}
