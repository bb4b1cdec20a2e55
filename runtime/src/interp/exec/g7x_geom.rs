//! Geometry of LinuxCNC's lathe roughing and finishing cycles (G70, G71, G72 and their
//! .1/.2 forms), written to produce the same passes as LinuxCNC 2.9's interpreter.
//!
//! Points are complex numbers with Z as the real part and X (a radius) as the
//! imaginary part, the way the profile is laid out in the XZ plane. The profile is
//! first turned and mirrored so that it runs towards decreasing Z and X; the passes
//! are computed in that frame and mapped back when they are emitted.  Every
//! tolerance and rule below is LinuxCNC's, because the goal is the same motion.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Distance under which two coordinates are the same point for the cycle.
const TOL: f64 = 1e-6;

/// A point or vector: `re` is Z, `im` is X.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct C {
    pub re: f64,
    pub im: f64,
}

pub(crate) const fn c(re: f64, im: f64) -> C {
    C { re, im }
}

impl C {
    fn conj(self) -> C {
        c(self.re, -self.im)
    }
    fn norm(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
    fn scale(self, k: f64) -> C {
        c(self.re * k, self.im * k)
    }
    fn div_by(self, k: f64) -> C {
        c(self.re / k, self.im / k)
    }
    /// A quarter turn clockwise, computed as `-p * i` with full complex
    /// arithmetic so that the signs of zeros come out as in LinuxCNC's output.
    fn turn(self) -> C {
        (-self) * I
    }
}

impl Add for C {
    type Output = C;
    fn add(self, o: C) -> C {
        c(self.re + o.re, self.im + o.im)
    }
}
impl Sub for C {
    type Output = C;
    fn sub(self, o: C) -> C {
        c(self.re - o.re, self.im - o.im)
    }
}
impl Neg for C {
    type Output = C;
    fn neg(self) -> C {
        c(-self.re, -self.im)
    }
}
impl Mul for C {
    type Output = C;
    fn mul(self, o: C) -> C {
        c(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}
/// The imaginary unit.
const I: C = c(0.0, 1.0);

impl Div for C {
    type Output = C;
    /// Smith's division, as the C runtime divides complex doubles.
    fn div(self, o: C) -> C {
        let (a, b, cr, d) = (self.re, self.im, o.re, o.im);
        if cr.abs() < d.abs() {
            let ratio = cr / d;
            let denom = cr * ratio + d;
            c((a * ratio + b) / denom, (b * ratio - a) / denom)
        } else {
            let ratio = d / cr;
            let denom = d * ratio + cr;
            c((b * ratio + a) / denom, (b - a * ratio) / denom)
        }
    }
}

/// What a profile element is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    Line,
    Arc,
    /// A rounded corner (A word): an arc whose ends and centre are found from its
    /// neighbours before the cycle runs.
    Fillet,
    /// A chamfered corner (C word): a line found the same way.
    Chamfer,
}

/// One element of the profile.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Seg {
    pub kind: Kind,
    pub s: C,
    pub e: C,
    /// Arc centre (arcs and fillets).
    pub c: C,
    pub ccw: bool,
    /// Size of a corner still to be resolved (fillets, chamfers).
    pub finish: f64,
}

/// One move of the cycle, in the frame where it was computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Out {
    Rapid(C),
    Feed(C),
    Arc { ccw: bool, c: C, e: C },
}

type Res<T> = Result<T, String>;

/// Makes sure no computation runs away: LinuxCNC's own loop could spin forever on
/// some profiles, a dry run must not.
const MAX_OUT: usize = 200_000;

struct Sink {
    moves: Vec<Out>,
}

impl Sink {
    fn push(&mut self, m: Out) -> Res<()> {
        if self.moves.len() >= MAX_OUT {
            return Err("the cycle does not converge (too many moves)".into());
        }
        self.moves.push(m);
        Ok(())
    }
    fn feed(&mut self, p: C) -> Res<()> {
        self.push(Out::Feed(p))
    }
    fn rapid(&mut self, p: C) -> Res<()> {
        self.push(Out::Rapid(p))
    }
    fn line(&mut self, p: C, fast: bool) -> Res<()> {
        if fast {
            self.rapid(p)
        } else {
            self.feed(p)
        }
    }
    fn arc(&mut self, ccw: bool, c: C, e: C) -> Res<()> {
        self.push(Out::Arc { ccw, c, e })
    }
}

