//! Variables whose value lives in the machine: FANUC common variables #500–#999
//! (retained at power-off, fanuc.md §4.1), which an operator, a probe cycle or a
//! cell controller leaves there, and system variables the dry run does not model
//! (#1000 and above: interface signals, tool offsets, Haas NGC's #10000 range).
//! Unless a variable file gives them or the program sets them, the dry run reads
//! them as vacant, as a control just after a memory clear would, but remembers
//! when such a read decided a branch, so that an alarm that follows is reported
//! as depending on the machine rather than as certain; and a loop that keeps
//! testing one of them (a mailbox the other side answers) as waiting, not as a
//! runaway.

use super::*;

/// The retained common variables.
pub(super) const RETAINED: std::ops::RangeInclusive<usize> = 500..=999;
/// From here on, a variable the dry run does not compute is the machine's.
const SYSTEM: usize = 1000;
/// FANUC variable numbers beyond the modelled table (#20000 and up: extended
/// common and system ranges of control options): the machine's, unknown here.
pub(super) const UNMODELLED: std::ops::RangeInclusive<i64> = 20_000..=999_999;

/// Whether `#n` is shared with the machine: the machine may change it while the
/// program runs.
pub(super) fn shared(n: usize) -> bool {
    RETAINED.contains(&n) || n >= SYSTEM
}

/// How many executed blocks after a decision by a machine value a step-budget
/// stop still counts as waiting on it (a wait loop re-reads it every few blocks).
const WAIT_WINDOW: u64 = 10_000;

/// What the run knows about the retained variables.
#[derive(Debug, Default, Clone, PartialEq)]
pub(super) struct MachineVars {
    /// Set by the program (or the variable file) during this run.
    known: Vec<bool>,
    /// Set system variables (#1000 and above) in the order they were set.
    set_system: std::collections::BTreeSet<usize>,
    /// The first branch a value unknown to the dry run decided: the variable and
    /// the condition's line.
    pub(super) first_decision: Option<(usize, u32)>,
    /// The latest condition that tested a shared variable: the variable, the
    /// condition's line and the step.
    last_shared_test: Option<(usize, u32, u64)>,
    /// Variables the program computed from a machine value it could not know
    /// (`#110 = #5061` after G31), and that value's variable.
    derived: std::collections::BTreeMap<usize, usize>,
    /// The note on an unmodelled variable range was given.
    pub(super) unmodelled_noted: bool,
}

impl MachineVars {
    pub(super) fn new(params: &[Option<f64>]) -> MachineVars {
        let known = RETAINED
            .map(|n| params.get(n).copied().flatten().is_some())
            .collect();
        MachineVars {
            known,
            ..MachineVars::default()
        }
    }

    /// Whether `#n`, read as vacant, has a value only the machine knows.
    pub(super) fn unknown(&self, n: usize) -> bool {
        if RETAINED.contains(&n) {
            return !self
                .known
                .get(n - RETAINED.start())
                .copied()
                .unwrap_or(true);
        }
        n >= SYSTEM && !self.set_system.contains(&n)
    }

    /// The machine value `#n` stands for when the dry run does not know it: `n`
    /// itself, read as vacant, or the one it was computed from.
    pub(super) fn unknown_origin(&self, n: usize, vacant: bool) -> Option<usize> {
        if let Some(origin) = self.derived.get(&n) {
            return Some(*origin);
        }
        (vacant && self.unknown(n)).then_some(n)
    }

    /// `#n` was set from an expression that read `from`, a machine value the dry
    /// run does not know (or from known values, `None`).
    pub(super) fn derive(&mut self, n: usize, from: Option<usize>) {
        match from {
            Some(origin) if origin != n => {
                self.derived.insert(n, origin);
            }
            _ => {
                self.derived.remove(&n);
            }
        }
    }

    pub(super) fn assigned(&mut self, n: usize) {
        if RETAINED.contains(&n) {
            if let Some(k) = self.known.get_mut(n - RETAINED.start()) {
                *k = true;
            }
        } else if n >= SYSTEM {
            self.set_system.insert(n);
        }
    }

    /// A condition read `unknown` first (a value the dry run does not know) and
    /// `shared` first (a variable the machine may change).
    pub(super) fn tested(
        &mut self,
        unknown: Option<usize>,
        shared: Option<usize>,
        line: u32,
        step: u64,
    ) {
        if let Some(var) = unknown {
            self.first_decision.get_or_insert((var, line));
        }
        if let Some(var) = shared {
            self.last_shared_test = Some((var, line, step));
        }
    }

    /// Whether the run, stopped by its step budget at `step`, was waiting on the
    /// machine: the variable and the line of the condition that tests it.
    pub(super) fn waiting(&self, step: u64) -> Option<(usize, u32)> {
        let (var, line, at) = self.last_shared_test?;
        (step.saturating_sub(at) <= WAIT_WINDOW).then_some((var, line))
    }
}

impl Interp<'_, '_> {
    /// Evaluates a branch or loop condition; when it read a machine value,
    /// remembers that the branch depends on the machine.
    pub(super) fn eval_condition(&mut self, p: &Program, id: ExprId) -> Result<Val, Diagnostic> {
        let (v, (unknown, shared)) = self.eval_reading(p, id);
        let (line, step) = (self.cur_line, self.steps);
        self.machine_vars.tested(unknown, shared, line, step);
        v
    }

    /// The words that say an outcome depends on the machine, if it does.
    pub(super) fn machine_dependence(&self) -> Option<String> {
        let (var, line) = self.machine_vars.first_decision?;
        Some(format!(
            "the branch on line {} read #{var}, {}, whose value this dry run does not know (read as vacant); give it in a variable file (--var-file) to decide",
            line + 1,
            describe(var)
        ))
    }
}

/// What kind of machine variable `#n` is, for messages.
pub(super) fn describe(n: usize) -> &'static str {
    if RETAINED.contains(&n) {
        "a common variable kept in the machine (#500–#999)"
    } else {
        "a system variable the machine sets"
    }
}
