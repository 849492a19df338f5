//! Which stage starts next: the first waiting stage, in the plan's order,
//! whose prerequisites have all passed. A stage whose prerequisite failed
//! does not run; it ends failed at once, naming that prerequisite.

use crate::plan::Stage;

/// Where a stage is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Waiting,
    Running,
    Ended { passed: bool },
}

/// What a free worker does next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Next {
    /// Run the stage at this index.
    Run(usize),
    /// The stage at this index cannot run: its prerequisite (the name) failed.
    Skip(usize, &'static str),
}

/// The stages of one run and where each is.
#[derive(Debug, Clone)]
pub struct Board {
    stages: Vec<Stage>,
    state: Vec<State>,
}

impl Board {
    /// Every stage waiting.
    pub fn new(stages: Vec<Stage>) -> Self {
        let state = vec![State::Waiting; stages.len()];
        Board { stages, state }
    }

    /// The stages, in the plan's order.
    pub fn stages(&self) -> &[Stage] {
        &self.stages
    }

    /// The next stage for a free worker, marked running (or ended, when
    /// skipped); `None` when none can start now.
    pub fn next(&mut self) -> Option<Next> {
        for i in 0..self.stages.len() {
            if self.state[i] != State::Waiting {
                continue;
            }
            let mut ready = true;
            for &before in self.stages[i].after {
                // A prerequisite outside this run (never selected) is met.
                match self.state_of(before) {
                    Some(State::Ended { passed: false }) => {
                        self.state[i] = State::Ended { passed: false };
                        return Some(Next::Skip(i, before));
                    }
                    Some(State::Ended { passed: true }) | None => {}
                    Some(State::Waiting | State::Running) => ready = false,
                }
            }
            if ready {
                self.state[i] = State::Running;
                return Some(Next::Run(i));
            }
        }
        None
    }

    /// The stage at `i` has ended.
    pub fn end(&mut self, i: usize, passed: bool) {
        debug_assert_eq!(self.state[i], State::Running);
        self.state[i] = State::Ended { passed };
    }

    /// True once every stage has ended.
    pub fn finished(&self) -> bool {
        self.state.iter().all(|s| matches!(s, State::Ended { .. }))
    }

    fn state_of(&self, name: &str) -> Option<State> {
        self.stages
            .iter()
            .position(|s| s.name == name)
            .map(|i| self.state[i])
    }
}
