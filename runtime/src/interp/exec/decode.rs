//! Decode: one block into the steps it runs, in its dialect's order of execution.
//!
//! `exec_block` reads the block's items (O-word statements, FANUC/ServoWorks macro
//! statements, words, comments, RS274/NGC assignments) into [`Words`]; `exec_words`
//! then runs the steps in order: comments, state checks, units, spindle and feed,
//! M codes (before the move except on ServoWorks), modal G groups, compensation, tool
//! length, coordinate system, calls, one-shot codes, motion, stops. This is where the
//! executor branches on the dialect's order; the steps themselves live in the
//! sibling modules.

use analyzer::syntax::{Block, Item};

use super::flow::macro_args;
use super::messages::rs274_parameter_message;
use super::*;
use crate::rules::{
    after_end::AFTER_END, coord_during_rotation::COORD_DURING_ROTATION, flow::FLOW, interp::INTERP,
    sub_not_found::SUB_NOT_FOUND, unknown_code::UNKNOWN_CODE, vacant_word::VACANT_WORD,
};

impl Interp<'_, '_> {
    pub(super) fn exec_block(&mut self, fi: usize, bi: u32) -> Result<Flow, Diagnostic> {
        let prog = self.files[fi].prog.clone();
        let Some(block) = prog.blocks.get(bi as usize).copied() else {
            return Ok(Flow::Next);
        };
        self.cur_line = block.line;
        self.st.line = block.line + 1;
        if let Some(c) = self.canon.as_mut() {
            c.line_number = None;
        }
        match block.kind {
            BlockKind::Normal => {}
            BlockKind::Percent => {
                if self.ngc() && fi == 0 && self.percent_open && self.seen_content_before(&prog, bi)
                {
                    self.saw_end = true;
                    self.canon("FINISH()");
                    return Ok(Flow::Stop);
                }
                if self.ngc()
                    && fi == 0
                    && !self.percent_open
                    && self.seen_content_before(&prog, bi)
                {
                    // Only a file that opens with `%` may close with one; elsewhere
                    // rs274 reads `%` as a bad character.
                    return Err(self.err(&INTERP, block.span, "Bad character '%' used"));
                }
                if self.dialect == Dialect::Fanuc && fi == 0 && self.seen_code_before(&prog, bi) {
                    self.saw_end = true;
                    return Ok(Flow::Stop);
                }
                return Ok(Flow::Next);
            }
            BlockKind::Deleted | BlockKind::Ignored => return Ok(Flow::Next),
        }
        if block.skip().is_some() && self.cfg.block_skip {
            return Ok(Flow::Next);
        }
        // RS274/NGC and FANUC stop at a block they cannot read; the parser
        // already reported why (ServoWorks skips unknown data).
        if self.dialect != Dialect::Servoworks
            && !self.files[fi].error_blocks.is_empty()
            && self.files[fi].error_blocks.contains(&bi)
        {
            if self.ngc() && self.canon.is_some() && self.out.canon_error.is_none() {
                let line = self.line_text(fi, bi);
                if let Some(msg) = rs274_parameter_message(&line) {
                    self.out.canon_error = Some(format!("{msg}\n{line}"));
                }
            }
            self.stopped_at_block(
                fi,
                bi,
                "the control cannot read this block (the syntax error on this line)",
            );
            return Ok(Flow::Stop);
        }
        let items = prog.items_of(&block);
        if items.is_empty() {
            return Ok(Flow::Next);
        }
        self.spec_items(&prog, items);
        // A bare O-word line (program title, M98 target) does nothing, not even its comments.
        if self.ngc()
            && items
                .iter()
                .any(|it| matches!(&it.kind, ItemKind::OWord(ow) if ow.keyword.is_none()))
        {
            return Ok(Flow::Next);
        }
        // O-word statements (RS274/NGC) own their block.
        if let Some((ow, span)) = items.iter().find_map(|it| match &it.kind {
            ItemKind::OWord(ow) if ow.keyword.is_some() => Some((*ow, it.span)),
            _ => None,
        }) {
            return self.exec_oword(fi, bi, &prog, ow, span);
        }
        // Macro statements and assignments in FANUC/ServoWorks run in order.
        if !self.ngc() {
            let mut skip_next = false;
            let mut has_words = false;
            for (k, it) in items.iter().enumerate() {
                if skip_next {
                    skip_next = false;
                    continue;
                }
                match &it.kind {
                    ItemKind::Assign { target, value } => {
                        let (v, (unknown, _)) = self.eval_reading(&prog, *value);
                        let v = v?;
                        let tainted = self.taint.last.get();
                        self.assign(&prog, *target, v, it.span, tainted, unknown)?;
                    }
                    ItemKind::Macro(m) => match *m {
                        MacroStmt::IfThen { cond } => {
                            let c = self.eval_condition(&prog, cond)?;
                            self.note_tainted_branch(it.span);
                            if c.unwrap_or(0.0) == 0.0 {
                                skip_next = true;
                            }
                            let _ = k;
                        }
                        MacroStmt::Goto { target } => {
                            let n = self.eval_num(&prog, target)?;
                            return self.goto_seq(fi, bi, n, it.span);
                        }
                        MacroStmt::IfGoto { cond, target } => {
                            let c = self.eval_condition(&prog, cond)?;
                            self.note_tainted_branch(it.span);
                            if c.unwrap_or(0.0) != 0.0 {
                                let n = self.eval_num(&prog, target)?;
                                return self.goto_seq(fi, bi, n, it.span);
                            }
                        }
                        MacroStmt::While { cond, .. } => {
                            let c = self.eval_condition(&prog, cond)?;
                            self.note_tainted_branch(it.span);
                            if c.unwrap_or(0.0) == 0.0 {
                                let Some(end) = self.files[fi].loops.get(&bi).copied() else {
                                    return Err(self.err(
                                        &FLOW,
                                        it.span,
                                        "WHILE … DO has no matching END (PS0124)",
                                    ));
                                };
                                return Ok(Flow::Goto(fi, end + 1));
                            }
                        }
                        MacroStmt::Do { .. } => {}
                        MacroStmt::End { .. } => {
                            let Some(head) = self.files[fi].loops.get(&bi).copied() else {
                                return Err(self.err(
                                    &FLOW,
                                    it.span,
                                    "END has no matching DO (PS0126)",
                                ));
                            };
                            return Ok(Flow::Goto(fi, head));
                        }
                        MacroStmt::Output => {}
                    },
                    ItemKind::Word(_) => has_words = true,
                    _ => {}
                }
            }
            if !has_words {
                return Ok(Flow::Next);
            }
        }
        // The words of the last block are emptied and refilled: their lists keep
        // their buffers, so a block allocates nothing for its words.
        let mut w = self.block_words.take().unwrap_or_default();
        w.clear();
        let r = self.exec_block_words(fi, bi, &prog, block, items, &mut w);
        self.block_words = Some(w);
        r
    }

