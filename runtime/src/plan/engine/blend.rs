//! G64 blend arcs as LinuxCNC 2.9 builds them (`tpCreate…Blend` in `tp.c`,
//! `blendmath.c`): the corner geometry, the blend radius and speed, and how much
//! of each neighbouring move the arc replaces.

use std::f64::consts::PI;

use super::{
    acc_ratio_normal, cross3, dot3, norm3, sub3, unit3, Planner, Run, Tc, TcType, Term,
    ACC_RATIO_TAN, ANGLE_EPS, GAP_CYCLES, POS_EPS,
};

impl Planner {
    /// Builds the blend element for a G64 corner (`tpCreate…Blend`): line-line,
    /// arc-line, line-arc and arc-arc corners follow LinuxCNC; corners next to
    /// other curves use the line-line construction on the tangents.
    pub(super) fn blend_arc(&self, prev: &Tc, tc: &Tc) -> Option<Blend> {
        match (prev.ty, tc.ty, &prev.circ, &tc.circ) {
            (TcType::Circle, TcType::Line, Some(c), _) => self.blend_arc_line(prev, tc, c),
            (TcType::Line, TcType::Circle, _, Some(c)) => self.blend_line_arc(prev, tc, c),
            (TcType::Circle, TcType::Circle, Some(c1), Some(c2)) => {
                self.blend_arc_arc(prev, tc, c1, c2)
            }
            // A helix is not coplanar with its neighbour's corner plane, so LinuxCNC
            // builds no blend arc for it.
            (TcType::Circle, _, None, _) | (_, TcType::Circle, _, None) => None,
            _ => self.blend_line_line(prev, tc),
        }
    }

    /// `blendGeom3Init`: tangents at the corner, intersection half-angle, binormal.
    fn corner_geometry(prev: &Tc, tc: &Tc) -> Option<Corner> {
        let u1 = prev.u_end;
        let u2 = tc.u_start;
        let theta = (-dot3(&u1, &u2)).clamp(-1.0, 1.0).acos() / 2.0;
        if PI / 2.0 - theta < ANGLE_EPS || theta < ANGLE_EPS {
            return None;
        }
        Some((u1, u2, theta, unit3(&cross3(&u1, &u2))))
    }

    /// `blendParamKinematics` + `blendComputeParameters`. `u1`, `u2` are the
    /// directions used for the speed triangle (secants for convex arcs).
    #[allow(clippy::too_many_arguments)]
    fn blend_params(
        &self,
        prev: &Tc,
        tc: &Tc,
        u1: &[f64; 3],
        u2: &[f64; 3],
        binormal: &[f64; 3],
        theta: f64,
        l1: f64,
        l2: f64,
    ) -> Option<BlendParams> {
        let phi = PI - 2.0 * theta;
        let t1 = if prev.tolerance == 0.0 {
            prev.nominal * 0.25
        } else {
            prev.tolerance
        };
        let t2 = if tc.tolerance == 0.0 {
            tc.nominal * 0.25
        } else {
            tc.tolerance
        };
        let tolerance = t1.min(t2).min(prev.nominal * 0.25).min(tc.nominal * 0.25);
        let acc_b = [self.acc[0], self.acc[1], self.acc[2]];
        let vel_b = [self.vel[0], self.vel[1], self.vel[2]];
        let a_max = inscribed(binormal, &acc_b);
        let a_n_max = a_max * acc_ratio_normal();
        let v_req = prev.max_target_vel().max(tc.max_target_vel());
        let v_planar_max = inscribed(binormal, &vel_b);
        let phi_eff = phi.min(PI * 0.49);
        let v_max1 = prev.maxvel.min(tc.maxvel / phi_eff.cos());
        let v_max2 = tc.maxvel.min(prev.maxvel / phi_eff.cos());
        let v_area = v_max1 * v_max2 / 2.0 * phi.sin();
        let diff = [
            u2[0] * v_max2 - u1[0] * v_max1,
            u2[1] * v_max2 - u1[1] * v_max1,
            u2[2] * v_max2 - u1[2] * v_max1,
        ];
        let base = norm3(&diff);
        let mut v_alt = if base > 0.0 { 2.0 * v_area / base } else { 0.0 };
        if prev.ty != TcType::Line || tc.ty != TcType::Line {
            v_alt = 0.0;
        }
        let v_goal = v_req.min(v_alt.max(v_planar_max));
        let h_tol = tolerance / (1.0 - theta.sin());
        let d_tol = theta.cos() * h_tol;
        let d_geom = l1.min(l2).min(d_tol);
        let r_geom = theta.tan() * d_geom;
        let v_normal = (a_n_max * r_geom).sqrt();
        let v_plan = v_normal.min(v_goal);
        let a_par = a_max * 0.5;
        let v_tri = (2.0 * a_par * d_geom).sqrt();
        let t_blend = v_tri.min(v_plan) / a_par;
        let s_blend = t_blend * v_plan;
        let r_blend = (s_blend / phi).min(r_geom);
        let r_plan = (v_plan * v_plan / a_n_max).max(r_blend);
        let d_plan = r_plan / theta.tan();
        let s_arc = r_plan * phi;
        if r_plan.is_nan()
            || r_plan < POS_EPS
            || s_arc < 1e-6
            || !v_plan.is_finite()
            || v_plan <= 0.0
        {
            return None;
        }
        Some(BlendParams {
            tolerance,
            a_max,
            v_req,
            v_plan,
            r_plan,
            d_plan,
            s_arc,
        })
    }

