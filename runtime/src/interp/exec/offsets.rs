//! Tool and offsets: work offsets (G54–G59.x, G54.1), the program ↔ machine frame
//! transforms (G92/G52 shifts, rotation, scaling, mirror), tool selection and the
//! tool table, tool length compensation (G43/G43.1/G49), G10 offset writes, G28/G30
//! reference points and G92/G52 (`exec_modal0`: the one-shot codes that consume the
//! block's axis words).

use super::*;
use crate::interp::frame;
use crate::rules::{
    coord_during_rotation::COORD_DURING_ROTATION, cycle_state::CYCLE_STATE, interp::INTERP,
    unknown_tool::UNKNOWN_TOOL,
};

impl Interp<'_, '_> {
    /// Work offset of the active origin, mm.
    pub(super) fn g5x_prog(&self) -> [f64; 6] {
        self.g5x_of(self.st.modal.origin)
    }

    pub(super) fn g5x_of(&self, origin: usize) -> [f64; 6] {
        let base = if origin >= 100 {
            7001 + 20 * origin.saturating_sub(101)
        } else {
            5201 + 20 * origin
        };
        // Every move asks for this: one slice of the parameters, one unit factor. The
        // highest origin (G54.1 P300) ends far below `NUM_PARAMS`; an unset or missing
        // parameter reads 0, as `param` reads it.
        let raw = self.st.params.get(base..base + 6).unwrap_or(&[None; 6]);
        let f = self.pfac();
        let mut o = [0.0; 6];
        for (k, (v, r)) in o.iter_mut().zip(raw).enumerate() {
            let r = r.unwrap_or(0.0);
            *v = if k < 3 { r * f } else { r };
        }
        o
    }

    /// Program-frame commanded point → machine.
    pub(super) fn to_machine(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = self.transform(p);
        for i in 0..6 {
            q[i] += self.st.g92[i] + self.st.g52[i];
        }
        let rot = self.xy_rotation();
        if rot != 0.0 {
            // LinuxCNC rotates the offset point about the work origin (G10 L2 R).
            [q[0], q[1]] = frame::rotate(&frame::plane_rotation(rot), [q[0], q[1]]);
        }
        let o = self.g5x_prog();
        let mut m = [0.0; 6];
        for i in 0..6 {
            m[i] = q[i] + o[i] + self.st.tlo[i];
            if rot != 0.0 && m[i].abs() < 1e-12 {
                // Round-off from the rotation would print as -0.000000.
                m[i] = 0.0;
            }
        }
        m
    }

    pub(super) fn to_program(&self, m: [f64; 6]) -> [f64; 6] {
        let o = self.g5x_prog();
        let mut q = [0.0; 6];
        for i in 0..6 {
            q[i] = m[i] - o[i] - self.st.tlo[i];
        }
        let rot = self.xy_rotation();
        if rot != 0.0 {
            let back = frame::rotate(&frame::plane_rotation(-rot), [q[0], q[1]]);
            // Round-off from the rotation would print as -0.000000.
            let snap = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
            [q[0], q[1]] = back.map(snap);
        }
        for i in 0..6 {
            q[i] -= self.st.g92[i] + self.st.g52[i];
        }
        self.untransform(q)
    }

    /// Inverse of [`Self::transform`]: rotation, then scaling, then mirror undone.
    pub(super) fn untransform(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = p;
        let m = &self.st.modal;
        if m.rotation {
            let (a, b) = self.plane_axes();
            let (c, ang) = self.st.rotation;
            [q[a], q[b]] = frame::rotate_about(&frame::plane_rotation(-ang), c, [q[a], q[b]]);
        }
        if m.scaling {
            let (c, f) = self.st.scale;
            [q[0], q[1], q[2]] = frame::unscale_about(c, f, [q[0], q[1], q[2]]);
        }
        if m.mirror {
            let (mask, c) = self.st.mirror;
            [q[0], q[1], q[2]] = frame::mirror(mask, c, [q[0], q[1], q[2]]);
        }
        q
    }

    /// XY rotation (degrees) of the active RS274/NGC coordinate system.
    pub(super) fn xy_rotation(&self) -> f64 {
        self.rotation_of(self.st.modal.origin)
    }

    pub(super) fn rotation_of(&self, origin: usize) -> f64 {
        if self.ngc() && (1..=9).contains(&origin) {
            self.param(5210 + 20 * origin)
        } else {
            0.0
        }
    }