    /// The rest of `exec_block` once the block's words are read into `w`.
    fn exec_block_words(
        &mut self,
        fi: usize,
        bi: u32,
        prog: &Program,
        block: Block,
        items: &[Item],
        w: &mut Words,
    ) -> Result<Flow, Diagnostic> {
        let mut comments: Vec<(CommentKind, Span)> = Vec::new();
        let mut assigns: Vec<(ExprId, Val, Span, bool)> = Vec::new();
        for it in items {
            match &it.kind {
                ItemKind::Word(word) => {
                    let mut machine_value = None;
                    let val = match word.value {
                        WordValue::Num(n) => Some(n.value),
                        WordValue::Expr(e) => {
                            let (v, (unknown, _)) = self.eval_reading(prog, e);
                            machine_value = unknown;
                            v?
                        }
                        WordValue::Name(s) => {
                            w.pname = Some(prog.str_of(s).into_owned());
                            None
                        }
                        WordValue::Missing => None,
                    };
                    let point = word.num().is_none_or(|n| n.has_point);
                    if word.letter == b'F' && !word.comma {
                        // A feed from a machine value (`F#650`): the dry run cannot
                        // know it, so a zero feed after it is no certain alarm.
                        self.mark_taint(|| "F".into(), val.is_none() && machine_value.is_some());
                    }
                    let Some(val) = val else {
                        // FANUC/ServoWorks: a vacant value drops the word (FAN141);
                        // a machine value the dry run does not know is not vacant.
                        if !self.ngc()
                            && matches!(word.value, WordValue::Expr(_))
                            && machine_value.is_none()
                        {
                            let letter = word.letter as char;
                            self.diag(&VACANT_WORD, Severity::Warning, it.span, format!("the value of {letter} is vacant (an unset variable): the control omits the whole {letter} word; set the variable or leave the word out"));
                        }
                        continue;
                    };
                    match word.letter {
                        b'G' => match analyzer::dialect::CodeNum::from_value(val) {
                            Some(c) => w.push_g(c.0, it.span),
                            None => {
                                return Err(self.err(
                                    &UNKNOWN_CODE,
                                    it.span,
                                    format!("G{val} is not a G code"),
                                ))
                            }
                        },
                        b'M' => {
                            // LinuxCNC reads M as an integer within 0.0001 of a whole
                            // number (read_integer_value), so `M3.00005` is M3.
                            let val = if self.ngc() && (val - val.round()).abs() < 1e-4 {
                                val.round()
                            } else {
                                val
                            };
                            if val < 0.0 || val.fract().abs() > 1e-6 {
                                return Err(self.err(
                                    &UNKNOWN_CODE,
                                    it.span,
                                    format!("M{val} is not an M code"),
                                ));
                            }
                            w.m.push(((val * 10.0).round() as u32, it.span));
                        }
                        b'N' => {
                            w.n = Some(val as i64);
                            w.n_span = word.num().map(|n| n.span);
                        }
                        b'O' => {}
                        // A G7x profile may use U and W (relative X and Z).
                        c @ (b'U' | b'V' | b'W')
                            if self.ngc()
                                && !self.input.settings.axes.contains(&(c as char))
                                && !(self.g7x_capturing() && c != b'V') =>
                        {
                            return Err(self.err(
                                &INTERP,
                                it.span,
                                format!(
                                    "bad character '{}' used: this machine has no {} axis",
                                    (c as char).to_ascii_lowercase(),
                                    c as char
                                ),
                            ));
                        }
                        b'@' => w.polar_r = Some(val),
                        b'^' => w.polar_a = Some(val),
                        c @ b'A'..=b'Z' if !word.comma => {
                            // ServoWorks uses the first of duplicated words (§1.4).
                            if self.dialect == Dialect::Servoworks && w.has(c) {
                                continue;
                            }
                            w.set_word(c, val, it.span, point);
                            // The written order of G65/G66 arguments (FANUC and
                            // ServoWorks macro calls; RS274/NGC has none).
                            if !self.ngc()
                                && matches!(
                                    c,
                                    b'I' | b'J'
                                        | b'K'
                                        | b'A'
                                        | b'B'
                                        | b'C'
                                        | b'D'
                                        | b'E'
                                        | b'F'
                                        | b'H'
                                        | b'M'
                                        | b'Q'
                                        | b'R'
                                        | b'S'
                                        | b'T'
                                        | b'U'
                                        | b'V'
                                        | b'W'
                                        | b'X'
                                        | b'Y'
                                        | b'Z'
                                )
                            {
                                w.ijk_order.push((c, val));
                            }
                        }
                        _ => {}
                    }
                }
                ItemKind::Comment(k) => comments.push((*k, it.span)),
                ItemKind::Assign { target, value } if self.ngc() => {
                    let v = self.eval(prog, *value)?;
                    assigns.push((*target, v, it.span, self.taint.last.get()));
                }
                _ => {}
            }
        }
        // Canonical output reproduces rs274, which refuses the whole line before
        // running any of it (the static rules report these in every other mode).
        if self.ngc() && self.canon.is_some() {
            self.check_ngc_codes(w)?;
        }
        // RS274/NGC: parameters are set after the whole line was read.
        for (t, v, s, tainted) in assigns {
            self.assign(prog, t, v, s, tainted, None)?;
        }
        if let Some(c) = self.canon.as_mut() {
            c.line_number = n_text(prog, w);
        }
        if self.st.ended {
            if !self.after_end_reported {
                self.after_end_reported = true;
                self.diag(
                    &AFTER_END,
                    if self.dialect == Dialect::Fanuc {
                        // An operator may start there (cursor, sequence-number search).
                        Severity::Info
                    } else {
                        Severity::Warning
                    },
                    block.span,
                    "code after the program end is never executed",
                );
            }
            return Ok(Flow::Stop);
        }
        w.raw_k = w.get(b'K');
        self.scale_words(w);
        // A G7x profile block only adds to the profile; LinuxCNC reads it
        // without executing any of its other words.
        if self.g7x_capturing() {
            self.g7x_profile_block(w, block.span)?;
            return Ok(Flow::Next);
        }
        self.inv_rate_set = false;
        let before = (self.out.motions.len(), self.st.tlo);
        let flow = self.exec_words(fi, bi, prog, w, &comments, block.span)?;
        self.refresh_after_tool_change(w, before);
        Ok(flow)
    }

