#!/usr/bin/env python3
"""Writes the cycle-time validation programs into programs/.

The programs only use G0/G1/G2/G3/G4/G17/G20/G21/G61/G64/G90/G91/F/M2 so that the
interpreter integration can run them unchanged. Output is deterministic (fixed seed).
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "programs")
os.makedirs(OUT, exist_ok=True)


def write(name, lines):
    with open(os.path.join(OUT, name + ".ngc"), "w") as f:
        f.write("\n".join(lines) + "\nM2\n")


def fmt(v):
    s = "%.4f" % v
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


# Straight moves in exact-stop mode: trapezoid and triangle profiles.
write("line_x1_f6000", ["G21 G90 G17 G61", "G1 X1 F6000"])
write("line_x5_f3000", ["G21 G90 G17 G61", "G1 X5 F3000"])
write("line_x20_f3000", ["G21 G90 G17 G61", "G1 X20 F3000"])
write("line_x100_f1200", ["G21 G90 G17 G61", "G1 X100 F1200"])
write("line_xy_f6000", ["G21 G90 G17 G61", "G1 X60 Y80 F6000"])
write("rapid_xyz", ["G21 G90 G17 G61", "G0 X30 Y40 Z-20"])

# Two-segment corners: the second move turns by the given angle.
for ang in (30, 60, 90, 120, 150):
    ex = 30 + 30 * math.cos(math.radians(ang))
    ey = 30 * math.sin(math.radians(ang))
    body = ["G1 X30 F3000", "G1 X%s Y%s" % (fmt(ex), fmt(ey))]
    write("corner%03d_g61" % ang, ["G21 G90 G17 G61"] + body)
    write("corner%03d_g64" % ang, ["G21 G90 G17 G64"] + body)
for tol, tag in (("0.01", "p001"), ("0.1", "p01")):
    write("corner090_g64%s" % tag, ["G21 G90 G17 G64 P%s" % tol, "G1 X30 F3000", "G1 X30 Y30"])

# Arcs: slow (feed-limited) and fast (centripetal-limited), several radii.
write("arc_r5_f1200_full", ["G21 G90 G17 G61", "G0 X5", "G2 X5 Y0 I-5 J0 F1200"])
write("arc_r5_f6000_full", ["G21 G90 G17 G61", "G0 X5", "G2 X5 Y0 I-5 J0 F6000"])
write("arc_r20_f3000_half", ["G21 G90 G17 G61", "G0 X20", "G3 X-20 Y0 I-20 J0 F3000"])
write("arc_r50_f6000_quarter", ["G21 G90 G17 G61", "G0 X50", "G3 X0 Y50 I-50 J0 F6000"])
write("helix_r10_f1200", ["G21 G90 G17 G61", "G0 X10", "G2 X10 Y0 Z-5 I-10 J0 F1200"])
write("arcs_s_g64", ["G21 G90 G17 G64", "G1 X10 F3000", "G3 X20 Y10 I0 J10",
                      "G2 X30 Y20 I10 J0", "G1 X40"])

# Short-segment polylines (the case where naive distance/feed estimates fail).
lines = ["G21 G90 G17 G64", "F3000"]
for i in range(1, 301):
    x = i * 0.1
    lines.append("G1 X%s Y%s" % (fmt(x), fmt(2 * math.sin(x))))
write("poly_sine_0p1_g64", lines)

lines = ["G21 G90 G17 G64", "G0 X10 Y0", "F3000"]
n = 126
for i in range(1, n + 1):
    t = 2 * math.pi * i / n
    lines.append("G1 X%s Y%s" % (fmt(10 * math.cos(t)), fmt(10 * math.sin(t))))
write("poly_circle_0p5_g64", lines)

lines = ["G21 G90 G17 G61", "G0 X10 Y0", "F3000"]
n = 32
for i in range(1, n + 1):
    t = 2 * math.pi * i / n
    lines.append("G1 X%s Y%s" % (fmt(10 * math.cos(t)), fmt(10 * math.sin(t))))
write("poly_circle_2mm_g61", lines)

rng = random.Random(7)
for tol, tag in (("", ""), (" P0.01", "p001")):
    lines = ["G21 G90 G17 G64" + tol, "F6000"]
    x = y = 0.0
    heading = 0.0
    for i in range(200):
        heading += math.radians(rng.uniform(-60, 60))
        step = rng.uniform(0.2, 1.0)
        x += step * math.cos(heading)
        y += step * math.sin(heading)
        lines.append("G1 X%s Y%s" % (fmt(x), fmt(y)))
    write("poly_walk_1mm_g64" + tag, lines)
    rng = random.Random(7)

# Incremental distance mode with a square and a rapid return.
write("incr_square_g64p01", ["G21 G91 G17 G64 P0.1", "G1 X40 F2400", "G1 Y40",
                              "G1 X-40", "G1 Y-40", "G0 X20 Y20"])

# Inch programs on the mm machine.
write("inch_line_g61", ["G20 G90 G17 G61", "G1 X2 F120"])
write("inch_square_g64", ["G20 G90 G17 G64", "G1 X1 F100", "G1 Y1", "G1 X0", "G1 Y0"])
write("inch_arc_g61", ["G20 G90 G17 G61", "G0 X0.5", "G3 X-0.5 Y0 I-0.5 J0 F60"])

# A dwell between moves: motion_s must not include it.
write("dwell_between", ["G21 G90 G17 G61", "G1 X10 F6000", "G4 P0.3", "G1 X0"])

# Arcs followed by more motion (LinuxCNC then finalises the arc's acceleration split).
write("arc_then_line_g61", ["G21 G90 G17 G61", "G0 X10", "G2 X10 Y0 I-10 J0 F3000", "G1 X30"])
write("arc_then_line_g64", ["G21 G90 G17 G64", "G0 X10", "G2 X10 Y0 I-10 J0 F3000", "G1 X30"])
# Rapids blend with each other in G64.
write("rapid_corner_g64", ["G21 G90 G17 G64", "G0 X30", "G0 X30 Y30"])
# A zigzag of 0.5 mm teeth: every junction is a sharp corner on a short segment.
lines = ["G21 G90 G17 G64 P0.05", "F2400"]
for i in range(1, 121):
    lines.append("G1 X%s Y%s" % (fmt(i * 0.25), "0.5" if i % 2 else "0"))
write("poly_zigzag_g64p005", lines)


def walk(n, lengths, turns):
    x = y = h = 0.0
    pts = []
    for i in range(n):
        h += math.radians(turns(i))
        step = lengths(i)
        x += step * math.cos(h)
        y += step * math.sin(h)
        pts.append("G1 X%s Y%s" % (fmt(x), fmt(y)))
    return pts


# Alternating 30° turns with varying lengths: blend arcs swallow most lines here.
rng = random.Random(4)
write("walk_randlen_alt30_g64", ["G21 G90 G17 G64", "F6000"]
      + walk(150, lambda i: rng.uniform(0.2, 1.0), lambda i: 30 if i % 2 else -30))
write("walk_len4_alt30_g64", ["G21 G90 G17 G64", "F6000"]
      + walk(120, lambda i: [0.4, 0.5, 0.6, 0.7][i % 4], lambda i: 30 if i % 2 else -30))

# Corners between lines and arcs in G64 (LinuxCNC builds dedicated blend arcs).
write("line_then_arc_g64", ["G21 G90 G17 G64", "G1 X20 F3000", "G3 X40 Y0 I10 J0", "G1 Y20"])
write("arc_arc_g64p01", ["G21 G90 G17 G64 P0.1", "G1 X10 F3000", "G2 X30 Y0 I10 J0",
                         "G2 X50 Y0 I10 J0", "G1 X60"])
write("arc_then_line_g64p001", ["G21 G90 G17 G64 P0.01", "G0 X10",
                                "G2 X10 Y0 I-10 J0 F3000", "G1 X30"])

# Moves with a rotary axis (machine "rot": XYZA). LinuxCNC never builds blend arcs
# for them: G64 uses parabolic blends.
write("rot_only_g61", ["G21 G90 G17 G61", "G1 A90 F3600", "G1 A0"])
write("rot_mixed_g61", ["G21 G90 G17 G61", "G1 X20 A45 F1200", "G1 X40 A0"])
write("rot_mixed_g64", ["G21 G90 G17 G64", "G1 X20 A45 F1200", "G1 X40 A0",
                        "G1 X40 Y20 A30", "G1 X0 Y0 A0"])
lines = ["G21 G90 G17 G64", "F2400"]
for i in range(1, 41):
    lines.append("G1 X%s Y%s A%s" % (fmt(i * 1.0), "1" if i % 2 else "0", fmt(i * 2.0)))
write("rot_zigzag_g64", lines)
write("arc_arc_corner_g64", ["G21 G90 G17 G64", "G1 X10 F3000", "G3 X20 Y10 I0 J10",
                             "G2 X30 Y0 I0 J-10", "G1 X40"])