    /// The blend element itself (`tpInitBlendArcFromPrev`).
    fn blend_tc(&self, prev: &Tc, bp: &BlendParams, length: f64, u1: [f64; 3], u2: [f64; 3]) -> Tc {
        Tc {
            ty: TcType::Blend,
            rapid: prev.rapid,
            rotary: false,
            pure_rotary: false,
            u_start: u1,
            u_end: u2,
            radius: bp.r_plan,
            circ: None,
            target: length,
            nominal: length,
            reqvel: bp.v_req,
            maxvel: bp.v_plan.min(length / self.cycle),
            maxaccel: bp.a_max,
            term: Term::Tangent,
            tolerance: prev.tolerance,
            kink_vel: -1.0,
            kink_reduce: 0.0,
            kink_reduce_prev: 0.0,
            blend_prev: false,
            acc_ratio_tan: ACC_RATIO_TAN,
            finalized: true,
            finalvel: 0.0,
            block: prev.block,
            tool: prev.tool,
            halve_parabolic: true,
            at_max: false,
            run_vmax: 0.0,
            optimized: false,
            dogleg: false,
            travel: None,
            feed: prev.feed,
            axis_vel: prev.axis_vel,
            run: Run::default(),
        }
    }

    /// `tpCreateLineLineBlend`.
    fn blend_line_line(&self, prev: &Tc, tc: &Tc) -> Option<Blend> {
        let (u1, u2, theta, binormal) = Self::corner_geometry(prev, tc)?;
        let l1 = prev.target.min(prev.nominal * 0.5);
        let l2 = tc.target * 0.5;
        let bp = self.blend_params(prev, tc, &u1, &u2, &binormal, theta, l1, l2)?;
        let l_prev = prev.target - bp.d_plan;
        let consume = prev.ty == TcType::Line
            && !prev.blend_prev
            && l_prev / bp.v_plan < GAP_CYCLES * self.cycle;
        // A swallowed rest of the previous line becomes a straight lead-in of the
        // blend element (`arcFromBlendPoints3`), run under the blend's limits.
        let length = bp.s_arc + if consume { l_prev.max(0.0) } else { 0.0 };
        Some(Blend {
            arc: self.blend_tc(prev, &bp, length, u1, u2),
            trim_prev: bp.d_plan,
            trim_next: bp.d_plan,
            consume,
            prev_circ: None,
            next_circ: None,
        })
    }

