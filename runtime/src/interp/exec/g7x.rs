//! RS274/NGC lathe cycles G70 (finishing), G71/G72 (roughing along Z / along X) and
//! their .1 (no pockets) and .2 (pockets only) forms, as LinuxCNC 2.9 runs them.
//!
//! The block first rapids to its X/Z. The profile is the subroutine named by Q: it
//! is run for its control flow and parameters only, its motion blocks add elements
//! to the profile instead of moving (`Capture`), and the passes computed from the
//! profile (`g7x_geom`) are then executed as G0/G1/G2/G3 moves.

use super::g7x_geom::{self, c, Out, Path, Seg, C};
use super::*;
use crate::rules::{lathe_cycle::LATHE_CYCLE, step_budget::STEP_BUDGET};

/// The profile being read from the Q subroutine.
#[derive(Debug, Clone)]
pub(in crate::interp) struct Capture {
    /// Where the previous element ended (Z, X in program units, X a radius).
    start: C,
    segs: Vec<Seg>,
    /// Group-1 mode of the profile blocks (it starts as G0).
    mode: u32,
    /// G91 and G90.1 as they were at the cycle block: the profile is read with
    /// them, the moves are made in absolute coordinates.
    incremental: bool,
    ijk_abs: bool,
}

fn diam(st: &State) -> bool {
    st.modal.diameter
}

impl Interp<'_, '_> {
    /// Whether a profile is being read (motion blocks only add to it).
    pub(super) fn g7x_capturing(&self) -> bool {
        self.g7x.is_some()
    }

    /// Adds a profile block's element(s) (LinuxCNC's G7x profile reader).
    pub(super) fn g7x_profile_block(&mut self, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let Some(mut cap) = self.g7x.take() else {
            return Ok(());
        };
        let r = self.g7x_profile_inner(&mut cap, w, bspan);
        self.g7x = Some(cap);
        r
    }

    fn g7x_profile_inner(
        &mut self,
        cap: &mut Capture,
        w: &Words,
        bspan: Span,
    ) -> Result<(), Diagnostic> {
        let err = |s: &Self, m: &str| s.err(&LATHE_CYCLE, bspan, m);
        let start = cap.start;
        let mut end = if cap.incremental { c(0.0, 0.0) } else { start };
        let mut center = c(0.0, 0.0);
        if let Some(u) = w.get(b'U') {
            if cap.incremental {
                return Err(err(
                    self,
                    "G7x error: Cannot use U in incremental mode (G91)",
                ));
            }
            if w.has(b'X') {
                return Err(err(self, "G7x error: Cannot use U and X in the same block"));
            }
            end.im += if diam(&self.st) { u / 2.0 } else { u };
        } else if let Some(x) = w.get(b'X') {
            end.im = x;
        }
        if let Some(wv) = w.get(b'W') {
            if cap.incremental {
                return Err(err(
                    self,
                    "G7x error: Cannot use W in incremental mode (G91)",
                ));
            }
            if w.has(b'Z') {
                return Err(err(self, "G7x error: Cannot use W and Z in the same block"));
            }
            end.re += wv;
        } else if let Some(z) = w.get(b'Z') {
            end.re = z;
        }
        if let Some(i) = w.get(b'I') {
            center.im = i;
        }
        if let Some(k) = w.get(b'K') {
            center.re = k;
        }
        if cap.incremental {
            end = end + start;
        }
        if let Some(m) = w.g().iter().map(|g| g.0).find(|g| is_group_1(*g)) {
            cap.mode = m;
        }
        if start == end {
            return Ok(());
        }
        match cap.mode {
            0 | 10 => cap.segs.push(Seg::line(start, end)),
            20 | 30 => {
                if let Some(r) = w.get(b'R') {
                    if w.has(b'I') || w.has(b'K') {
                        return Err(err(self, "G7X error: both R and I or K flag used for arc"));
                    }
                    center = g7x_geom::radius_center(start, end, r, cap.mode == 30);
                } else {
                    if !w.has(b'I') && !w.has(b'K') {
                        return Err(err(
                            self,
                            "G7X error: either I or K must be present for arc",
                        ));
                    }
                    if !cap.ijk_abs {
                        center = center + start;
                    }
                }
                cap.segs.push(Seg::arc(cap.mode == 30, start, center, end));
            }
            _ => {}
        }
        if matches!(cap.mode, 0 | 10 | 20 | 30) {
            if w.has(b'A') && w.has(b'C') {
                return Err(err(self, "G7X error: Both A and C parameters on a corner"));
            }
            if let Some(a) = w.get(b'A') {
                cap.segs.push(Seg::fillet(a, end));
            }
            if let Some(cv) = w.get(b'C') {
                cap.segs.push(Seg::chamfer(cv, end));
            }
        }
        // `#<_x>` and `#<_z>` in the next profile blocks read the profile point.
        self.st.pos[0] = end.im;
        self.st.pos[2] = end.re;
        cap.start = end;
        Ok(())
    }