    /// rs274's checks of a line's G and M codes: unknown codes, two codes of one
    /// modal group, user M codes (M100-M199) without a program to run.
    pub(super) fn check_ngc_codes(&self, w: &Words) -> Result<(), Diagnostic> {
        use analyzer::dialect::{lookup, CodeNum};
        let custom = |letter: char, n: u32| {
            self.input.settings.custom_codes.iter().any(|c| {
                let c = c.trim();
                c.len() > 1
                    && c[..1].eq_ignore_ascii_case(&letter.to_string())
                    && c[1..]
                        .parse::<f64>()
                        .is_ok_and(|v| (v * 10.0).round() as u32 == n)
            })
        };
        let mut seen: Vec<(char, u8, u32)> = Vec::new();
        for (letter, list) in [('G', w.g()), ('M', &w.m)] {
            for (n, span) in list.iter().copied() {
                if custom(letter, n) {
                    continue;
                }
                let info = lookup(Dialect::Rs274ngc, letter, CodeNum(n));
                let user_m = letter == 'M' && (1000..=1990).contains(&n);
                let Some(info) = info.filter(|_| !user_m) else {
                    let msg = if letter == 'G' {
                        "Unknown g code used".to_string()
                    } else {
                        format!("Unknown m code used: M{}", n / 10)
                    };
                    return Err(self.err(&UNKNOWN_CODE, span, msg));
                };
                let Some(group) = info.group else { continue };
                if let Some(&(_, _, other)) =
                    seen.iter().find(|(l, g, _)| *l == letter && *g == group)
                {
                    // rs274 lets G80 share a line with another motion code.
                    if letter == 'G' && group == 1 && (other == 800 || n == 800) {
                        continue;
                    }
                    let msg = if letter == 'G' {
                        "Two g codes used from same modal group"
                    } else {
                        "Two m codes used from same modal group"
                    };
                    return Err(self.err(&UNKNOWN_CODE, span, msg));
                }
                seen.push((letter, group, n));
            }
        }
        Ok(())
    }

