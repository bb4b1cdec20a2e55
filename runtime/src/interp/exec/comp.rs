//! Cutter radius compensation (G40/G41/G42, LinuxCNC semantics): entry and exit
//! moves, the one-move queue in `State::comp_queue` (a compensated move waits until
//! the next one gives its corner), convex corner arcs, concave corner trimming and
//! the gouge checks.

use super::*;
use crate::rules::interp::INTERP;

/// The 2007 EMC2 interpreter refuses every concave corner under cutter radius
/// compensation (rs274ngc.md NGC416); LinuxCNC 2.9 stops the tool short instead.
const EMC2_CONCAVE: &str = "Concave corner with cutter radius comp";

impl Interp<'_, '_> {
    /// Whether the tool runs left of the path under G41/G42 (the machine's
    /// `trc_g41_side` decides which code means left).
    pub(super) fn comp_left(&self) -> bool {
        (self.st.modal.comp == 410) != self.cfg.g41_right
    }

    pub(super) fn exec_comp(&mut self, w: &Words) -> Result<(), Diagnostic> {
        if w.has_g(400) {
            self.st.modal.comp = 400;
            self.st.comp_radius = 0.0;
            self.comp_flush();
            self.canon_comment("interpreter: cutter radius compensation off");
        }
        for given in [410u32, 420, 411, 421] {
            // LinuxCNC G41.1/G42.1: dynamic compensation with the diameter in D.
            let dynamic = given % 10 == 1;
            if !w.has_g(given) || (dynamic && !self.ngc()) {
                continue;
            }
            let code = given - given % 10;
            {
                self.st.modal.comp = code;
                let dia = match w.get(b'D') {
                    Some(d) if dynamic => self.lin(d),
                    Some(d)
                        if self.dialect == Dialect::Servoworks
                            && w.point[(b'D' - b'A') as usize] =>
                    {
                        self.lin(d)
                    }
                    d => self.tool_diameter(d),
                };
                // A negative diameter puts the tool on the other side.
                if dia < 0.0 {
                    self.st.modal.comp = if code == 410 { 420 } else { 410 };
                }
                self.st.comp_radius = dia.abs() / 2.0;
                // G41.1/G42.1 take the orientation from L (G18 only); G41/G42 from the table.
                self.st.comp_orientation = if dynamic {
                    w.get(b'L').map(|l| l.clamp(0.0, 9.0) as u8).unwrap_or(0)
                } else {
                    let idx = w
                        .get(b'D')
                        .map(|v| v.round() as u32)
                        .unwrap_or(self.st.tool);
                    self.cfg.tools.get(&idx).map(|t| t.orientation).unwrap_or(0)
                };
                let side = if self.comp_left() { "left" } else { "right" };
                self.st.comp_first = true;
                self.comp_flush();
                self.canon_comment(&format!(
                    "interpreter: cutter radius compensation on {side}"
                ));
            }
        }
        Ok(())
    }