    pub(super) fn rotation_canon(&self, origin: usize) -> String {
        format!("SET_XY_ROTATION({})", f4(self.rotation_of(origin)))
    }

    /// Mirror, scaling and rotation (FANUC/ServoWorks).
    pub(super) fn transform(&self, p: [f64; 6]) -> [f64; 6] {
        let mut q = p;
        let m = &self.st.modal;
        if m.mirror {
            let (mask, c) = self.st.mirror;
            [q[0], q[1], q[2]] = frame::mirror(mask, c, [q[0], q[1], q[2]]);
        }
        if m.scaling {
            let (c, f) = self.st.scale;
            [q[0], q[1], q[2]] = frame::scale_about(c, f, [q[0], q[1], q[2]]);
        }
        if m.rotation {
            let (a, b) = self.plane_axes();
            let (c, ang) = self.st.rotation;
            [q[a], q[b]] = frame::rotate_about(&frame::plane_rotation(ang), c, [q[a], q[b]]);
        }
        q
    }

    /// rs274 re-reads the current point after a block with a tool change (M6, M61)
    /// from its canon, which never saw the tool length offsets given since the last
    /// move (`T4 M6 G43 H4` then a canned cycle starts from the old height).  Only
    /// the canon output follows this: a real LinuxCNC re-reads the machine position
    /// with the new offset, which is what the simulation keeps.
    pub(super) fn refresh_after_tool_change(&mut self, w: &Words, before: (usize, [f64; 6])) {
        if !self.ngc() || self.canon.is_none() {
            return;
        }
        if self.out.motions.len() != before.0 {
            // Offsets apply before the block's move, which ends at the point the
            // interpreter holds.
            self.tlo_drift = [0.0; 6];
        } else {
            for i in 0..6 {
                self.tlo_drift[i] += before.1[i] - self.st.tlo[i];
            }
        }
        if w.has_m(60) || w.has_m(610) {
            // After G40 the programmed point is where the last compensated move was
            // aimed, but the canon last commanded the tool's offset point, which
            // the tool change re-reads.
            if self.st.modal.comp == 400 {
                let (a, b) = self.plane_axes();
                let here = self.to_program(self.st.mpos);
                self.st.pos[a] = here[a];
                self.st.pos[b] = here[b];
            }
            for i in 0..6 {
                self.st.pos[i] -= self.tlo_drift[i];
            }
            // The machine point follows, so that a later G43/G49 (which re-reads the
            // programmed point from it) starts where rs274 believes the tool is.
            if self.tlo_drift.iter().any(|d| *d != 0.0) {
                self.st.mpos = self.to_machine(self.st.pos);
            }
            self.tlo_drift = [0.0; 6];
        }
    }

    /// LinuxCNC stops at a T or H number its tool table lacks (spec NGC413/NGC503:
    /// error, in rs274's words); the other controls run on with a zero offset.
    pub(super) fn check_tool(&mut self, t: u32, span: Span) -> Result<(), Diagnostic> {
        let have_table = self.input.tool_table.is_some() || !self.cfg.tools.is_empty();
        if have_table && t != 0 && !self.cfg.tools.contains_key(&t) {
            if self.ngc() {
                return Err(self.err(
                    &UNKNOWN_TOOL,
                    span,
                    format!("Requested tool {t} not found in the tool table"),
                ));
            }
            self.diag(
                &UNKNOWN_TOOL,
                Severity::Warning,
                span,
                format!("tool T{t} is not in the tool table"),
            );
        }
        Ok(())
    }

    pub(super) fn tool_diameter(&self, d: Option<f64>) -> f64 {
        tool_diameter_of(&self.cfg, &self.st, self.ngc(), d)
    }