    pub(super) fn seen_content_before(&self, p: &Program, bi: u32) -> bool {
        p.blocks
            .iter()
            .take(bi as usize)
            .any(|b| b.kind == BlockKind::Normal && !p.items_of(b).is_empty())
    }

    /// Whether a block before `bi` holds more than comments: on FANUC, comment
    /// lines before the first `%` are tape leader (a `(partscope: dialect=…)`
    /// line, a title), so that `%` opens the program instead of ending it.
    pub(super) fn seen_code_before(&self, p: &Program, bi: u32) -> bool {
        p.blocks.iter().take(bi as usize).any(|b| {
            b.kind == BlockKind::Normal
                && p.items_of(b)
                    .iter()
                    .any(|i| !matches!(i.kind, ItemKind::Comment(_)))
        })
    }

    /// FANUC decimal-point rules and ServoWorks integer machine units.
    pub(super) fn scale_words(&self, w: &mut Words) {
        let dist = b"XYZABCUVWIJKRQ";
        match self.dialect {
            Dialect::Fanuc if !self.cfg.decimal_point_input => {
                let inc = if self.st.modal.inch { 0.0001 } else { 0.001 };
                for &c in dist {
                    if w.has(c) && !w.point[(c - b'A') as usize] {
                        if c == b'Q' && w.has_g(760) {
                            continue;
                        }
                        w.map(c, |v| v * inc);
                    }
                }
            }
            Dialect::Servoworks if self.cfg.integer_machine_unit => {
                let mu = self.cfg.machine_unit / if self.st.modal.inch { 25.4 } else { 1.0 };
                for &c in dist {
                    if w.has(c) && !w.point[(c - b'A') as usize] {
                        w.map(c, |v| v * mu);
                    }
                }
            }
            Dialect::Rs274ngc => {
                // G7: rs274 halves X words as it reads them (G7/G8 in the block
                // itself take effect for its own X word).
                let diameter = if w.has_g(70) {
                    true
                } else if w.has_g(80) {
                    false
                } else {
                    self.st.modal.diameter
                };
                if diameter {
                    w.map(b'X', |v| v / 2.0);
                }
            }
            _ => {}
        }
    }

