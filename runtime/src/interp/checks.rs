//! State checks that look at a block against the modal state in force before
//! it runs: cutter compensation conflicts, inverse-time feed, spindle state,
//! and modes left on at the program end.

use super::*;

/// Group-01 codes that move (tenths), canned cycles aside.
fn is_feed_motion(g: u32) -> bool {
    matches!(g, 10 | 20 | 30)
}

/// What the state checks remember between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(super) struct Mem {
    /// A T word has been given since the start.
    t_seen: bool,
    /// A T word was given and no M6 has used it yet (line span of that T).
    t_unused: Option<Span>,
    /// Cutter compensation was just turned off and no motion has followed.
    after_g40: bool,
    /// An M6 left the tool length offset of the old tool while G43 was in use.
    m6_without_g43: bool,
    /// The cycle (tenths) whose block last stored Q (FANUC/ServoWorks).
    q_from: Option<u32>,
    /// FANUC: rigid tapping was cancelled and no S has been given since.
    rigid_s_cleared: bool,
    /// The current block's motion, computed once per block.
    motion: Option<(u32, Span)>,
    /// A canned cycle has been given an R (FANUC: a later cycle without R then
    /// lost it to a cancel).
    pub(super) cycle_r_seen: bool,
}

impl Mem {
    /// Applies `f` to the source spans remembered (a rerun moves them).
    pub(super) fn shift_spans(&mut self, f: impl Fn(Span) -> Span) {
        if let Some(s) = self.t_unused.as_mut() {
            *s = f(*s);
        }
        if let Some((_, s)) = self.motion.as_mut() {
            *s = f(*s);
        }
    }
}

impl Interp<'_, '_> {
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

    pub(super) fn m_span(w: &Words, m: u32) -> Span {
        w.m.iter()
            .find(|x| x.0 == m)
            .map(|x| x.1)
            .unwrap_or_default()
    }

    /// Checks run before any word of the block takes effect.
    pub(super) fn state_checks(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        self.chk.motion = self.block_motion(w);
        self.comp_conflicts(w)?;
        self.inverse_time_checks(w, bspan)?;
        self.spindle_checks(w)?;
        self.cycle_checks(w)?;
        self.tool_offset_checks(w)?;
        self.coordinate_checks(w)?;
        self.comp_motion_checks(w)?;
        self.probe_checks(w)?;
        self.arc_checks(w)?;
        self.misc_checks(w);
        self.spec_checks(w, bspan, self.chk.motion)?;
        Ok(())
    }