impl Seg {
    pub(crate) fn line(s: C, e: C) -> Seg {
        Seg {
            kind: Kind::Line,
            s,
            e,
            c: C::default(),
            ccw: false,
            finish: 0.0,
        }
    }
    pub(crate) fn arc(ccw: bool, s: C, c: C, e: C) -> Seg {
        Seg {
            kind: Kind::Arc,
            s,
            e,
            c,
            ccw,
            finish: 0.0,
        }
    }
    pub(crate) fn fillet(d: f64, at: C) -> Seg {
        Seg {
            kind: Kind::Fillet,
            s: at,
            e: at,
            c: at,
            ccw: false,
            finish: d,
        }
    }
    pub(crate) fn chamfer(d: f64, at: C) -> Seg {
        Seg {
            kind: Kind::Chamfer,
            s: at,
            e: at,
            c: C::default(),
            ccw: false,
            finish: d,
        }
    }

    fn round(&self) -> bool {
        matches!(self.kind, Kind::Arc | Kind::Fillet)
    }

    fn radius(&self) -> f64 {
        if self.round() {
            (self.s - self.e).abs().min((self.s - self.c).abs())
        } else {
            (self.s - self.e).abs()
        }
    }

    fn monotonic(&self) -> bool {
        if !self.round() {
            return self.e.re - self.s.re <= 1e-3;
        }
        if self.finish != 0.0 {
            return true;
        }
        let entry = self.s.im - self.c.im;
        let exit = self.e.im - self.c.im;
        let dz = self.e.re - self.s.re;
        if self.ccw {
            entry >= -1e-3 && exit >= -1e-3 && dz <= -1e-3
        } else {
            entry <= 1e-3 && exit <= 1e-3 && dz <= -1e-3
        }
    }

    fn flip_im(&mut self) {
        self.s = self.s.conj();
        self.e = self.e.conj();
        if self.round() {
            self.ccw = !self.ccw;
            self.c = self.c.conj();
        }
    }

    fn flip_re(&mut self) {
        self.s = -self.s.conj();
        self.e = -self.e.conj();
        if self.round() {
            self.ccw = !self.ccw;
            self.c = -self.c.conj();
        }
    }

    fn rotate(&mut self) {
        self.s = self.s.turn();
        self.e = self.e.turn();
        if self.round() {
            self.c = self.c.turn();
        }
    }

    fn shift(&mut self, d: C) {
        self.s = self.s + d;
        self.e = self.e + d;
        if self.round() {
            self.c = self.c + d;
        }
    }

    /// Moves the element sideways by `d` (positive: to the left of a line, away
    /// from the centre of a counter-clockwise arc).
    fn offset(&mut self, d: f64) {
        if self.round() {
            let r = (self.s - self.c).abs();
            let k = (r + if self.ccw { d } else { -d }) / r;
            self.s = (self.s - self.c).scale(k) + self.c;
            self.e = (self.e - self.c).scale(k) + self.c;
        } else {
            let v = self.s - self.e;
            let n = (I.scale(d) * v).div_by(v.abs());
            self.s = self.s + n;
            self.e = self.e + n;
        }
    }

    /// Whether `p` (on the arc's circle) lies between the arc's ends.
    fn on_arc(&self, p: C) -> bool {
        let a = ((self.s - self.c).conj() * (p - self.c)).im;
        let b = ((self.e - self.c).conj() * (p - self.c)).im;
        if self.ccw {
            a >= -TOL && b <= TOL
        } else {
            a <= TOL && b >= -TOL
        }
    }

    /// Z values where the element crosses the line X = `x`, in LinuxCNC's order.
    fn cross_z(&self, x: f64) -> Vec<f64> {
        let mut v = Vec::new();
        if self.round() {
            let r = (self.s - self.c).abs();
            let mut q = -(x - r - self.c.im) * (x + r - self.c.im);
            if q < -TOL {
                return v;
            }
            if q < 0.0 {
                q = 0.0;
            }
            let q = q.sqrt();
            for z in [self.c.re + q, self.c.re - q] {
                if self.on_arc(c(z, x)) {
                    v.push(z);
                }
            }
        } else {
            if self.s.im.min(self.e.im) > x + TOL || self.s.im.max(self.e.im) < x - TOL {
                return v;
            }
            if (self.s.im - self.e.im).abs() < TOL {
                v.push(self.s.re);
                v.push(self.e.re);
            } else {
                v.push(
                    (x - self.s.im) / (self.e.im - self.s.im) * (self.e.re - self.s.re) + self.s.re,
                );
            }
        }
        v
    }

