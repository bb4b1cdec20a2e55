//! Modal codes outside motion: RS274/NGC unit switching (stored lengths converted
//! as LinuxCNC does), the M codes run before the move (tool change M6/M61, spindle,
//! coolant, overrides M48–M53, M70–M73 through `context.rs`), G4 dwell, and the
//! FANUC/ServoWorks modes: polar coordinates (G15/G16), scaling (G50/G51), mirror
//! (G50.1/G51.1), rotation (G68/G69), rigid tapping (M29) and ServoWorks 3D-DLACC.

use super::*;
use crate::rules::{
    dlacc_incompatible::DLACC_INCOMPATIBLE, dlacc_tcp::DLACC_TCP, interp::INTERP,
    rigid_tap::RIGID_TAP,
};

impl Interp<'_, '_> {
    /// Switches RS274/NGC program units, converting the stored lengths as
    /// LinuxCNC does.
    pub(super) fn switch_units(&mut self, inch: bool) {
        if inch == self.st.modal.inch {
            return;
        }
        let f = if inch { 1.0 / 25.4 } else { 25.4 };
        if self.ngc() {
            let st = &mut self.st;
            for v in [
                &mut st.pos,
                &mut st.mpos,
                &mut st.g92,
                &mut st.g52,
                &mut st.tlo,
                &mut st.comp_tip,
            ] {
                for x in v.iter_mut().take(3) {
                    *x *= f;
                }
            }
            st.comp_radius *= f;
            st.feed *= f;
            st.modal.path_tol = st.modal.path_tol.map(|t| t * f);
            for x in [
                &mut st.cycle.r,
                &mut st.cycle.z,
                &mut st.cycle.q,
                &mut st.cycle.i,
                &mut st.cycle.j,
                &mut st.cycle.k,
                &mut st.cycle.initial,
            ] {
                if let Some(v) = x.as_mut() {
                    *v *= f;
                }
            }
        }
        self.st.modal.inch = inch;
    }

    pub(super) fn exec_m_before(&mut self, w: &Words) -> Result<(), Diagnostic> {
        // Every step below is an M code's.
        if w.m.is_empty() {
            return Ok(());
        }
        let ngc = self.ngc();
        if w.has_m(60) && !(self.dialect == Dialect::Servoworks) {
            let t = self.st.next_tool;
            self.canon("START_CHANGE()");
            self.canon("STOP_SPINDLE_TURNING(0)");
            // rs274 prints the tool's slot in the tool table, not its number.
            let slot = if self.cfg.tool_order.is_empty() {
                t as usize
            } else {
                self.cfg
                    .tool_order
                    .iter()
                    .position(|x| *x == t)
                    .map(|i| i + 1)
                    .unwrap_or(0)
            };
            canon!(self, "CHANGE_TOOL({slot})");
            self.st.tool = t;
            self.event(EventKind::ToolChange { tool: t });
        }
        if w.has_m(610) {
            let t = w.get(b'Q').unwrap_or(0.0) as u32;
            // Like M6, M61 stops at a tool number the table lacks.
            if ngc {
                self.check_tool(t, w.sp(b'Q'))?;
            }
            // The standalone rs274 announces the new number but keeps reading the old
            // tool's data (#5400-#5410, G43 without H); `--emit canon` copies it, the
            // dry run loads the tool as a real LinuxCNC does.
            if self.canon.is_none() || !ngc {
                self.st.tool = t;
            }
            canon!(self, "CHANGE_TOOL_NUMBER({t})");
        }
        for (m, dir) in [(30u32, 1i8), (40, -1), (50, 0)] {
            if w.has_m(m) {
                self.st.spindle_dir = dir;
                self.canon(match dir {
                    1 => "START_SPINDLE_CLOCKWISE(0)",
                    -1 => "START_SPINDLE_COUNTERCLOCKWISE(0)",
                    _ => "STOP_SPINDLE_TURNING(0)",
                });
                let rpm = if dir == 0 { 0.0 } else { self.st.spindle };
                self.event(EventKind::Spindle { rpm, dir });
            }
        }
        if w.has_m(190) && ngc {
            let r = w.get(b'R').unwrap_or(0.0);
            let q = w.get(b'P').unwrap_or(0.0) as i32;
            canon!(self, "ORIENT_SPINDLE(0, {}, {q})", f4(r));
        }
        if ngc {
            self.exec_context_codes(w)?;
        }
        let mut coolant = false;
        if w.has_m(70) {
            self.st.mist = true;
            self.canon("MIST_ON()");
            coolant = true;
        }
        if w.has_m(80) {
            self.st.flood = true;
            self.canon("FLOOD_ON()");
            coolant = true;
        }
        if w.has_m(90) {
            self.st.mist = false;
            self.st.flood = false;
            self.canon("MIST_OFF()");
            self.canon("FLOOD_OFF()");
            coolant = true;
        }
        if coolant {
            let (mist, flood) = (self.st.mist, self.st.flood);
            self.event(EventKind::Coolant { mist, flood });
        }
        if ngc {
            // Override switches: M48/M49 both overrides, M50-M53 one each, on
            // unless P is 0.
            if w.has_m(480) {
                self.feed_override_off = false;
                self.canon("ENABLE_FEED_OVERRIDE()");
                self.canon("ENABLE_SPEED_OVERRIDE(0)");
            }
            if w.has_m(490) {
                self.feed_override_off = true;
                self.canon("DISABLE_FEED_OVERRIDE()");
                self.canon("DISABLE_SPEED_OVERRIDE(0)");
            }
            let on = w.get(b'P').is_none_or(|p| p != 0.0);
            if w.has_m(500) {
                self.feed_override_off = !on;
            }
            for (m, what) in [
                (500u32, "FEED_OVERRIDE()"),
                (510, "SPEED_OVERRIDE(0)"),
                (520, "ADAPTIVE_FEED()"),
                (530, "FEED_HOLD()"),
            ] {
                if w.has_m(m) {
                    let verb = if on { "ENABLE" } else { "DISABLE" };
                    canon!(self, "{verb}_{what}");
                }
            }
        }
        // Every other M code goes to the dry run, whose profile may give it a time.
        for (m, _) in &w.m {
            if !has_own_event(*m, ngc) {
                let code = *m;
                self.event(EventKind::MCode { code });
            }
        }
        if ngc {
            for (m, text) in [
                (620u32, "SET_MOTION_OUTPUT_BIT"),
                (630, "CLEAR_MOTION_OUTPUT_BIT"),
                (640, "SET_AUX_OUTPUT_BIT"),
                (650, "CLEAR_AUX_OUTPUT_BIT"),
            ] {
                if w.has_m(m) {
                    let p = w.get(b'P').unwrap_or(0.0) as i32;
                    canon!(self, "{text}({p})");
                }
            }
        }
        Ok(())
    }

