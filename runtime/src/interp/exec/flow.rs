//! Flow and calls: RS274/NGC O-word statements (sub/call/return, if, while, do,
//! repeat, break, continue), FANUC/ServoWorks GOTO and M98/M99, G65 and G66 macro
//! calls with their argument frames, loading of called files through the resolver,
//! and the stops and ends (M0, M1, M2, M30, M99 at the top level).

use super::*;
use crate::rules::{
    after_end::AFTER_END, call_depth::CALL_DEPTH, flow::FLOW, interp::INTERP,
    sub_not_found::SUB_NOT_FOUND,
};

impl Interp<'_, '_> {
    pub(super) fn goto_seq(
        &mut self,
        fi: usize,
        bi: u32,
        n: f64,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        let blocks = self.files[fi]
            .seq
            .get(&(n.max(0.0) as u64))
            .cloned()
            .unwrap_or_default();
        // Search forward first, then from the top of the program.
        if let Some(b) = blocks.iter().find(|b| **b > bi).or(blocks.first()) {
            return Ok(Flow::Goto(fi, *b));
        }
        Err(self.err(
            &FLOW,
            span,
            format!("sequence number N{n} not found (PS0128)"),
        ))
    }

    pub(super) fn exec_oword(
        &mut self,
        fi: usize,
        bi: u32,
        p: &Program,
        ow: analyzer::syntax::OWord,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        let Some(kw) = ow.keyword else {
            return Ok(Flow::Next);
        };
        let ctrl = self.files[fi].ctrl.get(&bi).cloned().unwrap_or_default();
        let args: Vec<ExprId> = p.expr_list(ow.args()).to_vec();
        let cond = |s: &Self| -> Result<bool, Diagnostic> {
            match args.first() {
                Some(e) => {
                    let v = s.eval_num(p, *e)?;
                    s.note_tainted_branch(span);
                    Ok(v != 0.0)
                }
                None => Ok(false),
            }
        };
        let after = |b: Option<u32>| -> Result<u32, Diagnostic> {
            b.map(|b| b + 1).ok_or_else(|| {
                self.err(
                    &FLOW,
                    span,
                    format!("O-word `{}` has no matching end", kw.as_str()),
                )
            })
        };
        if self.ngc()
            && ctrl.partner.is_none()
            && matches!(
                kw,
                OKeyword::Endwhile
                    | OKeyword::Endrepeat
                    | OKeyword::Endif
                    | OKeyword::Else
                    | OKeyword::Elseif
            )
        {
            // rs274 finds no open block of that label when it reaches the closer.
            return Err(self.err(
                &FLOW,
                span,
                format!(
                    "{}: undefined O-word label: '{}'",
                    self.cur_line + 1,
                    self.line_text(fi, bi)
                ),
            ));
        }
        match kw {
            OKeyword::Sub => {
                // rs274 refuses a definition inside a definition while it skips over
                // the outer one, and names the inner `sub` line.
                let stop = ctrl.partner.unwrap_or(p.blocks.len() as u32);
                let nested = (bi + 1..stop).find(|b| {
                    p.blocks.get(*b as usize).is_some_and(|blk| {
                        p.items_of(blk).iter().any(|it| {
                            matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(OKeyword::Sub))
                        })
                    })
                });
                if let (true, Some(b)) = (self.ngc(), nested) {
                    self.cur = (fi, b);
                    let at = p.blocks.get(b as usize).map(|x| x.span).unwrap_or(span);
                    return Err(self.err(&FLOW, at, "Nested subroutine definition"));
                }
                if self.ngc() && fi == 0 && ctrl.partner.is_none() {
                    // rs274 skips the definition looking for its endsub and runs off
                    // the end of the file.
                    return Ok(Flow::Goto(fi, p.blocks.len() as u32));
                }
                // A definition met in flow is skipped.
                Ok(Flow::Goto(fi, after(ctrl.partner)?))
            }
            OKeyword::Endsub | OKeyword::Return => {
                let v = match args.first() {
                    Some(e) => Some(self.eval_num(p, *e)?),
                    None => None,
                };
                if self.frames.is_empty() {
                    if kw == OKeyword::Return {
                        return Err(self.err(&FLOW, span, "`return` outside a subroutine"));
                    }
                    return Ok(Flow::Next);
                }
                let named = Arc::make_mut(&mut self.st.named);
                named.insert("_value".into(), v.unwrap_or(0.0));
                named.insert(
                    "_value_returned".into(),
                    if v.is_some() { 1.0 } else { 0.0 },
                );
                let saved = self.frames.last_mut().and_then(|f| f.context.take());
                self.ret_from_sub(None);
                self.auto_restore(saved)?;
                Ok(Flow::Goto(self.cur.0, self.cur.1))
            }
            OKeyword::Call => {
                let mut vals = Vec::new();
                for a in &args {
                    vals.push(self.eval_num(p, *a)?);
                }
                let key = match ow.label {
                    OLabel::Expr(e) => Some(format!("{}", self.eval_num(p, e)?.round() as i64)),
                    _ => label_key(p, &ow),
                };
                let Some(key) = key else {
                    return Err(self.err(&FLOW, span, "call without a subroutine name"));
                };
                self.call_ngc(fi, bi, &key, vals, span)
            }
            OKeyword::While => {
                if ctrl.closes_do {
                    let head = ctrl.partner.unwrap_or(bi);
                    if std::mem::take(&mut self.pending_break) {
                        return Ok(Flow::Next);
                    }
                    return Ok(if cond(self)? {
                        Flow::Goto(fi, head + 1)
                    } else {
                        Flow::Next
                    });
                }
                if cond(self)? {
                    Ok(Flow::Next)
                } else {
                    Ok(Flow::Goto(fi, after(ctrl.partner)?))
                }
            }
            OKeyword::Endwhile => Ok(Flow::Goto(fi, ctrl.partner.unwrap_or(bi + 1))),
            OKeyword::Do => Ok(Flow::Next),
            OKeyword::Repeat => {
                let n = match args.first() {
                    Some(e) => {
                        let n = self.eval_num(p, *e)?.round() as i64;
                        self.note_tainted_branch(span);
                        n
                    }
                    None => 0,
                };
                if n <= 0 {
                    return Ok(Flow::Goto(fi, after(ctrl.partner)?));
                }
                self.repeats.push((fi, bi, n));
                Ok(Flow::Next)
            }
            OKeyword::Endrepeat => {
                let head = ctrl.partner.unwrap_or(bi);
                if let Some(top) = self
                    .repeats
                    .iter_mut()
                    .rev()
                    .find(|r| r.0 == fi && r.1 == head)
                {
                    top.2 -= 1;
                    if top.2 > 0 {
                        return Ok(Flow::Goto(fi, head + 1));
                    }
                }
                self.repeats.retain(|r| !(r.0 == fi && r.1 == head));
                Ok(Flow::Next)
            }
            OKeyword::If => {
                if cond(self)? {
                    return Ok(Flow::Next);
                }
                for b in &ctrl.branches {
                    let blk = p.blocks.get(*b as usize).copied();
                    let Some(blk) = blk else { continue };
                    let item = p.items_of(&blk).iter().find_map(|it| match it.kind {
                        ItemKind::OWord(o) => Some(o),
                        _ => None,
                    });
                    let Some(o) = item else { continue };
                    if o.keyword == Some(OKeyword::Else) {
                        return Ok(Flow::Goto(fi, b + 1));
                    }
                    let a = p.expr_list(o.args()).first().copied();
                    if let Some(a) = a {
                        let v = self.eval_num(p, a)?;
                        self.note_tainted_branch(blk.span);
                        if v != 0.0 {
                            return Ok(Flow::Goto(fi, b + 1));
                        }
                    }
                }
                Ok(Flow::Goto(fi, after(ctrl.partner)?))
            }
            OKeyword::Elseif | OKeyword::Else => Ok(Flow::Goto(fi, after(ctrl.partner)?)),
            OKeyword::Endif => Ok(Flow::Next),
            OKeyword::Break | OKeyword::Continue => {
                let Some(head) = ctrl.partner else {
                    return Err(self.err(&FLOW, span, format!("`{}` outside a loop", kw.as_str())));
                };
                let hc = self.files[fi].ctrl.get(&head).cloned().unwrap_or_default();
                let end = hc.partner.unwrap_or(head);
                let head_kw = |k: OKeyword| {
                    p.blocks.get(head as usize).is_some_and(|b| {
                        p.items_of(b)
                            .iter()
                            .any(|it| matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(k)))
                    })
                };
                let is_do = head_kw(OKeyword::Do);
                // LinuxCNC leaves a loop by skipping forward to its end, and a `break`
                // of the same loop met while skipping still runs (even inside a false
                // `if`).  Its flag is cleared only where a `do` loop closes, so a
                // break out of a while or repeat loop also ends the next do-while
                // after one pass.
                let breaks_ahead = (bi + 1..end).any(|b| {
                    self.files[fi].ctrl.get(&b).is_some_and(|c| c.partner == Some(head))
                        && p.blocks.get(b as usize).is_some_and(|blk| {
                            p.items_of(blk).iter().any(|it| matches!(it.kind, ItemKind::OWord(o) if o.keyword == Some(OKeyword::Break)))
                        })
                });
                if kw == OKeyword::Break || (is_do && breaks_ahead) {
                    self.repeats.retain(|r| !(r.0 == fi && r.1 == head));
                    if !is_do {
                        self.pending_break = true;
                    }
                    Ok(Flow::Goto(fi, end + 1))
                } else {
                    if breaks_ahead {
                        self.pending_break = true;
                    }
                    let is_repeat_or_do = is_do || head_kw(OKeyword::Repeat);
                    Ok(Flow::Goto(fi, if is_repeat_or_do { end } else { head }))
                }
            }
        }
    }

    pub(super) fn load_file(&mut self, name: &str, span: Span) -> Option<usize> {
        let key = name.to_ascii_lowercase();
        if let Some(i) = self.file_names.get(&key) {
            return Some(*i);
        }
        let from = self.file_id();
        let rf = self.input.resolver.resolve(name, from)?;
        let _ = span;
        let opts = analyzer::syntax::ParseOptions {
            dialect: self.dialect,
            variant: self.variant,
        };
        // The interpreter never reads tokens.
        let prog = analyzer::syntax::parse_lean(opts, rf.text.clone());
        let idx = self.files.len();
        // A file for another control is reported once, as such; its syntax errors
        // would be a flood about a language it is not written in.
        let foreign = analyzer::program_mismatch(&prog, self.input.settings);
        let reports = match &foreign {
            Some(d) => std::slice::from_ref(d),
            None => &prog.diagnostics[..],
        };
        for d in reports {
            self.out
                .diagnostics
                .push(d.clone().in_file(FileId(idx as u32)));
        }
        let mut entry = FileEntry::new(ProgRef::Shared(Arc::new(prog)), FileId(idx as u32));
        entry.foreign = foreign.is_some();
        self.files.push(entry);
        self.file_names.insert(key, idx);
        // Keep the resolved path for the output list.
        self.file_names.insert(rf.path.clone(), idx);
        self.file_names.remove(&rf.path);
        self.out.files.push(rf.path);
        self.spec_file_loaded(idx, name);
        Some(idx)
    }

    pub(super) fn depth_check(&self, span: Span) -> Result<(), Diagnostic> {
        if self.frames.len() >= self.cfg.max_depth {
            return Err(self.err(
                &CALL_DEPTH,
                span,
                format!("subprogram nesting deeper than {} levels (recursion?): the control alarms here", self.cfg.max_depth),
            ));
        }
        Ok(())
    }

    pub(super) fn call_ngc(
        &mut self,
        fi: usize,
        bi: u32,
        key: &str,
        vals: Vec<f64>,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        self.depth_check(span)?;
        let (tf, tb) = if let Some(b) = self.files[fi].subs.get(key).copied() {
            (fi, b)
        } else if let Some(b) = self.files[0].subs.get(key).copied() {
            (0, b)
        } else if let Some(f) = self.load_file(key, span) {
            match self.files[f].subs.get(key).copied() {
                Some(b) => (f, b),
                None => (f, u32::MAX),
            }
        } else {
            if let Some(why) = self.input.resolver.refused(key) {
                return Err(self.skip_call(Severity::Warning, span, refused_call(&why)));
            }
            if self.ngc() && self.canon.is_some() && self.out.canon_error.is_none() {
                // rs274 reads on to the end of the file looking for the definition
                // and shows the last line it read.
                let last = self.files[0]
                    .prog
                    .blocks
                    .iter()
                    .rev()
                    .map(|b| self.files[0].prog.str_of(b.span).trim().to_string())
                    .find(|t| !t.is_empty())
                    .unwrap_or_default();
                self.out.canon_error = Some(format!(
                    "EOF in file:{CANON_FILE_NAME} seeking o-word: o<{key}> from line: {}\n{last}",
                    self.cur_line + 1
                ));
            }
            if !self.input.resolver.searches_like_the_control() {
                // LinuxCNC would also look in PROGRAM_PREFIX and SUBROUTINE_PATH,
                // which nobody configured here: the file may well be on the machine.
                return Err(self.skip_call(
                    Severity::Info,
                    span,
                    format!("subroutine o<{key}> is not defined in this file and no file `{key}.ngc` was found beside it; LinuxCNC also searches its SUBROUTINE_PATH, so the dry run skips the call. Set machine.subroutine_path (or ini) to check the call"),
                ));
            }
            return Err(self.skip_call(Severity::Error, span, format!("subroutine o<{key}> is not defined in this file and no file `{key}.ngc` was found")));
        };
        // Save the caller's #1-#30 and pass the arguments.
        let saved: Vec<Option<f64>> = (1..=30)
            .map(|n| self.st.params.get(n).copied().flatten())
            .collect();
        for n in 1..=30usize {
            self.set_param(n, Some(vals.get(n - 1).copied().unwrap_or(0.0)));
        }
        Arc::make_mut(&mut self.st.named).remove("_value_returned");
        self.frames.push(Frame {
            kind: FrameKind::NgcSub,
            ret_file: fi,
            ret_block: bi + 1,
            saved: Some(saved),
            named_locals: HashMap::new(),
            call_span: span,
            modal_call: false,
            context: None,
            motions_at_call: self.motions_drained + self.out.motions.len(),
        });
        let start = if tb == u32::MAX { 0 } else { tb + 1 };
        Ok(Flow::Goto(tf, start))
    }

    /// Returns from the innermost frame; sets `self.cur`. `seq` is M99 P.
    pub(super) fn ret_from_sub(&mut self, seq: Option<f64>) -> bool {
        let Some(mut f) = self.frames.pop() else {
            return false;
        };
        if let FrameKind::Sub { start, repeat } = f.kind {
            if repeat > 1 {
                f.kind = FrameKind::Sub {
                    start,
                    repeat: repeat - 1,
                };
                let file = self.cur.0;
                self.frames.push(f);
                self.cur = (file, start);
                return true;
            }
        }
        if let Some(saved) = f.saved {
            let n0 = 1;
            for (k, v) in saved.into_iter().enumerate() {
                self.set_param(n0 + k, v);
            }
        }
        self.cur = (f.ret_file, f.ret_block);
        if let Some(n) = seq {
            if let Some(b) = self.files[f.ret_file]
                .seq
                .get(&(n as u64))
                .and_then(|v| v.first())
            {
                self.cur = (f.ret_file, *b);
            }
        }
        let _ = f.call_span;
        true
    }

    /// M98 / G65: `name` is the program name or number as written.
    pub(super) fn call_program(
        &mut self,
        fi: usize,
        bi: u32,
        name: &str,
        repeat: u32,
        args: Option<Vec<Option<f64>>>,
        span: Span,
    ) -> Result<Flow, Diagnostic> {
        self.depth_check(span)?;
        let number = name.parse::<u32>().ok();
        let (tf, tb) = if let Some(b) = number.and_then(|n| self.files[fi].heads.get(&n).copied()) {
            (fi, b + 1)
        } else if let Some(b) = number.and_then(|n| self.files[0].heads.get(&n).copied()) {
            (0, b + 1)
        } else {
            let f = self
                .load_file(name, span)
                .or_else(|| number.and_then(|n| self.load_file(&format!("{n:04}"), span)));
            match f {
                Some(f) if self.files[f].foreign => {
                    return Err(self.skip_call(Severity::Warning, span, format!("O{name} looks written for another control (P010 in its file): the dry run skips the call, so what it would set and move is unknown")));
                }
                Some(f) => {
                    let p = self.files[f].prog.clone();
                    // Start after the program head, if the file has one.
                    let head = p.blocks.iter().position(|b| {
                        p.items_of(b)
                            .iter()
                            .any(|it| matches!(it.kind, ItemKind::ProgramHead { .. }))
                    });
                    (f, head.map(|h| h as u32 + 1).unwrap_or(0))
                }
                None => {
                    let refused = self.input.resolver.refused(name).or_else(|| {
                        number.and_then(|n| self.input.resolver.refused(&format!("{n:04}")))
                    });
                    if let Some(why) = refused {
                        return Err(self.skip_call(Severity::Warning, span, refused_call(&why)));
                    }
                    let what = if self.dialect == Dialect::Servoworks {
                        format!("subprogram O{name} (file O{name}.dat) not found")
                    } else {
                        format!("program O{name} not found (PS0076)")
                    };
                    // The run goes on without the call, so its figures leave the
                    // call out; the feed is not made unknown, as the control alarms here.
                    self.st.skipped_call = true;
                    return Err(self.err(&SUB_NOT_FOUND, span, what));
                }
            }
        };
        let saved = if let Some(a) = &args {
            let saved: Vec<Option<f64>> = (1..=33)
                .map(|n| self.st.params.get(n).copied().flatten())
                .collect();
            for n in 1..=33usize {
                self.set_param(n, a.get(n).copied().flatten());
            }
            Some(saved)
        } else {
            None
        };
        self.frames.push(Frame {
            kind: FrameKind::Sub {
                start: tb,
                repeat: repeat.max(1),
            },
            ret_file: fi,
            ret_block: bi + 1,
            saved,
            named_locals: HashMap::new(),
            call_span: span,
            modal_call: false,
            context: None,
            motions_at_call: self.motions_drained + self.out.motions.len(),
        });
        Ok(Flow::Goto(tf, tb))
    }

    pub(super) fn exec_call_words(
        &mut self,
        fi: usize,
        bi: u32,
        w: &Words,
    ) -> Result<Flow, Diagnostic> {
        let span =
            w.m.iter()
                .find(|(m, _)| *m == 980)
                .map(|x| x.1)
                .unwrap_or(w.g_span(650));
        if w.has_g(650) {
            let Some(p) = w.get(b'P') else {
                return Err(self.err(&SUB_NOT_FOUND, span, "G65 without P (macro number)"));
            };
            let l = w.get(b'L').unwrap_or(1.0).max(1.0) as u32;
            let args = macro_args(w);
            let name = format!("{}", p.round() as i64);
            return self.call_program(fi, bi, &name, l, Some(args), span);
        }
        // M98.
        let (name, repeat) = match (&w.pname, w.get(b'P')) {
            (Some(n), _) => (n.clone(), w.get(b'R').or(w.get(b'L')).unwrap_or(1.0)),
            (None, Some(p)) => {
                let p = p.round() as i64;
                if self.dialect == Dialect::Fanuc && !w.has(b'L') && p > 9999 {
                    (format!("{}", p % 10000), (p / 10000) as f64)
                } else {
                    let r = if self.dialect == Dialect::Servoworks {
                        w.get(b'R')
                    } else {
                        w.get(b'L')
                    };
                    (format!("{p}"), r.unwrap_or(1.0))
                }
            }
            (None, None) => {
                return Err(self.err(&SUB_NOT_FOUND, span, "M98 without P (subprogram name)"))
            }
        };
        if w.any_axis() {
            self.diag(
                &INTERP,
                Severity::Warning,
                span,
                "M98 shares its block with axis words: the motion in this block is ignored",
            );
        }
        // LinuxCNC runs `M98 P.. L0` zero times.
        if self.ngc() && repeat < 1.0 {
            return Ok(Flow::Next);
        }
        self.call_program(fi, bi, &name, repeat.max(1.0) as u32, None, span)
    }

    pub(super) fn exec_stops(&mut self, w: &Words, fi: usize) -> Result<Flow, Diagnostic> {
        // Every stop and end is an M code.
        if w.m.is_empty() {
            return Ok(Flow::Next);
        }
        if w.has_m(600) && self.ngc() {
            self.canon("PALLET_SHUTTLE()");
        }
        // LinuxCNC's M60 is a pallet shuttle and a program stop; elsewhere the
        // pallet code is the machine builder's and stops nothing.
        if w.has_m(0) || (w.has_m(600) && self.ngc()) {
            self.canon("PROGRAM_STOP()");
            self.event(EventKind::Stop { optional: false });
        }
        if w.has_m(10) {
            self.canon("OPTIONAL_PROGRAM_STOP()");
            // With the optional-stop switch off the control runs through M1.
            if self.cfg.optional_stop {
                self.event(EventKind::Stop { optional: true });
            }
        }
        if w.has_m(990) && (!self.ngc() || !self.frames.is_empty()) {
            if self.frames.is_empty() {
                // `M99 P<n>` in a main program jumps to block N<n> of the main
                // program (a common way to skip to the end or a restart point);
                // a missing N is alarm PS0078.
                if let Some(n) = w.get(b'P') {
                    let span =
                        w.m.iter()
                            .find(|m| m.0 == 990)
                            .map(|m| m.1)
                            .unwrap_or_default();
                    return self.goto_seq(fi, self.cur.1, n, span);
                }
                // M99 in a main program: the control loops back to the start.
                self.diag(
                    &INTERP,
                    Severity::Warning,
                    w.m.iter()
                        .find(|m| m.0 == 990)
                        .map(|m| m.1)
                        .unwrap_or_default(),
                    "M99 in the main program restarts it from the top: an endless loop (the dry run stops here)",
                );
                self.saw_end = true;
                self.st.ended = true;
                self.event(EventKind::ProgramEnd);
                return Ok(Flow::Stop);
            }
            let seq = w.get(b'P');
            self.ret_from_sub(seq);
            return Ok(Flow::Goto(self.cur.0, self.cur.1));
        }
        if self.ngc() && w.has_m(990) && self.frames.is_empty() {
            // LinuxCNC ends the program at M99 in the main file, like M2.
            self.program_end(false);
            self.saw_end = true;
            self.st.ended = true;
            self.event(EventKind::ProgramEnd);
            return Ok(Flow::Stop);
        }
        if w.has_m(20) || w.has_m(300) {
            let span = w.m_span(if w.has_m(20) { 20 } else { 300 });
            self.end_checks(span);
            self.program_end(w.has_m(300));
            self.saw_end = true;
            self.st.ended = true;
            self.event(EventKind::ProgramEnd);
            // Later blocks are never run; flag the first one that has content.
            self.flag_after_end(fi);
            return Ok(Flow::Stop);
        }
        Ok(Flow::Next)
    }

    pub(super) fn flag_after_end(&mut self, fi: usize) {
        if fi != 0 || !self.frames.is_empty() {
            return;
        }
        let p = self.files[0].prog.clone();
        let start = self.cur.1 as usize + 1;
        for b in p.blocks.iter().skip(start) {
            if b.kind != BlockKind::Normal {
                continue;
            }
            let items = p.items_of(b);
            let only_heads = items
                .iter()
                .all(|it| matches!(it.kind, ItemKind::Comment(_)));
            if items.is_empty() || only_heads {
                continue;
            }
            // FANUC/ServoWorks files may hold subprograms after M30; they start with O.
            if self.dialect != Dialect::Rs274ngc
                && items
                    .iter()
                    .any(|it| matches!(it.kind, ItemKind::ProgramHead { .. }))
            {
                return;
            }
            if self.dialect == Dialect::Rs274ngc {
                return;
            }
            // `IF [#890 NE 1] GOTO2 … M30 / N2 #3000 = 15`: a numbered block a
            // branch can reach runs on another path, although not on this one.
            let numbered = items
                .iter()
                .any(|it| matches!(&it.kind, ItemKind::Word(w) if w.letter == b'N'));
            if numbered && self.files[0].branches {
                return;
            }
            self.diag(
                &AFTER_END,
                if self.dialect == Dialect::Fanuc {
                    // An operator may start there (cursor, sequence-number search).
                    Severity::Info
                } else {
                    Severity::Warning
                },
                b.span,
                "code after the program end (M02/M30) is never executed",
            );
            return;
        }
    }

    pub(super) fn program_end(&mut self, m30: bool) {
        self.comp_flush();
        if self.ngc() {
            // LinuxCNC resets: origin G54, plane XY, absolute, feed mode, spindle, coolant.
            self.st.modal.origin = 1;
            self.st.pos = self.to_program(self.st.mpos);
            let u = self.unit();
            let g = self.g5x_prog();
            canon!(self, "SET_G5X_OFFSET(1, {})", Canon::six(&scale6(g, u)));
            let r = self.rotation_canon(1);
            self.canon(r);
            if self.st.modal.plane != 170 {
                self.canon("SELECT_PLANE(CANON_PLANE_XY)");
            }
            self.st.modal.plane = 170;
            self.st.modal.incremental = false;
            self.st.modal.feed_mode = 940;
            self.canon("SET_FEED_MODE(0, 0)");
            self.canon("SET_FEED_RATE(0.0000)");
            if self.feed_override_off && self.ngc() {
                self.feed_override_off = false;
                self.canon("ENABLE_FEED_OVERRIDE()");
            }
            self.st.modal.comp = 400;
            self.canon("STOP_SPINDLE_TURNING(0)");
            self.canon("SET_SPINDLE_MODE(0 0.0000)");
            self.st.spindle_dir = 0;
            self.st.modal.motion = 10;
            if self.st.mist {
                self.canon("MIST_OFF()");
            }
            if self.st.flood {
                self.canon("FLOOD_OFF()");
            }
            self.st.mist = false;
            self.st.flood = false;
            if m30 {
                self.canon("PALLET_SHUTTLE()");
            }
            self.canon("PROGRAM_END()");
            if self.percent_open && self.cur.0 == 0 {
                let p = self.files[0].prog.clone();
                let closed = p
                    .blocks
                    .iter()
                    .skip(self.cur.1 as usize + 1)
                    .any(|b| b.kind == BlockKind::Percent);
                if !closed {
                    self.canon_comment("interpreter: percent sign missing from end of file");
                }
            }
        }
    }
}

