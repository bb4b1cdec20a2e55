#!/usr/bin/env python3
"""Generate large, realistic part programs for benchmarks and robustness tests.

The output looks like CAM post-processor output: thousands of tiny 3D
surfacing segments, drilling patterns with canned cycles and tool changes, or
macro loops, in the syntax of one of the three dialects. Output is
deterministic for a given seed.

Examples:
    gen_programs.py surfacing --dialect rs274ngc --lines 500000 > big.ngc
    gen_programs.py drilling --dialect fanuc --lines 20000 > holes.nc
    gen_programs.py macro --dialect servoworks --lines 5000 > loops.nc
    gen_programs.py mixed --dialect fanuc --lines 100000 --seed 7 > mix.nc
    gen_programs.py g1xyz --dialect fanuc --lines 500000 > cam.nc

Kinds (the shapes of scripts/bench_matrix.sh):
    surfacing  modal axis-only lines (`X… Z…`), a G1 with feed every 500 blocks
    g1xyz      `G1 X… Y… Z…` on every line, as most post-processors write
    arcs       G2/G3 every few lines, alternating R and I/J forms
    drilling   canned cycles over hole grids and bolt circles
    fusion     FANUC/Fusion-style: N numbers in steps of 5, `G43 … H`, G1 only on change
    macro      macro-variable loops (WHILE, o-word while, G65 calls)
    mixed      drilling, surfacing and macro thirds
"""

import argparse
import math
import random
import sys

DIALECTS = ("servoworks", "rs274ngc", "fanuc")


class Writer:
    """Buffers lines and numbers them N10, N20 … when the dialect likes it."""

    def __init__(self, out, dialect, numbered):
        self.out = out
        self.dialect = dialect
        self.numbered = numbered
        self.n = 0
        self.count = 0
        self.buf = []

    def line(self, text):
        if self.numbered and text and not text.startswith(("%", "O", "o", "(", "#", "WHILE", "END")):
            self.n += 10
            if self.n > 99999:
                self.n = 10
            text = "N%d %s" % (self.n, text)
        self.buf.append(text)
        self.count += 1
        if len(self.buf) >= 4096:
            self.flush()

    def flush(self):
        if self.buf:
            self.out.write("\n".join(self.buf))
            self.out.write("\n")
            self.buf = []


def fmt(v, places=4):
    """CAM style: fixed decimals, trailing zeros dropped but the point kept."""
    s = ("%." + str(places) + "f") % v
    s = s.rstrip("0")
    if s.endswith("."):
        s += "0" if places == 0 else ""
    if s in ("-0.", "-0", "-0.0"):
        s = "0."
    return s


def header(w, dialect, title):
    if dialect == "servoworks":
        w.line("%")
        w.line("(partscope: dialect=servoworks)")
        w.line("(%s)" % title)
        w.line("G90 G17 G21 G40 G49 G80")
    elif dialect == "rs274ngc":
        w.line("(partscope: dialect=rs274ngc)")
        w.line("(%s)" % title)
        w.line("G21 G17 G90 G94 G40 G49 G80 G64 P0.01")
    else:
        w.line("%")
        w.line("O1000 (%s)" % title.upper())
        w.line("G21 G17 G90 G94 G40 G49 G80")


def footer(w, dialect):
    w.line("G0 Z50.")
    w.line("M5")
    w.line("M30")
    if dialect != "rs274ngc":
        w.line("%")


def tool_change(w, dialect, tool, rpm):
    if dialect == "servoworks":
        w.line("T%02d M6" % tool)
        w.line("G43 H%d Z50." % tool)
    elif dialect == "rs274ngc":
        # LinuxCNC refuses axis words in a G43 block.
        w.line("T%d M6" % tool)
        w.line("G43 H%d" % tool)
        w.line("G0 Z50.")
    else:
        w.line("T%d M6" % tool)
        w.line("G43 H%d Z50." % tool)
    w.line("S%d M3" % rpm)


def surface_z(x, y):
    return -2.0 + 1.5 * math.sin(x / 17.0) * math.cos(y / 11.0) + 0.4 * math.sin((x + y) / 5.0)


def surfacing(w, dialect, budget, rng):
    """Raster finishing of a free-form surface with 0.05–0.2 mm segments."""
    tool_change(w, dialect, 3, 12000)
    step_over = 0.25
    seg = 0.1 + rng.random() * 0.1
    y = 0.0
    direction = 1
    width = 120.0
    w.line("G0 X0. Y0. Z5.")
    w.line("G1 Z%s F800." % fmt(surface_z(0.0, 0.0)))
    feed_every = 500
    k = 0
    while w.count < budget:
        x = 0.0 if direction > 0 else width
        end = width if direction > 0 else 0.0
        while (x < end) if direction > 0 else (x > end):
            if w.count >= budget:
                return
            x += direction * seg * (0.8 + 0.4 * rng.random())
            x = min(x, width) if direction > 0 else max(x, 0.0)
            z = surface_z(x, y)
            k += 1
            if k % feed_every == 0:
                w.line("G1 X%s Y%s Z%s F%d." % (fmt(x), fmt(y), fmt(z), rng.choice((1500, 2000, 2500))))
            else:
                w.line("X%s Z%s" % (fmt(x), fmt(z)))
        y += step_over
        direction = -direction
        w.line("Y%s Z%s" % (fmt(y), fmt(surface_z(x, y))))