    /// `tpCreateArcLineBlend`: the arc is shortened at its end, the line at its start.
    fn blend_arc_line(&self, prev: &Tc, tc: &Tc, c1: &Circ) -> Option<Blend> {
        let (u_tan1, u_tan2, theta_tan, binormal) = Self::corner_geometry(prev, tc)?;
        let p = c1.point(c1.angle);
        let (center1, radius1) = c1.spiral_fit(&p, &u_tan1);
        // Convex when the line leaves the circle's outside.
        let convex1 = dot3(&sub3(&p, &center1), &u_tan2) < 0.0;
        let blend_angle_1 = if convex1 { theta_tan } else { PI / 2.0 };
        let phi1_max = (c1.angle * 2.0 / 3.0).min(blend_angle_1);
        let mut theta = theta_tan;
        let mut u1 = u_tan1;
        if convex1 {
            let bpnt = c1.point(c1.angle - phi1_max / 2.0);
            u1 = unit3(&sub3(&p, &bpnt));
            theta = theta.min(theta_tan - phi1_max / 4.0);
        }
        let l1 = if convex1 {
            (phi1_max / 4.0).sin() * radius1
        } else {
            phi1_max * radius1
        };
        let l2 = tc.nominal / 2.0;
        if !colinear(&binormal, &c1.normal) {
            return None;
        }
        let bp = self.blend_params(prev, tc, &u1, &u_tan2, &binormal, theta, l1, l2)?;
        // blendArcLinePostProcess: centre of the blend circle tangent to both.
        let d1 = if convex1 { -bp.r_plan } else { bp.r_plan } + radius1;
        let n2 = unit3(&cross3(&binormal, &u_tan2));
        let r_pc1 = sub3(&center1, &p);
        let c1_u = dot3(&r_pc1, &u_tan2);
        let c1_n = dot3(&r_pc1, &n2);
        let (root0, root1) = quadratic(
            1.0,
            2.0 * c1_u,
            c1_u * c1_u - d1 * d1 + (bp.r_plan - c1_n).powi(2),
        )?;
        let d_l = root0.abs().min(root1.abs());
        let r_pc = [
            u_tan2[0] * d_l + n2[0] * bp.r_plan,
            u_tan2[1] * d_l + n2[1] * bp.r_plan,
            u_tan2[2] * d_l + n2[2] * bp.r_plan,
        ];
        let arc_center = [p[0] + r_pc[0], p[1] + r_pc[1], p[2] + r_pc[2]];
        if norm3(&r_pc) - bp.r_plan > bp.tolerance {
            return None;
        }
        let trim1 = trim_angle(&p, &arc_center, &center1);
        if trim1 > phi1_max {
            return None;
        }
        let new_angle = c1.angle - trim1;
        if new_angle <= 0.0 || d_l >= tc.target {
            return None;
        }
        let arc_start = c1.point(new_angle);
        let line_start = [
            p[0] + u_tan2[0] * d_l,
            p[1] + u_tan2[1] * d_l,
            p[2] + u_tan2[2] * d_l,
        ];
        let (length, t_start, t_end) =
            spherical_arc(&arc_start, &line_start, &arc_center, &binormal)?;
        // checkTangentAngle: the arc must leave the circle (nearly) tangentially.
        let u_circ = c1.tangent(new_angle);
        let angle = dot3(&u_circ, &t_start).clamp(-1.0, 1.0).acos();
        let angle_max = acc_ratio_normal() * 0.25 * bp.a_max / (bp.v_plan / self.cycle).max(1e-12);
        if angle > angle_max {
            return None;
        }
        let mut prev_circ = *c1;
        prev_circ.trim_end(new_angle);
        Some(Blend {
            arc: self.blend_tc(prev, &bp, length, t_start, t_end),
            trim_prev: trim1 * radius1,
            trim_next: d_l,
            consume: false,
            prev_circ: Some(prev_circ),
            next_circ: None,
        })
    }