    pub(super) fn exec_dwell(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let secs = match self.dialect {
            Dialect::Rs274ngc => match w.get(b'P') {
                Some(p) => p,
                None => {
                    return Err(self.err(
                        &INTERP,
                        w.g_span(40),
                        "dwell time P word missing with G4",
                    ))
                }
            },
            _ => {
                if let Some(x) = w.get(b'X') {
                    x
                } else if let Some(p) = w.get(b'P') {
                    p / 1000.0
                } else {
                    w.get(b'U').unwrap_or(0.0)
                }
            }
        };
        canon!(self, "DWELL({})", f4(secs));
        self.event(EventKind::Dwell(secs.max(0.0)));
        Ok(())
    }

    pub(super) fn exec_fanuc_modes(&mut self, w: &Words) -> Result<(), Diagnostic> {
        // (ServoWorks look-ahead and FANUC/ServoWorks coordinate transforms.)
        if self.ngc() {
            return Ok(());
        }
        // Between M29 and the G84/G74 block the spindle is already switched to position control:
        // the seed (§5.2.1) says an S command or axis movement there stops with PS0203.
        let starts_tap = w.has_g(840) || w.has_g(740);
        if self.dialect == Dialect::Fanuc
            && self.st.modal.rigid_tap
            && !matches!(self.st.modal.motion, 740 | 840)
            && !starts_tap
            && !w.has_m(290)
            && (w.has(b'S') || w.any_axis())
        {
            let span = if w.has(b'S') {
                w.sp(b'S')
            } else {
                w.first_axis().map(|c| w.sp(c)).unwrap_or_default()
            };
            self.diag(&RIGID_TAP, Severity::Error, span, "S command or axis movement between M29 and G84/G74: the control alarms (PS0203); position the tool before M29 and give the tap right after it");
        }
        // M29 is the rigid-tapping code (parameter 5210's default) only where a tap
        // follows: without any G84/G74 in the file it is a builder's M code.
        let taps = self.files.get(self.cur.0).is_some_and(|f| f.taps);
        if w.has_m(290) && taps {
            let span =
                w.m.iter()
                    .find(|m| m.0 == 290)
                    .map(|m| m.1)
                    .unwrap_or_default();
            if matches!(self.st.modal.motion, 740 | 840) {
                self.diag(&RIGID_TAP, Severity::Error, span, "M29 given while a tapping cycle is already modal: give M29 before G84/G74 (PS0204)");
            }
            self.st.modal.rigid_tap = true;
        }
        if w.has_g(800) || w.g().iter().any(|(g, _)| matches!(g, 0 | 10 | 20 | 30)) {
            self.st.modal.rigid_tap = false;
        }
        if w.has_g(150) {
            self.st.modal.polar = false;
        }
        if w.has_g(160) {
            self.st.modal.polar = true;
        }
        if w.has_g(500) {
            self.st.modal.scaling = false;
        }
        if w.has_g(510) {
            let c = [
                w.get(b'X').map(|v| self.lin(v)).unwrap_or(self.st.pos[0]),
                w.get(b'Y').map(|v| self.lin(v)).unwrap_or(self.st.pos[1]),
                w.get(b'Z').map(|v| self.lin(v)).unwrap_or(self.st.pos[2]),
            ];
            let p = w.get(b'P');
            let f = match p {
                Some(p) => {
                    let p = if w.point[(b'P' - b'A') as usize] {
                        p
                    } else {
                        p * 0.001
                    };
                    [p; 3]
                }
                None => {
                    // ServoWorks (§6.3.19, SW106): a factor left out keeps its value from
                    // the previous G51; elsewhere it is 1.
                    let kept = if self.dialect == Dialect::Servoworks {
                        self.st.scale.1
                    } else {
                        [1.0; 3]
                    };
                    [
                        w.get(b'I').unwrap_or(kept[0]),
                        w.get(b'J').unwrap_or(kept[1]),
                        w.get(b'K').unwrap_or(kept[2]),
                    ]
                }
            };
            self.st.scale = (c, f);
            self.st.modal.scaling = true;
        }
        if w.has_g(501) {
            // G50.1 cancels the mirror of the axes it names (all when it names none).
            let named: Vec<usize> = [b'X', b'Y', b'Z']
                .iter()
                .enumerate()
                .filter(|(_, c)| w.has(**c))
                .map(|(i, _)| i)
                .collect();
            if named.is_empty() {
                self.st.mirror = ([false; 3], [0.0; 3]);
            }
            for i in named {
                self.st.mirror.0[i] = false;
            }
            self.st.modal.mirror = self.st.mirror.0.iter().any(|b| *b);
        }
        if w.has_g(511) {
            for (i, c) in [b'X', b'Y', b'Z'].iter().enumerate() {
                if let Some(v) = w.get(*c) {
                    self.st.mirror.0[i] = true;
                    self.st.mirror.1[i] = self.lin(v);
                }
            }
            self.st.modal.mirror = self.st.mirror.0.iter().any(|b| *b);
        }
        if w.has_g(690) {
            self.st.modal.rotation = false;
        }
        if w.has_g(680) {
            let (a, b) = self.plane_axes();
            let letters = [b'X', b'Y', b'Z'];
            let ca = w
                .get(letters[a])
                .map(|v| self.lin(v))
                .unwrap_or(self.st.pos[a]);
            let cb = w
                .get(letters[b])
                .map(|v| self.lin(v))
                .unwrap_or(self.st.pos[b]);
            let r = w.get(b'R').unwrap_or(0.0);
            self.st.rotation = ([ca, cb], r);
            self.st.modal.rotation = true;
        }
        if self.dialect == Dialect::Servoworks && (w.has_g(50) || w.has_g(80)) {
            // Exactly four forms switch 3D-DLACC (§6.3.7); anything else is ignored.
            let p = w.get(b'P').map(|p| p.round() as i64);
            let on = match (w.has_g(50), p) {
                (true, Some(10000)) | (false, Some(1)) => Some(true),
                (_, Some(0)) => Some(false),
                _ => None,
            };
            if on == Some(true) && self.st.modal.tlo_mode == 432 {
                let span = w
                    .g()
                    .iter()
                    .find(|g| g.0 == 50 || g.0 == 80)
                    .map(|g| g.1)
                    .unwrap_or_default();
                return Err(self.err(&DLACC_TCP, span, "3D-DLACC cannot be combined with tool centre point control (G43.2): the control stops"));
            }
            if let Some(on) = on {
                self.st.modal.dlacc = on;
            }
        }
        if self.st.modal.dlacc {
            self.check_dlacc(w)?;
        }
        Ok(())
    }

