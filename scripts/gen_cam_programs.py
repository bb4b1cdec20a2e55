#!/usr/bin/env python3
"""Writes CAM-shaped cycle-time validation programs into tests/cycle_time/cam/programs/.

The shapes CAM output is made of: long chains of short segments under G64 P, G64 Q (the
naive CAM combiner) and plain G64; tiny corner arcs; XY, XZ and YZ planes; inch and mm;
feeds above the velocity cap; helices; block-deleted lines. Every program is written by
this script (fixed seed, deterministic). The file name prefix is the shape class the
report groups by (the text before the first `__`).
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "cycle_time", "cam", "programs")
os.makedirs(OUT, exist_ok=True)
for f in os.listdir(OUT):
    if f.endswith(".ngc"):
        os.remove(os.path.join(OUT, f))

rng = random.Random(19)


def fmt(v, digits=4):
    s = ("%." + str(digits) + "f") % v
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def write(cls, name, lines):
    with open(os.path.join(OUT, "%s__%s.ngc" % (cls, name)), "w") as f:
        f.write("\n".join(lines) + "\nM2\n")


PLANES = {
    # plane word, first and second in-plane axis, normal axis
    "xy": ("G17", "X", "Y", "Z"),
    "xz": ("G18", "Z", "X", "Y"),
    "yz": ("G19", "Y", "Z", "X"),
}


def point(plane, u, v, w=None):
    _, a, b, n = PLANES[plane]
    s = "%s%s %s%s" % (a, fmt(u), b, fmt(v))
    if w is not None:
        s += " %s%s" % (n, fmt(w))
    return s


def wiggle(n, step, amp, rng, curve=0.0):
    """A near-straight chain: n steps of about `step` along u, v jittered by +-amp,
    bending by `curve` radians per step."""
    pts = []
    u = v = 0.0
    ang = 0.0
    for _ in range(n):
        ang += curve
        u += step * math.cos(ang)
        v += step * math.sin(ang)
        pts.append((u, v + rng.uniform(-amp, amp)))
    return pts


def chain(cls, name, mode, plane, units, feed, pts, header_extra=()):
    g = PLANES[plane][0]
    lines = ["%s G90 %s" % ("G20" if units == "inch" else "G21", g)]
    lines += list(header_extra)
    if mode:
        lines.append(mode)
    lines.append("G1 %s F%s" % (point(plane, pts[0][0], pts[0][1]), fmt(feed)))
    for u, v in pts[1:]:
        lines.append("G1 " + point(plane, u, v))
    write(cls, name, lines)


# 1. Random walks of tiny segments (the combiner joins whatever stays within Q).
for n, step, q, feed in ((2000, 0.001, "0.0002", 999), (1500, 0.002, "0.0005", 2000),
                         (800, 0.01, "0.002", 3000)):
    pts = []
    u = v = 0.0
    for _ in range(n):
        a = rng.uniform(0, math.tau)
        u += step * math.cos(a)
        v += step * math.sin(a)
        pts.append((u, v))
    tag = "s%s_q%s_f%d" % (fmt(step).replace(".", "p"), q.replace(".", "p"), feed)
    chain("walk_q", tag, "G64 Q" + q, "xy", "mm", feed, pts)
    chain("walk_none", tag, "G64", "xy", "mm", feed, pts)

# 2. Near-straight chains with jitter below / above the tolerance, P, Q and neither.
for step, amp, feed in ((0.05, 0.0005, 3000), (0.2, 0.002, 6000), (0.02, 0.0002, 1500),
                        (0.5, 0.01, 100000)):
    n = int(min(600, 40.0 / step))
    pts = wiggle(n, step, amp, rng, curve=0.0)
    tag = "s%s_a%s_f%d" % (fmt(step).replace(".", "p"), fmt(amp).replace(".", "p"), feed)
    tol = fmt(amp * 4)
    chain("line_q", tag, "G64 Q" + tol, "xy", "mm", feed, pts)
    chain("line_p", tag, "G64 P" + tol, "xy", "mm", feed, pts)
    chain("line_pq", tag, "G64 P%s Q%s" % (fmt(amp * 20), fmt(amp / 4)), "xy", "mm", feed, pts)
    chain("line_none", tag, "G64", "xy", "mm", feed, pts)
    chain("line_g61", tag, "G61", "xy", "mm", feed, pts)

# 3. Curves in short segments (gcmc/CAM output): arcs and sines, every plane.
for plane in ("xy", "xz", "yz"):
    for seg, q, feed in ((0.06, "0.0001", 9999), (0.2, "0.03", 100000), (0.1, "0.005", 3000)):
        r = 15.0
        n = int(min(900, (math.pi * r) / seg))
        pts = [(r * math.cos(i * seg / r) - r, r * math.sin(i * seg / r)) for i in range(n)]
        tag = "%s_s%s_q%s_f%d" % (plane, fmt(seg).replace(".", "p"), q.replace(".", "p"), feed)
        chain("curve_q", tag, "G64 Q" + q, plane, "mm", feed, pts)
        chain("curve_p", tag, "G64 P" + q, plane, "mm", feed, pts)
        chain("curve_none", tag, "G64", plane, "mm", feed, pts)
    # A sine at 0.2 mm steps.
    pts = [(i * 0.2, 3 * math.sin(i * 0.2 / 3)) for i in range(400)]
    chain("curve_q", "%s_sine_s0p2_q0p01_f4000" % plane, "G64 Q0.01", plane, "mm", 4000, pts)
    chain("curve_none", "%s_sine_s0p2_f4000" % plane, "", plane, "mm", 4000, pts)

# 4. Inch chains.
for seg, q, feed in ((0.002, "0.00001", 400), (0.01, "0.0005", 4000)):
    r = 0.6
    n = int(min(800, (math.pi * r) / seg))
    pts = [(r * math.cos(i * seg / r) - r, r * math.sin(i * seg / r)) for i in range(n)]
    tag = "s%s_q%s_f%d" % (fmt(seg).replace(".", "p"), q.replace(".", "p"), feed)
    chain("inch_q", tag, "G64 Q" + q, "xy", "inch", feed, pts)
    chain("inch_p", tag, "G64 P" + q, "xy", "inch", feed, pts)
    chain("inch_none", tag, "G64", "xy", "inch", feed, pts)


# 5. Pockets: rectangles with tiny corner arcs, default blending (no G61/G64),
#    spindle and tool lines, some block-deleted.
def pocket(cls, name, units, r, feed, loops, deleted, mode=""):
    k = 1 / 25.4 if units == "inch" else 1.0
    lines = ["%s G90 G17" % ("G20" if units == "inch" else "G21")]
    if mode:
        lines.append(mode)
    lines += ["%sM06 T3" % ("/" if deleted else ""), "M03 S8000",
              "G0 X%s Y%s" % (fmt(0), fmt(0)), "G0 Z%s" % fmt(2 * k), "G1 Z%s F%s" % (fmt(-1 * k), fmt(feed / 2))]
    w, h = 20.0, 12.0
    for i in range(loops):
        s = 1.5 * i
        x0, y0, x1, y1 = (s) * k, (s) * k, (w - s) * k, (h - s) * k
        rr = r * k
        lines += [
            "G1 X%s Y%s F%s" % (fmt(x1 - rr), fmt(y0), fmt(feed)),
            "G3 X%s Y%s I0 J%s" % (fmt(x1), fmt(y0 + rr), fmt(rr)),
            "G1 Y%s" % fmt(y1 - rr),
            "G3 X%s Y%s I%s J0" % (fmt(x1 - rr), fmt(y1), fmt(-rr)),
            "G1 X%s" % fmt(x0 + rr),
            "G3 X%s Y%s I0 J%s" % (fmt(x0), fmt(y1 - rr), fmt(-rr)),
            "G1 Y%s" % fmt(y0 + rr),
            "G3 X%s Y%s I%s J0" % (fmt(x0 + rr), fmt(y0), fmt(rr)),
        ]
        if i == 0:
            lines.append("%sG1 X%s Y%s" % ("/" if deleted else "", fmt(x0 + 5 * k), fmt(y0 + 3 * k)))
            lines.append("G1 X%s Y%s" % (fmt(x0 + rr), fmt(y0)))
    lines += ["G0 Z%s" % fmt(5 * k), "%sM05" % ("/" if deleted else ""),
              "%sM06 T3" % ("/" if deleted else ""), "G0 X0 Y0"]
    write(cls, name, lines)


for units in ("mm", "inch"):
    for r, feed in ((0.125, 400), (0.125, 3000), (1.0, 1500)):
        tag = "%s_r%s_f%d" % (units, fmt(r).replace(".", "p"), feed)
        pocket("pocket_bd", tag, units, r, feed, 3, True)
        pocket("pocket", tag, units, r, feed, 3, False)
pocket("pocket_bd", "mm_r0p125_f400_g64p002", "mm", 0.125, 400, 3, True, "G64 P0.02")
pocket("pocket_bd", "mm_r0p125_f400_g61", "mm", 0.125, 400, 3, True, "G61")


# 6. Chains of tiny arcs (corner arcs between short lines), every plane.
def offsets(plane, du, dv):
    """Arc centre words for an offset (du, dv) in the plane's (first, second) axes."""
    words = {"xy": ("I", "J"), "xz": ("K", "I"), "yz": ("J", "K")}[plane]
    return "%s%s %s%s" % (words[0], fmt(du), words[1], fmt(dv))


