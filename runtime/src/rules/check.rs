//! What a flow-sensitive rule's check sees and may change. The interpreter
//! builds one [`Cx`] per block, before any word of the block takes effect
//! (`interp/checks.rs` holds the ordered list of calls), from borrows of its own
//! fields: no allocation and no copy of the state. A check reads the state before
//! the block, the block's words and its motion; it writes only its own rule's
//! memory (a field of [`Memory`]) and diagnostics, and stops the block by
//! returning the error.
//!
//! The per-block checks are `#[inline(always)]` and these accessors `#[inline]`:
//! they run for every block but sit in other codegen units than the block loop,
//! where as calls they cost measurably more than the methods they replaced. Each
//! check has one call site, in the dispatch, so forcing it duplicates nothing.

use analyzer::rules::RuleMeta;
use analyzer::{Diagnostic, Dialect, FileId, Severity, Span, Variant};

use crate::interp::{MachineCfg, RunInput, State, Words};

use super::{
    arc_uvw_plane, comp_motion, context_restore, cycle_hygiene, feed_spindle_off, involute,
    no_effect, polar_interp, rapid_no_motion, rotary_only_feed, spindle_stopped, tlc_type,
    tool_offset_state, trc_lookahead, unknown_user_m,
};

/// Axis letters whose words (and bare letters) the checks look at.
pub(crate) const AXES: &[u8; 6] = b"XYZABC";

/// Group-01 codes that move (tenths), canned cycles aside.
#[inline]
pub(crate) fn is_feed_motion(g: u32) -> bool {
    matches!(g, 10 | 20 | 30)
}

/// Where a check's diagnostics go: the run's list, in the current file.
pub(crate) struct Sink<'c> {
    pub(crate) file: FileId,
    pub(crate) diags: &'c mut Vec<Diagnostic>,
}

impl Sink<'_> {
    #[inline]
    pub(crate) fn diag(
        &mut self,
        rule: &'static RuleMeta,
        sev: Severity,
        span: Span,
        msg: impl Into<String>,
    ) {
        self.diags
            .push(rule.diagnostic(sev, span, msg).in_file(self.file));
    }

    /// The error that stops the block (the caller reports it).
    #[inline]
    pub(crate) fn err(
        &self,
        rule: &'static RuleMeta,
        span: Span,
        msg: impl Into<String>,
    ) -> Diagnostic {
        rule.error(span, msg).in_file(self.file)
    }

    /// Removes the last diagnostic of `rule` at `span` in this file; false when there is none.
    pub(crate) fn withdraw(&mut self, rule: &RuleMeta, span: Span) -> bool {
        let file = self.file;
        match self
            .diags
            .iter()
            .rposition(|d| d.code == rule.code && d.span == span && d.file == file)
        {
            Some(j) => {
                self.diags.remove(j);
                true
            }
            None => false,
        }
    }
}

/// One block as the checks see it, before it runs.
pub(crate) struct Cx<'c, 'a> {
    /// The state before the block.
    pub(crate) st: &'c State,
    pub(crate) dialect: Dialect,
    pub(crate) variant: Variant,
    pub(crate) cfg: &'c MachineCfg,
    pub(crate) input: &'c RunInput<'a>,
    pub(crate) w: &'c Words,
    pub(crate) bspan: Span,
    /// The motion the block performs (`interp/checks.rs`: `block_motion`).
    pub(crate) motion: Option<(u32, Span)>,
    /// The call depth (frames on the stack).
    pub(crate) call_level: usize,
    /// Motions made before the innermost call, when in one.
    pub(crate) motions_at_call: Option<usize>,
    /// Motions made so far, streamed ones included.
    pub(crate) motions_made: usize,
    /// Motions still in the run's buffer (the look-ahead count compares these).
    pub(crate) motions_buffered: usize,
    /// File index and block being run.
    pub(crate) cur: (usize, u32),
    /// A G5.2 NURBS block is open with control points.
    pub(crate) nurbs_open: bool,
    /// `$` words and bare axis letters of the block (`Interp::spec_items`).
    pub(crate) items: &'c BlockItems,
    pub(crate) out: Sink<'c>,
}

impl Cx<'_, '_> {
    #[inline]
    pub(crate) fn ngc(&self) -> bool {
        self.dialect == Dialect::Rs274ngc
    }