    pub(super) fn exec_tlo(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let set = |s: &mut Self, z: f64, x: f64, y: f64| {
            // The programmed point stays; the machine position follows at the next move.
            s.st.tlo = [x, y, z, 0.0, 0.0, 0.0];
            s.st.pos = s.to_program(s.st.mpos);
            let u = s.unit();
            canon!(
                s,
                "USE_TOOL_LENGTH_OFFSET({} {} {}, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)",
                f4(x / u),
                f4(y / u),
                f4(z / u)
            );
        };
        if w.has_g(490) {
            self.st.modal.tlo_mode = 490;
            set(self, 0.0, 0.0, 0.0);
        }
        for code in [430u32, 440] {
            if w.has_g(code) {
                self.st.modal.tlo_mode = code;
                let h = w
                    .get(b'H')
                    .map(|v| v.round() as u32)
                    .unwrap_or(self.st.tool);
                if w.has(b'H') {
                    self.check_tool(h, w.sp(b'H'))?;
                }
                let t = self.cfg.tools.get(&h).copied().unwrap_or_default();
                let sign = if code == 440 { -1.0 } else { 1.0 };
                let f = self.pfac();
                set(
                    self,
                    sign * t.length * f,
                    sign * t.x_offset * f,
                    sign * t.y_offset * f,
                );
            }
        }
        if w.has_g(432) {
            self.st.modal.tlo_mode = 432;
            if self.dialect == Dialect::Servoworks {
                let h = w.get(b'H').map(|v| v.round().max(0.0) as u32).unwrap_or(0);
                let tool = self.cfg.tools.get(&h).copied().unwrap_or_default();
                self.st.tcp_length = self.cfg.tcp_arm_length + tool.length * self.pfac();
            }
            if self.ngc() {
                // LinuxCNC G43.2 adds a tool's offset (H) to the one in force.
                let add;
                if let Some(h) = w.get(b'H').map(|v| v.round().max(0.0) as u32) {
                    self.check_tool(h, w.sp(b'H'))?;
                    let t = self.cfg.tools.get(&h).copied().unwrap_or_default();
                    let f = self.pfac();
                    add = [t.x_offset * f, t.y_offset * f, t.length * f];
                } else {
                    // LinuxCNC 2.9 looks up tool -1 for G43.2 without H and stops.
                    return Err(self.err(
                        &UNKNOWN_TOOL,
                        w.g_span(432),
                        "Requested tool -1 not found in the tool table",
                    ));
                }
                let cur = self.st.tlo;
                set(self, cur[2] + add[2], cur[0] + add[0], cur[1] + add[1]);
            }
        }
        if w.has_g(431) && self.ngc() {
            // Dynamic tool length offset from the block's axis words.
            self.st.modal.tlo_mode = 431;
            let x = w.get(b'X').map(|v| self.lin(v)).unwrap_or(0.0);
            let z = w.get(b'Z').map(|v| self.lin(v)).unwrap_or(0.0);
            set(self, z, x, 0.0);
        }
        Ok(())
    }

    pub(super) fn exec_coord_select(&mut self, w: &Words) -> Result<(), Diagnostic> {
        let mut origin = None;
        for (code, o) in [
            (540u32, 1usize),
            (550, 2),
            (560, 3),
            (570, 4),
            (580, 5),
            (590, 6),
            (591, 7),
            (592, 8),
            (593, 9),
        ] {
            if w.has_g(code) {
                origin = Some(o);
            }
        }
        if w.has_g(541) {
            // FANUC has at most 300 extended work offsets; clamping keeps the
            // parameter arithmetic (`100 + p`, `20 * (origin - 101)`) from
            // overflowing on `P1e30` (fuzz: interpret, add overflow).
            // A NaN P (from a macro expression) would cast to 0 and select
            // the nonexistent origin 100 (fuzz: interpret, subtract overflow).
            let p = w
                .get(b'P')
                .filter(|v| v.is_finite())
                .unwrap_or(1.0)
                .round()
                .clamp(1.0, 300.0) as usize;
            origin = Some(100 + p);
        }
        let Some(o) = origin else { return Ok(()) };
        if self.st.modal.rotation {
            let span = w
                .g()
                .iter()
                .find(|(g, _)| (540..=593).contains(g))
                .map(|x| x.1)
                .unwrap_or_default();
            self.diag(&COORD_DURING_ROTATION, Severity::Error, span, "work coordinate systems cannot be changed while coordinate rotation (G68) is on: cancel it with G69 first");
        }
        if o == self.st.modal.origin {
            self.canon_comment("interpreter: continuing to use same coordinate system");
            return Ok(());
        }
        self.st.modal.origin = o;
        self.st.pos = self.to_program(self.st.mpos);
        let u = self.unit();
        let g = self.g5x_prog();
        let g92 = self.st.g92;
        if o < 100 {
            canon!(self, "SET_G5X_OFFSET({o}, {})", Canon::six(&scale6(g, u)));
            canon!(self, "SET_G92_OFFSET({})", Canon::six(&scale6(g92, u)));
            let r = self.rotation_canon(o);
            self.canon(r);
        }
        Ok(())
    }