for plane in ("xy", "xz", "yz"):
    for r, feed, mode in ((0.125, 2000, ""), (0.5, 6000, "G64 P0.01"), (0.05, 100000, "G64 Q0.001")):
        g = PLANES[plane][0]
        lines = ["G21 G90 %s" % g]
        if mode:
            lines.append(mode)
        u = v = 0.0
        lines.append("G1 %s F%d" % (point(plane, 0, 0), feed))
        for i in range(40):
            # Stairs: a 2 mm leg along u, a quarter arc, a 1 mm leg along v, a quarter arc back.
            d = 1 if i % 2 == 0 else -1
            u += 2.0
            lines.append("G1 " + point(plane, u, v))
            lines.append("%s %s %s" % ("G3" if d > 0 else "G2", point(plane, u + r, v + d * r),
                                       offsets(plane, 0, d * r)))
            u, v = u + r, v + d * r + d * 1.0
            lines.append("G1 " + point(plane, u, v))
            lines.append("%s %s %s" % ("G2" if d > 0 else "G3", point(plane, u + r, v + d * r),
                                       offsets(plane, r, 0)))
            u, v = u + r, v + d * r
        tag = "%s_r%s_f%d_%s" % (plane, fmt(r).replace(".", "p"), feed,
                                 mode.replace(" ", "").replace(".", "p").lower() or "default")
        write("arcs_tiny", tag, lines)