    /// A straight move, offset for cutter radius compensation when it is on
    /// (LinuxCNC's algorithm: entry move perpendicular to the path, arcs around
    /// convex corners, held-back moves whose end points concave corners pull back).
    pub(super) fn comp_move(
        &mut self,
        t: [f64; 6],
        rapid: bool,
        span: Span,
    ) -> Result<(), Diagnostic> {
        if self.st.modal.comp == 400 || self.st.comp_radius <= 0.0 {
            if rapid {
                self.rapid_to(t);
            } else {
                self.feed_to(t, span)?;
            }
            return Ok(());
        }
        if self.st.modal.feed_mode == 930 && !rapid {
            self.check_feed(span)?;
            let len = dist(&self.st.pos, &t);
            let rate = if len == 0.0 {
                0.1
            } else {
                len * self.st.feed / self.unit()
            };
            canon!(self, "SET_FEED_RATE({})", f4(rate));
            self.inv_rate_set = true;
        }
        use std::f64::consts::{FRAC_PI_2, PI};
        let (a, b) = self.plane_axes();
        let r = self.st.comp_radius;
        let left = self.comp_left();
        let op = self.st.pos;
        // rs274 stores its ±π/2 in a double and takes the cosine of a double sum: along the
        // axes the sign of the tiny remainder decides whether `-0.0000` or `0.0000` is
        // printed, so no rounding to zero here.
        let dir = |ang: f64, gamma: f64| {
            let (s, c) = (ang + gamma).sin_cos();
            (c, s)
        };
        if self.st.comp_first {
            let dist = (t[a] - op[a]).hypot(t[b] - op[b]);
            if dist <= r && self.ngc() {
                return Err(self.err(
                    &INTERP,
                    span,
                    "length of cutter compensation entry move is not greater than the tool radius",
                ));
            }
            let alpha =
                (t[b] - op[b]).atan2(t[a] - op[a]) + if left { FRAC_PI_2 } else { -FRAC_PI_2 };
            let mut end = t;
            end[a] += r * alpha.cos();
            end[b] += r * alpha.sin();
            self.comp_flush();
            self.st.comp_endpoint = Some([op[a], op[b]]);
            // LinuxCNC records the offset direction, not the travel direction, for this move.
            self.comp_emit(end, rapid, [alpha.cos(), alpha.sin()], span)?;
            self.st.comp_first = false;
            self.st.pos = t;
            self.st.comp_tip = end;
            return Ok(());
        }
        let c = self.st.comp_tip;
        if t[a] == op[a] && t[b] == op[b] {
            let mut end = t;
            end[a] = c[a];
            end[b] = c[b];
            self.comp_emit(end, rapid, [0.0, 0.0], span)?;
            self.st.pos = t;
            self.st.comp_tip = end;
            return Ok(());
        }
        let mut theta = (c[b] - op[b]).atan2(c[a] - op[a]);
        let mut alpha = (t[b] - op[b]).atan2(t[a] - op[a]);
        let (beta, gamma) = if left {
            if theta < alpha {
                let (hi, lo) = add_ld(theta, 2.0 * PI);
                theta = hi + lo;
            }
            (theta - alpha - FRAC_PI_2, FRAC_PI_2)
        } else {
            if alpha < theta {
                let (hi, lo) = add_ld(alpha, 2.0 * PI);
                alpha = hi + lo;
            }
            (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
        };
        let (ex, ey) = dir(alpha, gamma);
        let mut end = t;
        end[a] += r * ex;
        end[b] += r * ey;
        let mut mid = c;
        mid[a] = op[a] + r * ex;
        mid[b] = op[b] + r * ey;
        let small = 0.05;
        let front = self.st.comp_queue.first().copied();
        let front_arc = front.filter(|q| q.kind == 2);
        // An "h" shape (tangent arc into a line with the tool outside the arc) is
        // treated as concave, as LinuxCNC does.
        let concave = beta < -small
            || beta > PI + small
            || (beta > PI - small
                && front_arc.is_some_and(|q| (q.turn > 0) != left && q.turn != 0));
        if !concave && beta > small {
            self.comp_move_endpoint([c[a], c[b]], span)?;
            if rapid {
                self.rapid_to(mid);
            } else {
                self.comp_corner_arc(c, mid, op, left, span)?;
            }
            self.st.comp_endpoint = Some([mid[a], mid[b]]);
        } else if concave {
            if self.variant == Variant::Emc2 {
                return Err(self.err(&INTERP, span, EMC2_CONCAVE));
            }
            match front_arc {
                None => {
                    let half = (beta + PI) / 2.0;
                    if half == 0.0 {
                        return Err(self.err(
                            &INTERP,
                            span,
                            "zero degree inside corner is invalid for cutter compensation",
                        ));
                    }
                    let retreat = r / half.tan();
                    let (rx, ry) = dir(theta, gamma);
                    let back = [c[a] + retreat * rx, c[b] + retreat * ry];
                    self.comp_move_endpoint(back, span)?;
                }
                Some(prev) => {
                    // Arc into line: the held-back arc (already compensated) ends where
                    // it meets the line's offset.
                    let oldrad = (prev.center[1] - c[b]).hypot(prev.center[0] - c[a]);
                    let base = (t[b] - op[b]).atan2(t[a] - op[a]);
                    let th = if prev.turn > 0 {
                        base + FRAC_PI_2
                    } else {
                        base - FRAC_PI_2
                    };
                    let phi = (prev.center[1] - op[b]).atan2(prev.center[0] - op[a]);
                    let inside = tool_inside_arc(left, prev.turn);
                    let oldrad_uncomp = if inside { oldrad + r } else { oldrad - r };
                    let d = oldrad_uncomp * (th - phi).cos();
                    let d2 = if inside { d - r } else { d + r };
                    let l = d2 / oldrad;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.err(
                            &INTERP,
                            span,
                            "Arc to straight motion makes a corner the compensated tool can't fit in without gouging",
                        ));
                    }
                    let ang = if inside == (prev.turn > 0) {
                        -l.acos() + th + PI
                    } else {
                        l.acos() + th + PI
                    };
                    let back = [
                        prev.center[0] + oldrad * ang.cos(),
                        prev.center[1] + oldrad * ang.sin(),
                    ];
                    self.comp_move_endpoint(back, span)?;
                }
            }
        } else {
            // Collinear lines or a tangent arc into a line: nothing to adjust.
            self.comp_flush();
            self.st.comp_endpoint = Some([c[a], c[b]]);
        }
        self.comp_emit(end, rapid, [t[a] - op[a], t[b] - op[b]], span)?;
        self.st.pos = t;
        self.st.comp_tip = end;
        Ok(())
    }

    pub(super) fn comp_emit(
        &mut self,
        end: [f64; 6],
        rapid: bool,
        dir: [f64; 2],
        span: Span,
    ) -> Result<(), Diagnostic> {
        let end = self.lathe_origin(end);
        if rapid {
            self.rapid_to(end);
        } else {
            self.feed_to(end, span)?;
        }
        self.comp_hold(u8::from(rapid), dir, [0.0; 2], 0, 0.0);
        Ok(())
    }

    /// Holds back the move just emitted (its canonical line and motion are the last ones).
    pub(super) fn comp_hold(
        &mut self,
        kind: u8,
        dir: [f64; 2],
        center: [f64; 2],
        turn: i32,
        sweep: f64,
    ) {
        let canon = self
            .canon
            .as_ref()
            .map(|c| c.lines.len().saturating_sub(1))
            .unwrap_or(0);
        self.st.comp_queue.push(CompQueued {
            canon,
            motion: self.out.motions.len().saturating_sub(1),
            kind,
            dir,
            center,
            turn,
            sweep,
        });
    }

    /// Releases the held-back moves. LinuxCNC queues them (and every canonical
    /// call after them) until now, so they carry this block's N number.
    pub(super) fn comp_flush(&mut self) {
        self.st.comp_endpoint = None;
        let Some(first) = self.st.comp_queue.first().map(|q| q.canon) else {
            return;
        };
        self.st.comp_queue.clear();
        if let Some(c) = self.canon.as_mut() {
            let prefix = c.current_prefix();
            for line in c.lines.iter_mut().skip(first) {
                if line.starts_with(" N") && line.len() >= 8 && line.is_char_boundary(8) {
                    line.replace_range(..8, &prefix);
                }
            }
        }
    }

    /// Moves the plane end point of every held-back move to `p`, refusing moves
    /// that would reverse (the tool would gouge), then releases them.
    pub(super) fn comp_move_endpoint(&mut self, p: [f64; 2], span: Span) -> Result<(), Diagnostic> {
        let queue = std::mem::take(&mut self.st.comp_queue);
        let endpoint = self.st.comp_endpoint;
        let (a, b) = self.plane_axes();
        let shift = self.lathe_origin([0.0; 6]);
        let u = self.unit();
        for q in queue.iter().copied() {
            if q.kind == 2 {
                if let Some(e) = endpoint {
                    let new_sweep = find_turn(e, q.center, q.turn, p);
                    let tol = if self.st.modal.inch { 0.001 } else { 0.0254 };
                    if q.sweep != 0.0 && new_sweep.abs() > q.sweep.abs() + tol {
                        self.st.comp_queue.clone_from(&queue);
                        return Err(self.err(
                            &INTERP,
                            span,
                            "Arc move in concave corner cannot be reached by the tool without gouging",
                        ));
                    }
                }
            } else if let Some(e) = endpoint {
                let dot = q.dir[0] * (p[0] - e[0]) + q.dir[1] * (p[1] - e[1]);
                if dot < 0.0 {
                    self.st.comp_queue.clone_from(&queue);
                    let what = if q.kind == 1 {
                        "Straight traverse"
                    } else {
                        "Straight feed"
                    };
                    return Err(self.err(
                        &INTERP,
                        span,
                        format!("{what} in concave corner cannot be reached by the tool without gouging"),
                    ));
                }
            }
            if let Some(line) = self.canon.as_mut().and_then(|c| c.lines.get_mut(q.canon)) {
                let name = match q.kind {
                    2 => "ARC_FEED(",
                    1 => "STRAIGHT_TRAVERSE(",
                    _ => "STRAIGHT_FEED(",
                };
                if let Some(at) = line.find(name) {
                    let head = line[..at + name.len()].to_string();
                    let mut args: Vec<String> = line[at + name.len()..]
                        .trim_end_matches(')')
                        .split(", ")
                        .map(str::to_string)
                        .collect();
                    let (ia, ib) = if q.kind == 2 { (0, 1) } else { (a, b) };
                    if args.len() > ia.max(ib) {
                        args[ia] = f4((p[0] + shift[a]) / u);
                        args[ib] = f4((p[1] + shift[b]) / u);
                        *line = format!("{head}{})", args.join(", "));
                    }
                }
            }
            let mut tip = self.st.comp_tip;
            tip[a] = p[0];
            tip[b] = p[1];
            let m_end = self.to_machine(self.lathe_origin(tip));
            // Motions are stored in mm, the machine position in program units.
            let lu = self.lu();
            if let Some(m) = self.out.motions.get_mut(q.motion) {
                m.end[a] = m_end[a] * lu;
                m.end[b] = m_end[b] * lu;
            }
        }
        self.st.comp_queue = queue;
        if !self.st.comp_queue.is_empty() {
            let mut tip = self.st.comp_tip;
            tip[a] = p[0];
            tip[b] = p[1];
            let m_end = self.to_machine(self.lathe_origin(tip));
            self.st.mpos[a] = m_end[a];
            self.st.mpos[b] = m_end[b];
            self.st.comp_tip = tip;
        }
        self.comp_flush();
        self.st.comp_endpoint = Some(p);
        Ok(())
    }

    /// The arc LinuxCNC inserts around a convex corner (radius = tool radius).
    pub(super) fn comp_corner_arc(
        &mut self,
        from: [f64; 6],
        to: [f64; 6],
        center: [f64; 6],
        left: bool,
        span: Span,
    ) -> Result<(), Diagnostic> {
        self.check_feed(span)?;
        let (to, center) = (self.lathe_origin(to), self.lathe_origin(center));
        let (a, b) = self.plane_axes();
        let n = self.normal_axis();
        let u = self.unit();
        let rot = if left { -1 } else { 1 };
        canon!(
            self,
            "ARC_FEED({}, {}, {}, {}, {}, {}, {}, {}, {})",
            f4(to[a] / u),
            f4(to[b] / u),
            f4(center[a] / u),
            f4(center[b] / u),
            rot,
            f4(from[n] / u),
            f4(to[3]),
            f4(to[4]),
            f4(to[5])
        );
        let mut c3 = from;
        c3[a] = center[a];
        c3[b] = center[b];
        let cm = self.to_machine(c3);
        let mut normal = [0.0; 3];
        normal[n] = if left { -1.0 } else { 1.0 };
        let mut end_p = to;
        end_p[n] = from[n];
        let end = self.to_machine(end_p);
        let radius = (from[a] - center[a]).hypot(from[b] - center[b]);
        let m = self.motion_base(
            MotionKind::Arc {
                center: [cm[0], cm[1], cm[2]],
                normal,
                turns: 0,
                radius,
            },
            self.st.mpos,
            end,
            self.st.feed,
        );
        self.out.motions.push(m);
        self.st.mpos = end;
        Ok(())
    }

    /// Cutter compensation of an arc, following LinuxCNC (entry arcs get a new
    /// centre; concave corners pull the held-back move back to the offset arc;
    /// convex corners get an arc around the programmed corner).
    pub(super) fn comp_arc(
        &mut self,
        t: [f64; 6],
        e2: [f64; 2],
        c: [f64; 2],
        r: f64,
        turn: i32,
        span: Span,
    ) -> Result<CompArc, Diagnostic> {
        let plain = CompArc {
            end: e2,
            target: t,
            radius: r,
            center: c,
            sweep: 0.0,
        };
        if self.st.modal.comp == 400 || self.st.comp_radius <= 0.0 {
            return Ok(plain);
        }
        use std::f64::consts::{FRAC_PI_2, PI};
        let (a, b) = self.plane_axes();
        let rt = self.st.comp_radius;
        let left = self.comp_left();
        let cw = turn < 0;
        let inside = left != cw;
        let op = self.st.pos;
        let o2 = [op[a], op[b]];
        let too_big = || {
            self.err(
                &INTERP,
                span,
                "Tool radius not less than arc radius with comp",
            )
        };
        if self.st.comp_first {
            // Entry arc: the end point moves off the contour and the arc gets a
            // new centre so that it still starts at the current point.
            if (e2[0] - o2[0]).hypot(e2[1] - o2[1]) <= rt {
                return Err(self.err(
                    &INTERP,
                    span,
                    "Radius of cutter compensation entry arc is not greater than the tool radius",
                ));
            }
            let gamma = if inside {
                (c[1] - e2[1]).atan2(c[0] - e2[0])
            } else {
                (e2[1] - c[1]).atan2(e2[0] - c[0])
            };
            let end = [e2[0] + rt * gamma.cos(), e2[1] + rt * gamma.sin()];
            let b_len = (o2[1] - end[1]).hypot(o2[0] - end[0]) / 2.0;
            let ab_ang = (c[1] - end[1]).atan2(c[0] - end[0]);
            let a_ang = (o2[1] - end[1]).atan2(o2[0] - end[0]) - ab_ang;
            if a_ang.cos().abs() < 0.0001 {
                return Err(too_big());
            }
            let c_len = b_len / a_ang.cos();
            let center = [end[0] + c_len * ab_ang.cos(), end[1] + c_len * ab_ang.sin()];
            // A lathe tool first moves its origin to where the compensated arc starts, or
            // the arc would not be one (LinuxCNC queues this feed before the arc).
            if self.lathe_origin([0.0; 6]) != [0.0; 6] {
                let here = self.st.pos;
                self.comp_emit(here, false, [0.0; 2], span)?;
                self.st.pos = here;
            }
            self.st.comp_first = false;
            let mut target = t;
            target[a] = end[0];
            target[b] = end[1];
            return Ok(CompArc {
                end,
                target,
                radius: c_len.abs(),
                center,
                sweep: find_turn(o2, center, turn, end),
            });
        }
        let small = 0.05;
        let cx = [self.st.comp_tip[a], self.st.comp_tip[b]];
        let arc_radius = (c[0] - e2[0]).hypot(c[1] - e2[1]);
        let mut theta = (cx[1] - o2[1]).atan2(cx[0] - o2[0]);
        theta = if left {
            theta - FRAC_PI_2
        } else {
            theta + FRAC_PI_2
        };
        let mut delta = (c[1] - o2[1]).atan2(c[0] - o2[0]);
        let alpha = if cw {
            delta + FRAC_PI_2
        } else {
            delta - FRAC_PI_2
        };
        let mut beta = if left { theta - alpha } else { alpha - theta };
        if beta > 1.5 * PI {
            beta -= 2.0 * PI;
        } else if beta < -FRAC_PI_2 {
            beta += 2.0 * PI;
        }
        let gamma = if inside {
            if arc_radius <= rt {
                return Err(too_big());
            }
            (c[1] - e2[1]).atan2(c[0] - e2[0])
        } else {
            delta += PI;
            (e2[1] - c[1]).atan2(e2[0] - c[0])
        };
        let end = [e2[0] + rt * gamma.cos(), e2[1] + rt * gamma.sin()];
        let newrad = if inside {
            arc_radius - rt
        } else {
            arc_radius + rt
        };
        let gouge = |s: &Self, what: &str| -> Diagnostic {
            s.err(
                &INTERP,
                span,
                format!("{what} makes a corner the compensated tool can't fit in without gouging"),
            )
        };
        if beta < -small || beta > PI + small || ((beta - PI).abs() < small && !inside) {
            if self.variant == Variant::Emc2 {
                return Err(self.err(&INTERP, span, EMC2_CONCAVE));
            }
            let front_arc = self.st.comp_queue.first().copied().filter(|q| q.kind == 2);
            let mid = match front_arc {
                None => {
                    // Line into arc.
                    let cyy = arc_radius * (beta - FRAC_PI_2).sin();
                    let (dist, toward) = if inside {
                        (arc_radius - rt, cyy + rt)
                    } else {
                        (arc_radius + rt, cyy - rt)
                    };
                    let l = toward / dist;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.err(
                            &INTERP,
                            span,
                            "Arc move in concave corner cannot be reached by the tool without gouging",
                        ));
                    }
                    let ang = match (inside, turn > 0) {
                        (true, true) => theta + l.asin(),
                        (true, false) => theta - l.asin(),
                        (false, true) => theta + PI - l.asin(),
                        (false, false) => theta + PI + l.asin(),
                    };
                    [c[0] + dist * ang.cos(), c[1] + dist * ang.sin()]
                }
                Some(prev) => {
                    // Arc into arc: where the two offset circles meet.
                    let oldrad = (prev.center[1] - cx[1]).hypot(prev.center[0] - cx[0]);
                    let arc_cc = (prev.center[1] - c[1]).hypot(prev.center[0] - c[0]);
                    if oldrad == 0.0 || arc_cc == 0.0 {
                        return Err(self.err(
                            &INTERP,
                            span,
                            "Arc to arc motion is invalid because the arcs have the same center",
                        ));
                    }
                    let ca = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad)
                        / (2.0 * oldrad * arc_cc);
                    if !(-1.0..=1.0).contains(&ca) {
                        return Err(gouge(self, "Arc to arc motion"));
                    }
                    let pullback = ca.acos();
                    let cc_dir = (c[1] - prev.center[1]).atan2(c[0] - prev.center[0]);
                    let dir = if tool_inside_arc(left, prev.turn) == (turn > 0) {
                        cc_dir + pullback
                    } else {
                        cc_dir - pullback
                    };
                    [
                        prev.center[0] + oldrad * dir.cos(),
                        prev.center[1] + oldrad * dir.sin(),
                    ]
                }
            };
            self.comp_move_endpoint(mid, span)?;
        } else if beta > small {
            // Convex: an arc around the programmed corner first.
            self.comp_flush();
            let tip = self.st.comp_tip;
            let mut mid = tip;
            mid[a] = o2[0] + rt * delta.cos();
            mid[b] = o2[1] + rt * delta.sin();
            self.comp_corner_arc(tip, mid, op, left, span)?;
            self.st.comp_tip[a] = mid[a];
            self.st.comp_tip[b] = mid[b];
            self.st.comp_endpoint = Some([mid[a], mid[b]]);
        } else {
            self.comp_flush();
            self.st.comp_endpoint = Some(cx);
        }
        let mut target = t;
        target[a] = end[0];
        target[b] = end[1];
        Ok(CompArc {
            end,
            target,
            radius: newrad,
            center: c,
            sweep: find_turn(o2, c, turn, e2),
        })
    }
}