def g1xyz(w, dialect, budget, rng):
    """Raster finishing with the motion code and all three axes on every line."""
    tool_change(w, dialect, 3, 12000)
    w.line("G0 X0. Y0. Z5.")
    w.line("G1 Z%s F800." % fmt(surface_z(0.0, 0.0)))
    x, y, direction, width = 0.0, 0.0, 1, 120.0
    while w.count < budget:
        x += direction * (0.08 + 0.12 * rng.random())
        if x >= width or x <= 0.0:
            x = min(max(x, 0.0), width)
            y += 0.25
            direction = -direction
        w.line("G1 X%s Y%s Z%s" % (fmt(x), fmt(y), fmt(surface_z(x, y))))


def arcs(w, dialect, budget, rng):
    """Contours of short lines and quarter circles: a G2/G3 every few lines,
    alternately in R and in I/J form."""
    tool_change(w, dialect, 2, 8000)
    w.line("G0 X0. Y0. Z5.")
    w.line("G1 Z-1. F600.")
    x, y, k = 0.0, 0.0, 0
    while w.count < budget:
        for _ in range(rng.randint(1, 3)):
            x += 0.5 + rng.random()
            w.line("G1 X%s Y%s" % (fmt(x), fmt(y)))
        r = 0.5 + rng.random() * 4.0
        # A quarter circle to (x + r, y + r): centre above the start for G3,
        # to its right for G2.
        end = "X%s Y%s" % (fmt(x + r), fmt(y + r))
        code = "G3" if k % 2 == 0 else "G2"
        if k % 4 < 2:
            w.line("%s %s R%s" % (code, end, fmt(r)))
        elif code == "G3":
            w.line("G3 %s I0. J%s" % (end, fmt(r)))
        else:
            w.line("G2 %s I%s J0." % (end, fmt(r)))
        x, y = float(fmt(x + r)), float(fmt(y + r))
        k += 1
        if y > 200.0 or x > 200.0:
            w.line("G0 Z5.")
            x, y = 0.0, 0.0
            w.line("G0 X0. Y0.")
            w.line("G1 Z-1. F600.")


def fusion(w, dialect, budget, rng):
    """The layout of a Fusion 360 FANUC post: sequence numbers in steps of 5,
    tool length offset as `G43 Z… H…`, modal G1 written only when the motion
    mode changes, feed on the first move of each pass."""
    n = [0]

    def out(text):
        n[0] += 5
        if n[0] > 99995:
            n[0] = 5
        w.line("N%d %s" % (n[0], text))

    tool = 1
    while w.count < budget:
        out("M5")
        out("G91 G28 Z0.")
        out("G90")
        out("T%d M6" % tool)
        out("S%d M3" % rng.choice((6000, 8000, 10000)))
        out("G54")
        out("M8")
        out("G0 X0. Y0.")
        if dialect == "rs274ngc":
            out("G43 H%d" % tool)
            out("G0 Z15.")
        else:
            out("G43 Z15. H%d" % tool)
        y = 0.0
        for _ in range(rng.randint(50, 400)):
            if w.count >= budget:
                break
            out("G0 Z5.")
            out("G1 Z-1. F300.")
            x = 0.0
            first = True
            for _ in range(rng.randint(20, 200)):
                if w.count >= budget:
                    break
                x += 0.1 + rng.random() * 0.4
                z = surface_z(x, y)
                if first:
                    out("X%s Z%s F1200." % (fmt(x), fmt(z)))
                    first = False
                else:
                    out("X%s Z%s" % (fmt(x), fmt(z)))
            y += 0.3
            out("G0 Z5.")
            out("X0. Y%s" % fmt(y))
        out("M9")
        tool = tool % 3 + 1