    /// While 3D-DLACC is on only the manual's whitelist of G codes may run;
    /// the control stops at the first other one (SW056).
    pub(super) fn check_dlacc(&mut self, w: &Words) -> Result<(), Diagnostic> {
        const ALLOWED: &[u32] = &[
            0, 10, 20, 30, 40, 50, 80, 170, 180, 190, 200, 210, 280, 290, 300, 500, 510, 501, 511,
            520, 530, 540, 550, 560, 570, 580, 590, 541, 610, 640, 641, 650, 900, 910, 920, 3100,
            3110,
        ];
        for (g, s) in w.g() {
            if !ALLOWED.contains(g) {
                let name = analyzer::dialect::CodeNum(*g).display();
                let rule = if *g == 432 {
                    &DLACC_TCP
                } else {
                    &DLACC_INCOMPATIBLE
                };
                return Err(self.err(rule, *s, format!("G{name} cannot be used while 3D dynamic look-ahead is on: turn it off with G08 P0 (or G05 P0) first")));
            }
        }
        Ok(())
    }
}

/// M codes (× 10) with an event or a meaning of their own: stops and ends, calls,
/// spindle, tool change, coolant, FANUC/ServoWorks M29 (rigid tapping mode), and
/// the RS274/NGC overrides, I/O, M61 and modal-state codes, which take no time
/// the machine waits for.
fn has_own_event(m: u32, ngc: bool) -> bool {
    matches!(
        m,
        0 | 10 | 20 | 300 | 980 | 990 | 1980 | 30 | 40 | 50 | 60 | 70 | 80 | 90 | 290
    ) || (ngc && matches!(m, 480..=530 | 610..=680 | 700..=730))
}