    /// Runs a G70/G71/G72 block (`mode` 700, 710, 711, 712, 720, 721, 722).
    pub(super) fn exec_g7x(&mut self, mode: u32, w: &Words, bspan: Span) -> Result<(), Diagnostic> {
        let span = w.g().iter().find(|g| g.0 == mode).map_or(bspan, |g| g.1);
        let Some(q) = w.get(b'Q') else {
            return Err(self.err(&LATHE_CYCLE, span, "G7x.x  requires a Q word"));
        };
        let (cycle, sub) = (mode / 10, mode % 10);
        if self.st.modal.comp != 400 && cycle != 70 {
            return Err(self.err(
                &LATHE_CYCLE,
                span,
                format!("G{cycle}.{sub} cannot be used with cutter compensation enabled"),
            ));
        }
        if self.st.modal.plane != 180 {
            return Err(self.err(
                &LATHE_CYCLE,
                span,
                format!("G{cycle}.{sub} can only be used in XZ plane (G18)"),
            ));
        }
        let (incremental, ijk_abs) = (self.st.modal.incremental, self.st.modal.ijk_abs);
        let mut x = self.st.pos[0];
        let mut z = self.st.pos[2];
        if let Some(v) = w.get(b'X') {
            x = if incremental { x + v } else { v };
        }
        if let Some(v) = w.get(b'Z') {
            z = if incremental { z + v } else { v };
        }
        // The approach is made with the block's own numbers as absolute
        // coordinates (LinuxCNC switches to G90 before it), also under G91.
        let mut approach = Words::default();
        for &l in b"XYZABC" {
            if let Some(v) = w.get(l) {
                approach.set(l, v);
            }
        }
        approach.push_g(0, span);
        self.g7x_move(&approach, span)?;

        // Read the profile: run the subroutine with motion diverted.
        let depth = self.frames.len();
        let (fi, bi) = self.cur;
        let key = format!("{}", q.trunc() as i64);
        let flow = self.call_ngc(fi, bi, &key, Vec::new(), span)?;
        self.g7x = Some(Capture {
            start: c(z, x),
            segs: Vec::new(),
            mode: 0,
            incremental,
            ijk_abs,
        });
        let here = self.cur;
        let pos_before = self.st.pos;
        let mut at = match flow {
            Flow::Goto(f, b) => (f, b),
            _ => (fi, bi + 1),
        };
        let budget = self.input.step_budget.max(1);
        let mut last = at;
        let read = loop {
            if self.frames.len() <= depth {
                break Ok(());
            }
            let nblocks = self.files.get(at.0).map_or(0, |f| f.prog.blocks.len());
            if at.1 as usize >= nblocks {
                if at.0 == 0 || !self.ret_from_sub(None) {
                    break Err(self.err(
                        &LATHE_CYCLE,
                        span,
                        "the profile subroutine of the cycle never returns",
                    ));
                }
                at = self.cur;
                continue;
            }
            self.steps += 1;
            if self.steps > budget {
                break Err(self.err(
                    &STEP_BUDGET,
                    span,
                    format!("execution stopped after {budget} blocks while reading a G7x profile: the step budget was reached; raise it with --step-budget"),
                ));
            }
            self.cur = at;
            last = at;
            match self.exec_block(at.0, at.1) {
                Ok(Flow::Next) => at = (self.cur.0, self.cur.1 + 1),
                Ok(Flow::Goto(f, b)) => at = (f, b),
                Ok(Flow::Stop) => {
                    break Err(self.err(
                        &LATHE_CYCLE,
                        span,
                        "the program stopped inside the profile of a G7x cycle",
                    ))
                }
                Err(e) => break Err(e),
            }
        };
        let cap = self.g7x.take();
        read?;
        // Errors of the cycle itself show the last profile line read (its
        // `endsub`), as rs274 does.
        self.cur = last;
        let Some(cap) = cap else {
            return Ok(());
        };
        // The block's mode is what the profile left, until a move sets it.
        self.st.modal.motion = cap.mode;
        if cap.segs.len() <= 1 {
            self.cur = here;
            return Ok(());
        }
        let num = |l: u8, d: f64| w.get(l).unwrap_or(d);
        let (d, e, i, p, r, u, wv) = (
            num(b'D', 0.0),
            num(b'E', 0.0),
            num(b'I', 1.0),
            num(b'P', 1.0),
            num(b'R', 0.5),
            num(b'U', 0.0),
            num(b'W', 0.0),
        );
        if i <= 0.0 {
            return Err(self.err(
                &LATHE_CYCLE,
                span,
                "G7X error: I must be greater than zero.",
            ));
        }
        // Under cutter compensation (G70 only) rs274 keeps the programmed point
        // where the approach left it, but the profile reader has moved its
        // current (compensated) point to the profile's end.
        if self.st.modal.comp != 400 {
            self.st.comp_tip[0] = self.st.pos[0];
            self.st.comp_tip[2] = self.st.pos[2];
            self.st.pos = pos_before;
        }
        let mut path = Path::new(cap.segs);
        let mut moves = Vec::new();
        let res = match cycle {
            70 => path.g70(x, z, d, e, p, &mut moves),
            71 => path.g71(sub as u8, x, z, u, wv, d, i, r, false, &mut moves),
            _ => path.g71(sub as u8, x, z, u, wv, d, i, r, true, &mut moves),
        };
        for m in moves {
            self.g7x_emit(&path, m, span)?;
        }
        if let Err(s) = res {
            return Err(self.err(&LATHE_CYCLE, span, format!("G7X error: {s}")));
        }
        self.cur = here;
        Ok(())
    }