    /// `tpCreateArcArcBlend`: the first arc is shortened at its end, the second at
    /// its start.
    fn blend_arc_arc(&self, prev: &Tc, tc: &Tc, c1: &Circ, c2: &Circ) -> Option<Blend> {
        if !colinear(&c1.normal, &c2.normal) {
            return None;
        }
        let (u_tan1, u_tan2, theta_tan, binormal) = Self::corner_geometry(prev, tc)?;
        let normal = unit3(&sub3(&u_tan2, &u_tan1));
        let p = c2.start;
        let (center1, radius1) = c1.spiral_fit(&p, &u_tan1);
        let (center2, radius2) = c2.spiral_fit(&p, &u_tan2);
        let convex1 = dot3(&sub3(&p, &center1), &u_tan2) < 0.0;
        let convex2 = dot3(&sub3(&p, &center2), &u_tan1) >= 0.0;
        let blend_angle_1 = if convex1 { theta_tan } else { PI / 2.0 };
        let blend_angle_2 = if convex2 { theta_tan } else { PI / 2.0 };
        let phi1_max = (c1.angle * 2.0 / 3.0).min(blend_angle_1);
        let phi2_max = (c2.angle / 3.0).min(blend_angle_2);
        let mut theta = theta_tan;
        let (mut u1, mut u2) = (u_tan1, u_tan2);
        if convex1 {
            let bpnt = c1.point(c1.angle - phi1_max / 2.0);
            u1 = unit3(&sub3(&p, &bpnt));
            theta = theta.min(theta_tan - phi1_max / 4.0);
        }
        if convex2 {
            let bpnt = c2.point(phi2_max / 2.0);
            u2 = unit3(&sub3(&bpnt, &p));
            theta = theta.min(theta_tan - phi2_max / 4.0);
        }
        if theta < PI / 12.0 {
            return None;
        }
        let l1 = if convex1 {
            (phi1_max / 4.0).sin() * radius1
        } else {
            phi1_max * radius1
        };
        let l2 = if convex2 {
            (phi2_max / 4.0).sin() * radius2
        } else {
            phi2_max * radius2
        };
        if !colinear(&binormal, &c1.normal) || !colinear(&binormal, &c2.normal) {
            return None;
        }
        let bp = self.blend_params(prev, tc, &u1, &u2, &binormal, theta, l1, l2)?;
        // blendArcArcPostProcess: the blend circle's centre is at distance d1 from
        // the first centre and d2 from the second.
        let d1 = if convex1 { -bp.r_plan } else { bp.r_plan } + radius1;
        let d2 = if convex2 { -bp.r_plan } else { bp.r_plan } + radius2;
        let r_c1c2 = sub3(&center2, &center1);
        let c2x = norm3(&r_c1c2);
        if c2x < 1e-12 {
            return None;
        }
        let cx = (-d1 * d1 + d2 * d2 - c2x * c2x) / (-2.0 * c2x);
        let cy = (d1 * d1 - cx * cx).sqrt();
        if cy.is_nan() {
            return None;
        }
        let uc = unit3(&r_c1c2);
        let mut nc = cross3(&binormal, &uc);
        if dot3(&normal, &nc) < 0.0 {
            nc = [-nc[0], -nc[1], -nc[2]];
        }
        let nc = unit3(&nc);
        let c_x = [uc[0] * cx, uc[1] * cx, uc[2] * cx];
        let mut c_y = [nc[0] * cy, nc[1] * cy, nc[2] * cy];
        let r_pc1 = sub3(&center1, &p);
        let base = [r_pc1[0] + c_x[0], r_pc1[1] + c_x[1], r_pc1[2] + c_x[2]];
        let t1 = [base[0] + c_y[0], base[1] + c_y[1], base[2] + c_y[2]];
        let t2 = [base[0] - c_y[0], base[1] - c_y[1], base[2] - c_y[2]];
        if norm3(&t2) < norm3(&t1) {
            c_y = [-c_y[0], -c_y[1], -c_y[2]];
        }
        let arc_center = [
            center1[0] + c_x[0] + c_y[0],
            center1[1] + c_x[1] + c_y[1],
            center1[2] + c_x[2] + c_y[2],
        ];
        if norm3(&sub3(&arc_center, &p)) - bp.r_plan > bp.tolerance {
            return None;
        }
        let trim1 = trim_angle(&p, &arc_center, &center1);
        let trim2 = trim_angle(&p, &arc_center, &center2);
        if trim1 > phi1_max || trim2 > phi2_max {
            return None;
        }
        let new1 = c1.angle - trim1;
        let new2 = c2.angle - trim2;
        if new1 <= 0.0 || new2 <= 0.0 {
            return None;
        }
        let mut prev_circ = *c1;
        prev_circ.trim_end(new1);
        let mut next_circ = *c2;
        next_circ.trim_start(trim2);
        let arc_start = prev_circ.point(new1);
        let (length, t_start, t_end) =
            spherical_arc(&arc_start, &next_circ.start, &arc_center, &binormal)?;
        let angle_max = acc_ratio_normal() * 0.25 * bp.a_max / (bp.v_plan / self.cycle).max(1e-12);
        let a1 = dot3(&prev_circ.tangent(new1), &t_start)
            .clamp(-1.0, 1.0)
            .acos();
        let a2 = dot3(&next_circ.tangent(0.0), &t_end)
            .clamp(-1.0, 1.0)
            .acos();
        if a1 > angle_max || a2 > angle_max {
            return None;
        }
        Some(Blend {
            arc: self.blend_tc(prev, &bp, length, t_start, t_end),
            trim_prev: trim1 * radius1,
            trim_next: trim2 * radius2,
            consume: false,
            prev_circ: Some(prev_circ),
            next_circ: Some(next_circ),
        })
    }