    pub(super) fn lin(&self, v: f64) -> f64 {
        v * self.unit()
    }

    /// The G codes that change how the block's own words read: units, spindle
    /// speed mode and feed mode.
    fn exec_g_before_words(&mut self, w: &Words) {
        // Units first so that every word of the block is read in them.
        if w.has_g(200) || w.has_g(210) {
            self.switch_units(w.has_g(200));
        }
        // G96/G97.
        if w.has_g(960) {
            self.st.modal.css = true;
            let d = w.get(b'D').map(|v| self.lin(v)).unwrap_or(0.0);
            canon!(self, "SET_SPINDLE_MODE(0 {})", f4(d / self.unit()));
        }
        if w.has_g(970) {
            self.st.modal.css = false;
            self.canon("SET_SPINDLE_MODE(0 0.0000)");
        }
        // Feed mode.
        for (code, text, mode) in [
            (930u32, "inverse time", 0),
            (940, "units per minute", 0),
            (950, "units per revolution", 1),
        ] {
            if w.has_g(code) {
                self.canon_comment(&format!("interpreter: feed mode set to {text}"));
                canon!(self, "SET_FEED_MODE(0, {mode})");
                self.st.modal.feed_mode = code;
                if code != 930 {
                    self.st.feed = 0.0;
                    self.canon("SET_FEED_RATE(0.0000)");
                }
            }
        }
    }