    /// [`Self::state_checks`] reduced to what can act on a plain motion line of the
    /// fast path (`fast.rs`: RS274/NGC, only X/Y/Z/F numbers, a modal G0/G1, no cutter
    /// compensation, feed per minute, no diameter mode, no G66). Every other check
    /// needs a G/M code, another letter, or a state the fast path excludes; what
    /// remains, in the general order, is:
    /// - the block's motion (`block_motion`): the modal code, at the first axis word;
    /// - `tool_offset_checks`: Z after an M6 that kept the old tool's length offset;
    /// - `comp_motion_checks`: the first motion after G40 clears the flag (a line,
    ///   so never an error);
    /// - `ngc_spec_checks`: M70/M73 levels left by a return, feed with the spindle
    ///   stopped (when selected), and the look-ahead count of `spec_checks`.
    ///
    /// `runtime/tests/fast_path.rs` runs programs both ways and compares everything.
    pub(super) fn plain_motion_checks(&mut self, w: &Words, bspan: Span) {
        let span = [b'X', b'Y', b'Z']
            .iter()
            .find(|c| w.has(**c))
            .map(|c| w.sp(*c))
            .unwrap_or_default();
        let m = self.st.modal.motion;
        self.chk.motion = Some((m, span));
        if self.chk.m6_without_g43 && w.has(b'Z') {
            self.chk.m6_without_g43 = false;
            self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.sp(b'Z'), "M6 loaded a new tool but the length offset is still the old tool's: give G43 (H of the new tool) before moving Z");
        }
        self.chk.after_g40 = false;
        self.plain_spec_checks(m, span, bspan);
    }

    /// Codes LinuxCNC (and FANUC, for planes and G45–G48) refuse while cutter
    /// radius compensation is on.
    fn comp_conflicts(&mut self, w: &Words) -> Result<(), Diagnostic> {
        if self.st.modal.comp == 400 {
            return Ok(());
        }
        let plane = w.g.iter().find(|g| matches!(g.0, 170 | 180 | 190)).copied();
        if self.dialect == Dialect::Fanuc {
            if let Some((p, s)) = plane {
                if p != self.st.modal.plane {
                    self.diag(codes::COMP_CONFLICT, Severity::Error, s, "the plane cannot be changed while cutter compensation (G41/G42) is on: the control alarms (PS0037); cancel with G40 first");
                }
            }
            if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 450 | 460 | 470 | 480)) {
                self.diag(codes::COMP_CONFLICT, Severity::Error, s, format!("G{} tool position offset cannot be used while cutter compensation (G41/G42) is on: the control alarms (PS0042); cancel with G40 first", g / 10));
            }
            return Ok(());
        }
        if !self.ngc() {
            return Ok(());
        }
        let emc2 = self.variant == Variant::Emc2;
        let msg_tail =
            "while cutter radius compensation is on: LinuxCNC stops; cancel it with G40 first";
        // Plane and units are applied before G40 in LinuxCNC's order of execution.
        if let Some((p, s)) = plane {
            let bad = if emc2 {
                p != 170
            } else {
                p != self.st.modal.plane
            };
            if bad {
                return Err(self.err(
                    codes::COMP_CONFLICT,
                    s,
                    format!("cannot change the plane to G{} {msg_tail}", p / 10),
                ));
            }
        }
        // LinuxCNC 2.9 accepts a units change under compensation; the 2007 EMC2 refused it.
        for (code, inch) in [(200u32, true), (210, false)] {
            if emc2 && w.has_g(code) && inch != self.st.modal.inch {
                return Err(self.err(
                    codes::COMP_CONFLICT,
                    w.g_span(code),
                    format!("cannot change units {msg_tail}"),
                ));
            }
        }
        if w.has_g(400) {
            return Ok(());
        }
        if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 410 | 420 | 411 | 421)) {
            return Err(self.err(
                codes::COMP_CONFLICT,
                s,
                format!(
                    "G{}{} turns cutter radius compensation on when it is already on: LinuxCNC stops; give G40 first",
                    g / 10,
                    if g % 10 == 1 { ".1" } else { "" }
                ),
            ));
        }
        let modes: [(u32, &str); 13] = [
            (430, "change the tool length offset (G43)"),
            (431, "change the tool length offset (G43.1)"),
            (432, "change the tool length offset (G43.2)"),
            (490, "change the tool length offset (G49)"),
            (610, "change the path control mode (G61)"),
            (611, "change the path control mode (G61.1)"),
            (640, "change the path control mode (G64)"),
            (980, "change the retract mode (G98)"),
            (990, "change the retract mode (G99)"),
            (281, "set the G28 reference point"),
            (301, "set the G30 reference point"),
            (51, "run a spline (G5.1)"),
            (52, "run a NURBS block (G5.2)"),
        ];
        if let Some((code, what)) = modes.iter().find(|(c, _)| w.has_g(*c)) {
            return Err(self.err(
                codes::COMP_CONFLICT,
                w.g_span(*code),
                format!("cannot {what} {msg_tail}"),
            ));
        }
        if let Some(&(m, s)) =
            w.m.iter()
                .find(|m| (480..=530).contains(&m.0) || (620..=680).contains(&m.0))
        {
            return Err(self.err(
                codes::COMP_CONFLICT,
                s,
                format!(
                    "M{} (overrides or motion I/O) cannot be used {msg_tail}",
                    m / 10
                ),
            ));
        }
        if w.has_g(100) {
            let l = w.get(b'L').map(|l| l.round() as i64).unwrap_or(-1);
            let p = w.get(b'P').map(|p| p.round() as usize).unwrap_or(0);
            let active = p == 0 || p == self.st.modal.origin;
            // LinuxCNC 2.9 refuses only a change of the active system; EMC2 also tool data.
            if (emc2 && matches!(l, 1 | 10 | 11)) || (matches!(l, 2 | 20) && active) {
                return Err(self.err(
                    codes::COMP_CONFLICT,
                    w.g_span(100),
                    format!("G10 L{l} changes an offset in use {msg_tail}"),
                ));
            }
        }
        for (code, what) in [
            (280u32, "G28 reference return"),
            (300, "G30 reference return"),
            (530, "G53 machine-coordinate move"),
            (920, "G92 offset"),
            (520, "G52 offset"),
        ] {
            if w.has_g(code) {
                return Err(self.err(
                    codes::COMP_CONFLICT,
                    w.g_span(code),
                    format!("cannot use {what} {msg_tail}"),
                ));
            }
        }
        if let Some(&(g, s)) = w.g.iter().find(|g| (540..=593).contains(&g.0)) {
            let name = if g % 10 == 0 {
                format!("G{}", g / 10)
            } else {
                format!("G{}.{}", g / 10, g % 10)
            };
            return Err(self.err(
                codes::COMP_CONFLICT,
                s,
                format!("cannot change the coordinate system to {name} {msg_tail}"),
            ));
        }
        if w.has_m(60) {
            let s = Self::m_span(w, 60);
            if emc2 {
                self.diag(codes::COMP_CONFLICT, Severity::Warning, s, "tool change while cutter radius compensation is on: the old tool's radius stays in use; give G40 before M6");
            } else {
                return Err(self.err(
                    codes::COMP_CONFLICT,
                    s,
                    format!("cannot change tools {msg_tail}"),
                ));
            }
        }
        Ok(())
    }

    /// G93: every feed move needs its own F; F alone does nothing; no cycles.
    fn inverse_time_checks(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        if !self.ngc() {
            return Ok(());
        }
        let g93 =
            w.has_g(930) || (self.st.modal.feed_mode == 930 && !w.has_g(940) && !w.has_g(950));
        if !g93 {
            return Ok(());
        }
        let motion = self.chk.motion;
        match motion {
            Some((g, s)) if is_cycle(g) => Err(self.err(
                codes::INVERSE_TIME,
                s,
                "canned cycles cannot be used in inverse-time feed mode (G93): switch to G94 first",
            )),
            Some((g, s)) if is_feed_motion(g) && !w.has(b'F') => Err(self.err(
                codes::INVERSE_TIME,
                s,
                // LinuxCNC's own words: each move in G93 carries its own F.
                if g == 10 {
                    "F word missing with inverse time g1 move"
                } else {
                    "F word missing with inverse time arc move"
                },
            )),
            Some((g, _)) if is_feed_motion(g) => Ok(()),
            _ => {
                if w.has(b'F') {
                    let _ = bspan;
                    self.diag(
                        codes::INVERSE_TIME,
                        Severity::Info,
                        w.sp(b'F'),
                        "F on a line without a feed move is ignored in inverse-time mode (G93): each move carries its own F",
                    );
                }
                Ok(())
            }
        }
    }

    /// Spindle state against spindle-synchronised motion and canned cycles.
    fn spindle_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let ngc = self.ngc();
        let speed = w.get(b'S').unwrap_or(self.st.spindle);
        let dir = if w.has_m(30) {
            1
        } else if w.has_m(40) {
            -1
        } else if w.has_m(50) {
            0
        } else {
            self.st.spindle_dir
        };
        if ngc && speed <= 0.0 {
            for m in [30u32, 40] {
                if w.has_m(m) {
                    let s = Self::m_span(w, m);
                    self.diag(
                        codes::SPINDLE_STOPPED,
                        Severity::Warning,
                        s,
                        format!(
                            "M{} starts the spindle with speed S0: program S before or with M{}",
                            m / 10,
                            m / 10
                        ),
                    );
                }
            }
        }
        let motion = self.chk.motion;
        let Some((g, s)) = motion else {
            return Ok(());
        };
        let feed_mode = if w.has_g(950) {
            950
        } else if w.has_g(930) || w.has_g(940) {
            0
        } else {
            self.st.modal.feed_mode
        };
        if ngc {
            if matches!(g, 330 | 760) && dir == 0 {
                return Err(self.err(
                    codes::SPINDLE_STOPPED,
                    s,
                    format!(
                        "G{} needs the spindle turning (M3 or M4): LinuxCNC stops",
                        g / 10
                    ),
                ));
            }
            if feed_mode == 950 && is_feed_motion(g) && speed <= 0.0 {
                return Err(self.err(codes::SPINDLE_STOPPED, s, "feed per revolution (G95) with spindle speed 0: the move would never finish; program S"));
            }
            return Ok(());
        }
        if feed_mode == 950 && is_feed_motion(g) && speed <= 0.0 {
            self.diag(
                codes::SPINDLE_STOPPED,
                Severity::Warning,
                s,
                "feed per revolution (G95) with no spindle speed: the feed is zero; program S",
            );
        }
        // Rigid tapping (M29) turns the spindle itself, in position control.
        let rigid = self.st.modal.rigid_tap && matches!(g, 740 | 840);
        if is_cycle(g) {
            if dir == 0 && !rigid {
                self.diag(
                    codes::CYCLE_SPINDLE,
                    Severity::Warning,
                    s,
                    format!(
                        "G{} drills with the spindle stopped: start it with M03/M04 and S first",
                        g / 10
                    ),
                );
            } else if g == 840 && dir == -1 {
                self.diag(
                    codes::CYCLE_SPINDLE,
                    Severity::Warning,
                    s,
                    "G84 taps with the spindle turning CCW (M04): right-hand tapping needs M03",
                );
            } else if g == 740 && dir == 1 {
                self.diag(
                    codes::CYCLE_SPINDLE,
                    Severity::Warning,
                    s,
                    "G74 taps with the spindle turning CW (M03): left-hand tapping needs M04",
                );
            }
        }
        Ok(())
    }

    /// Modes a program should cancel before M2/M30: each one left on is reported.
    pub(super) fn end_checks(&mut self, span: Span) {
        let d = self.dialect;
        let m = self.st.modal.clone();
        let mut left: Vec<&str> = Vec::new();
        if m.comp != 400 && d != Dialect::Fanuc {
            left.push("cutter radius compensation (cancel with G40)");
        }
        match d {
            Dialect::Rs274ngc => {
                if self.st.g92.iter().any(|v| *v != 0.0) {
                    left.push("a G92/G52 offset (clear with G92.1, or G52 with zeros)");
                }
            }
            Dialect::Servoworks => {
                if m.dlacc {
                    left.push("3D-DLACC look-ahead (cancel with G08)");
                }
                if self.st.g52.iter().any(|v| *v != 0.0) {
                    left.push("a G52 local coordinate system (cancel with G52 and zero axes)");
                }
                if m.modal_cycle() {
                    left.push("a canned cycle (cancel with G80)");
                }
            }
            Dialect::Fanuc => {
                if m.polar {
                    left.push("polar coordinates (cancel with G15)");
                }
                if self.st.g66.is_some() {
                    left.push("a G66 modal macro call (cancel with G67)");
                }
                if m.rotation {
                    left.push("coordinate rotation (cancel with G69)");
                }
                if m.scaling {
                    left.push("scaling (cancel with G50)");
                }
            }
        }
        for what in left {
            self.diag(
                codes::MODE_LEFT_ON,
                Severity::Warning,
                span,
                format!("the program ends with {what} still active: the next program or MDI command starts in that mode"),
            );
        }
    }
}