    fn draw(&self, out: &mut Sink) -> Res<()> {
        if self.round() {
            out.arc(self.ccw, self.c, self.e)
        } else {
            out.feed(self.e)
        }
    }

    /// Follows the element upwards from `loc`; true when it does not climb
    /// (the caller then looks for a pocket).
    fn climb(&self, loc: &mut C, out: &mut Sink) -> Res<bool> {
        if !self.round() {
            if self.e.im + TOL < self.s.im {
                return Ok(true);
            }
            if (*loc - self.s).abs() > TOL {
                return Err("How did we get here?".into());
            }
            out.feed(self.e)?;
            *loc = self.e;
            return Ok(false);
        }
        if !self.ccw {
            if loc.re > self.c.re {
                return Ok(true);
            }
            if (*loc - self.e).abs() > 1e-3 {
                out.arc(false, self.c, self.e)?;
            }
            *loc = self.e;
            Ok(false)
        } else {
            if loc.re < self.c.re {
                return Ok(true);
            }
            let ep = self.top_or_end();
            if (*loc - ep).abs() > 1e-3 {
                out.arc(true, self.c, ep)?;
            }
            *loc = ep;
            Ok(true)
        }
    }

    /// A counter-clockwise arc climbs only up to its top: that, or its end.
    fn top_or_end(&self) -> C {
        if self.e.re < self.c.re {
            c(self.c.re, self.c.im + (self.s - self.c).abs())
        } else {
            self.e
        }
    }

    /// Like `climb`, from wherever the tool is at height `loc.im`, without
    /// going down into pockets (G71.1/G72.1).
    fn climb_only(&self, loc: &mut C, out: &mut Sink) -> Res<()> {
        if !self.round() {
            if self.e.im < self.s.im {
                return Ok(());
            }
            let is = self.cross_z(loc.im);
            let Some(&z) = is.first() else {
                return Ok(());
            };
            loc.re = z;
            out.feed(*loc)?;
            out.feed(self.e)?;
            *loc = self.e;
            return Ok(());
        }
        let is = self.cross_z(loc.im);
        let (Some(&first), Some(&last)) = (is.first(), is.last()) else {
            return Ok(());
        };
        if !self.ccw {
            if last > self.c.re {
                return Ok(());
            }
            loc.re = last;
            out.feed(*loc)?;
            if (*loc - self.e).abs() > 1e-3 {
                out.arc(false, self.c, self.e)?;
            }
            *loc = self.e;
        } else {
            if first < self.c.re {
                return Ok(());
            }
            loc.re = first;
            out.feed(*loc)?;
            let ep = self.top_or_end();
            if (*loc - ep).abs() > 1e-3 {
                out.arc(true, self.c, ep)?;
            }
            *loc = ep;
        }
        Ok(())
    }

    /// Follows the element downwards from `loc` to height `x` at most; true when
    /// it does not go down.
    fn dive(&self, loc: &mut C, x: f64, out: &mut Sink, fast: bool) -> Res<bool> {
        if !self.round() {
            if self.s.im <= self.e.im + TOL {
                return Ok(true);
            }
            if x < self.e.im {
                out.line(self.e, fast)?;
                *loc = self.e;
                return Ok(false);
            }
            let is = self.cross_z(x);
            let Some(&z) = is.first() else {
                return Err("x too large in straight dive".into());
            };
            let ep = c(z, x);
            out.line(ep, fast)?;
            *loc = ep;
            return Ok(false);
        }
        if (*loc - self.e).abs() < TOL || loc.re - self.e.re <= TOL {
            *loc = self.e;
            return Ok(false);
        }
        let mut is = self.cross_z(x);
        if is.is_empty() {
            is = self.cross_z(x - TOL);
        }
        if self.ccw {
            if loc.re - TOL > self.c.re {
                return Ok(true);
            }
            match is.last() {
                Some(&z) if z <= self.c.re => {
                    let ep = c(z, x);
                    out.arc(true, self.c, ep)?;
                    *loc = ep;
                }
                _ => {
                    out.arc(true, self.c, self.e)?;
                    *loc = self.e;
                }
            }
            Ok(false)
        } else {
            if loc.re <= self.c.re {
                return Ok(true);
            }
            match is.first() {
                None => {
                    out.arc(false, self.c, self.e)?;
                    *loc = self.e;
                }
                // Only the far side of the arc is at this height: the pocket
                // loop lowers x and comes back.
                Some(&z) if z < self.c.re => {}
                Some(&z) => {
                    let ep = c(z, x);
                    out.arc(false, self.c, ep)?;
                    *loc = ep;
                }
            }
            Ok(false)
        }
    }
}

