//! The rule checks of a block, in the order they run and report (diagnostic
//! order is output). Each check is a function in its rule's file
//! (`crate::rules::<rule>`) over a `rules::check::Cx`, built here once per block
//! from borrows of the interpreter's fields; a new runtime rule adds its line here.

use super::*;
use crate::rules::check::{BlockItems, Cx, Memory, Sink};
use crate::rules::{
    arc_uvw_plane, arc_words, comp_conflict, comp_motion, context_restore, coordinate_mode,
    cycle_hygiene, cycle_still_active, feed_spindle_off, inverse_time, involute, lathe_cycle,
    mode_left_on, no_effect, nurbs_block, offset_number, polar_interp, probe_state,
    rapid_no_motion, rigid_tap_feed, rotary_only_feed, scaling_magnification, smoothing_time,
    spindle_stopped, thread_lead, tlc_type, tool_offset_state, trc_lookahead, unknown_user_m,
    word_unused,
};

impl<'a> Interp<'a, '_> {
    /// The motion the block performs: an explicit group-01 code, or the modal
    /// one when the block has axis words and no code that consumes them.
    fn block_motion(&self, w: &Words) -> Option<(u32, Span)> {
        if let Some(&(g, s)) = w.g.iter().find(|(g, _)| moves_to_axis_words(*g)) {
            return Some((g, s));
        }
        let consumed = [100u32, 280, 300, 920, 520, 650]
            .iter()
            .any(|g| w.has_g(*g));
        if w.any_axis() && !consumed && self.st.modal.motion != 800 {
            let span = w.g.first().map(|g| g.1).unwrap_or_else(|| {
                b"XYZABCUVW"
                    .iter()
                    .find(|c| w.has(**c))
                    .map(|c| w.sp(*c))
                    .unwrap_or_default()
            });
            return Some((self.st.modal.motion, span));
        }
        None
    }

    /// The block as the checks see it, and the checks' memory.
    fn check_cx<'c>(
        &'c mut self,
        w: &'c Words,
        bspan: Span,
        motion: Option<(u32, Span)>,
    ) -> (Cx<'c, 'a>, &'c mut Memory) {
        let file = self.file_id();
        let cx = Cx {
            st: &self.st,
            dialect: self.dialect,
            variant: self.variant,
            cfg: &self.cfg,
            input: self.input,
            w,
            bspan,
            motion,
            call_level: self.frames.len(),
            motions_at_call: self.frames.last().map(|f| f.motions_at_call),
            motions_made: self.motions_drained + self.out.motions.len(),
            motions_buffered: self.out.motions.len(),
            cur: self.cur,
            nurbs_open: !self.nurbs.is_empty(),
            items: &self.items,
            out: Sink {
                file,
                diags: &mut self.out.diagnostics,
            },
        };
        (cx, &mut self.rules)
    }

    /// Checks run before any word of the block takes effect.
    pub(super) fn state_checks(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let motion = self.block_motion(w);
        let (mut cx, mem) = self.check_cx(w, bspan, motion);
        let cx = &mut cx;
        comp_conflict::check(cx)?;
        inverse_time::check(cx)?;
        spindle_stopped::check(cx)?;
        cycle_hygiene::check(cx, &mut mem.cycle_hygiene)?;
        tool_offset_state::check(cx, &mut mem.tool_offset_state)?;
        coordinate_mode::check(cx)?;
        if let Err(stop) = comp_motion::check(cx, &mut mem.comp_motion) {
            if stop.release_comp {
                self.comp_flush();
                self.canon_comment("interpreter: cutter radius compensation off");
            }
            return Err(stop.error);
        }
        probe_state::check(cx)?;
        arc_words::check(cx)?;
        no_effect::check(cx, &mut mem.no_effect);
        match cx.dialect {
            Dialect::Rs274ngc => {
                word_unused::check(cx)?;
                unknown_user_m::check(cx, &mut mem.unknown_user_m)?;
                context_restore::check(cx, &mut mem.context_restore)?;
                nurbs_block::check(cx)?;
                lathe_cycle::check(cx)?;
                arc_uvw_plane::check(cx, &mut mem.arc_uvw_plane)?;
                rapid_no_motion::check(cx, &mut mem.rapid_no_motion);
                feed_spindle_off::check(cx, &mut mem.feed_spindle_off);
                cycle_still_active::check(cx);
            }
            Dialect::Servoworks => {
                tlc_type::check(cx, &mut mem.tlc_type);
                smoothing_time::check(cx);
                rotary_only_feed::check(cx, &mut mem.rotary_only_feed);
            }
            Dialect::Fanuc => {
                let motion = involute::check(cx, &mut mem.involute);
                polar_interp::check(cx, &mut mem.polar_interp, motion);
                thread_lead::check(cx, motion);
                rigid_tap_feed::check(cx, motion);
                offset_number::check(cx);
                scaling_magnification::check(cx);
            }
        }
        trc_lookahead::check(cx, &mut mem.trc_lookahead);
        Ok(())
    }

    /// [`Self::state_checks`] reduced to what can act on a plain motion line of the
    /// fast path (`fast.rs`: RS274/NGC, only X/Y/Z/F numbers, a modal G0/G1, no cutter
    /// compensation, feed per minute, no diameter mode, no G66). Every other check
    /// needs a G/M code, another letter, or a state the fast path excludes; what
    /// remains, in the general order, is:
    /// - the block's motion (`block_motion`): the modal code, at the first axis word;
    /// - T003: Z after an M6 that kept the old tool's length offset;
    /// - T004: the first motion after G40 clears the flag (a line, so never an error);
    /// - the M70/M73 levels left by a return, feed with the spindle stopped (when
    ///   selected), and the look-ahead count.
    ///
    /// `runtime/tests/fast_path.rs` runs programs both ways and compares everything.
    pub(super) fn plain_motion_checks(&mut self, w: &Words, bspan: Span) {
        let span = [b'X', b'Y', b'Z']
            .iter()
            .find(|c| w.has(**c))
            .map(|c| w.sp(*c))
            .unwrap_or_default();
        let motion = Some((self.st.modal.motion, span));
        // No `$` words or bare letters on a plain line.
        let BlockItems { dollar, bare_axes } = &mut self.items;
        dollar.clear();
        bare_axes.clear();
        let (mut cx, mem) = self.check_cx(w, bspan, motion);
        let cx = &mut cx;
        tool_offset_state::plain_check(cx, &mut mem.tool_offset_state);
        comp_motion::plain_check(&mut mem.comp_motion);
        context_restore::plain_check(cx, &mut mem.context_restore);
        feed_spindle_off::plain_check(cx, &mut mem.feed_spindle_off);
        trc_lookahead::plain_check(cx, &mut mem.trc_lookahead);
    }

    /// Modes a program should cancel before M2/M30.
    pub(super) fn end_checks(&mut self, span: Span) {
        let mut out = Sink {
            file: self.file_id(),
            diags: &mut self.out.diagnostics,
        };
        mode_left_on::check(&self.st, self.dialect, span, &mut out);
    }
}