/// The result of compensating an arc: plane end point, full target, radius,
/// centre (plane) and the programmed sweep LinuxCNC keeps for its gouge check.
pub(super) struct CompArc {
    pub(super) end: [f64; 2],
    pub(super) target: [f64; 6],
    pub(super) radius: f64,
    pub(super) center: [f64; 2],
    pub(super) sweep: f64,
}

/// LinuxCNC's `TOOL_INSIDE_ARC`: the tool is on the centre's side of the arc.
fn tool_inside_arc(left: bool, turn: i32) -> bool {
    (left && turn > 0) || (!left && turn < 0)
}

/// Signed sweep (radians) of an arc from `s` to `e` about `c` with `turn` turns
/// (positive counter-clockwise), as LinuxCNC's `find_turn` computes it.
fn find_turn(s: [f64; 2], c: [f64; 2], turn: i32, e: [f64; 2]) -> f64 {
    use std::f64::consts::TAU;
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (s[1] - c[1]).atan2(s[0] - c[0]);
    let mut beta = (e[1] - c[1]).atan2(e[0] - c[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += TAU;
        }
        beta - alpha + f64::from(turn - 1) * TAU
    } else {
        if alpha <= beta {
            alpha += TAU;
        }
        beta - alpha + f64::from(turn + 1) * TAU
    }
}

/// `a + b` where `b` is the double constant 2π standing for LinuxCNC's long-double
/// `2 * M_PIl`: the sum as a double and the remainder, including what the double constant
/// lacks of the true value; their sum rounds as rs274's long-double sum stored in a double.
fn add_ld(a: f64, b: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    // 2π − 2.0 * PI (the double constant is short of the true value by this much).
    const TWO_PI_LO: f64 = 2.449_293_598_294_706_4e-16;
    let b_lo = if b == 2.0 * PI { TWO_PI_LO } else { 0.0 };
    let s = a + b;
    let bb = s - a;
    let err = (a - (s - bb)) + (b - bb);
    (s, err + b_lo)
}