    /// Non-modal codes that consume axis words. Returns whether they did.
    pub(super) fn exec_modal0(&mut self, w: &Words) -> Result<bool, Diagnostic> {
        // Every code below is a G code other than a motion code.
        if !w.has_other_g() {
            return Ok(false);
        }
        if self.dialect == Dialect::Servoworks && w.has_g(370) {
            self.exec_g37(w)?;
            return Ok(true);
        }
        // Scaling, mirror and rotation codes take their centre from the axis words.
        if !self.ngc() && [510u32, 511, 501, 680].iter().any(|g| w.has_g(*g)) {
            return Ok(true);
        }
        if self.ngc() && w.has_g(431) {
            return Ok(true);
        }
        // FANUC/ServoWorks `G04 X…` gives the dwell time in X, not a move.
        if !self.ngc() && w.has_g(40) {
            return Ok(true);
        }
        let u = self.unit();
        let letters = [b'X', b'Y', b'Z', b'A', b'B', b'C'];
        let axis = |s: &Self, i: usize| -> Option<f64> {
            w.get(letters[i]).map(|v| if i < 3 { s.lin(v) } else { v })
        };
        if w.has_g(100) {
            let l = w.get(b'L').unwrap_or(0.0).round() as i64;
            let p = w.get(b'P').unwrap_or(0.0).round() as i64;
            match l {
                // FANUC/ServoWorks tool offset memory: L10/L11 length (H), L12/L13
                // radius (D); R is the value, added under G91.
                10..=13 if !self.ngc() => {
                    let t = p.max(0) as u32;
                    let mut tool = self.cfg.tools.get(&t).copied().unwrap_or_default();
                    let f = self.pfac();
                    if let Some(r) = w.get(b'R') {
                        let r = self.lin(r) / f;
                        let inc = self.st.modal.incremental;
                        if l <= 11 {
                            tool.length = if inc { tool.length + r } else { r };
                        } else {
                            let rad = if inc { tool.diameter / 2.0 + r } else { r };
                            tool.diameter = 2.0 * rad;
                        }
                    }
                    self.cfg.tools.insert(t, tool);
                }
                20 if self.input.program.dialect == Dialect::Servoworks => {
                    self.servoworks_axis_types(w, p);
                }
                2 | 20 => {
                    let origin = if p == 0 {
                        self.st.modal.origin
                    } else {
                        p.clamp(1, 9) as usize
                    };
                    let base = 5201 + 20 * origin;
                    if let Some(r) = w.get(b'R').filter(|_| self.ngc()) {
                        if l == 20 {
                            return Err(self.err(&INTERP, w.sp(b'R'), "R not allowed in G10 L20"));
                        }
                        self.set_param(5210 + 20 * origin, Some(r));
                    }
                    let cur_machine = self.st.mpos;
                    let rot = self.read_param((5210 + 20 * origin) as i64);
                    let rotated_l20 = l == 20
                        && rot != 0.0
                        && (axis(self, 0).is_some() || axis(self, 1).is_some());
                    if rotated_l20 {
                        // The point is given in the rotated system: both X and Y of the
                        // origin move (LinuxCNC's convert_setup).
                        let f = self.pfac();
                        let abs: Vec<f64> = (0..2)
                            .map(|i| {
                                cur_machine[i] - self.st.g92[i] - self.st.g52[i] - self.st.tlo[i]
                            })
                            .collect();
                        let off = [
                            self.read_param(base as i64) * f,
                            self.read_param(base as i64 + 1) * f,
                        ];
                        let turn = frame::plane_rotation(rot);
                        let cur = frame::unrotate(&turn, [abs[0] - off[0], abs[1] - off[1]]);
                        let want = [
                            axis(self, 0).unwrap_or(cur[0]),
                            axis(self, 1).unwrap_or(cur[1]),
                        ];
                        let rw = frame::rotate(&turn, want);
                        // Round-off from the rotation would print as -0.0000.
                        let snap = |v: f64| if v.abs() < 1e-12 { 0.0 } else { v };
                        self.set_param(base, Some(snap((abs[0] - rw[0]) / f)));
                        self.set_param(base + 1, Some(snap((abs[1] - rw[1]) / f)));
                    }
                    for i in 0..6 {
                        if rotated_l20 && i < 2 {
                            continue;
                        }
                        let Some(v) = axis(self, i) else { continue };
                        let scale = if i < 3 { self.pfac() } else { 1.0 };
                        let new = if l == 2 {
                            v
                        } else {
                            cur_machine[i] - self.st.g92[i] - self.st.g52[i] - self.st.tlo[i] - v
                        };
                        self.set_param(base + i, Some(new / scale));
                    }
                    if origin == self.st.modal.origin {
                        self.st.pos = self.to_program(self.st.mpos);
                        let g = self.g5x_of(origin);
                        canon!(
                            self,
                            "SET_G5X_OFFSET({origin}, {})",
                            Canon::six(&scale6(g, u))
                        );
                        let r = self.rotation_canon(origin);
                        self.canon(r);
                    } else {
                        self.canon_comment("interpreter: setting coordinate system origin");
                    }
                }
                1 | 10 | 11 => {
                    let t = p.max(0) as u32;
                    if self.ngc() {
                        self.check_tool(t, w.sp(b'P'))?;
                    }
                    let mut tool = self.cfg.tools.get(&t).copied().unwrap_or_default();
                    let f = self.pfac();
                    if l == 1 {
                        for (i, slot) in [&mut tool.x_offset, &mut tool.y_offset, &mut tool.length]
                            .into_iter()
                            .enumerate()
                        {
                            if let Some(v) = axis(self, i) {
                                *slot = v / f;
                            }
                        }
                    } else {
                        // L10/L11 make the current point read the given value in the
                        // current system (L10) or in G59.3, the touch-off fixture (L11),
                        // as LinuxCNC's convert_setup_tool: the spindle point in that
                        // system without tool offset, unrotated; G92/G52 count for L10
                        // only, so that they do not move the fixture.
                        let dest = if l == 11 { 9 } else { self.st.modal.origin };
                        let g5 = self.g5x_of(dest);
                        let rot = if dest < 100 {
                            self.read_param((5210 + 20 * dest) as i64)
                        } else {
                            0.0
                        };
                        let mut t = [0.0; 3];
                        for (i, v) in t.iter_mut().enumerate() {
                            *v = self.st.mpos[i] - g5[i];
                        }
                        let rotate = |x: f64, y: f64, deg: f64| {
                            let [x, y] = frame::rotate(&frame::plane_rotation(deg), [x, y]);
                            (x, y)
                        };
                        (t[0], t[1]) = rotate(t[0], t[1], -rot);
                        if l == 10 {
                            for (i, v) in t.iter_mut().enumerate() {
                                *v -= self.st.g92[i] + self.st.g52[i];
                            }
                        }
                        let (x, y) = (axis(self, 0), axis(self, 1));
                        if x.is_some() || y.is_some() {
                            // The component of the old offset along the axis not given
                            // is kept (in the possibly rotated system).
                            let (mut ox, mut oy) =
                                rotate(tool.x_offset * f, tool.y_offset * f, -rot);
                            let (mut tx, mut ty) = (t[0], t[1]);
                            match (x, y) {
                                (Some(xv), Some(yv)) => {
                                    (ox, oy) = (0.0, 0.0);
                                    tx -= xv;
                                    ty -= yv;
                                }
                                (Some(xv), None) => {
                                    ox = 0.0;
                                    tx -= xv;
                                    ty = 0.0;
                                }
                                (None, Some(yv)) => {
                                    oy = 0.0;
                                    ty -= yv;
                                    tx = 0.0;
                                }
                                (None, None) => {}
                            }
                            let (ox, oy) = rotate(ox, oy, rot);
                            let (tx, ty) = rotate(tx, ty, rot);
                            tool.x_offset = (tx + ox) / f;
                            tool.y_offset = (ty + oy) / f;
                        }
                        if let Some(z) = axis(self, 2) {
                            tool.length = (t[2] - z) / f;
                        }
                    }
                    if let Some(r) = w.get(b'R') {
                        tool.diameter = 2.0 * self.lin(r) / f;
                    }
                    self.cfg.tools.insert(t, tool);
                    if !self.cfg.tool_order.contains(&t) {
                        self.cfg.tool_order.push(t);
                    }
                    if self.canon.is_some() {
                        let slot = self
                            .cfg
                            .tool_order
                            .iter()
                            .position(|x| *x == t)
                            .map(|i| i + 1)
                            .unwrap_or(0);
                        // rs274 reports the entry in the tool table's units, not the program's.
                        let entry = format!(
                            "{} {} {} 0.0000 0.0000 0.0000 0.0000 0.0000 0.0000, 0.0000, 0.0000, 0",
                            f4(tool.x_offset),
                            f4(tool.y_offset),
                            f4(tool.length)
                        );
                        canon!(self, "SET_TOOL_TABLE_ENTRY({slot}, {t}, {entry})");
                        if t == self.st.tool || self.st.tool == 0 {
                            canon!(self, "SET_TOOL_TABLE_ENTRY(0, {t}, {entry})");
                        }
                    }
                }
                _ => {}
            }
            return Ok(true);
        }
        for (code, base) in [(281u32, 5161usize), (301, 5181)] {
            if w.has_g(code) && self.ngc() {
                // Store the current absolute position as the G28/G30 home.
                for i in 0..6 {
                    let scale = if i < 3 { self.pfac() } else { 1.0 };
                    self.set_param(base + i, Some(self.st.mpos[i] / scale));
                }
                return Ok(true);
            }
        }
        if w.has_g(280) || w.has_g(300) {
            let g30 = w.has_g(300);
            let span = w.g_span(if g30 { 300 } else { 280 });
            if self.st.modal.rotation {
                self.diag(&COORD_DURING_ROTATION, Severity::Error, span, "reference-position return (G28/G30) is not allowed while coordinate rotation (G68) is on");
            }
            // G80 in the same block cancels the cycle first (`G80 G28 G91 X0 Y0 Z0`
            // ends the FANUC manual's cycle examples).
            if !self.ngc() && self.st.modal.modal_cycle() && !w.has_g(800) {
                self.diag(&CYCLE_STATE, Severity::Error, span, "reference-position return while a canned cycle is modal: cancel it with G80 first (PS0044)");
                self.st.modal.motion = 800;
                self.st.cycle = CycleMem::default();
            }
            let mut mid = self.st.pos;
            for (i, m) in mid.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    *m = if self.st.modal.incremental { *m + v } else { v };
                }
            }
            self.rapid_to(mid);
            self.st.g28_mid = Some(mid);
            let home_base = if g30 { 5181 } else { 5161 };
            // FANUC/ServoWorks: reference position 1 for G28, P2 (default), P3 or P4 for
            // G30, from the machine profile (a P outside 2-4 is W007; the second is used).
            let reference = if g30 {
                w.get(b'P')
                    .map(f64::round)
                    .filter(|p| (2.0..=4.0).contains(p))
                    .map_or(1, |p| p as usize - 1)
            } else {
                0
            };
            let mut home_m = self.st.mpos;
            let all = !w.any_axis() || self.ngc() && !w.any_axis();
            for (i, h) in home_m.iter_mut().enumerate() {
                if all || w.has(letters[i]) {
                    let raw = if self.ngc() {
                        self.param(home_base + i)
                    } else {
                        self.cfg.reference_positions[reference][i] / self.cfg.param_unit
                    };
                    *h = if i < 3 { raw * self.pfac() } else { raw };
                }
            }
            let target = self.to_program(home_m);
            self.rapid_to(target);
            return Ok(true);
        }
        if w.has_g(290) && !self.ngc() {
            // G29: back through the G28/G30 intermediate point to the commanded point.
            let target = self.target(w);
            if let Some(mid) = self.st.g28_mid {
                let mut via = self.st.pos;
                for (i, v) in via.iter_mut().enumerate() {
                    if w.has(letters[i]) {
                        *v = mid[i];
                    }
                }
                self.rapid_to(via);
            }
            self.rapid_to(target);
            return Ok(true);
        }
        if w.has_g(520) && !self.ngc() {
            // ServoWorks ignores a G52 given in incremental mode (SW107; K003 says so).
            if self.dialect == Dialect::Servoworks && self.st.modal.incremental {
                return Ok(true);
            }
            if self.st.modal.rotation {
                self.diag(
                    &COORD_DURING_ROTATION,
                    Severity::Error,
                    w.g_span(520),
                    "G52 is not allowed while coordinate rotation (G68) is on",
                );
            }
            let mut g52 = self.st.g52;
            for (i, g) in g52.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    *g = v;
                }
            }
            self.st.g52 = g52;
            self.st.pos = self.to_program(self.st.mpos);
            return Ok(true);
        }
        if w.has_g(920) || (w.has_g(520) && self.ngc()) {
            if self.dialect != Dialect::Rs274ngc && !w.any_axis() {
                return Ok(true);
            }
            // Make the current point read as the given values.
            let cur = self.st.pos;
            let mut g92 = self.st.g92;
            let g52_ngc = w.has_g(520);
            for (i, g) in g92.iter_mut().enumerate() {
                if let Some(v) = axis(self, i) {
                    // LinuxCNC's G52 sets the offset itself; G92 makes the current point read `v`.
                    *g = if g52_ngc { v } else { cur[i] + *g - v };
                }
            }
            self.st.g92 = g92;
            for i in 0..6 {
                self.set_param(
                    5211 + i,
                    Some(g92[i] / if i < 3 { self.pfac() } else { 1.0 }),
                );
            }
            self.set_param(5210, Some(1.0));
            self.st.pos = self.to_program(self.st.mpos);
            canon!(self, "SET_G92_OFFSET({})", Canon::six(&scale6(g92, u)));
            return Ok(true);
        }
        for code in [921u32, 922] {
            if w.has_g(code) {
                self.st.g92 = [0.0; 6];
                if code == 921 {
                    for i in 0..7 {
                        self.set_param(5210 + i, Some(0.0));
                    }
                } else {
                    self.set_param(5210, Some(0.0));
                }
                self.st.pos = self.to_program(self.st.mpos);
                canon!(self, "SET_G92_OFFSET({})", Canon::six(&[0.0; 6]));
            }
        }
        if w.has_g(923) {
            let mut g92 = [0.0; 6];
            for (i, g) in g92.iter_mut().enumerate() {
                *g = self.param(5211 + i) * if i < 3 { self.pfac() } else { 1.0 };
            }
            self.st.g92 = g92;
            self.set_param(5210, Some(1.0));
            self.st.pos = self.to_program(self.st.mpos);
            canon!(self, "SET_G92_OFFSET({})", Canon::six(&scale6(g92, u)));
        }
        Ok(false)
    }

    /// Emits a compensated straight move and holds it back (LinuxCNC's enqueue).
    /// Where a compensated point `p` puts the tool's origin. LinuxCNC compensates the centre
    /// of a lathe tool's nose radius, and moves its origin (the imaginary tip the tool table
    /// measures) by the radius along X and Z as the orientation says; mill cutters
    /// (orientation 0 or 9) and other planes than G18 are not moved.
    pub(super) fn lathe_origin(&self, mut p: [f64; 6]) -> [f64; 6] {
        if !self.ngc()
            || self.st.modal.plane != 180
            || self.st.modal.comp == 400
            || matches!(self.st.comp_orientation, 0 | 9)
        {
            return p;
        }
        let r = self.st.comp_radius;
        match self.st.comp_orientation {
            1 | 2 | 6 => p[0] -= r,
            3 | 4 | 8 => p[0] += r,
            _ => {}
        }
        match self.st.comp_orientation {
            2 | 3 | 7 => p[2] -= r,
            1 | 4 | 5 => p[2] += r,
            _ => {}
        }
        p
    }
}

/// The diameter of tool `d` (the tool in the spindle without one) in internal units.
pub(crate) fn tool_diameter_of(cfg: &MachineCfg, st: &State, ngc: bool, d: Option<f64>) -> f64 {
    let idx = d.map(|v| v.round() as u32).unwrap_or(st.tool);
    let Some(t) = cfg.tools.get(&idx) else {
        return 0.0;
    };
    if ngc && cfg.param_unit == 25.4 {
        // rs274 divides by its external length unit, the rounded constant
        // 0.03937007874016 (a hair above 1/25.4), then by 25.4 in an inch program:
        // compensated points at an exact half of the last printed digit round as
        // they do there.
        let prog = if st.modal.inch { 25.4 } else { 1.0 };
        return t.diameter / 0.039_370_078_740_16 / prog;
    }
    t.diameter * pfac_of(cfg, ngc, st.modal.inch)
}