    /// Makes one move of the cycle (absolute coordinates, absolute arc centres).
    fn g7x_emit(&mut self, path: &Path, m: Out, span: Span) -> Result<(), Diagnostic> {
        let mut w = Words::default();
        let set = |w: &mut Words, l: u8, v: f64| w.set(l, v);
        let put = |w: &mut Words, p: C| {
            set(w, b'X', p.im);
            set(w, b'Z', p.re);
        };
        match m {
            Out::Rapid(p) => {
                w.push_g(0, span);
                put(&mut w, path.unmap(p));
            }
            Out::Feed(p) => {
                w.push_g(10, span);
                put(&mut w, path.unmap(p));
            }
            Out::Arc { ccw, c: ctr, e } => {
                let ccw = ccw != path.mirrored();
                let (e, ctr) = (path.unmap(e), path.unmap(ctr));
                // A zero-length arc is left out, as LinuxCNC does.
                if (self.st.pos[2] - e.re).abs() < 1e-4 && (self.st.pos[0] - e.im).abs() < 1e-4 {
                    return Ok(());
                }
                w.push_g(if ccw { 30 } else { 20 }, span);
                put(&mut w, e);
                set(&mut w, b'I', ctr.im);
                set(&mut w, b'K', ctr.re);
            }
        }
        self.g7x_move(&w, span)
    }

    /// Runs a synthesized G0/G1/G2/G3 in G90 and G90.1.
    fn g7x_move(&mut self, w: &Words, span: Span) -> Result<(), Diagnostic> {
        let saved = (self.st.modal.incremental, self.st.modal.ijk_abs);
        self.st.modal.incremental = false;
        self.st.modal.ijk_abs = true;
        let r = self.exec_motion(w, span);
        self.st.modal.incremental = saved.0;
        self.st.modal.ijk_abs = saved.1;
        r
    }
}