def drilling(w, dialect, budget, rng):
    """Grids and bolt circles with peck drilling, tapping and tool changes."""
    tool = 1
    while w.count < budget:
        tool_change(w, dialect, tool, rng.choice((2000, 3000, 4500)))
        cycle = rng.choice(("G81", "G83", "G73", "G82"))
        extra = {"G81": "", "G83": " Q2.", "G73": " Q1.5", "G82": " P500"}[cycle]
        if dialect == "servoworks" and cycle == "G83":
            extra = " Q2."
        w.line("G0 X0. Y0. Z10.")
        w.line("G98 %s X0. Y0. Z-%s R2.%s F%d." % (cycle, fmt(5 + rng.random() * 15, 2), extra, rng.choice((100, 150, 200))))
        if rng.random() < 0.5:
            cols, rows, pitch = rng.randint(5, 40), rng.randint(5, 40), rng.choice((5.0, 7.5, 10.0))
            for r in range(rows):
                for c in range(cols):
                    if w.count >= budget:
                        w.line("G80")
                        return
                    cc = c if r % 2 == 0 else cols - 1 - c
                    w.line("X%s Y%s" % (fmt(cc * pitch, 3), fmt(r * pitch, 3)))
        else:
            n = rng.randint(6, 72)
            radius = 10 + rng.random() * 80
            for i in range(n):
                if w.count >= budget:
                    w.line("G80")
                    return
                a = 2 * math.pi * i / n
                w.line("X%s Y%s" % (fmt(radius * math.cos(a), 3), fmt(radius * math.sin(a), 3)))
        w.line("G80")
        # Tools 1-3 exist in LinuxCNC's sample tool table, so `rs274` can run
        # the output unchanged.
        tool = tool % 3 + 1


def macro(w, dialect, budget, rng):
    """Parametric pockets and hole circles driven by macro-variable loops."""
    loop = 0
    subs = []
    while w.count + 6 * len(subs) < budget - 12:
        loop += 1
        count = rng.randint(4, 60)
        radius = fmt(5 + rng.random() * 60, 3)
        depth = fmt(1 + rng.random() * 4, 3)
        if dialect == "rs274ngc":
            # LinuxCNC refuses a label used twice: every loop has its own.
            label = 100 + loop
            w.line("#1 = 0")
            w.line("o%d while [#1 lt %d]" % (label, count))
            w.line("  #2 = [%s * cos[#1 * 360 / %d]]" % (radius, count))
            w.line("  #3 = [%s * sin[#1 * 360 / %d]]" % (radius, count))
            w.line("  G0 X#2 Y#3 Z2.")
            w.line("  G1 Z-%s F200." % depth)
            w.line("  G0 Z2.")
            w.line("  #1 = [#1 + 1]")
            w.line("o%d endwhile" % label)
        elif dialect == "fanuc":
            w.line("#1=0")
            w.line("WHILE [#1 LT %d] DO1" % count)
            w.line("#2=%s*COS[#1*360/%d]" % (radius, count))
            w.line("#3=%s*SIN[#1*360/%d]" % (radius, count))
            w.line("G0 X#2 Y#3 Z2.")
            w.line("G1 Z-%s F200." % depth)
            w.line("G0 Z2.")
            w.line("#1=#1+1")
            w.line("END1")
        else:
            # ServoWorks has no WHILE: loops are repeated G65 macro calls
            # (the macro lives in the same file) that advance global macro
            # variables, as in the manual's examples.
            name = "%d" % (9000 + loop % 50)
            if loop <= 50:
                subs.append((name, radius, depth))
            w.line("#101 = 0.0")
            w.line("#102 = %s" % radius)
            w.line("G65 P%s L%d" % (name, count))
    if dialect == "servoworks":
        w.line("M30")
        for name, radius, depth in subs:
            w.line("O%s" % name)
            w.line("G01 X#102 Y#101 F500.0")
            w.line("G01 Z-%s" % depth)
            w.line("G00 Z2.0")
            w.line("#101 = #101 + 1.0")
            w.line("M99")
        w.line("%")
        return True
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(
        "kind", choices=("surfacing", "g1xyz", "arcs", "drilling", "fusion", "macro", "mixed")
    )
    ap.add_argument("--dialect", choices=DIALECTS, default="rs274ngc")
    ap.add_argument("--lines", type=int, default=10000, help="approximate number of lines")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--numbered", action="store_true", help="prefix blocks with N numbers")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    w = Writer(sys.stdout, args.dialect, args.numbered)
    header(w, args.dialect, "generated %s program, seed %d" % (args.kind, args.seed))
    budget = max(args.lines - 4, 10)
    done = False
    if args.kind == "surfacing":
        surfacing(w, args.dialect, budget, rng)
    elif args.kind == "g1xyz":
        g1xyz(w, args.dialect, budget, rng)
    elif args.kind == "arcs":
        arcs(w, args.dialect, budget, rng)
    elif args.kind == "fusion":
        fusion(w, args.dialect, budget, rng)
    elif args.kind == "drilling":
        drilling(w, args.dialect, budget, rng)
    elif args.kind == "macro":
        done = macro(w, args.dialect, budget, rng)
    else:
        third = budget // 3
        drilling(w, args.dialect, w.count + third, rng)
        surfacing(w, args.dialect, w.count + third, rng)
        if args.dialect != "servoworks":
            macro(w, args.dialect, budget, rng)
    if not done:
        footer(w, args.dialect)
    w.flush()


if __name__ == "__main__":
    main()