/// G65/G66 arguments: specification I, with the I/J/K sets of specification II.
pub(super) fn macro_args(w: &Words) -> Vec<Option<f64>> {
    let mut args = vec![None; 34];
    let mut ijk_set = 0usize;
    let mut last_ijk = 0u8;
    for (c, v) in &w.ijk_order {
        if matches!(c, b'I' | b'J' | b'K') {
            let ord = match c {
                b'I' => 0,
                b'J' => 1,
                _ => 2,
            };
            if ijk_set == 0 || ord <= last_ijk {
                ijk_set += 1;
            }
            last_ijk = ord;
            let n = 3 * ijk_set + 1 + ord as usize;
            if n <= 33 {
                args[n] = Some(*v);
            }
        } else if let Some(n) = super::super::types::macro_argument_variable(*c) {
            args[n] = Some(*v);
        }
    }
    args
}

/// The call of a file the host found but would not read: the dry run skips it.
fn refused_call(why: &str) -> String {
    format!("the called file was not read, so the dry run skips the call: {why}")
}

impl Interp<'_, '_> {
    /// A call the run cannot follow: the globals it may set are unknown, and so is
    /// the feed rate, which a called subprogram often programs. The diagnostic
    /// (`SUB_NOT_FOUND`, in the calling file) says why.
    fn skip_call(&mut self, severity: Severity, span: Span, msg: String) -> Diagnostic {
        self.st.skipped_call = true;
        self.mark_taint(|| "F".into(), true);
        SUB_NOT_FOUND
            .diagnostic(severity, span, msg)
            .in_file(self.file_id())
    }
}