# 7. Helices: single and multi-turn, every plane, blended into lines.
for plane in ("xy", "xz", "yz"):
    for r, rise, turns, feed, mode in ((3, -2, 1, 1200, "G61"), (0.5, -0.3, 4, 3000, "G64"),
                                       (2, -1, 2, 100000, "G64 P0.01")):
        g, a, b, n = PLANES[plane]
        ij = {"xy": "I%s J0", "xz": "K%s I0", "yz": "J%s K0"}[plane] % fmt(-r)
        lines = ["G21 G90 %s" % g, mode, "G0 %s" % point(plane, r, 0, 0),
                 "G1 %s F%d" % (point(plane, r + 5, 0, 0), feed), "G1 %s" % point(plane, r, 0, 0)]
        w = 0.0
        for k in range(2):
            w += rise
            lines.append("G2 %s %s P%d" % (point(plane, r, 0, w), ij, turns))
        lines.append("G1 %s" % point(plane, r + 5, 0, w))
        tag = "%s_r%s_t%d_f%d_%s" % (plane, fmt(r).replace(".", "p"), turns, feed, mode.replace(" ", "").replace(".", "p").lower())
        write("helix", tag, lines)

# 8. Feeds far above the velocity cap on short-segment zigzags (velocity-capped CAM output).
for plane in ("xy", "xz", "yz"):
    for step, q in ((0.2, "0.03"), (1.0, "0.05")):
        pts = [(i * step, 0.05 * ((i % 7) - 3) * step) for i in range(int(min(1000, 150 / step)))]
        tag = "%s_s%s_q%s" % (plane, fmt(step).replace(".", "p"), q.replace(".", "p"))
        chain("capped_q", tag, "G64 Q" + q, plane, "mm", 100000, pts)
        chain("capped_none", tag, "G64", plane, "mm", 100000, pts)



# 9. Arc-fitted CAM output: chains of small arcs whose chords deviate less than Q (the
#    canonical layer feeds XY ones to the naive-CAM detector as lines) or more.
for plane in ("xy", "xz", "yz"):
    for r, step_deg, q, feed in ((5.0, 2.0, "0.01", 3000), (2.0, 10.0, "0.005", 6000),
                                 (20.0, 1.0, "0.001", 100000)):
        g = PLANES[plane][0]
        lines = ["G21 G90 %s" % g, "G64 Q" + q, "G1 %s F%d" % (point(plane, r, 0), feed)]
        ang = 0.0
        n = int(min(300, 540 / step_deg))
        for i in range(n):
            ang += math.radians(step_deg)
            # Alternate the centre side every 30 arcs: an S-curve of arcs.
            lines.append("G3 %s %s" % (point(plane, r * math.cos(ang), r * math.sin(ang)),
                                       offsets(plane, -r * math.cos(ang - math.radians(step_deg)),
                                               -r * math.sin(ang - math.radians(step_deg)))))
        tag = "%s_r%s_d%s_q%s_f%d" % (plane, fmt(r).replace(".", "p"), fmt(step_deg), q.replace(".", "p"), feed)
        write("arcfit_q", tag, lines)
        if r == 5.0 and plane != "xy":
            # The same chain without the G64 corner: exact path (G61), and entered by a
            # rapid. They separate the chain's own kinks from the corner's blend.
            write("arcfit_g61", tag, [lines[0], "G61"] + lines[2:])
            start = lines[2].replace("G1 ", "G0 ").replace(" F%d" % feed, "")
            write("arcfit_g0", tag, lines[:2] + [start, "F%d" % feed] + lines[3:])

print(len([f for f in os.listdir(OUT) if f.endswith(".ngc")]), "programs in", os.path.relpath(OUT))