/// Moves the end of `p` and the start of `n` to where the two elements meet.
fn meet(p: &mut Seg, n: &mut Seg) -> Res<()> {
    match (p.round(), n.round()) {
        (false, false) => {
            let rot = (n.s - n.e).conj().div_by((n.s - n.e).abs());
            let ps = (p.s - n.e) * rot;
            let pe = (p.e - n.e) * rot;
            if (ps - pe).im == 0.0 {
                return Err("Cannot intersect parallel lines".into());
            }
            let f = ps.im / (ps - pe).im;
            let is = (ps + (pe - ps).scale(f)) / rot + n.e;
            n.s = is;
            p.e = is;
        }
        (true, false) => {
            if (n.s - p.e).abs() < TOL {
                return Ok(());
            }
            let rot = (n.s - n.e).conj().div_by((n.s - n.e).abs());
            let pe = (p.e - n.e) * rot;
            let pc = (p.c - n.e) * rot;
            let is = line_circle(pe, pc, rot, n.e, n.s);
            n.s = is;
            p.e = is;
        }
        (false, true) => {
            if (n.s - p.e).abs() < TOL {
                return Ok(());
            }
            let rot = (p.s - p.e).conj().div_by((p.s - p.e).abs());
            let pe = (n.e - p.e) * rot;
            let pc = (n.c - p.e) * rot;
            let is = line_circle(pe, pc, rot, p.e, n.s);
            n.s = is;
            p.e = is;
        }
        (true, true) => {
            let a = (n.s - n.c).abs();
            let b = (p.s - p.c).abs();
            let d = (n.c - p.c).abs();
            let cos = (d * d + a * a - b * b) / 2.0 / a / d;
            let cos2 = (cos * cos).min(1.0);
            let is = (c(cos, (1.0 - cos2).sqrt()) * (p.c - n.c))
                .div_by(d)
                .scale(a)
                + n.c;
            p.e = is;
            n.s = is;
        }
    }
    Ok(())
}

/// Where a line (rotated onto the real axis by `rot`, through `origin`) meets a
/// circle through `pe` about `pc` (both in the rotated frame): of the two
/// crossings, the one nearer `near`.
fn line_circle(pe: C, pc: C, rot: C, origin: C, near: C) -> C {
    let b = (pc - pe).norm() - pc.im * pc.im;
    let b = if b < 0.0 { 0.0 } else { b.sqrt() };
    let s1 = c(pc.re + b, 0.0) / rot + origin;
    let s2 = c(pc.re - b, 0.0) / rot + origin;
    if (near - s1).abs() < (near - s2).abs() {
        s1
    } else {
        s2
    }
}