    /// The modal G codes after the M codes: dwell, plane, units, diameter mode,
    /// compensation, tool length, coordinate system, path and distance modes.
    fn exec_modal_g(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        // Modal G codes.
        if w.has_g(40) {
            self.exec_dwell(w)?;
        }
        if self.st.modal.rotation && [170u32, 180, 190].iter().any(|g| w.has_g(*g)) {
            let span = w
                .g()
                .iter()
                .find(|g| matches!(g.0, 170 | 180 | 190))
                .map(|g| g.1)
                .unwrap_or_default();
            self.diag(&COORD_DURING_ROTATION, Severity::Error, span, "the plane cannot be changed while coordinate rotation (G68) is on: cancel it with G69 first");
        }
        for (code, name, plane) in [
            (170u32, "CANON_PLANE_XY", 170u32),
            (180, "CANON_PLANE_XZ", 180),
            (190, "CANON_PLANE_YZ", 190),
        ] {
            if w.has_g(code) {
                self.st.modal.plane = plane;
                canon!(self, "SELECT_PLANE({name})");
            }
        }
        if w.has_g(200) || w.has_g(210) {
            let inch = w.has_g(200);
            self.st.modal.inch = inch;
            self.canon(if inch {
                "USE_LENGTH_UNITS(CANON_UNITS_INCHES)"
            } else {
                "USE_LENGTH_UNITS(CANON_UNITS_MM)"
            });
        }
        if ngc {
            for (code, on) in [(70u32, true), (80, false)] {
                if w.has_g(code) && self.st.modal.diameter != on {
                    self.st.modal.diameter = on;
                    self.canon_comment(if on {
                        "interpreter: Lathe diameter mode changed to diameter"
                    } else {
                        "interpreter: Lathe diameter mode changed to radius"
                    });
                }
            }
        }
        self.exec_comp(w)?;
        self.exec_tlo(w)?;
        self.exec_coord_select(w)?;
        if self.input.program.dialect == analyzer::Dialect::Servoworks {
            if w.has_g(401) {
                self.st.modal.ndc = None;
            } else if w.has_g(411) {
                self.st.modal.ndc = Some(true);
            } else if w.has_g(421) {
                self.st.modal.ndc = Some(false);
            }
            if w.has_g(3110) {
                self.st.modal.feed_linear_only = true;
            } else if w.has_g(3100) {
                self.st.modal.feed_linear_only = false;
            }
        }
        for (code, mode) in [(610u32, "CANON_EXACT_PATH"), (611, "CANON_EXACT_STOP")] {
            if w.has_g(code) {
                self.st.modal.path = code;
                canon!(self, "SET_MOTION_CONTROL_MODE({mode})");
            }
        }
        if w.has_g(640) {
            self.st.modal.path = 640;
            let pt = if ngc {
                w.get(b'P').map(|v| self.lin(v))
            } else {
                None
            };
            self.st.modal.path_tol = pt;
            let tol = pt.unwrap_or(0.0) / self.unit();
            let q = w.get(b'Q').unwrap_or(tol);
            self.naive_tol = q;
            canon!(self, "SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, {tol:.6})");
            canon!(self, "SET_NAIVECAM_TOLERANCE({})", f4(q));
        }
        for (code, abs) in [(901u32, true), (911, false)] {
            if w.has_g(code) {
                if self.st.modal.ijk_abs != abs {
                    self.canon_comment(if abs {
                        "interpreter: IJK distance mode changed to absolute"
                    } else {
                        "interpreter: IJK distance mode changed to incremental"
                    });
                }
                self.st.modal.ijk_abs = abs;
            }
        }
        if w.has_g(900) {
            if self.st.modal.incremental {
                self.canon_comment("interpreter: distance mode changed to absolute");
            }
            self.st.modal.incremental = false;
        }
        if w.has_g(910) {
            if !self.st.modal.incremental {
                self.canon_comment("interpreter: distance mode changed to incremental");
            }
            self.st.modal.incremental = true;
        }
        if w.has_g(980) {
            self.st.modal.retract_old_z = true;
            self.canon_comment("interpreter: retract mode set to old_z");
        }
        if w.has_g(990) {
            self.st.modal.retract_old_z = false;
            self.canon_comment("interpreter: retract mode set to r_plane");
        }
        Ok(())
    }