    /// `tpCreateLineArcBlend`: the line is shortened at its end, the arc at its start.
    fn blend_line_arc(&self, prev: &Tc, tc: &Tc, c2: &Circ) -> Option<Blend> {
        let (u_tan1, u_tan2, theta_tan, binormal) = Self::corner_geometry(prev, tc)?;
        let p = c2.start;
        let (center2, radius2) = c2.spiral_fit(&p, &u_tan2);
        let convex2 = dot3(&sub3(&p, &center2), &u_tan1) >= 0.0;
        let blend_angle_2 = if convex2 { theta_tan } else { PI / 2.0 };
        let phi2_max = (c2.angle / 3.0).min(blend_angle_2);
        let mut theta = theta_tan;
        let mut u2 = u_tan2;
        if convex2 {
            let bpnt = c2.point(phi2_max / 2.0);
            u2 = unit3(&sub3(&bpnt, &p));
            theta = theta.min(theta_tan - phi2_max / 4.0);
        }
        let l1 = prev.target.min(prev.nominal / 2.0);
        let l2 = if convex2 {
            (phi2_max / 4.0).sin() * radius2
        } else {
            phi2_max * radius2
        };
        if !colinear(&binormal, &c2.normal) {
            return None;
        }
        let bp = self.blend_params(prev, tc, &u_tan1, &u2, &binormal, theta, l1, l2)?;
        // blendLineArcPostProcess
        let d2 = if convex2 { -bp.r_plan } else { bp.r_plan } + radius2;
        let n1 = unit3(&cross3(&binormal, &u_tan1));
        let r_pc2 = sub3(&center2, &p);
        let c2_u = dot3(&r_pc2, &u_tan1);
        let c2_n = dot3(&r_pc2, &n1);
        let (root0, root1) = quadratic(
            1.0,
            2.0 * c2_u,
            c2_u * c2_u - d2 * d2 + (bp.r_plan - c2_n).powi(2),
        )?;
        let d_l = root0.abs().min(root1.abs());
        let r_pc = [
            -u_tan1[0] * d_l + n1[0] * bp.r_plan,
            -u_tan1[1] * d_l + n1[1] * bp.r_plan,
            -u_tan1[2] * d_l + n1[2] * bp.r_plan,
        ];
        let arc_center = [p[0] + r_pc[0], p[1] + r_pc[1], p[2] + r_pc[2]];
        if norm3(&r_pc) - bp.r_plan > bp.tolerance {
            return None;
        }
        let trim2 = trim_angle(&p, &arc_center, &center2);
        if trim2 > phi2_max || trim2 >= c2.angle {
            return None;
        }
        let l_prev = prev.target - d_l;
        let consume = !prev.blend_prev && l_prev / bp.v_plan < GAP_CYCLES * self.cycle;
        if l_prev < 0.0 {
            return None;
        }
        let line_end = [
            p[0] - u_tan1[0] * d_l,
            p[1] - u_tan1[1] * d_l,
            p[2] - u_tan1[2] * d_l,
        ];
        let mut next_circ = *c2;
        next_circ.trim_start(trim2);
        let (arc_len, t_start, t_end) =
            spherical_arc(&line_end, &next_circ.start, &arc_center, &binormal)?;
        let u_circ = next_circ.tangent(0.0);
        let angle = dot3(&u_circ, &t_end).clamp(-1.0, 1.0).acos();
        let angle_max = acc_ratio_normal() * 0.25 * bp.a_max / (bp.v_plan / self.cycle).max(1e-12);
        if angle > angle_max {
            return None;
        }
        let length = arc_len + if consume { l_prev } else { 0.0 };
        Some(Blend {
            arc: self.blend_tc(prev, &bp, length, t_start, t_end),
            trim_prev: d_l,
            trim_next: trim2 * radius2,
            consume,
            prev_circ: None,
            next_circ: Some(next_circ),
        })
    }
}