    /// Internal length units per program unit.
    #[inline]
    pub(crate) fn unit(&self) -> f64 {
        crate::interp::unit_of(self.ngc(), self.st.modal.inch)
    }

    #[inline]
    pub(crate) fn lin(&self, v: f64) -> f64 {
        v * self.unit()
    }

    #[inline]
    pub(crate) fn plane_axes(&self) -> (usize, usize) {
        self.st.modal.plane_axes()
    }

    #[inline]
    pub(crate) fn normal_axis(&self) -> usize {
        self.st.modal.normal_axis()
    }

    /// The end point of a straight move from the block's axis words.
    pub(crate) fn target(&self) -> [f64; 6] {
        crate::interp::target_of(self.st, self.ngc(), self.w)
    }

    /// The diameter of the tool in the spindle.
    pub(crate) fn tool_diameter(&self) -> f64 {
        crate::interp::tool_diameter_of(self.cfg, self.st, self.ngc(), None)
    }

    /// The block's motion mode for the RS274/NGC word checks: splines and NURBS
    /// are not in the motion list of `motion`, so an explicit code of theirs wins,
    /// and with no motion the modal one holds.
    #[inline]
    pub(crate) fn motion_mode(&self) -> u32 {
        self.w
            .g()
            .iter()
            .find(|g| matches!(g.0, 50..=52))
            .map(|g| g.0)
            .or(self.motion.map(|m| m.0))
            .unwrap_or(self.st.modal.motion)
    }

    /// Whether any motion has been produced (also those already streamed out).
    #[inline]
    pub(crate) fn any_motion(&self) -> bool {
        self.motions_made > 0
    }
}

/// Per-block lists the item pass fills before the words are read (the word
/// reader drops them).
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct BlockItems {
    /// `$` words (value, span).
    pub(crate) dollar: Vec<(f64, Span)>,
    /// Axis letters without a value.
    pub(crate) bare_axes: Vec<(u8, Span)>,
}

impl BlockItems {
    /// Applies `f` to the source spans (a rerun moves them).
    pub(crate) fn shift_spans(&mut self, f: impl Fn(Span) -> Span) {
        for (_, s) in &mut self.dollar {
            *s = f(*s);
        }
        for (_, s) in &mut self.bare_axes {
            *s = f(*s);
        }
    }
}

/// What the checks remember between blocks, one field per rule that remembers
/// anything; a checkpoint keeps it whole.
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Memory {
    pub(crate) tool_offset_state: tool_offset_state::Mem,
    pub(crate) comp_motion: comp_motion::Mem,
    pub(crate) cycle_hygiene: cycle_hygiene::Mem,
    pub(crate) no_effect: no_effect::Mem,
    /// A canned cycle has been given an R (FANUC: a later cycle without R then
    /// lost it to a cancel). C001 is reported by the cycle code of the executor
    /// (`interp/exec/cycles.rs`), which writes and reads this.
    pub(crate) cycle_r_seen: bool,
    pub(crate) unknown_user_m: unknown_user_m::Mem,
    pub(crate) rotary_only_feed: rotary_only_feed::Mem,
    pub(crate) arc_uvw_plane: arc_uvw_plane::Mem,
    pub(crate) polar_interp: polar_interp::Mem,
    pub(crate) involute: involute::Mem,
    pub(crate) tlc_type: tlc_type::Mem,
    pub(crate) trc_lookahead: trc_lookahead::Mem,
    pub(crate) context_restore: context_restore::Mem,
    pub(crate) feed_spindle_off: feed_spindle_off::Mem,
    pub(crate) rapid_no_motion: rapid_no_motion::Mem,
    pub(crate) spindle_stopped: spindle_stopped::Mem,
}

impl Memory {
    /// Applies `f` to the source spans remembered (a rerun moves them).
    pub(crate) fn shift_spans(&mut self, f: impl Fn(Span) -> Span) {
        if let Some(s) = self.tool_offset_state.t_unused.as_mut() {
            *s = f(*s);
        }
    }

    /// Moves the remembered motion count (a rerun changes how many motions
    /// came before).
    pub(crate) fn shift_motion_count(&mut self, d: i64) {
        let m = &mut self.trc_lookahead.motions_seen;
        *m = (*m as i64 + d).max(0) as usize;
    }
}
