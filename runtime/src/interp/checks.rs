//! Every call of a flow-sensitive rule's check, in the order they run and
//! report (diagnostic order is output): the checks of a block against the state
//! before it (`state_checks`), the
//! pass over its items (`spec_items`), the input files, loaded subprograms and
//! the program end. Each check is a function in its rule's file
//! (`crate::rules::<rule>`); the per-block ones take a `rules::check::Cx`, built
//! here once per block from borrows of the interpreter's fields. A new runtime
//! rule adds its line here.

use analyzer::syntax::{Expr, Item};

use super::*;
use crate::rules::check::{Cx, Memory, Sink, AXES};
use crate::rules::{
    arc_uvw_plane, arc_words, comp_conflict, comp_motion, context_restore, coordinate_mode,
    cycle_hygiene, cycle_still_active, feed_spindle_off, inverse_time, involute, lathe_cycle,
    mode_left_on, no_effect, nurbs_block, offset_number, polar_interp, probe_state,
    rapid_no_motion, rigid_tap_feed, rotary_only_feed, scaling_magnification, smoothing_time,
    spindle_stopped, subprogram_file, thread_lead, tlc_type, tool_offset_state, tool_table,
    trc_lookahead, unknown_user_m, vacant_read, var_file, word_unused,
};

impl<'a> Interp<'a, '_> {
    /// The motion the block performs: an explicit group-01 code, or the modal
    /// one when the block has axis words and no code that consumes them.
    fn block_motion(&self, w: &Words) -> Option<(u32, Span)> {
        if let Some(&(g, s)) = w.g().iter().find(|(g, _)| moves_to_axis_words(*g)) {
            return Some((g, s));
        }
        // None of the codes that consume axis words is a motion code.
        let consumed = w.has_other_g()
            && [100u32, 280, 300, 920, 520, 650]
                .iter()
                .any(|g| w.has_g(*g));
        if w.any_axis() && !consumed && self.st.modal.motion != 800 {
            let span = w
                .g()
                .first()
                .map(|g| g.1)
                .unwrap_or_else(|| w.first_axis().map(|c| w.sp(c)).unwrap_or_default());
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
        spindle_stopped::check(cx, &mut mem.spindle_stopped)?;
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

    /// Modes a program should cancel before M2/M30.
    pub(super) fn end_checks(&mut self, span: Span) {
        let mut out = Sink {
            file: self.file_id(),
            diags: &mut self.out.diagnostics,
        };
        mode_left_on::check(&self.st, self.dialect, span, &mut out);
    }
}

impl Interp<'_, '_> {
    /// Runs once before the first block: the tool table and `.var` file the host read.
    pub(super) fn spec_input_files(&mut self) {
        let mut out = Sink {
            file: self.file_id(),
            diags: &mut self.out.diagnostics,
        };
        if let Some(t) = self.input.tool_table {
            tool_table::check(t, &mut out);
        }
        if let Some(v) = self.input.var_file {
            var_file::check(v, &mut out);
        }
    }

    /// ServoWorks: a subprogram file that was just loaded for `M98 P<name>`.
    pub(super) fn spec_file_loaded(&mut self, idx: usize, name: &str) {
        if self.dialect != Dialect::Servoworks {
            return;
        }
        let Some(file) = self.files.get(idx) else {
            return;
        };
        let mut out = Sink {
            file: file.id,
            diags: &mut self.out.diagnostics,
        };
        subprogram_file::check(&file.prog, name, &mut out);
    }

    /// Runs on the items of a block before any of it executes: variable reads.
    pub(super) fn spec_items(&mut self, prog: &Program, items: &[Item]) {
        self.items.dollar.clear();
        self.items.bare_axes.clear();
        for it in items {
            match &it.kind {
                ItemKind::Word(wd) => {
                    if wd.letter == b'$' {
                        let v = match wd.value {
                            WordValue::Num(n) => n.value,
                            _ => 0.0,
                        };
                        self.items.dollar.push((v, it.span));
                    }
                    if matches!(wd.value, WordValue::Missing) && AXES.contains(&wd.letter) {
                        self.items.bare_axes.push((wd.letter, it.span));
                    }
                    if let WordValue::Expr(e) = wd.value {
                        self.vacant_reads(prog, e);
                    }
                }
                // A plain copy (`#10 = #1`) passes the vacancy on and computes nothing.
                ItemKind::Assign { value, .. } if plain_var(prog, *value) => {}
                ItemKind::Assign { value, .. } => self.vacant_reads(prog, *value),
                _ => {}
            }
        }
        self.spec_comma_words(items);
    }

    /// Reports reads of vacant variables in `e` (`rules::vacant_read`).
    fn vacant_reads(&mut self, prog: &Program, e: ExprId) {
        let (frames, files, machine_vars) = (&self.frames, &self.files, &self.machine_vars);
        let mut reads = vacant_read::Reads {
            dialect: self.dialect,
            params: &self.st.params,
            machine_value: &|k| machine_vars.unknown_origin(k, false).is_some(),
            // In a G65/G66 macro a local is an argument the caller may leave
            // out: it reads as 0 in arithmetic, which macros rely on.
            macro_level: &|| {
                frames.last().is_some_and(|f| f.saved.is_some())
                    // A main program that returns with M99 is a macro checked alone.
                    || (frames.iter().all(|f| f.saved.is_none())
                        && files.first().is_some_and(|f| f.returns))
            },
            out: Sink {
                file: self.files.get(self.cur.0).map(|f| f.id).unwrap_or_default(),
                diags: &mut self.out.diagnostics,
            },
        };
        reads.check(prog, e, false);
    }

    /// FANUC: optional chamfer / corner R in involute or polar mode (`rules::involute`).
    fn spec_comma_words(&mut self, items: &[Item]) {
        if self.dialect != Dialect::Fanuc {
            return;
        }
        let mut out = Sink {
            file: self.file_id(),
            diags: &mut self.out.diagnostics,
        };
        involute::comma_words(items, &self.st, &self.rules.polar_interp, &mut out);
    }
}

/// `#n` with a literal number, in any brackets.
fn plain_var(prog: &Program, e: ExprId) -> bool {
    prog.variable_index(e)
        .is_some_and(|i| matches!(prog.expr(i).expr, Expr::Num(_)))
}