    pub(super) fn exec_words(
        &mut self,
        fi: usize,
        bi: u32,
        p: &Program,
        w: &Words,
        comments: &[(CommentKind, Span)],
        bspan: Span,
    ) -> Result<Flow, Diagnostic> {
        let ngc = self.ngc();
        self.block_exact = !ngc && w.has_g(90);
        // Comments and messages.  rs274 keeps only the last parenthesised comment
        // of a line.
        let skip = if ngc {
            let paren = |(_, s): &&(CommentKind, Span)| !p.str_of(*s).starts_with(';');
            comments.iter().filter(paren).count().saturating_sub(1)
        } else {
            0
        };
        let mut seen = 0;
        for (k, s) in comments {
            if ngc && !p.str_of(*s).starts_with(';') {
                seen += 1;
                if seen <= skip {
                    continue;
                }
            }
            self.exec_comment(p, *k, *s)?;
        }
        self.state_checks(w, bspan)?;
        if w.has_other_g() {
            self.exec_g_before_words(w);
        }
        if let Some(f) = w.get(b'F') {
            let u = if ngc {
                self.unit()
            } else if self.st.modal.inch {
                25.4
            } else {
                1.0
            };
            self.st.feed = if self.st.modal.feed_mode == 930 {
                f
            } else {
                f * u
            };
            if self.st.modal.feed_mode != 930 {
                canon!(self, "SET_FEED_RATE({})", f4(f));
            }
        }
        if let Some(s) = w.get(b'S') {
            self.st.spindle = s;
            canon!(self, "SET_SPINDLE_SPEED(0, {})", f4(s));
            if self.st.spindle_dir != 0 {
                let (rpm, dir) = (s, self.st.spindle_dir);
                self.event(EventKind::Spindle { rpm, dir });
            }
        }
        if let Some(t) = w.get(b'T') {
            let t = t.round().max(0.0) as u32;
            self.st.next_tool = t;
            self.check_tool(t, w.sp(b'T'))?;
            canon!(self, "SELECT_TOOL({t})");
            if self.dialect == Dialect::Servoworks {
                // ServoWorks changes the tool with the T word itself.
                self.st.tool = t;
                self.event(EventKind::ToolChange { tool: t });
            } else {
                self.event(EventKind::ToolSelect { tool: t });
            }
        }
        // Subprogram calls (FANUC/ServoWorks) are handled at the end of the block.
        let sw_m_after = self.dialect == Dialect::Servoworks;
        if !sw_m_after {
            self.exec_m_before(w)?;
        }
        if w.has_other_g() {
            self.exec_modal_g(w)?;
        }
        self.exec_fanuc_modes(w)?;
        // Subprogram call blocks (FANUC / ServoWorks): the motion in the block is ignored.
        if w.has_m(980) || (!ngc && w.has_g(650)) {
            return self.exec_call_words(fi, bi, w);
        }
        // G66 registers a modal macro call (arguments only in this block); G67 cancels it.
        if !ngc && w.has_g(670) {
            self.st.g66 = None;
        }
        if !ngc && w.has_g(660) {
            let Some(p) = w.get(b'P') else {
                return Err(self.err(
                    &SUB_NOT_FOUND,
                    w.g_span(660),
                    "G66 without P (macro number)",
                ));
            };
            self.st.g66 = Some((format!("{}", p.round() as i64), Arc::new(macro_args(w))));
            return self.exec_stops(w, fi);
        }
        // One-shot codes that consume axis words.
        let consumed = self.exec_modal0(w)?;
        // Motion.
        if !consumed {
            let before = self.out.motions.len();
            self.exec_motion(w, bspan)?;
            if let Some(left) = self.st.modal.ndc {
                self.ndc_after_motion(before, left);
            }
            // A G66 modal call runs the macro after each block that moves an axis.
            if let Some((name, args)) = self.st.g66.clone() {
                if w.any_axis() && !self.frames.iter().any(|f| f.modal_call) {
                    let span = w.g().first().map(|g| g.1).unwrap_or(bspan);
                    let flow = self.call_program(fi, bi, &name, 1, Some(args.to_vec()), span)?;
                    if let Some(f) = self.frames.last_mut() {
                        f.modal_call = true;
                    }
                    return Ok(flow);
                }
            }
        }
        if sw_m_after {
            self.exec_m_before(w)?;
        }
        // Stops and ends.
        self.exec_stops(w, fi)
    }
}

/// The block's N number as written, for the canon: its digits without spaces or a
/// fraction.
fn n_text(prog: &Program, w: &Words) -> Option<String> {
    match (w.n_span, w.n) {
        (Some(span), _) => Some(
            prog.str_of(span)
                .chars()
                .filter(|c| !c.is_whitespace())
                .take_while(|c| *c != '.')
                .collect(),
        ),
        (None, Some(n)) => Some(format!("{n}")),
        (None, None) => None,
    }
}