impl Interp<'_, '_> {
    /// Canned-cycle modal hygiene: cancelling by group-01 codes, plane changes,
    /// blocks that make no hole, repeats on one spot, retract levels.
    fn cycle_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let d = self.dialect;
        let ngc = d == Dialect::Rs274ngc;
        // rs274 checks the words of spindle-synchronised motions with the rest of the block,
        // before anything in it runs (and before the spindle and plane checks of the move).
        if let Some((m @ (330 | 331 | 760), span)) = self.chk.motion.filter(|_| ngc) {
            let missing = if m == 760 {
                if !w.has(b'P') {
                    Some("P word missing with G76")
                } else if !(w.has(b'I') && w.has(b'J') && w.has(b'K')) {
                    Some("I J or K words missing with G76")
                } else {
                    None
                }
            } else if !w.has(b'K') {
                Some("K word missing with g33/g33.1")
            } else if w.has(b'F') {
                Some("F word used with a g33/g33.1")
            } else {
                None
            };
            if let Some(msg) = missing {
                return Err(self.err(codes::CYCLE_STATE, span, msg));
            }
        }
        let modal = self.st.modal.modal_cycle() && !w.has_g(800);
        if modal && !ngc {
            if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 0 | 10 | 20 | 30)) {
                let (sev, msg) = if d == Dialect::Fanuc {
                    (Severity::Info, format!("G{:02} while canned cycle G{} is modal cancels the cycle, as G80 would", g / 10, self.st.modal.motion / 10))
                } else {
                    (Severity::Warning, format!("G{:02} while canned cycle G{} is modal: the manual does not say what happens (assumed to cancel the cycle); give G80 first", g / 10, self.st.modal.motion / 10))
                };
                self.diag(codes::CYCLE_HYGIENE, sev, s, msg);
            }
            if let Some(&(p, s)) = w.g.iter().find(|g| matches!(g.0, 170 | 180 | 190)) {
                if p != self.st.modal.plane {
                    let sev = if d == Dialect::Fanuc {
                        Severity::Warning
                    } else {
                        Severity::Error
                    };
                    self.diag(codes::CYCLE_HYGIENE, sev, s, "the plane (drilling axis) changes while a canned cycle is modal: cancel the cycle with G80 first");
                }
            }
        }
        if w.has_g(800) {
            self.chk.q_from = None;
        }
        let explicit = w.g.iter().find(|g| is_cycle(g.0)).copied();
        if modal && !ngc && explicit.is_none() {
            let fanuc = d == Dialect::Fanuc;
            let kept: &[u8] = if fanuc { b"QP" } else { b"QR" };
            if !w.any_axis() {
                if let Some(c) = kept.iter().copied().find(|c| w.has(*c)) {
                    self.diag(codes::CYCLE_HYGIENE, Severity::Warning, w.sp(c), format!("{} in a canned-cycle block that makes no hole is not stored as cycle data: give it with the hole position", c as char));
                }
            }
            if fanuc {
                let inc = self.st.modal.incremental;
                let changes = (w.has_g(900) && inc) || (w.has_g(910) && !inc);
                let zl = [b'X', b'Y', b'Z'][self.normal_axis()];
                // Absolute R, Z = r, z; incremental R = I + r, Z = R + z: with the
                // initial level I and r both zero the two readings agree.
                let c = &self.st.cycle;
                let initial = c.initial.unwrap_or(self.st.pos[self.normal_axis()]);
                let same_either_way = initial.abs() < 1e-9 && c.r.is_none_or(|r| r.abs() < 1e-9);
                if changes && !(w.has(b'R') && w.has(zl)) && !same_either_way {
                    let s = w.g_span(if w.has_g(900) { 900 } else { 910 });
                    self.diag(codes::CYCLE_HYGIENE, Severity::Warning, s, "G90/G91 changes in canned-cycle mode without R and Z on the line: the stored R and Z are now read in the other mode; give R and Z again");
                }
                if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 430 | 440 | 490)) {
                    self.diag(codes::CYCLE_HYGIENE, Severity::Warning, s, format!("G{} in canned-cycle mode: the new length offset takes effect at the positioning to point R, not at once", g / 10));
                }
                if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 450 | 460 | 470 | 480)) {
                    self.diag(
                        codes::CYCLE_HYGIENE,
                        Severity::Warning,
                        s,
                        format!(
                            "G{} tool position offset is ignored in canned-cycle mode",
                            g / 10
                        ),
                    );
                }
            }
        }
        if !ngc && (modal || explicit.is_some()) {
            let mode = explicit.map(|e| e.0).unwrap_or(self.st.modal.motion);
            let class = |m: u32| match m {
                730 | 830 => Some("peck depth"),
                760 | 870 => Some("shift amount"),
                _ => None,
            };
            if w.has(b'Q') {
                self.chk.q_from = Some(mode);
            } else if let (Some(from), Some(now)) = (self.chk.q_from, class(mode)) {
                if let Some(before) = class(from) {
                    if before != now && (w.any_axis() || explicit.is_some()) {
                        let s = explicit.map(|e| e.1).unwrap_or_default();
                        self.diag(codes::CYCLE_HYGIENE, Severity::Warning, s, format!("G{} reuses Q stored by G{}: the {before} becomes the {now}; give Q on this block", mode / 10, from / 10));
                        self.chk.q_from = Some(mode);
                    }
                }
            }
        }
        let Some((mode, span)) = explicit else {
            return Ok(());
        };
        if d == Dialect::Servoworks && self.st.modal.comp != 400 && !w.has_g(400) {
            self.diag(codes::CYCLE_HYGIENE, Severity::Warning, span, "tool radius compensation is ignored inside canned cycles: the holes are drilled at the programmed points");
        }
        let n = self.normal_axis();
        let zl = [b'X', b'Y', b'Z'][n];
        if !ngc && !w.any_axis() && !w.has(b'R') {
            self.diag(codes::CYCLE_HYGIENE, Severity::Warning, span, "a canned-cycle block without X/Y/Z/R or other axis words makes no hole: it only stores the cycle data");
        }
        let absolute = if w.has_g(910) {
            false
        } else {
            w.has_g(900) || !self.st.modal.incremental
        };
        // LinuxCNC's G76 is a threading cycle whose L word selects the tapers.
        let repeats = if ngc && mode == 760 {
            None
        } else if ngc {
            w.get(b'L').map(|l| l.round() as i64)
        } else if d == Dialect::Fanuc {
            w.raw_k.map(|k| k.round() as i64)
        } else {
            None
        };
        if let Some(k) = repeats {
            if k >= 2 && absolute {
                let which = if ngc { "L" } else { "K" };
                self.diag(codes::CYCLE_HYGIENE, Severity::Warning, w.sp(if ngc { b'L' } else { b'K' }), format!("{which}{k} repeats the cycle in absolute mode (G90): every repeat drills the same hole; use G91 to step between holes"));
            }
        }
        let g98 = if w.has_g(990) {
            false
        } else {
            w.has_g(980) || self.st.modal.retract_old_z
        };
        if mode == 870 && !g98 && !ngc {
            let (sev, msg) = if d == Dialect::Fanuc {
                (Severity::Warning, "G87 with G99: the back-boring cycle returns to the initial level, not to point R")
            } else {
                (
                    Severity::Error,
                    "G87 works only with G98: G99 is an error; use G98",
                )
            };
            self.diag(codes::CYCLE_HYGIENE, sev, span, msg);
        }
        if !absolute {
            return Ok(());
        }
        let init = if self.st.modal.modal_cycle() {
            self.st.cycle.initial.unwrap_or(self.st.pos[n])
        } else {
            self.st.pos[n]
        };
        let r = w.get(b'R').map(|v| self.lin(v)).or(if ngc {
            self.st.cycle.r
        } else {
            self.st.cycle.r_abs
        });
        let z = w.get(zl).map(|v| self.lin(v)).or(if ngc {
            self.st.cycle.z
        } else {
            self.st.cycle.z_abs
        });
        let eps = 1e-9;
        if ngc {
            if let Some(r) = r {
                if g98 && init < r - eps {
                    self.diag(codes::CYCLE_HYGIENE, Severity::Info, span, format!("G98 has no effect here: the start height {} is below R {}, so the cycle retracts to R", fmt_len(init / self.unit()), fmt_len(r / self.unit())));
                }
            }
            return Ok(());
        }
        let (Some(r), Some(z)) = (r, z) else {
            return Ok(());
        };
        let u = if self.st.modal.inch { 25.4 } else { 1.0 };
        if mode == 870 {
            if r > z + eps {
                self.diag(codes::CYCLE_HYGIENE, Severity::Warning, span, format!("in G87 point R ({}) must lie beyond point Z ({}): the back-boring cycle starts below the hole", fmt_len(r / u), fmt_len(z / u)));
            }
        } else if r > init + eps {
            // Advice, not a fault: the cycle rapids up to R and drills from there,
            // and real programs run that way (FAN081; the tool moves away from the work).
            self.diag(codes::CYCLE_HYGIENE, Severity::Info, span, format!("point R ({}) is above the initial level ({}): the tool retracts upward to R before drilling", fmt_len(r / u), fmt_len(init / u)));
        } else if z > r + eps {
            self.diag(codes::CYCLE_HYGIENE, Severity::Warning, span, format!("point Z ({}) is above point R ({}): R must lie between the initial level and Z", fmt_len(z / u), fmt_len(r / u)));
        }
        Ok(())
    }

    /// Tool selection and length offsets.
    fn tool_offset_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let d = self.dialect;
        let ngc = d == Dialect::Rs274ngc;
        if d == Dialect::Servoworks {
            if self.st.modal.tlo_mode == 432 {
                for code in [430u32, 440] {
                    if w.has_g(code) {
                        self.diag(codes::TOOL_OFFSET_STATE, Severity::Error, w.g_span(code), format!("G{} cannot be given while tool centre point control (G43.2) is on: cancel it with G49 first", code / 10));
                    }
                }
            }
            if w.has(b'T') && matches!(self.st.modal.tlo_mode, 430 | 440) && !w.has(b'H') {
                self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.sp(b'T'), "the tool changes while length compensation is on: the old length offset stays until G43/G44 with an explicit H");
            }
            return Ok(());
        }
        if !ngc {
            return Ok(());
        }
        if w.has_g(430) {
            if let Some(h) = w.get(b'H') {
                if h < 0.0 {
                    return Err(self.err(codes::TOOL_OFFSET_STATE, w.sp(b'H'), format!("G43 H{h}: negative tool numbers do not exist; use G43.1 for a dynamic offset")));
                }
                let h = h.round() as u32;
                if h != self.st.tool {
                    self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.sp(b'H'), format!("G43 H{h} applies the length of tool {h}, but tool {} is in the spindle", self.st.tool));
                }
            } else if self.st.tool == 0
                && self.variant != Variant::Emc2
                && !w.has_m(60)
                && self.cfg.tools.get(&0).is_none_or(|t| t.length == 0.0)
            {
                // LinuxCNC's G43 without H takes the tool in the spindle (spec/rs274ngc.md
                // 3.12); before any M6 (or after M61 Q0) that is tool 0, whose length is zero.
                // A program may expect the tool already in the spindle: a note, not a warning.
                self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.g_span(430), "G43 without H applies the length of the tool in the spindle, and none is loaded (tool 0): the offset is zero; load the tool first (T… M6) or give H");
            }
        }
        if w.has(b'T') {
            if let Some(prev) = self.chk.t_unused {
                if !w.has_m(60) {
                    let _ = prev;
                    self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.sp(b'T'), "this T replaces an earlier T that no M6 used: only the last selected tool is loaded");
                }
            }
            self.chk.t_seen = true;
            self.chk.t_unused = Some(w.sp(b'T'));
        }
        if w.has_m(60) {
            let s = Self::m_span(w, 60);
            // LinuxCNC 2.9 (its rs274) loads tool 0 without complaint: a warning only.
            if !self.chk.t_seen {
                self.diag(
                    codes::TOOL_OFFSET_STATE,
                    Severity::Warning,
                    s,
                    "M6 with no tool selected: the spindle gets tool 0 (no tool); give T before M6",
                );
            }
            self.chk.t_unused = None;
            if self.st.modal.tlo_mode == 430 && !w.has_g(430) && !w.has_g(490) {
                self.chk.m6_without_g43 = true;
            }
        }
        if w.has_g(430) || w.has_g(490) {
            self.chk.m6_without_g43 = false;
        } else if self.chk.m6_without_g43 && w.has(b'Z') && !w.has_m(60) {
            self.chk.m6_without_g43 = false;
            self.diag(codes::TOOL_OFFSET_STATE, Severity::Info, w.sp(b'Z'), "M6 loaded a new tool but the length offset is still the old tool's: give G43 (H of the new tool) before moving Z");
        }
        Ok(())
    }

    /// G53, G29, G52 and unit changes, and (ServoWorks) the order of scaling,
    /// mirror, rotation and cutter compensation.
    fn coordinate_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let d = self.dialect;
        let m = self.st.modal.clone();
        if d == Dialect::Rs274ngc && w.has_g(530) {
            let s = w.g_span(530);
            if let Some((g, _)) = self.chk.motion {
                if !matches!(g, 0 | 10) {
                    return Err(self.err(
                        codes::COORDINATE_MODE,
                        s,
                        "G53 works only with G0 or G1: LinuxCNC stops",
                    ));
                }
            }
            if (m.incremental && !w.has_g(900)) || w.has_g(910) {
                return Err(self.err(
                    codes::COORDINATE_MODE,
                    s,
                    "G53 cannot be used in incremental mode (G91): give G90 on the line",
                ));
            }
        }
        if d == Dialect::Rs274ngc && w.has_g(100) {
            let s = w.g_span(100);
            let l = w.get(b'L').map(|l| l.round() as i64);
            let valid: &[i64] = if self.variant == Variant::Emc2 {
                &[2]
            } else {
                &[0, 1, 2, 10, 11, 20]
            };
            if !l.is_some_and(|l| valid.contains(&l)) {
                let list = valid
                    .iter()
                    .map(|v| format!("L{v}"))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(self.err(
                    codes::COORDINATE_MODE,
                    s,
                    format!("G10 needs one of {list}: LinuxCNC stops"),
                ));
            }
            if l == Some(0) && self.st.tool != 0 {
                return Err(self.err(codes::COORDINATE_MODE, s, format!("G10 L0 (reload the tool table) is not allowed while tool {} is loaded: unload it with T0 M6 first", self.st.tool)));
            }
        }
        if d != Dialect::Servoworks {
            return Ok(());
        }
        if w.has_g(290) && self.st.g28_mid.is_none() {
            self.diag(codes::COORDINATE_MODE, Severity::Warning, w.g_span(290), "G29 without an earlier G28/G30: there is no intermediate point, so the move goes straight to the target");
        }
        for (code, inch) in [(200u32, true), (210, false)] {
            if w.has_g(code) && inch != m.inch && self.any_motion() {
                self.diag(codes::COORDINATE_MODE, Severity::Info, w.g_span(code), "units change after motion has been programmed: positions, offsets and feeds given earlier are not converted; set G20/G21 once at the top");
            }
        }
        if w.has_g(520) && ((m.incremental && !w.has_g(900)) || w.has_g(910)) {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Warning,
                w.g_span(520),
                "G52 in incremental mode (G91) is ignored: give it in G90",
            );
        }
        let comp_on = m.comp != 400 && !w.has_g(400);
        if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 410 | 420)) {
            if m.scaling || m.mirror || w.has_g(510) || w.has_g(511) {
                self.diag(codes::COORDINATE_MODE, Severity::Error, s, format!("G{} cannot be combined with scaling (G51) or mirror image (G51.1): cancel them first", g / 10));
            }
        }
        if w.has_g(510) && (m.mirror || w.has_g(511)) {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Error,
                w.g_span(510),
                "scaling (G51) cannot be active together with mirror image (G51.1)",
            );
        }
        if w.has_g(511) && (m.scaling || w.has_g(510)) {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Error,
                w.g_span(511),
                "mirror image (G51.1) cannot be active together with scaling (G51)",
            );
        }
        if w.has_g(510) && (m.rotation || comp_on) {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Warning,
                w.g_span(510),
                "G51 after G68 or G41/G42: the order must be G51, then G68, then G41/G42",
            );
        }
        if w.has_g(680) && comp_on {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Warning,
                w.g_span(680),
                "G68 after G41/G42: the order must be G51, then G68, then G41/G42",
            );
        }
        if w.has_g(500) && m.rotation && !w.has_g(690) {
            self.diag(
                codes::COORDINATE_MODE,
                Severity::Warning,
                w.g_span(500),
                "G50 while rotation (G68) is on: cancel rotation with G69 before scaling",
            );
        }
        Ok(())
    }

    /// Motion rules at the start and end of cutter compensation.
    fn comp_motion_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let d = self.dialect;
        let comp_on = self.st.modal.comp != 400;
        let cancel = comp_on && w.has_g(400);
        let motion = self.chk.motion;
        let arc = matches!(motion, Some((20 | 30, _)));
        if d == Dialect::Rs274ngc {
            if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 410 | 420 | 411 | 421)) {
                let plane =
                    w.g.iter()
                        .find(|g| matches!(g.0, 170 | 180 | 190))
                        .map(|g| g.0)
                        .unwrap_or(self.st.modal.plane);
                let emc2 = self.variant == Variant::Emc2;
                if (emc2 && plane != 170) || plane == 190 {
                    return Err(self.err(codes::COMP_MOTION, s, format!("cutter radius compensation (G{}) is not allowed in the G{} plane: LinuxCNC compensates only in {}", g / 10, plane / 10, if emc2 { "G17" } else { "G17 and G18" })));
                }
            }
            if cancel {
                self.chk.after_g40 = true;
            }
            if self.chk.after_g40 {
                if let Some((g, s)) = motion {
                    self.chk.after_g40 = false;
                    if arc {
                        if cancel && self.ngc() {
                            // rs274 turns compensation off (releasing the held-back
                            // moves) before it rejects the arc.
                            self.comp_flush();
                            self.canon_comment("interpreter: cutter radius compensation off");
                        }
                        return Err(self.err(codes::COMP_MOTION, s, format!("G{} is the first move after G40: LinuxCNC needs a straight move to leave cutter compensation", g / 10)));
                    }
                }
            }
            return Ok(());
        }
        if d != Dialect::Servoworks {
            return Ok(());
        }
        if let Some((g, s)) = motion {
            let first =
                w.g.iter().any(|x| matches!(x.0, 410 | 420)) || (comp_on && self.st.comp_first);
            if arc && (first || cancel) {
                let which = if cancel { "last" } else { "first" };
                self.diag(codes::COMP_MOTION, Severity::Error, s, format!("the {which} motion of tool radius compensation cannot be G{:02}: use G00 or G01 to start and end it", g / 10));
            }
        }
        if comp_on && !cancel {
            if let Some(&(g, s)) =
                w.g.iter()
                    .find(|x| !matches!(x.0, 0 | 10 | 20 | 30 | 40 | 400 | 410 | 420))
            {
                let name = if g % 10 == 0 {
                    format!("G{:02}", g / 10)
                } else {
                    format!("G{}.{}", g / 10, g % 10)
                };
                self.diag(codes::COMP_MOTION, Severity::Error, s, format!("{name} is not allowed in tool radius compensation mode (only G00–G03, G04, M, S, B and F): cancel with G40 first"));
            }
        }
        Ok(())
    }

    /// Probe moves (LinuxCNC G38.2–G38.5).
    fn probe_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        if !self.ngc() {
            return Ok(());
        }
        let Some((g, s)) = self.chk.motion else {
            return Ok(());
        };
        if !(382..=385).contains(&g) {
            return Ok(());
        }
        if self.st.modal.comp != 400 && !w.has_g(400) {
            return Err(self.err(
                codes::PROBE_STATE,
                s,
                "probing (G38) is not allowed with cutter radius compensation on: give G40 first",
            ));
        }
        let mode = if w.has_g(950) {
            950
        } else if w.has_g(930) {
            930
        } else if w.has_g(940) {
            940
        } else {
            self.st.modal.feed_mode
        };
        let emc2 = self.variant == Variant::Emc2;
        if mode == 950 || (emc2 && mode == 930) {
            return Err(self.err(
                codes::PROBE_STATE,
                s,
                "probing (G38) needs feed per minute: give G94 first",
            ));
        }
        Ok(())
    }
}

