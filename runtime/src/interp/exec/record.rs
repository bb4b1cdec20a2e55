//! Recording the values of the main file's expressions into a
//! [`ValueRecord`] (`interp/values.rs`) while they are evaluated, when the
//! host asked for it: every variable read, every computed expression and every
//! assignment target, under its block and span.

use std::cell::RefCell;

use super::*;
use crate::interp::values::ValueRecord;

/// The value record and the main-file block being evaluated.
struct Recorder<'s> {
    cell: &'s RefCell<ValueRecord>,
    block: u32,
    base: u32,
}

impl Recorder<'_> {
    fn note(&self, span: Span, v: Val) {
        // Empty spans are no expression of the text.
        if span.is_empty() || span.start < self.base {
            return;
        }
        if let Ok(mut r) = self.cell.try_borrow_mut() {
            r.record(self.block, span.start - self.base, span.end - self.base, v);
        }
    }
}

/// A variable source that records what it reads.
struct Recording<'s, 'v> {
    inner: &'v dyn VarSource,
    rec: Recorder<'s>,
}

impl VarSource for Recording<'_, '_> {
    fn get_num(&self, n: i64, span: Span) -> Result<Val, EvalError> {
        let v = self.inner.get_num(n, span)?;
        self.rec.note(span, v);
        Ok(v)
    }
    fn get_named(&self, name: &str, span: Span) -> Result<Val, EvalError> {
        let v = self.inner.get_named(name, span)?;
        self.rec.note(span, v);
        Ok(v)
    }
    fn named_exists(&self, name: &str) -> bool {
        self.inner.named_exists(name)
    }
}

impl Interp<'_, '_> {
    /// Where values of `p`'s expressions go: only the main file's, and only
    /// when the host asked for them.
    fn recorder(&self, p: &Program) -> Option<Recorder<'_>> {
        let cell = self.values.as_ref()?;
        if self.cur.0 != 0 || !std::ptr::eq(p, self.input.program) {
            return None;
        }
        let block = self.cur.1;
        let base = p.blocks.get(block as usize)?.span.start;
        Some(Recorder { cell, block, base })
    }

    /// `expr::eval`, recording the values when asked to.
    pub(super) fn eval_recorded(
        &self,
        p: &Program,
        id: ExprId,
        vars: &dyn VarSource,
    ) -> Result<Val, EvalError> {
        let Some(rec) = self.recorder(p) else {
            return expr::eval(p, id, self.dialect, vars, 0);
        };
        let node = p.expr(id);
        let recording = Recording { inner: vars, rec };
        let v = expr::eval(p, id, self.dialect, &recording, 0)?;
        // Literals say their value; variable reads were recorded as they were read.
        if !matches!(
            node.expr,
            Expr::Num(_) | Expr::Var { .. } | Expr::Named { .. }
        ) {
            recording.rec.note(node.span, v);
        }
        Ok(v)
    }

    /// Records the value an assignment gives its target (as the target then holds it).
    pub(super) fn record_assigned(&self, p: &Program, target: ExprId, v: Val) {
        if let Some(r) = self.recorder(p) {
            let v = if self.ngc() {
                Some(v.unwrap_or(0.0))
            } else {
                v
            };
            r.note(p.expr(target).span, v);
        }
    }
}