/// Direction of acceleration at the start of an element, which LinuxCNC uses for
/// the corner angle of a parabolic blend (`tcGetStartAccelUnitVector`): on a
/// planar arc the tangent tilted towards the centre by the normal acceleration at
/// half the requested speed, so a corner into an arc counts as sharper than its
/// tangents say.
pub(super) fn start_accel_dir(tc: &Tc) -> [f64; 3] {
    let Some(c) = tc.circ.filter(|_| tc.ty == TcType::Circle) else {
        return tc.u_start;
    };
    // The plain circle tangent: LinuxCNC leaves the spiral out here.
    let t = unit3(&cross3(&c.normal, &sub3(&c.start, &c.center)));
    let inward = unit3(&sub3(&c.center, &c.start));
    let a_t = tc.overall_accel();
    let a_n = (0.5 * tc.reqvel).powi(2) / c.radius.max(1e-12);
    unit3(&[
        t[0] * a_t + inward[0] * a_n,
        t[1] * a_t + inward[1] * a_n,
        t[2] * a_t + inward[2] * a_n,
    ])
}

/// `calculateInscribedDiameter`: the largest vector length in the plane with
/// unit normal `n` that stays within the per-axis `bounds` (0 = axis absent).
fn inscribed(n: &[f64; 3], bounds: &[f64; 3]) -> f64 {
    let mut extents = [0.0; 3];
    for i in 0..3 {
        let mut planar = [-n[0] * n[i], -n[1] * n[i], -n[2] * n[i]];
        planar[i] += 1.0;
        let mut p = planar.map(f64::abs);
        p[i] = p[i].max(POS_EPS);
        let scale = norm3(&p);
        if bounds[i] != 0.0 {
            extents[i] = bounds[i] / scale;
        }
    }
    let mut d = extents[0].max(extents[1]).max(extents[2]);
    for i in 0..3 {
        if bounds[i] != 0.0 {
            d = d.min(extents[i]);
        }
    }
    d
}

/// Tangent at the end of the first move, at the start of the second, the
/// intersection half-angle, and the unit binormal of their plane.
type Corner = ([f64; 3], [f64; 3], f64, [f64; 3]);

/// A planar arc as the blend code sees it: it turns counter-clockwise about
/// `normal` by `angle` from `start`, its radius changing evenly by `spiral` on the
/// way (an end point off the circle, as LinuxCNC's `PmCircle` keeps it).
#[derive(Debug, Clone, Copy)]
pub(super) struct Circ {
    pub(super) center: [f64; 3],
    pub(super) normal: [f64; 3],
    pub(super) start: [f64; 3],
    pub(super) angle: f64,
    pub(super) radius: f64,
    pub(super) spiral: f64,
}

impl Circ {
    /// Point reached after turning by `a` from the start (`pmCirclePoint`).
    pub(super) fn point(&self, a: f64) -> [f64; 3] {
        let r = self.radial(a);
        [
            self.center[0] + r[0],
            self.center[1] + r[1],
            self.center[2] + r[2],
        ]
    }

    /// Vector from the centre to the point at `a`.
    fn radial(&self, a: f64) -> [f64; 3] {
        let r = sub3(&self.start, &self.center);
        let perp = cross3(&self.normal, &r);
        let (s, c) = a.sin_cos();
        let p = [
            r[0] * c + perp[0] * s,
            r[1] * c + perp[1] * s,
            r[2] * c + perp[2] * s,
        ];
        let grow = if self.angle > 0.0 {
            a / self.angle * self.spiral
        } else {
            0.0
        };
        let u = unit3(&p);
        [p[0] + u[0] * grow, p[1] + u[1] * grow, p[2] + u[2] * grow]
    }

    /// Radius change per radian.
    fn spiral_rate(&self) -> f64 {
        if self.angle > 0.0 {
            self.spiral / self.angle
        } else {
            0.0
        }
    }