/// A length for a message: up to four decimals, no trailing zeros.
fn fmt_len(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

impl Interp<'_, '_> {
    /// Arc words against the active plane, and radius-format arcs whose centre
    /// is ill-defined (sweep near 180° or 360°).
    fn arc_checks(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let Some((g, span)) = self.chk.motion else {
            return Ok(());
        };
        if !matches!(g, 20 | 30) {
            return Ok(());
        }
        let d = self.dialect;
        let ngc = d == Dialect::Rs274ngc;
        // A plane code on the arc's own line applies before the arc.
        let plane =
            w.g.iter()
                .find(|g| matches!(g.0, 170 | 180 | 190))
                .map(|g| g.0)
                .unwrap_or(self.st.modal.plane);
        let (a, b, n) = match plane {
            180 => (2, 0, 1),
            190 => (1, 2, 0),
            _ => (0, 1, 2),
        };
        let axes = [b'X', b'Y', b'Z'];
        let ijk = [b'I', b'J', b'K'];
        let has_r = w.has(b'R');
        let has_c = w.has(ijk[a]) || w.has(ijk[b]);
        let plane = format!("G{}", plane / 10);
        if d != Dialect::Fanuc && w.has(ijk[n]) && !(ngc && g == 20 && w.has_g(330)) {
            let msg = format!(
                "{} is the centre offset along the axis normal to the {plane} plane: an arc in {plane} takes {} and {}",
                ijk[n] as char, ijk[a] as char, ijk[b] as char
            );
            if ngc {
                return Err(self.err(codes::ARC_WORDS, w.sp(ijk[n]), msg));
            }
            self.diag(codes::ARC_WORDS, Severity::Error, w.sp(ijk[n]), msg);
        }
        let in_plane_end = w.has(axes[a]) || w.has(axes[b]);
        if ngc && !in_plane_end {
            let emc2 = self.variant == Variant::Emc2;
            if has_r {
                return Err(self.err(codes::ARC_WORDS, span, format!("a radius-format arc needs an end point in the {plane} plane ({} or {}): without one there is no arc", axes[a] as char, axes[b] as char)));
            }
            if emc2 && has_c {
                return Err(self.err(
                    codes::ARC_WORDS,
                    span,
                    format!(
                        "a centre-format arc needs an end point in the {plane} plane ({} or {})",
                        axes[a] as char, axes[b] as char
                    ),
                ));
            }
        }
        if ngc && !has_r && self.st.modal.ijk_abs && has_c && !(w.has(ijk[a]) && w.has(ijk[b])) {
            return Err(self.err(
                codes::ARC_WORDS,
                span,
                format!(
                    "with absolute arc centres (G90.1) both {} and {} are needed",
                    ijk[a] as char, ijk[b] as char
                ),
            ));
        }
        if d == Dialect::Servoworks {
            if w.has(axes[n]) && (w.has(axes[a]) != w.has(axes[b])) {
                self.diag(codes::ARC_WORDS, Severity::Error, span, format!("the arc's axis words do not match the {plane} plane: give both {} and {} (or neither) with a helical {}", axes[a] as char, axes[b] as char, axes[n] as char));
            }
            let extra = b"XYZABCUVW"
                .iter()
                .filter(|c| **c != axes[a] && **c != axes[b] && w.has(**c))
                .count();
            if extra > 2 {
                self.diag(codes::ARC_WORDS, Severity::Error, span, format!("{extra} axes outside the {plane} plane move with this arc: at most two helical axes are allowed"));
            }
        }
        // Radius format: the sweep follows from the chord and |R|.
        if d == Dialect::Servoworks || !has_r {
            return Ok(());
        }
        let Some(r) = w.get(b'R').map(|v| self.lin(v)) else {
            return Ok(());
        };
        let t = self.target(w);
        let chord = (t[a] - self.st.pos[a]).hypot(t[b] - self.st.pos[b]);
        if r == 0.0 || chord == 0.0 || chord > 2.0 * r.abs() {
            return Ok(());
        }
        if r.abs() > 1e6 * chord {
            let sagitta = chord * chord / (8.0 * r.abs());
            let shape = if r > 0.0 {
                format!("it differs from a straight line by {sagitta:.1e} mm; program G1")
            } else {
                "as a negative radius it is an almost full circle of that size; check the sign and the radius".to_string()
            };
            self.diag(codes::ARC_ILL_CONDITIONED, Severity::Warning, w.sp(b'R'), format!("radius {} is over a million times the chord ({chord:.4}): the centre lies too far away to be computed exactly, and {shape}", r.abs()));
            return Ok(());
        }
        let half = (chord / (2.0 * r.abs())).min(1.0).asin().to_degrees();
        let sweep = if r > 0.0 {
            2.0 * half
        } else {
            360.0 - 2.0 * half
        };
        let near_half = (165.0..=195.0).contains(&sweep);
        let near_full = ngc && sweep >= 345.0;
        if near_half || near_full {
            self.diag(codes::ARC_ILL_CONDITIONED, Severity::Info, w.sp(b'R'), format!("this radius-format arc sweeps {sweep:.1}°: near {}° a tiny change of the end point moves the centre a lot; program the centre with {}/{}", if near_full { 360 } else { 180 }, ijk[a] as char, ijk[b] as char));
        }
        Ok(())
    }
}

impl Interp<'_, '_> {
    /// Hints that never stop the run: moves that do nothing, axis words taken
    /// by a non-modal code, polar-mode subtleties, redundant mode switches.
    fn misc_checks(&mut self, w: &Words) {
        let d = self.dialect;
        let motion = self.chk.motion;
        // NGC107: axis words taken by a group-0 code while a motion mode is only modal.
        if d == Dialect::Rs274ngc && w.any_axis() {
            let explicit = w.g.iter().any(|g| moves_to_axis_words(g.0));
            if let Some(&(g, s)) =
                w.g.iter()
                    .find(|g| matches!(g.0, 100 | 280 | 300 | 520 | 920))
            {
                if !explicit && self.st.modal.motion != 800 {
                    let name = analyzer::dialect::CodeNum(g).display();
                    self.diag(codes::NO_EFFECT, Severity::Info, s, format!("the axis words of this line belong to G{name}: the modal motion G{} does not run here", analyzer::dialect::CodeNum(self.st.modal.motion).display()));
                }
            }
        }
        // NGC427: rotary axis motion under cutter compensation.
        if d == Dialect::Rs274ngc && self.st.modal.comp != 400 && !w.has_g(400) && motion.is_some()
        {
            if let Some(c) = b"ABC".iter().copied().find(|c| w.has(*c)) {
                self.diag(codes::COMP_MOTION, Severity::Info, w.sp(c), format!("{} moves while cutter radius compensation is on: the offset is computed in the plane only, so check the path", c as char));
            }
        }
        // SW084: G41/G42 with no D/H and no radius for the current tool.
        if d == Dialect::Servoworks {
            if let Some(&(g, s)) = w.g.iter().find(|g| matches!(g.0, 410 | 420)) {
                if !w.has(b'D') && !w.has(b'H') && self.tool_diameter(None) == 0.0 {
                    self.diag(codes::COMP_MOTION, Severity::Warning, s, format!("G{} without D or H and no radius for tool {}: the compensation offset is zero", g / 10, self.st.tool));
                }
            }
            // SW112: G68 centre words outside the plane.
            if w.has_g(680) {
                let n = [b'X', b'Y', b'Z'][self.normal_axis()];
                if w.has(n) {
                    self.diag(codes::COORDINATE_MODE, Severity::Warning, w.sp(n), format!("{} is not in the G{} plane: the G68 rotation centre takes only the plane's two axes", n as char, self.st.modal.plane / 10));
                }
            }
            // SW059: G05 P10000 / G08 P1 while on, or P0 while off.
            for code in [50u32, 80] {
                if w.has_g(code) {
                    if let Some(p) = w.get(b'P') {
                        let on = p != 0.0;
                        if on == self.st.modal.dlacc {
                            self.diag(
                                codes::NO_EFFECT,
                                Severity::Info,
                                w.g_span(code),
                                format!(
                                    "3D-DLACC is already {}: this G{:02} changes nothing",
                                    if on { "on" } else { "off" },
                                    code / 10
                                ),
                            );
                        }
                    }
                }
            }
        }
        if d != Dialect::Fanuc {
            return;
        }
        // FAN060 / FAN062: polar coordinate mode (G16).
        if self.st.modal.polar && !w.has_g(150) {
            if let Some(&(g, s)) =
                w.g.iter()
                    .find(|g| matches!(g.0, 40 | 100 | 520 | 920 | 530 | 220 | 680 | 510))
            {
                if w.any_axis() {
                    self.diag(codes::NO_EFFECT, Severity::Info, s, format!("in polar mode (G16) the axis words of G{:02} are Cartesian, not radius and angle", g / 10));
                }
            }
            if let Some((g, s)) = motion {
                let (a, b) = self.plane_axes();
                let axes = [b'X', b'Y', b'Z'];
                if matches!(g, 0 | 10 | 20 | 30) && w.has(axes[b]) && !w.has(axes[a]) {
                    self.diag(codes::NO_EFFECT, Severity::Warning, s, format!("polar radius ({}) omitted: the current distance from the workpiece origin is used as the radius", axes[a] as char));
                }
            }
        }
        // FAN107: S is cleared when rigid tapping is cancelled.
        if w.has(b'S') {
            self.chk.rigid_s_cleared = false;
        }
        if self.chk.rigid_s_cleared {
            if let Some(&(m, s)) = w.m.iter().find(|m| matches!(m.0, 30 | 40)) {
                self.chk.rigid_s_cleared = false;
                self.diag(codes::NO_EFFECT, Severity::Info, s, format!("M{:02} after rigid tapping was cancelled: S was cleared to S0, so give S again", m / 10));
            }
        }
        if self.st.modal.rigid_tap
            && (w.has_g(800) || w.g.iter().any(|g| matches!(g.0, 0 | 10 | 20 | 30)))
        {
            self.chk.rigid_s_cleared = true;
        }
    }
}