/// `%g`-like text of a point for messages, as C++ streams print a complex.
fn point_text(p: C) -> String {
    fn g(v: f64) -> String {
        if v == 0.0 {
            return "0".into();
        }
        let exp = v.abs().log10().floor() as i32;
        if !(-5..6).contains(&exp) {
            let s = format!("{:.5e}", v);
            return s;
        }
        let decimals = (5 - exp).max(0) as usize;
        let s = format!("{:.*}", decimals, v);
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
    format!("({},{})", g(p.re), g(p.im))
}

/// Resolves the corner at `segs[h]` between its neighbours; returns the
/// corner's centre.
fn corner_finish(segs: &mut [Seg], h: usize) -> Res<C> {
    let (prev, next) = (segs[h - 1], segs[h + 1]);
    let mut finish = segs[h].finish;
    let (mut p, mut n) = (prev, next);
    p.offset(finish);
    n.offset(finish);
    if p.e.re - n.s.re > 1e-2 {
        finish = -finish;
        p = prev;
        n = next;
        p.offset(finish);
        n.offset(finish);
    }
    if p.e.re - n.s.re > 1e-2 {
        return Err(format!("Corner finish failed at {}", point_text(prev.e)));
    }
    meet(&mut p, &mut n)?;
    let center = (p.e + n.s).scale(0.5);
    p.offset(-finish);
    n.offset(-finish);
    segs[h].finish = finish;
    segs[h].s = p.e;
    segs[h - 1].e = p.e;
    segs[h].e = n.s;
    segs[h + 1].s = n.s;
    Ok(center)
}

/// The profile and the state of one cycle.
#[derive(Clone)]
pub(crate) struct Path {
    pub segs: Vec<Seg>,
    delta: f64,
    escape: C,
    flip: u8,
    pocket_starts: Vec<C>,
}

impl Path {
    pub(crate) fn new(segs: Vec<Seg>) -> Path {
        Path {
            segs,
            delta: 0.5,
            escape: c(0.3, 0.3),
            flip: 0,
            pocket_starts: Vec::new(),
        }
    }

    fn rotate(&mut self) {
        for s in &mut self.segs {
            s.rotate();
        }
        self.flip ^= 4;
    }

    /// Mirrors the profile so that it runs towards decreasing X and Z.
    fn swap(&mut self) {
        let (Some(f), Some(b)) = (self.segs.first(), self.segs.last()) else {
            return;
        };
        let d = f.e - b.e;
        if d.im > 0.0 {
            for s in &mut self.segs {
                s.flip_im();
            }
            self.flip ^= 2;
        }
        if d.re < 0.0 {
            for s in &mut self.segs {
                s.flip_re();
            }
            self.flip ^= 1;
        }
    }

    fn monotonic(&mut self) -> Res<()> {
        if let Some(f) = self.segs.first_mut() {
            if f.e.re - f.s.re > 0.0 {
                f.s.re = f.e.re;
            }
        }
        if self.segs.iter().any(|s| !s.monotonic()) {
            return Err("Not monotonic".into());
        }
        Ok(())
    }

    fn do_finish(&mut self) -> Res<()> {
        for h in 1..self.segs.len().saturating_sub(1) {
            match self.segs[h].kind {
                Kind::Fillet => {
                    let center = corner_finish(&mut self.segs, h)?;
                    let s = &mut self.segs[h];
                    s.c = center;
                    s.ccw = s.s.im - center.im > 0.0 || s.e.im - center.im > 0.0;
                    s.finish = 0.0;
                }
                Kind::Chamfer => {
                    corner_finish(&mut self.segs, h)?;
                }
                _ => {}
            }
        }
        self.segs.retain(|s| s.radius() >= 1e-3);
        Ok(())
    }

    /// Maps a point of the working frame back to the program's Z/X.
    pub(crate) fn unmap(&self, p: C) -> C {
        let i = |q: C| I * q;
        match self.flip {
            0 => p,
            1 => -p.conj(),
            2 => p.conj(),
            3 => -p,
            4 => i(p),
            5 => i(p).conj(),
            6 => -i(p).conj(),
            _ => (-I) * p,
        }
    }

    /// Whether the working frame mirrors the profile once (arcs change direction).
    pub(crate) fn mirrored(&self) -> bool {
        matches!(self.flip, 1 | 2 | 5 | 6)
    }

    /// Moves the profile (without its approach) `distance` away from the part,
    /// rounding the corners that open up.
    fn add_distance(&mut self, distance: f64) -> Res<()> {
        let (Some(f), Some(b)) = (self.segs.first().copied(), self.segs.last().copied()) else {
            return Ok(());
        };
        let side = (f.e - f.s) / (b.s - f.s);
        let distance = if side.im < 0.0 { -distance } else { distance };
        let mut approach = self.segs.remove(0);
        let mut done = 0.0;
        let mut rounds = 0;
        while done != distance {
            rounds += 1;
            if rounds > 10_000 || self.segs.is_empty() {
                return Err("the profile cannot be offset".into());
            }
            let mut step = 1e9_f64;
            for s in &self.segs {
                step = step.min(s.radius() / 2.0);
            }
            step = step.min((distance - done).abs());
            if distance < 0.0 {
                step = -step;
            }
            for s in &mut self.segs {
                s.offset(step);
            }
            self.segs.retain(|s| s.radius() >= 1e-3);
            // Corners that open up get an arc about the old corner.
            let mut i = 0;
            while i + 1 < self.segs.len() {
                let (p, n) = (self.segs[i], self.segs[i + 1]);
                if p.e.re - n.s.re > 1e-2 {
                    let (mut a, mut b) = (p, n);
                    a.offset(-step);
                    b.offset(-step);
                    let center = (a.e + b.s).scale(0.5);
                    self.segs
                        .insert(i + 1, Seg::arc(distance > 0.0, p.e, center, n.s));
                    i += 1;
                }
                i += 1;
            }
            // Elements that turned back on themselves go; neighbours meet.
            let mut i = 0;
            while i + 1 < self.segs.len() {
                if !self.segs[i].monotonic() {
                    if i == 0 || self.segs[i].radius() < self.segs[i - 1].radius() {
                        self.segs.remove(i);
                    } else {
                        self.segs.remove(i - 1);
                    }
                    i = 0;
                    if i + 1 >= self.segs.len() {
                        break;
                    }
                }
                if self.segs[i].radius() < 1e-3 {
                    self.segs.remove(i);
                    i = 0;
                } else {
                    let (a, b) = self.segs.split_at_mut(i + 1);
                    meet(&mut a[i], &mut b[0])?;
                }
                i += 1;
            }
            done += step;
        }
        for i in 0..self.segs.len().saturating_sub(1) {
            let mid = (self.segs[i].e + self.segs[i + 1].s).scale(0.5);
            self.segs[i].e = mid;
            self.segs[i + 1].s = mid;
        }
        if let Some(f) = self.segs.first() {
            approach.e = f.s;
        }
        self.segs.insert(0, approach);
        Ok(())
    }

    /// G70: `passes` finishing passes from `d` to `e` away from the profile, each
    /// starting from (z, x).
    pub(crate) fn g70(
        &mut self,
        x: f64,
        z: f64,
        d: f64,
        e: f64,
        passes: f64,
        out: &mut Vec<Out>,
    ) -> Res<()> {
        let mut sink = Sink {
            moves: std::mem::take(out),
        };
        let r = self.g70_inner(x, z, d, e, passes, &mut sink);
        *out = sink.moves;
        r
    }

    fn g70_inner(&mut self, x: f64, z: f64, d: f64, e: f64, p: f64, out: &mut Sink) -> Res<()> {
        if let Some(f) = self.segs.first_mut() {
            f.s = c(z, x);
        }
        // Decide from the profile alone (without the approach) whether it must be
        // turned to run along Z.
        let mut probe = self.clone();
        probe.segs.remove(0);
        probe.swap();
        if probe.segs.iter().any(|s| !s.monotonic()) {
            probe.rotate();
            probe.swap();
        }
        probe.monotonic()?;
        if probe.flip & 4 != 0 {
            self.rotate();
        }
        self.swap();
        self.do_finish()?;
        self.monotonic()?;
        // C++ converts the pass count to an integer for the loop only.
        let mut pass = p as i64;
        while pass > 0 {
            let distance = (pass - 1) as f64 * (d - e) / p + e;
            let mut path = self.clone();
            path.add_distance(distance)?;
            if let Some(f) = path.segs.first() {
                out.rapid(f.s)?;
                out.rapid(f.e)?;
            }
            for s in path.segs.iter().skip(1) {
                s.draw(out)?;
            }
            pass -= 1;
        }
        Ok(())
    }

    /// G71 (`rotate` false) and G72 (true); `cycle` is 0, 1 (no pockets) or 2
    /// (pockets only).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn g71(
        &mut self,
        cycle: u8,
        x: f64,
        z: f64,
        u: f64,
        w: f64,
        d: f64,
        i: f64,
        r: f64,
        rotate: bool,
        out: &mut Vec<Out>,
    ) -> Res<()> {
        let mut sink = Sink {
            moves: std::mem::take(out),
        };
        let res = (|| {
            if let Some(f) = self.segs.first_mut() {
                f.s = c(z, x);
            }
            if rotate {
                self.rotate();
            }
            self.swap();
            self.do_finish()?;
            self.monotonic()?;
            self.add_distance(d)?;
            for s in &mut self.segs {
                s.shift(c(w, u));
            }
            self.delta = i.max(2.0 * TOL);
            self.escape = c(r, r);
            let (Some(f), Some(b)) = (self.segs.first().copied(), self.segs.last().copied()) else {
                return Ok(());
            };
            sink.rapid(f.s)?;
            if b.e.im < f.s.im {
                self.segs.push(Seg::line(b.e, c(b.e.re, f.s.im)));
            }
            self.pocket_starts.push(f.s);
            self.pocket(cycle, f.s, &mut sink)
        })();
        *out = sink.moves;
        res
    }

    fn pocket(&mut self, mut cycle: u8, mut loc: C, out: &mut Sink) -> Res<()> {
        let n = self.segs.len();
        let mut p = 0usize;
        let mut guard = 0u64;
        'call: loop {
            let mut x = self.pocket_starts.last().map_or(0.0, |s| s.im);
            if cycle == 2 {
                // Skip the first roughing pass: go down the profile at once.
                while p < n {
                    if self.segs[p].dive(&mut loc, -1e9, out, p == 0)? {
                        break;
                    }
                    p += 1;
                }
                cycle = 3;
            }
            while p < n {
                guard += 1;
                if guard > 10_000_000 {
                    return Err("the cycle does not converge".into());
                }
                while x - TOL > loc.im {
                    // Stepping down one depth of cut at a time keeps LinuxCNC's
                    // rounding; a tiny depth on a tall profile must still end.
                    guard += 1;
                    if guard > 10_000_000 {
                        return Err("the cycle does not converge".into());
                    }
                    x -= self.delta;
                }
                if self.segs[p].dive(&mut loc, x, out, p == 0)? {
                    if cycle == 1 {
                        // No pockets: the rest of the profile is followed once.
                        while p < n {
                            self.segs[p].climb_only(&mut loc, out)?;
                            p += 1;
                        }
                    } else {
                        while p < n {
                            if self.segs[p].climb(&mut loc, out)? {
                                if cycle == 3 {
                                    let top = self.pocket_starts.last().map_or(0.0, |s| s.im);
                                    if loc.im > top && self.pocket_starts.len() > 1 {
                                        self.pocket_starts.pop();
                                    }
                                    if self.pocket_starts.len() == 1 {
                                        self.pocket_starts.push(loc);
                                    }
                                }
                                continue 'call;
                            }
                            p += 1;
                        }
                    }
                    return Ok(());
                }
                if (loc.im - x).abs() > TOL {
                    p += 1;
                    continue;
                }
                for ip in p..n {
                    let is = self.segs[ip].cross_z(loc.im);
                    let (Some(&first), Some(&last)) = (is.first(), is.last()) else {
                        continue;
                    };
                    let dz = if ip != p { first } else { last };
                    let distance = (dz - loc.re).abs();
                    if dz - TOL > loc.re {
                        continue;
                    }
                    if distance < TOL {
                        if p == ip {
                            continue;
                        } else if (loc - self.segs[ip].s).abs() < TOL {
                            p = ip;
                            break;
                        } else {
                            x -= self.delta;
                            break;
                        }
                    }
                    let mut dest = c(dz, loc.im);
                    out.feed(dest)?;
                    let k = (distance / 2.0 / self.escape.re).min(1.0);
                    dest = dest + self.escape.scale(k);
                    out.rapid(dest)?;
                    dest = loc - self.escape.scale(k).conj();
                    out.rapid(dest)?;
                    out.line(loc, p == 0)?;
                    x -= self.delta;
                    break;
                }
            }
            return Ok(());
        }
    }
}