    /// Unit direction of travel after turning by `a` (`pmCircleTangentVector`).
    pub(super) fn tangent(&self, a: f64) -> [f64; 3] {
        let r = self.radial(a);
        let t = cross3(&self.normal, &r);
        let u = unit3(&r);
        let dr = self.spiral_rate();
        unit3(&[t[0] + u[0] * dr, t[1] + u[1] * dr, t[2] + u[2] * dr])
    }

    /// The circle through `p` that the blend code puts in place of the spiral
    /// (`findSpiralApproximation`): the centre moved along the tangent `u_tan`
    /// by the radius change per radian.
    fn spiral_fit(&self, p: &[f64; 3], u_tan: &[f64; 3]) -> ([f64; 3], f64) {
        let dr = self.spiral_rate();
        let c = [
            self.center[0] + u_tan[0] * dr,
            self.center[1] + u_tan[1] * dr,
            self.center[2] + u_tan[2] * dr,
        ];
        (c, norm3(&sub3(p, &c)))
    }

    /// Shortens the arc at its end to `new_angle` (`pmCircleStretch`).
    fn trim_end(&mut self, new_angle: f64) {
        if self.angle > 0.0 {
            self.spiral *= new_angle / self.angle;
        }
        self.angle = new_angle;
    }

    /// Removes the first `trim` radians (`pmCircleStretch` from the end).
    fn trim_start(&mut self, trim: f64) {
        let new_angle = self.angle - trim;
        let start = self.point(trim);
        self.start = start;
        self.radius = norm3(&sub3(&start, &self.center));
        self.trim_end(new_angle);
    }
}

/// Result of a blend construction: the element to insert and what it removes
/// from its neighbours.
pub(super) struct Blend {
    pub(super) arc: Tc,
    /// Length removed from the end of the previous move.
    pub(super) trim_prev: f64,
    /// Length removed from the start of the next move.
    pub(super) trim_next: f64,
    pub(super) consume: bool,
    pub(super) prev_circ: Option<Circ>,
    pub(super) next_circ: Option<Circ>,
}

/// The blend parameters LinuxCNC derives for a corner.
struct BlendParams {
    tolerance: f64,
    a_max: f64,
    v_req: f64,
    v_plan: f64,
    r_plan: f64,
    d_plan: f64,
    s_arc: f64,
}

/// Parallel or anti-parallel unit vectors (`pmUnitCartsColinear`).
fn colinear(a: &[f64; 3], b: &[f64; 3]) -> bool {
    let d = sub3(a, b);
    let s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
    dot3(&d, &d) < ANGLE_EPS * ANGLE_EPS || dot3(&s, &s) < ANGLE_EPS * ANGLE_EPS
}

/// Real roots of `a·x² + b·x + c`.
fn quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let t = disc.sqrt();
    Some(((-b + t) / (2.0 * a), (-b - t) / (2.0 * a)))
}

/// Angle at `center` between the corner point and the blend centre (`findTrimAngle`).
fn trim_angle(p: &[f64; 3], arc_center: &[f64; 3], center: &[f64; 3]) -> f64 {
    let up = unit3(&sub3(p, center));
    let uc = unit3(&sub3(arc_center, center));
    dot3(&uc, &up).clamp(-1.0, 1.0).acos()
}

/// `arcInitFromPoints` + `arcTangent`: length of the blend arc from `start` to
/// `end` about `center`, and its unit tangents at both ends.
fn spherical_arc(
    start: &[f64; 3],
    end: &[f64; 3],
    center: &[f64; 3],
    binormal: &[f64; 3],
) -> Option<(f64, [f64; 3], [f64; 3])> {
    let r0 = sub3(start, center);
    let r1 = sub3(end, center);
    let (m0, m1) = (norm3(&r0), norm3(&r1));
    if m0 < 1e-12 || m1 < 1e-12 {
        return None;
    }
    let angle = (dot3(&r0, &r1) / (m0 * m1)).clamp(-1.0, 1.0).acos();
    if angle < 1e-6 {
        return None;
    }
    let dr = (m1 - m0) / angle;
    let tan = |r: &[f64; 3], m: f64| {
        let t = cross3(binormal, r);
        unit3(&[
            t[0] + r[0] / m * dr,
            t[1] + r[1] / m * dr,
            t[2] + r[2] / m * dr,
        ])
    };
    Some((m0 * angle, tan(&r0, m0), tan(&r1, m1)))
}