/// Centre of an arc given by its radius `r` (G2, or G3 when `ccw`), computed in
/// the order LinuxCNC computes it.
pub(crate) fn radius_center(s: C, e: C, r: f64, ccw: bool) -> C {
    let mid = (s + e).div_by(2.0);
    let v = e - s;
    let k = ((r * r - v.norm() / 4.0) / v.norm()).sqrt();
    let d = I.scale(k) * v;
    if ccw {
        mid + d
    } else {
        mid - d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// G71 Q… X10 Z2 D0 I1.5 R0.5 on the profile X4 Z0, X8 Z-5, Z-10: the moves
    /// rs274 (LinuxCNC 2.9) prints after the block's own approach.
    #[test]
    fn g71_passes_match_rs274() {
        let segs = vec![
            Seg::line(c(2.0, 10.0), c(0.0, 4.0)),
            Seg::line(c(0.0, 4.0), c(-5.0, 8.0)),
            Seg::line(c(-5.0, 8.0), c(-10.0, 8.0)),
        ];
        let mut path = Path::new(segs);
        let mut out = Vec::new();
        let r = path.g71(0, 10.0, 2.0, 0.0, 0.0, 0.0, 1.5, 0.5, false, &mut out);
        assert_eq!(r, Ok(()));
        let (rp, fd) = (true, false);
        let want = [
            (rp, 2.0, 10.0),
            (rp, 2.0, 10.0),
            (fd, -10.0, 10.0),
            (rp, -9.5, 10.5),
            (rp, 1.5, 10.5),
            (rp, 2.0, 10.0),
            (rp, 1.5, 8.5),
            (fd, -10.0, 8.5),
            (rp, -9.5, 9.0),
            (rp, 1.0, 9.0),
            (rp, 1.5, 8.5),
            (rp, 1.0, 7.0),
            (fd, -3.75, 7.0),
            (rp, -3.25, 7.5),
            (rp, 0.5, 7.5),
            (rp, 1.0, 7.0),
            (rp, 0.5, 5.5),
            (fd, -1.875, 5.5),
            (rp, -1.375, 6.0),
            (rp, 0.0, 6.0),
            (rp, 0.5, 5.5),
            (rp, 0.0, 4.0),
            (fd, -5.0, 8.0),
            (fd, -10.0, 8.0),
            (fd, -10.0, 10.0),
        ];
        assert_eq!(out.len(), want.len());
        for (k, (m, (rapid, z, x))) in out.iter().zip(want).enumerate() {
            let (is_rapid, p) = match *m {
                Out::Rapid(p) => (true, p),
                Out::Feed(p) => (false, p),
                Out::Arc { e, .. } => (false, e),
            };
            let p = path.unmap(p);
            assert_eq!(is_rapid, rapid, "move {k}");
            assert!(
                (p.re - z).abs() < 1e-9 && (p.im - x).abs() < 1e-9,
                "move {k}: {p:?}"
            );
        }
    }

    /// A profile that turns back in Z cannot be roughed: rs274 says "Not monotonic".
    #[test]
    fn turning_back_is_an_error() {
        let segs = vec![
            Seg::line(c(2.0, 12.0), c(0.0, 4.0)),
            Seg::line(c(0.0, 4.0), c(-5.0, 8.0)),
            Seg::line(c(-5.0, 8.0), c(-2.0, 8.0)),
            Seg::line(c(-2.0, 8.0), c(-10.0, 10.0)),
        ];
        let mut out = Vec::new();
        let r = Path::new(segs).g71(0, 12.0, 2.0, 0.0, 0.0, 0.5, 1.0, 0.5, false, &mut out);
        assert_eq!(r, Err("Not monotonic".to_string()));
        assert!(out.is_empty());
    }

    /// Complex division follows Smith's method, so results keep the C runtime's
    /// rounding: (1 + 2i) / (3 - 4i) = -0.2 + 0.4i.
    #[test]
    fn division() {
        let q = c(1.0, 2.0) / c(3.0, -4.0);
        assert!((q.re + 0.2).abs() < 1e-15 && (q.im - 0.4).abs() < 1e-15);
    }

    /// The eight working frames map back as LinuxCNC's output stage does.
    #[test]
    fn unmap_frames() {
        let p = c(1.0, 2.0);
        let want = [
            (1.0, 2.0),
            (-1.0, 2.0),
            (1.0, -2.0),
            (-1.0, -2.0),
            (-2.0, 1.0),
            (-2.0, -1.0),
            (2.0, 1.0),
            (2.0, -1.0),
        ];
        for (f, (re, im)) in want.into_iter().enumerate() {
            let mut path = Path::new(Vec::new());
            path.flip = f as u8;
            assert_eq!(path.unmap(p), c(re, im), "frame {f}");
        }
    }
}
