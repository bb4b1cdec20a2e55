//! The RS274/NGC code and address tables (LinuxCNC 2.9 and the 2007 EMC2 seed),
//! from the rs274ngc spec digest (§1.4 words, §2 modal groups, §3 G codes,
//! §4 M codes, §11 modern extensions).
//!
//! Group numbers are LinuxCNC's internal ones; M-code groups use the same
//! numbers as the interpreter's M table (4 stopping, 5 I/O, 6 tool change,
//! 7 spindle, 8 coolant, 9 overrides, 10 user). Codes the seed lacks carry only
//! the `LINUXCNC` variant bit.

use super::{variants, AddressInfo, CodeInfo, CodeKind, CodeNum, Param};

use CodeKind::{AxisConsumer, Misc, Modal, Motion, OneShot};

const BOTH: u8 = variants::ALL_NGC;
const MODERN: u8 = variants::LINUXCNC;

const fn g(
    tenths: u32,
    group: Option<u8>,
    kind: CodeKind,
    summary: &'static str,
    doc: &'static str,
    params: &'static [Param],
) -> CodeInfo {
    CodeInfo::new(
        'G',
        CodeNum(tenths),
        group,
        kind,
        BOTH,
        summary,
        doc,
        params,
    )
}

const fn m(
    n: u32,
    group: Option<u8>,
    summary: &'static str,
    doc: &'static str,
    params: &'static [Param],
) -> CodeInfo {
    CodeInfo::new(
        'M',
        CodeNum::whole(n),
        group,
        Misc,
        BOTH,
        summary,
        doc,
        params,
    )
}

const fn o(letter: char, doc: &'static str) -> Param {
    Param::opt(letter, doc)
}

const fn r(letter: char, doc: &'static str) -> Param {
    Param::req(letter, doc)
}

const NONE: &[Param] = &[];

const AXES: &[Param] = &[
    o('X', "X end point"),
    o('Y', "Y end point"),
    o('Z', "Z end point"),
    o('A', "A (rotary about X) end point, degrees"),
    o('B', "B (rotary about Y) end point, degrees"),
    o('C', "C (rotary about Z) end point, degrees"),
    o('U', "U end point (LinuxCNC)"),
    o('V', "V end point (LinuxCNC)"),
    o('W', "W end point (LinuxCNC)"),
];

const AXES_SET: &[Param] = &[
    o('X', "value for X"),
    o('Y', "value for Y"),
    o('Z', "value for Z"),
    o('A', "value for A"),
    o('B', "value for B"),
    o('C', "value for C"),
    o('U', "value for U (LinuxCNC)"),
    o('V', "value for V (LinuxCNC)"),
    o('W', "value for W (LinuxCNC)"),
];

const ARC: &[Param] = &[
    o('X', "end point X"),
    o('Y', "end point Y"),
    o('Z', "end point Z (the helix axis under G17)"),
    o(
        'A',
        "rotary end point, moved at a constant rate with the arc",
    ),
    o('B', "rotary end point"),
    o('C', "rotary end point"),
    o('U', "end point U (LinuxCNC)"),
    o('V', "end point V (LinuxCNC)"),
    o('W', "end point W (LinuxCNC)"),
    o(
        'I',
        "X offset of the centre from the start point (absolute under G90.1)",
    ),
    o(
        'J',
        "Y offset of the centre from the start point (absolute under G90.1)",
    ),
    o(
        'K',
        "Z offset of the centre from the start point (absolute under G90.1)",
    ),
    o(
        'R',
        "radius; positive = 180° or less, negative = more than 180°; no full circles",
    ),
    o('P', "number of turns (LinuxCNC; default 1)"),
    o('F', "feed rate"),
];

const PROBE: &[Param] = &[
    o('X', "target X"),
    o('Y', "target Y"),
    o('Z', "target Z"),
    o('A', "target A"),
    o('B', "target B"),
    o('C', "target C"),
    o('U', "target U (LinuxCNC)"),
    o('V', "target V (LinuxCNC)"),
    o('W', "target W (LinuxCNC)"),
    o('F', "probing feed rate"),
];

const CYC_X: Param = o('X', "hole position X (G91: increment, repeated L times)");
const CYC_Y: Param = o('Y', "hole position Y (G91: increment, repeated L times)");
const CYC_Z: Param = o(
    'Z',
    "hole bottom (sticky; G91: relative to R); required on the first cycle block",
);
const CYC_R: Param = o(
    'R',
    "retract plane (sticky; G91: relative to the start height); required on the first cycle block",
);
const CYC_L: Param = o(
    'L',
    "repeat count, positive integer (default 1, not sticky)",
);
const CYC_F: Param = o('F', "feed rate");
const CYC_P: Param = o('P', "dwell at the bottom in seconds (sticky)");

const DRILL: &[Param] = &[CYC_X, CYC_Y, CYC_Z, CYC_R, CYC_L, CYC_F];
const DRILL_DWELL: &[Param] = &[CYC_X, CYC_Y, CYC_Z, CYC_R, CYC_P, CYC_L, CYC_F];
const PECK: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o('Q', "peck depth, positive (sticky)"),
    CYC_L,
    CYC_F,
];

const TURN_CYCLE: &[Param] = &[
    r('Q', "number of the O-sub that holds the profile"),
    o('X', "start X"),
    o('Z', "start Z"),
    o('D', "depth of cut per pass"),
    o('I', "increment of D per pass"),
    o('R', "retract distance"),
    o('P', "finishing passes / parameter (G70)"),
    o('E', "finishing allowance (G70)"),
];

const USER_M_PARAMS: &[Param] = &[
    o('P', "first argument passed to the program"),
    o('Q', "second argument passed to the program"),
];

const fn user_m(n: u32) -> CodeInfo {
    m(
        n,
        Some(10),
        "User-defined command",
        "Runs the executable file of the same name (M1nn, upper-case M, no extension) from the \
         configured program prefix, passing P and Q as its two arguments, and waits for it to \
         finish. An unknown or non-executable file is an error; a non-zero exit status stops the \
         program (LinuxCNC).",
        USER_M_PARAMS,
    )
}

const BASE: &[CodeInfo] = &[
    // Group 1: motion.
    g(
        0,
        Some(1),
        Motion,
        "Rapid linear move",
        "Straight coordinated move to the end point at the traverse rate; not for cutting. The G0 \
         may be left out while it is the active motion mode. In LinuxCNC a bare G0 only sets the \
         mode; the 2007 seed calls a G0 with no axis word an error. G64 blending may round the path.",
        AXES,
    ),
    g(
        10,
        Some(1),
        Motion,
        "Linear feed move",
        "Straight coordinated move at the current feed rate, read per G93/G94/G95. A zero or unset \
         feed is an error, and in G93 every G1 line needs its own F. M2/M30 leave G1 as the motion \
         mode.",
        AXES,
    ),
    g(
        20,
        Some(1),
        Motion,
        "Clockwise arc or helix",
        "Clockwise as seen from the positive end of the axis normal to the plane (G17 XY, G18 XZ, \
         G19 YZ). Centre by I/J/K offsets or radius R, never both; a centre word on the normal axis \
         is an error. Radius arcs cannot be full circles; centre arcs whose two radii differ beyond \
         the tolerance are rejected. Moving the normal axis too makes a helix.",
        ARC,
    ),
    g(
        30,
        Some(1),
        Motion,
        "Counter-clockwise arc or helix",
        "Counter-clockwise as seen from the positive end of the plane's normal axis. Same words and \
         checks as G2: R or I/J/K (not both), no centre word on the normal axis, zero feed is an \
         error, P gives extra turns in LinuxCNC.",
        ARC,
    ),
    g(
        50,
        Some(1),
        Motion,
        "Cubic B-spline (LinuxCNC)",
        "Cubic spline in the XY plane to X/Y. I/J give the start control point offset and P/Q the \
         end control point offset; I and J must come together, and the first G5 of a chain needs \
         them (later ones reuse the previous P/Q negated). G17 only; only X and Y may move.",
        &[
            o('X', "end point X"),
            o('Y', "end point Y"),
            o('I', "X offset of the first control point from the start"),
            o('J', "Y offset of the first control point from the start"),
            r('P', "X offset of the last control point from the end"),
            r('Q', "Y offset of the last control point from the end"),
            o('F', "feed rate"),
        ],
    )
    .only(MODERN),
    g(
        51,
        Some(1),
        Motion,
        "Quadratic B-spline (LinuxCNC)",
        "Quadratic spline in the XY plane to X/Y with one control point at offset I/J from the \
         start; I and J may not both be missing or zero. G17 only; only X and Y.",
        &[
            o('X', "end point X"),
            o('Y', "end point Y"),
            o('I', "X offset of the control point"),
            o('J', "Y offset of the control point"),
            o('F', "feed rate"),
        ],
    )
    .only(MODERN),
    g(
        52,
        Some(1),
        Motion,
        "NURBS block start (LinuxCNC, experimental)",
        "Opens a NURBS curve: this line and the following control-point lines (X Y with optional \
         weight P) are collected until G5.3. Default weight 1, default order L = 3; weights must be \
         positive and there must be at least L points. Nothing else may appear between G5.2 and G5.3.",
        &[
            o('X', "control point X"),
            o('Y', "control point Y"),
            o('P', "weight of this control point (> 0, default 1)"),
            o('L', "order of the curve (default 3)"),
            o('F', "feed rate"),
        ],
    )
    .only(MODERN),
    g(
        53,
        Some(0),
        OneShot,
        "NURBS block end (LinuxCNC, experimental)",
        "Closes the NURBS block opened by G5.2 and executes the curve. G5.3 without an open G5.2 is \
         an error.",
        NONE,
    )
    .only(MODERN),
    g(
        330,
        Some(1),
        Motion,
        "Spindle-synchronised motion",
        "Straight move whose speed follows the spindle: K is the distance per revolution (e.g. K.0625 \
         = 16 TPI). Needs an axis word and a turning spindle (M3/M4); an F word on the line is an \
         error. Each pass waits for the spindle index pulse.",
        &[
            o('X', "end point X"),
            o('Y', "end point Y"),
            o('Z', "end point Z"),
            r('K', "distance travelled per spindle revolution"),
        ],
    ),
    g(
        331,
        Some(1),
        Motion,
        "Rigid tapping (LinuxCNC)",
        "Synchronised move to the point at K per revolution, spindle reversal, synchronised return \
         to the start and spindle restored. K is required, F is forbidden and the spindle must turn. \
         Position X/Y beforehand.",
        &[
            o('X', "end point X"),
            o('Y', "end point Y"),
            o('Z', "tap depth Z"),
            r('K', "thread pitch, distance per revolution"),
            o('I', "spindle speed multiplier for the retract (minimum 1)"),
        ],
    )
    .only(MODERN),
    g(
        382,
        Some(1),
        Motion,
        "Probe toward work, error if no contact",
        "Feeds straight toward the point until the probe trips; reaching the point without a trip \
         is an error. The trip position is stored in #5061… (LinuxCNC: #5070 = 1 on success). Needs \
         a non-zero feed, an end point different from the start, and compensation off.",
        PROBE,
    ),
    g(
        383,
        Some(1),
        Motion,
        "Probe toward work, no error (LinuxCNC)",
        "Like G38.2 but no error when the probe does not trip; #5070 tells whether it did.",
        PROBE,
    )
    .only(MODERN),
    g(
        384,
        Some(1),
        Motion,
        "Probe away from work, error if no release (LinuxCNC)",
        "Moves until the probe opens; reaching the point while still tripped is an error.",
        PROBE,
    )
    .only(MODERN),
    g(
        385,
        Some(1),
        Motion,
        "Probe away from work, no error (LinuxCNC)",
        "Moves until the probe opens, without an error when it does not; #5070 tells the result.",
        PROBE,
    )
    .only(MODERN),
    g(
        700,
        Some(1),
        Motion,
        "Lathe finishing cycle (LinuxCNC)",
        "Runs the profile in O-sub Q as finishing passes. G18 plane required.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        710,
        Some(1),
        Motion,
        "Lathe roughing cycle along Z (LinuxCNC)",
        "Roughs the profile in O-sub Q with passes parallel to Z; the profile must be monotonic in \
         Z. G18 only; not with G41/G42.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        711,
        Some(1),
        Motion,
        "Lathe roughing along Z, no pockets (LinuxCNC)",
        "As G71 but pockets in the profile are not machined. G18 only.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        712,
        Some(1),
        Motion,
        "Lathe roughing along Z, pockets only (LinuxCNC)",
        "Skips the first roughing pass and cuts only the pockets after the first one, where \
         G71.1 stopped. G18 only; not with G41/G42.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        720,
        Some(1),
        Motion,
        "Lathe roughing cycle along X (LinuxCNC)",
        "Roughs the profile in O-sub Q with passes parallel to X; the profile must be monotonic in \
         X. G18 only; not with G41/G42.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        721,
        Some(1),
        Motion,
        "Lathe roughing along X, no pockets (LinuxCNC)",
        "As G72 but pockets are not machined. G18 only.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        722,
        Some(1),
        Motion,
        "Lathe roughing along X, pockets only (LinuxCNC)",
        "Skips the first roughing pass and cuts only the pockets after the first one, where \
         G72.1 stopped. G18 only; not with G41/G42.",
        TURN_CYCLE,
    )
    .only(MODERN),
    g(
        730,
        Some(1),
        Motion,
        "Chip-breaking peck drilling (LinuxCNC)",
        "Like G83 but between pecks the tool only backs off by a small clearance (0.010 in / \
         0.254 mm) instead of retracting to R. Q (peck) must be positive; R and Q are needed on \
         the first cycle block.",
        PECK,
    )
    .only(MODERN),
    g(
        740,
        Some(1),
        Motion,
        "Left-hand tapping with floating chuck (LinuxCNC)",
        "Feeds to Z with the spindle counter-clockwise (required), reverses, dwells P and feeds \
         back out. Feed and speed overrides are disabled during the cycle.",
        DRILL_DWELL,
    )
    .only(MODERN),
    g(
        760,
        Some(1),
        Motion,
        "Lathe threading cycle",
        "Cuts a thread along the drive line from the start to Z in G18: P pitch, I peak offset \
         (negative = external), J first cut depth, K full depth, R degression, Q compound angle, H \
         spring passes; LinuxCNC adds E/L taper. Each pass waits for the spindle index. LinuxCNC \
         requires P, I, J, K, K > J > 0; X/Y and rotary words are errors.",
        &[
            r('P', "thread pitch (distance per revolution)"),
            o('Z', "end of the drive line (default: current Z)"),
            r('I', "thread peak offset from the drive line; negative = external thread"),
            r('J', "depth of the first cut beyond the peak (> 0)"),
            r('K', "full thread depth beyond the peak (> J)"),
            o('R', "depth degression (≥ 1, default 1)"),
            o('Q', "compound slide angle in degrees (default 0)"),
            o('H', "number of spring passes (default 0)"),
            o('E', "taper length along the drive line (LinuxCNC)"),
            o('L', "taper ends: 0 none, 1 entry, 2 exit, 3 both (LinuxCNC)"),
        ],
    ),
    g(
        800,
        Some(1),
        Modal,
        "Cancel modal motion",
        "Sets the motion mode to none, ending any canned cycle. Axis words on a line in G80 mode \
         are an error unless a group-0 code such as G92 uses them. Power-on motion mode.",
        NONE,
    )
    .dflt(),
    g(
        810,
        Some(1),
        Motion,
        "Drilling cycle",
        "Per hole: rapid to X/Y and to R, feed to Z, rapid to the clear height (G98 initial level \
         or R for G99). R and Z are sticky and needed on the first cycle block; R below Z is an \
         error. No rotary words, no inverse time, no cutter compensation.",
        DRILL,
    ),
    g(
        820,
        Some(1),
        Motion,
        "Drilling cycle with dwell",
        "As G81 with a dwell of P seconds at the bottom; P is sticky and needed when G82 was not \
         already active.",
        DRILL_DWELL,
    ),
    g(
        830,
        Some(1),
        Motion,
        "Peck drilling cycle",
        "Feeds down by Q per peck; LinuxCNC rapids back to R between pecks (the 2007 seed to the \
         clear height) and returns to just above the last depth. Q must be positive and is sticky.",
        PECK,
    ),
    g(
        840,
        Some(1),
        Motion,
        "Right-hand tapping cycle",
        "LinuxCNC: floating-chuck tap, spindle must turn clockwise; feed to Z, stop, reverse, dwell \
         P, feed out. Overrides are disabled meanwhile. The 2007 seed accepts it but leaves the \
         behaviour undefined.",
        DRILL_DWELL,
    ),
    g(
        850,
        Some(1),
        Motion,
        "Boring cycle, feed out",
        "Feed to Z and feed back out; LinuxCNC feeds to R and then rapids to the clear height, the \
         2007 seed feeds all the way to the clear height.",
        DRILL,
    ),
    g(
        860,
        Some(1),
        Motion,
        "Boring cycle, spindle stop, rapid out",
        "Feed to Z, dwell P, stop the spindle, rapid to the clear height and restart the spindle in \
         its previous direction. The spindle must be turning.",
        DRILL_DWELL,
    ),
    g(
        870,
        Some(1),
        Motion,
        "Back boring cycle",
        "Documented as not implemented (accepted, behaviour undefined). The LinuxCNC code needs I, J \
         (offset for the oriented entry) and K (the back-bore depth, following G90/G91).",
        &[
            CYC_X,
            CYC_Y,
            CYC_Z,
            CYC_R,
            r('I', "X offset used to pass the tool through the hole"),
            r('J', "Y offset used to pass the tool through the hole"),
            r('K', "Z level of the back bore (absolute under G90)"),
            CYC_L,
            CYC_F,
        ],
    ),
    g(
        880,
        Some(1),
        Motion,
        "Boring cycle, spindle stop, manual out",
        "Documented as not implemented (accepted, behaviour undefined): feed to Z, dwell P, stop the \
         spindle for a manual retract. P is needed when not already sticky.",
        DRILL_DWELL,
    ),
    g(
        890,
        Some(1),
        Motion,
        "Boring cycle with dwell, feed out",
        "Feed to Z, dwell P seconds, feed back to the clear height. P is sticky.",
        DRILL_DWELL,
    ),
    // Group 0: non-modal.
    g(
        40,
        Some(0),
        OneShot,
        "Dwell",
        "Holds the axes still for P seconds (fractions allowed); P is required and must not be \
         negative. It forces an exact stop at the end of the previous move and runs before any \
         motion on the same line. LinuxCNC rejects G4 on a line with G2/G3 (both use P).",
        &[r('P', "dwell time in seconds")],
    ),
    g(
        100,
        Some(0),
        AxisConsumer,
        "Set coordinate system or tool data",
        "G10 L2 P1–9 sets the origin of G54…G59.3 to the given machine coordinates (axes not given \
         keep their values; LinuxCNC adds P0 = active system and R = rotation about Z). LinuxCNC \
         also has L20 (make the current point read the given values), L1/L10/L11 (tool table) and \
         L0 (reload tool table); the seed knows only L2. G91 does not affect G10.",
        &[
            r('L', "data kind: 2 (seed); LinuxCNC also 0, 1, 10, 11, 20"),
            o('P', "coordinate system 1–9 (0 = active, LinuxCNC) or tool number"),
            o('X', "value for X"),
            o('Y', "value for Y"),
            o('Z', "value for Z"),
            o('A', "value for A"),
            o('B', "value for B"),
            o('C', "value for C"),
            o('U', "value for U (LinuxCNC)"),
            o('V', "value for V (LinuxCNC)"),
            o('W', "value for W (LinuxCNC)"),
            o('R', "L2: XY rotation in degrees; L1/L10/L11: tool radius (LinuxCNC)"),
            o('I', "tool front angle (lathe, L1/L10/L11)"),
            o('J', "tool back angle (lathe, L1/L10/L11)"),
            o('Q', "tool orientation (lathe, L1/L10/L11)"),
        ],
    ),
    g(
        280,
        Some(0),
        AxisConsumer,
        "Go to stored position 1",
        "Rapids through the optional intermediate point to the position stored in #5161…. In \
         LinuxCNC only the axes named move to the stored point (all axes when none is named); the \
         seed moves every axis. Homing is assumed; not allowed with cutter compensation.",
        AXES,
    ),
    g(
        281,
        Some(0),
        OneShot,
        "Store position 1 (LinuxCNC)",
        "Saves the current absolute position in #5161… for later G28 moves. Not allowed with \
         cutter compensation on.",
        NONE,
    )
    .only(MODERN),
    g(
        300,
        Some(0),
        AxisConsumer,
        "Go to stored position 2",
        "As G28 but uses the position stored in #5181…: optional intermediate point, then rapid to \
         the stored point. Not allowed with cutter compensation.",
        AXES,
    ),
    g(
        301,
        Some(0),
        OneShot,
        "Store position 2 (LinuxCNC)",
        "Saves the current absolute position in #5181… for later G30 moves. Not allowed with \
         cutter compensation on.",
        NONE,
    )
    .only(MODERN),
    g(
        520,
        Some(0),
        AxisConsumer,
        "Local coordinate offset (LinuxCNC)",
        "Sets an offset applied on top of the active work system, stored in the same registers as \
         G92 (#5211…) but taken directly as given. Needs at least one axis word; it persists across \
         M2 and restarts like G92.",
        AXES_SET,
    )
    .only(MODERN),
    g(
        530,
        Some(0),
        OneShot,
        "Machine coordinates for this line",
        "Makes the G0 or G1 move on this line use machine coordinates, ignoring work, G92/G52 and \
         (LinuxCNC) tool offsets. Requires G0 or G1 as the motion mode; not with cutter \
         compensation or in G91. The axis words belong to the G0/G1 move.",
        NONE,
    ),
    g(
        920,
        Some(0),
        AxisConsumer,
        "Set axis offsets",
        "Makes the current point read the given coordinates without moving, by changing the offset \
         shared by all work systems (#5211…). At least one axis word; axes not named keep their \
         offset. G91 does not matter. Offsets persist in the parameter file.",
        AXES_SET,
    ),
    // G92.1–G92.3: group 16 in the 2.9 code (the docs and the seed say group 0).
    g(
        921,
        Some(16),
        OneShot,
        "Reset axis offsets and parameters",
        "Sets the G92 offsets to zero and also clears #5211…. The LinuxCNC 2.9 interpreter files it \
         in its own group 16.",
        NONE,
    ),
    g(
        922,
        Some(16),
        OneShot,
        "Reset axis offsets, keep parameters",
        "Sets the G92 offsets to zero but leaves #5211… unchanged so G92.3 can restore them.",
        NONE,
    ),
    g(
        923,
        Some(16),
        OneShot,
        "Restore axis offsets from parameters",
        "Applies the offsets saved in #5211…, e.g. to carry G92 offsets from one program to the next.",
        NONE,
    ),
    // Group 2: plane.
    g(
        170,
        Some(2),
        Modal,
        "XY plane",
        "Arcs in XY around Z, canned cycles drill along Z, cutter compensation allowed. Usual \
         start-up plane; M2 restores it.",
        NONE,
    )
    .dflt(),
    g(
        171,
        Some(2),
        Modal,
        "UV plane (LinuxCNC)",
        "Secondary-axis plane; no arcs. Canned cycles use U/V/W.",
        NONE,
    )
    .only(MODERN),
    g(
        180,
        Some(2),
        Modal,
        "XZ plane",
        "Arcs in XZ around Y (centre words I and K), cycles drill along Y. The seed forbids it with \
         cutter compensation; LinuxCNC allows compensation here.",
        NONE,
    ),
    g(
        181,
        Some(2),
        Modal,
        "WU plane (LinuxCNC)",
        "Secondary-axis plane; no arcs. Canned cycles use U/V/W.",
        NONE,
    )
    .only(MODERN),
    g(
        190,
        Some(2),
        Modal,
        "YZ plane",
        "Arcs in YZ around X (centre words J and K), cycles drill along X. Not with cutter \
         compensation.",
        NONE,
    ),
    g(
        191,
        Some(2),
        Modal,
        "VW plane (LinuxCNC)",
        "Secondary-axis plane; no arcs. Canned cycles use U/V/W.",
        NONE,
    )
    .only(MODERN),
    // Group 3: distance mode.
    g(
        900,
        Some(3),
        Modal,
        "Absolute distance mode",
        "Axis words are positions in the active coordinate system (I/J stay incremental unless \
         G90.1). Start-up default; M2 restores it.",
        NONE,
    )
    .dflt(),
    g(
        910,
        Some(3),
        Modal,
        "Incremental distance mode",
        "Axis words are increments from the current position; in canned cycles R is relative to the \
         start height and Z relative to R. G53 is an error in this mode.",
        NONE,
    ),
    // Group 4: arc centre mode.
    g(
        901,
        Some(4),
        Modal,
        "Absolute arc centres (LinuxCNC)",
        "I/J/K give the arc centre as a position instead of an offset; both in-plane centre words \
         are then required.",
        NONE,
    )
    .only(MODERN),
    g(
        911,
        Some(4),
        Modal,
        "Incremental arc centres (LinuxCNC)",
        "I/J/K are offsets from the start point; a missing in-plane offset counts as 0. Default.",
        NONE,
    )
    .only(MODERN)
    .dflt(),
    // Group 5: feed-rate mode.
    g(
        930,
        Some(5),
        Modal,
        "Inverse time feed",
        "F means the move takes 1/F minutes. Every G1/G2/G3 line needs its own F; F elsewhere is \
         ignored and G0 is unaffected. Canned cycles are not allowed in this mode.",
        NONE,
    ),
    g(
        940,
        Some(5),
        Modal,
        "Units per minute feed",
        "F is length units (or degrees) per minute. Start-up default. In LinuxCNC programming G94 \
         resets the feed to 0, so give F again (on the same line is fine).",
        NONE,
    )
    .dflt(),
    g(
        950,
        Some(5),
        Modal,
        "Units per revolution feed (LinuxCNC)",
        "F is distance per spindle revolution, so the speed follows S. A feed move with zero spindle \
         speed is an error, probing is not allowed, and programming G95 resets the feed to 0.",
        NONE,
    )
    .only(MODERN),
    // Group 6: units (start-up value comes from the machine configuration).
    g(
        200,
        Some(6),
        Modal,
        "Inch units",
        "Lengths and feeds are in inches from here on. Put it near the start before any motion; \
         the start-up units depend on the machine configuration. Not with cutter compensation on.",
        NONE,
    ),
    g(
        210,
        Some(6),
        Modal,
        "Millimetre units",
        "Lengths and feeds are in millimetres from here on. Put it near the start before any \
         motion; the start-up units depend on the machine configuration. Not with cutter \
         compensation on.",
        NONE,
    ),
    // Group 7: cutter radius compensation.
    g(
        400,
        Some(7),
        Modal,
        "Cutter compensation off",
        "Turns radius compensation off; fine when already off. In LinuxCNC the next move must be a \
         straight line (longer than the tool diameter). Start-up default.",
        NONE,
    )
    .dflt(),
    g(
        410,
        Some(7),
        Modal,
        "Cutter compensation left",
        "Keeps the tool left of the path looking along the motion. D picks the tool whose radius is \
         used (seed: carousel slot; LinuxCNC: tool number), none = current tool. Turning it on \
         while already on is an error; the seed allows only G17, LinuxCNC G17 or G18.",
        &[o('D', "tool (number or slot) whose radius is used; D0 = radius 0")],
    ),
    g(
        411,
        Some(7),
        Modal,
        "Dynamic cutter compensation left (LinuxCNC)",
        "Compensation to the left with the tool diameter given directly by D instead of the tool \
         table; L is the lathe tool orientation (G18 only). Not in G19, not while compensation is \
         on.",
        &[
            o('D', "tool diameter"),
            o('L', "lathe tool orientation 0–9 (G18 only)"),
        ],
    )
    .only(MODERN),
    g(
        420,
        Some(7),
        Modal,
        "Cutter compensation right",
        "Keeps the tool right of the path looking along the motion. D as for G41; same restrictions.",
        &[o('D', "tool (number or slot) whose radius is used; D0 = radius 0")],
    ),
    g(
        421,
        Some(7),
        Modal,
        "Dynamic cutter compensation right (LinuxCNC)",
        "Compensation to the right with the diameter from D and lathe orientation L. Not in G19, \
         not while compensation is on.",
        &[
            o('D', "tool diameter"),
            o('L', "lathe tool orientation 0–9 (G18 only)"),
        ],
    )
    .only(MODERN),
    // Group 8: tool length offset.
    g(
        430,
        Some(8),
        Modal,
        "Tool length offset",
        "Uses the length of tool H (seed: table index; LinuxCNC: tool number, defaulting to the \
         loaded tool). No motion: the offset is picked up by the next move. Not while cutter \
         compensation is on. The seed's G43 H-1 I- K- form is obsolete (use G43.1).",
        &[
            o('H', "tool whose length offset is used (seed: required index)"),
            o('I', "X offset for the seed's G43 H-1 form"),
            o('K', "Z offset for the seed's G43 H-1 form"),
        ],
    ),
    g(
        431,
        Some(8),
        Modal,
        "Dynamic tool length offset (LinuxCNC)",
        "Replaces the tool offset with the axis values on the line, without touching the tool \
         table. No motion may be on the same line.",
        AXES_SET,
    )
    .only(MODERN),
    g(
        432,
        Some(8),
        Modal,
        "Add tool length offset (LinuxCNC)",
        "Adds another offset to the current one, either from tool H or from the axis words; exactly \
         one of the two must be given.",
        &[
            o('H', "tool whose offsets are added"),
            o('X', "X offset to add"),
            o('Y', "Y offset to add"),
            o('Z', "Z offset to add"),
            o('A', "A offset to add"),
            o('B', "B offset to add"),
            o('C', "C offset to add"),
            o('U', "U offset to add"),
            o('V', "V offset to add"),
            o('W', "W offset to add"),
        ],
    )
    .only(MODERN),
    g(
        490,
        Some(8),
        Modal,
        "Cancel tool length offset",
        "Sets the tool length offset to zero; fine when none is active. Start-up default.",
        NONE,
    )
    .dflt(),
    // Group 10: canned-cycle return level (not initialised by the interpreter).
    g(
        980,
        Some(10),
        Modal,
        "Cycle retract to initial level",
        "Canned cycles retract to the height before the run of cycles began (or R if that is \
         lower). The interpreter does not initialise this group; configurations usually set G98 at \
         start-up.",
        NONE,
    ),
    g(
        990,
        Some(10),
        Modal,
        "Cycle retract to R",
        "Canned cycles retract to the R plane between holes. R means different things in G90 and \
         G91.",
        NONE,
    ),
    // Group 12: coordinate system.
    g(
        540,
        Some(12),
        Modal,
        "Coordinate system 1",
        "Selects work system 1 (#5221…). The start-up system comes from #5220, normally 1; M2 \
         selects G54. Not while cutter compensation is on.",
        NONE,
    )
    .dflt(),
    g(550, Some(12), Modal, "Coordinate system 2", "Selects work system 2 (#5241…). Not while cutter compensation is on.", NONE),
    g(560, Some(12), Modal, "Coordinate system 3", "Selects work system 3 (#5261…). Not while cutter compensation is on.", NONE),
    g(570, Some(12), Modal, "Coordinate system 4", "Selects work system 4 (#5281…). Not while cutter compensation is on.", NONE),
    g(580, Some(12), Modal, "Coordinate system 5", "Selects work system 5 (#5301…). Not while cutter compensation is on.", NONE),
    g(590, Some(12), Modal, "Coordinate system 6", "Selects work system 6 (#5321…). Not while cutter compensation is on.", NONE),
    g(591, Some(12), Modal, "Coordinate system 7", "Selects work system 7 (#5341…). Not while cutter compensation is on.", NONE),
    g(592, Some(12), Modal, "Coordinate system 8", "Selects work system 8 (#5361…). Not while cutter compensation is on.", NONE),
    g(593, Some(12), Modal, "Coordinate system 9", "Selects work system 9 (#5381…). Not while cutter compensation is on.", NONE),
    // Group 13: path control (start-up value from the motion controller, usually G64).
    g(
        610,
        Some(13),
        Modal,
        "Exact path mode",
        "Follows the programmed path exactly, slowing or stopping at sharp corners (LinuxCNC does \
         not stop between collinear moves). Canned cycles use this mode internally.",
        NONE,
    ),
    g(
        611,
        Some(13),
        Modal,
        "Exact stop mode",
        "Stops briefly at the end of every programmed move.",
        NONE,
    ),
    g(
        640,
        Some(13),
        Modal,
        "Continuous (blending) mode",
        "Keeps the feed up by rounding corners by at most P (no limit without P). LinuxCNC adds Q, \
         which merges nearly collinear G1 moves within that tolerance (Q defaults to P). Usually \
         the start-up mode; not changeable while cutter compensation is on.",
        &[
            o('P', "path blending tolerance"),
            o('Q', "naive-CAM merge tolerance (LinuxCNC; default P, Q0 = off)"),
        ],
    )
    .dflt(),
    // Group 14: spindle speed mode.
    g(
        960,
        Some(14),
        Modal,
        "Constant surface speed (LinuxCNC)",
        "S becomes surface speed (ft/min under G20, m/min under G21) and the rpm follows the X \
         distance from the rotation centre, capped by D. S is required; X0 must be the spindle \
         centre line.",
        &[
            r('S', "surface speed"),
            o('D', "maximum spindle rpm"),
        ],
    )
    .only(MODERN),
    g(
        970,
        Some(14),
        Modal,
        "Spindle speed in rpm (LinuxCNC)",
        "S is revolutions per minute. Default.",
        NONE,
    )
    .only(MODERN)
    .dflt(),
    // Group 15: lathe diameter mode.
    g(
        70,
        Some(15),
        Modal,
        "Lathe diameter mode (LinuxCNC)",
        "X words are diameters (G76 I/J/K are halved accordingly). Lathe configurations only.",
        NONE,
    )
    .only(MODERN),
    g(
        80,
        Some(15),
        Modal,
        "Lathe radius mode (LinuxCNC)",
        "X words are radii. Default; lathe configurations only.",
        NONE,
    )
    .only(MODERN)
    .dflt(),
    // M codes. Group 4: stopping.
    m(
        0,
        Some(4),
        "Program pause",
        "Pauses unconditionally; cycle start resumes at the next line. No visible effect in MDI.",
        NONE,
    ),
    m(
        1,
        Some(4),
        "Optional pause",
        "Pauses like M0 only when the optional-stop switch is on.",
        NONE,
    ),
    m(
        2,
        Some(4),
        "Program end",
        "Ends the program; nothing after it is read. Resets: G17, G90, G94, M48, G40, M5, G1 motion \
         mode, M9 and G54. The seed also clears G92 offsets (like G92.2); LinuxCNC keeps G92/G52 \
         offsets. Ending with % does none of this.",
        NONE,
    ),
    m(
        30,
        Some(4),
        "Pallet shuttle and program end",
        "Exchanges pallets, then ends the program with the same resets as M2.",
        NONE,
    ),
    m(
        60,
        Some(4),
        "Pallet shuttle and pause",
        "Exchanges pallets, then pauses unconditionally.",
        NONE,
    ),
    CodeInfo::new(
        'M',
        CodeNum::whole(98),
        None,
        Misc,
        MODERN,
        "Fanuc-style subprogram call (LinuxCNC)",
        "Calls the numbered sub O<P> (a bare oNNN line ending with M99, defined after the call) L \
         times. Must not be mixed with o-word subs in one program; disabled by \
         DISABLE_FANUC_STYLE_SUB.",
        &[
            r('P', "number of the subprogram"),
            o('L', "number of calls (default 1)"),
        ],
    ),
    m(
        99,
        Some(4),
        "Fanuc-style return (LinuxCNC)",
        "Returns from an M98 subprogram; in the main program it restarts the file from the top.",
        NONE,
    )
    .only(MODERN),
    // Group 7: spindle.
    m(
        3,
        Some(7),
        "Spindle clockwise",
        "Starts the spindle clockwise at the current S; with S0 it waits until S becomes non-zero. \
         LinuxCNC accepts $n to pick the spindle.",
        NONE,
    ),
    m(
        4,
        Some(7),
        "Spindle counter-clockwise",
        "Starts the spindle counter-clockwise at the current S.",
        NONE,
    ),
    m(
        5,
        Some(7),
        "Spindle stop",
        "Stops the spindle. Start-up state; M2 restores it.",
        NONE,
    )
    .dflt(),
    m(
        19,
        Some(7),
        "Spindle orient (LinuxCNC)",
        "Turns the spindle to angle R (0–360, plus the configured offset) within Q seconds, \
         direction P (0 shorter, 1 CW, 2 CCW). Cleared by M3/M4/M5.",
        &[
            o('R', "orientation angle 0–360°"),
            o('Q', "timeout in seconds (> 0)"),
            o('P', "direction: 0 shortest, 1 clockwise, 2 counter-clockwise"),
        ],
    )
    .only(MODERN),
    m(
        70,
        Some(7),
        "Save modal state (LinuxCNC)",
        "Saves units, plane, compensation, distance and feed modes, work system, tool offset, \
         retract mode, spindle and coolant state, F and S (not the motion mode) for M72.",
        NONE,
    )
    .only(MODERN),
    m(
        71,
        Some(7),
        "Invalidate saved state (LinuxCNC)",
        "Discards the state saved by M70 at this call level.",
        NONE,
    )
    .only(MODERN),
    m(
        72,
        Some(7),
        "Restore modal state (LinuxCNC)",
        "Restores the state saved by M70/M73 at this call level (units first). Without a save it \
         is an error.",
        NONE,
    )
    .only(MODERN),
    m(
        73,
        Some(7),
        "Save and auto-restore state (LinuxCNC)",
        "Saves the modal state like M70 and restores it automatically when the current sub returns.",
        NONE,
    )
    .only(MODERN),
    // Group 6: tool change.
    m(
        6,
        Some(6),
        "Tool change",
        "Swaps in the tool selected by T, leaving the spindle stopped and everything else unchanged \
         (it may move axes). It does not apply the tool length offset: follow it with G43. LinuxCNC \
         errors without a prepared T or with cutter compensation on.",
        NONE,
    ),
    m(
        61,
        Some(6),
        "Set current tool number (LinuxCNC)",
        "Declares tool Q as loaded without a tool change; the length offset is not changed.",
        &[r('Q', "tool number (≥ 0)")],
    )
    .only(MODERN),
    // Group 8: coolant.
    m(
        7,
        Some(8),
        "Mist coolant on",
        "Turns mist coolant on; can be on together with flood, but M7 and M8 may not share a line.",
        NONE,
    ),
    m(
        8,
        Some(8),
        "Flood coolant on",
        "Turns flood coolant on; can be on together with mist, but not on the same line as M7.",
        NONE,
    ),
    m(
        9,
        Some(8),
        "Coolant off",
        "Turns mist and flood coolant off. Start-up state; M2 restores it.",
        NONE,
    )
    .dflt(),
    // Group 9: override switches.
    m(
        48,
        Some(9),
        "Enable overrides",
        "Enables the feed and spindle speed override controls. Start-up state.",
        NONE,
    )
    .dflt(),
    m(
        49,
        Some(9),
        "Disable overrides",
        "Disables both override controls; the programmed feed and speed are used as written.",
        NONE,
    ),
    m(
        50,
        Some(9),
        "Feed override control",
        "P1 (or no P) enables the feed override, P0 disables it.",
        &[o('P', "1 = enable (default), 0 = disable")],
    ),
    m(
        51,
        Some(9),
        "Spindle speed override control",
        "P1 (or no P) enables the spindle override, P0 disables it.",
        &[o('P', "1 = enable (default), 0 = disable")],
    ),
    m(
        52,
        Some(9),
        "Adaptive feed control",
        "P1 (or no P) lets an external input scale the feed, P0 turns that off.",
        &[o('P', "1 = enable (default), 0 = disable")],
    ),
    m(
        53,
        Some(9),
        "Feed stop control",
        "P1 (or no P) enables the feed-stop input, P0 disables it.",
        &[o('P', "1 = enable (default), 0 = disable")],
    ),
    // Group 5: I/O.
    m(
        62,
        Some(5),
        "Digital output on, with motion",
        "Sets output P on at the start of the next motion command; without a later move it never \
         happens.",
        &[r('P', "output number")],
    ),
    m(
        63,
        Some(5),
        "Digital output off, with motion",
        "Sets output P off at the start of the next motion command.",
        &[r('P', "output number")],
    ),
    m(
        64,
        Some(5),
        "Digital output on, immediately",
        "Sets output P on at once; breaks path blending.",
        &[r('P', "output number")],
    ),
    m(
        65,
        Some(5),
        "Digital output off, immediately",
        "Sets output P off at once; breaks path blending.",
        &[r('P', "output number")],
    ),
    m(
        66,
        Some(5),
        "Wait on input (LinuxCNC)",
        "Waits for digital input P or analog input E: L0 immediate, 1 rise, 2 fall, 3 high, 4 low, \
         with timeout Q seconds. The result goes to #5399 (−1 on timeout). Exactly one of P and E; \
         analog only with L0.",
        &[
            o('P', "digital input number"),
            o('E', "analog input number"),
            o('L', "wait mode 0–4"),
            o('Q', "timeout in seconds"),
        ],
    )
    .only(MODERN),
    m(
        67,
        Some(5),
        "Analog output with motion (LinuxCNC)",
        "Sets analog output E to value Q at the start of the next move.",
        &[r('E', "analog output number"), r('Q', "value")],
    )
    .only(MODERN),
    m(
        68,
        Some(5),
        "Analog output immediately (LinuxCNC)",
        "Sets analog output E to value Q at once.",
        &[r('E', "analog output number"), r('Q', "value")],
    )
    .only(MODERN),
];

const LEN: usize = BASE.len() + 100;

/// Appends M100…M199 (user-defined commands) to [`BASE`].
const fn build() -> [CodeInfo; LEN] {
    let mut out = [BASE[0]; LEN];
    let mut i = 0;
    while i < BASE.len() {
        out[i] = BASE[i];
        i += 1;
    }
    let mut k = 0;
    while k < 100 {
        out[BASE.len() + k] = user_m(100 + k as u32);
        k += 1;
    }
    out
}

static ALL: [CodeInfo; LEN] = build();

/// Every G and M code of RS274/NGC (both profiles; see [`CodeInfo::variants`]).
pub static CODES: &[CodeInfo] = &ALL;

/// Meanings of the RS274/NGC words other than G and M.
pub static ADDRESSES: &[AddressInfo] = &[
    AddressInfo {
        letter: 'A',
        doc: "A axis, rotary about X (degrees)",
    },
    AddressInfo {
        letter: 'B',
        doc: "B axis, rotary about Y (degrees)",
    },
    AddressInfo {
        letter: 'C',
        doc: "C axis, rotary about Z (degrees)",
    },
    AddressInfo {
        letter: 'D',
        doc: "cutter compensation tool (G41/G42); LinuxCNC also: diameter for G41.1/G42.1, \
              maximum rpm for G96, depth of cut in G70–G72",
    },
    AddressInfo {
        letter: 'E',
        doc: "LinuxCNC only: G76 taper length, M66–M68 analog channel, G70 allowance",
    },
    AddressInfo {
        letter: 'F',
        doc: "feed rate: units per minute (G94), per revolution (G95) or inverse time (G93)",
    },
    AddressInfo {
        letter: 'H',
        doc: "tool length offset for G43 (seed: table index; LinuxCNC: tool number); G76 spring passes",
    },
    AddressInfo {
        letter: 'I',
        doc: "arc centre X offset; G87 offset; G76 thread peak; G10 L1 front angle, G33.1 \
              multiplier, G5/G5.1 control point (LinuxCNC)",
    },
    AddressInfo {
        letter: 'J',
        doc: "arc centre Y offset; G87 offset; G76 first cut depth; G10 L1 back angle, G5/G5.1 \
              control point (LinuxCNC)",
    },
    AddressInfo {
        letter: 'K',
        doc: "arc centre Z offset; G87 depth; G33/G33.1 distance per revolution; G76 full depth",
    },
    AddressInfo {
        letter: 'L',
        doc: "G10 data kind; canned-cycle repeat count; LinuxCNC also G76 taper ends, M66 wait \
              mode, G41.1/G42.1 orientation, G5.2 order, M98 call count",
    },
    AddressInfo {
        letter: 'N',
        doc: "line number (not a word; ignored by the interpreter)",
    },
    AddressInfo {
        letter: 'O',
        doc: "flow-control label: o-word subroutines, loops and conditionals",
    },
    AddressInfo {
        letter: 'P',
        doc: "dwell seconds (G4, cycles); G10 system or tool; LinuxCNC also arc turns, G64 \
              tolerance, M50–M53 switch, M62–M66 I/O number, M98 subprogram, G5 control point",
    },
    AddressInfo {
        letter: 'Q',
        doc: "peck depth (G83, G73); G76 compound angle; LinuxCNC also G64 merge tolerance, M19 \
              timeout, M61 tool, M66 timeout, M67/M68 value, G70–G72 profile sub",
    },
    AddressInfo {
        letter: 'R',
        doc: "arc radius; canned-cycle retract plane; G76 degression; LinuxCNC also G10 L2 \
              rotation and M19 angle",
    },
    AddressInfo {
        letter: 'S',
        doc: "spindle speed in rpm (G96: surface speed); must not be negative",
    },
    AddressInfo {
        letter: 'T',
        doc: "tool to prepare for the next M6 (seed: carousel slot; LinuxCNC: tool number); T0 = no tool",
    },
    AddressInfo {
        letter: 'U',
        doc: "U axis, secondary linear axis parallel to X (LinuxCNC)",
    },
    AddressInfo {
        letter: 'V',
        doc: "V axis, secondary linear axis parallel to Y (LinuxCNC)",
    },
    AddressInfo {
        letter: 'W',
        doc: "W axis, secondary linear axis parallel to Z (LinuxCNC)",
    },
    AddressInfo {
        letter: 'X',
        doc: "X axis coordinate",
    },
    AddressInfo {
        letter: 'Y',
        doc: "Y axis coordinate",
    },
    AddressInfo {
        letter: 'Z',
        doc: "Z axis coordinate",
    },
    AddressInfo {
        letter: '#',
        doc: "parameter (numbered #1…#5602, LinuxCNC also named #<name>)",
    },
    AddressInfo {
        letter: '$',
        doc: "spindle selector for spindle, speed and threading codes; $-1 = all (LinuxCNC)",
    },
    AddressInfo {
        letter: '@',
        doc: "polar distance from the XY origin (LinuxCNC, G17 only)",
    },
    AddressInfo {
        letter: '^',
        doc: "polar angle in degrees (LinuxCNC, G17 only)",
    },
];

#[cfg(test)]
mod tests {
    use super::super::{
        assert_all_present, check_table_invariants, codes_in_group, codes_in_letter_group,
        default_codes, lookup, lookup_address, Dialect, Variant,
    };
    use super::*;

    const D: Dialect = Dialect::Rs274ngc;

    fn get(letter: char, tenths: u32) -> &'static CodeInfo {
        match lookup(D, letter, CodeNum(tenths)) {
            Some(c) => c,
            None => panic!("{letter}{} missing", CodeNum(tenths).display()),
        }
    }

    fn names(it: impl Iterator<Item = &'static CodeInfo>) -> Vec<String> {
        it.map(|c| c.name()).collect()
    }

    #[test]
    fn table_invariants() {
        check_table_invariants(D);
    }

    #[test]
    fn every_code_of_the_group_table_and_extensions_is_present() {
        // Digest §2.1 (seed and modern members), §3, §4 and §11.3/§11.4.
        assert_all_present(
            D,
            &[
                "G0", "G1", "G2", "G3", "G4", "G5", "G5.1", "G5.2", "G5.3", "G7", "G8", "G10",
                "G17", "G17.1", "G18", "G18.1", "G19", "G19.1", "G20", "G21", "G28", "G28.1",
                "G30", "G30.1", "G33", "G33.1", "G38.2", "G38.3", "G38.4", "G38.5", "G40", "G41",
                "G41.1", "G42", "G42.1", "G43", "G43.1", "G43.2", "G49", "G52", "G53", "G54",
                "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3", "G61", "G61.1",
                "G64", "G70", "G71", "G71.1", "G71.2", "G72", "G72.1", "G72.2", "G73", "G74",
                "G76", "G80", "G81", "G82", "G83", "G84", "G85", "G86", "G87", "G88", "G89", "G90",
                "G90.1", "G91", "G91.1", "G92", "G92.1", "G92.2", "G92.3", "G93", "G94", "G95",
                "G96", "G97", "G98", "G99", "M0", "M1", "M2", "M3", "M4", "M5", "M6", "M7", "M8",
                "M9", "M19", "M30", "M48", "M49", "M50", "M51", "M52", "M53", "M60", "M61", "M62",
                "M63", "M64", "M65", "M66", "M67", "M68", "M70", "M71", "M72", "M73", "M98", "M99",
                "M100", "M150", "M199",
            ],
        );
        assert!(lookup(D, 'M', CodeNum::whole(200)).is_none());
        assert!(
            lookup(D, 'G', CodeNum(541)).is_none(),
            "G54.1 is not an RS274/NGC code"
        );
        assert!(lookup(D, 'G', CodeNum(150)).is_none());
    }

    #[test]
    fn groups_match_linuxcnc_numbers() {
        assert_eq!(get('G', 10).group, Some(1));
        assert_eq!(get('G', 800).group, Some(1));
        assert_eq!(get('G', 760).group, Some(1));
        assert_eq!(get('G', 901).group, Some(4));
        assert_eq!(get('G', 950).group, Some(5));
        assert_eq!(get('G', 593).group, Some(12));
        assert_eq!(get('G', 611).group, Some(13));
        assert_eq!(get('G', 960).group, Some(14));
        assert_eq!(get('G', 70).group, Some(15));
        assert_eq!(get('G', 921).group, Some(16));
        assert_eq!(get('G', 53).group, Some(0));
        assert_eq!(get('M', 70).group, Some(8));
        assert_eq!(get('M', 80).group, Some(8));
        assert_eq!(get('M', 190).group, Some(7));
        assert_eq!(get('M', 610).group, Some(6));
        assert_eq!(get('M', 660).group, Some(5));
        assert_eq!(get('M', 990).group, Some(4));
        assert_eq!(get('M', 1230).group, Some(10));
        assert_eq!(
            names(codes_in_group(D, 0)),
            ["G5.3", "G4", "G10", "G28", "G28.1", "G30", "G30.1", "G52", "G53", "G92"]
        );
        assert_eq!(names(codes_in_letter_group(D, 'M', 8)), ["M7", "M8", "M9"]);
        assert_eq!(
            names(codes_in_letter_group(D, 'M', 4)),
            ["M0", "M1", "M2", "M30", "M60", "M99"]
        );
        // M7 and M8 clash (same M group); G40 and M3 do not share a group.
        assert!(get('M', 70).same_group(get('M', 80)));
        assert!(!get('G', 400).same_group(get('M', 30)));
        // Group 0 counts for the same-group rule (G4 with G10 is two group-0 codes).
        assert!(get('G', 40).same_group(get('G', 100)));
    }

    #[test]
    fn defaults() {
        assert_eq!(
            names(default_codes(D)),
            [
                "G80", "G17", "G90", "G91.1", "G94", "G40", "G49", "G54", "G64", "G97", "G8", "M5",
                "M9", "M48"
            ]
        );
        // Units and retract mode have no interpreter default.
        assert!(codes_in_group(D, 6).all(|c| !c.default));
        assert!(codes_in_group(D, 10).all(|c| !c.default));
    }

    #[test]
    fn profiles() {
        for t in [
            50, 51, 52, 53, 70, 80, 171, 281, 301, 331, 383, 411, 431, 432, 520, 730, 740, 950,
            960, 970,
        ] {
            let c = get('G', t);
            assert!(
                c.on_variant(Variant::Linuxcnc) && !c.on_variant(Variant::Emc2),
                "{}",
                c.name()
            );
        }
        for t in [190, 610, 660, 670, 680, 700, 730, 980, 990] {
            assert_eq!(get('M', t).variants, variants::LINUXCNC, "M{}", t / 10);
        }
        for t in [0, 10, 330, 382, 760, 840, 870, 880, 921, 930, 593, 611] {
            assert_eq!(
                get('G', t).variants,
                variants::ALL_NGC,
                "G{}",
                CodeNum(t).display()
            );
        }
        assert_eq!(get('M', 1000).variants, variants::ALL_NGC);
        assert_eq!(get('M', 620).variants, variants::ALL_NGC);
    }

    #[test]
    fn kinds_and_params() {
        for t in [100, 280, 300, 520, 920] {
            assert_eq!(
                get('G', t).kind,
                CodeKind::AxisConsumer,
                "G{}",
                CodeNum(t).display()
            );
        }
        assert_eq!(get('G', 530).kind, CodeKind::OneShot);
        assert_eq!(get('G', 830).kind, CodeKind::Motion);
        assert_eq!(get('G', 800).kind, CodeKind::Modal);
        assert!(get('G', 40).param('P').is_some_and(|p| p.required));
        assert!(get('G', 330).param('K').is_some_and(|p| p.required));
        assert!(get('G', 100).param('L').is_some_and(|p| p.required));
        assert!(get('G', 830).param('Q').is_some_and(|p| !p.required));
        assert!(get('G', 810).param('Z').is_some_and(|p| !p.required));
        assert!(get('G', 20).param('P').is_some());
        assert!(get('M', 620).param('P').is_some_and(|p| p.required));
        assert!(get('M', 1420).param('Q').is_some());
    }

    #[test]
    fn addresses() {
        assert!(lookup_address(D, 'u').is_some());
        assert!(lookup_address(D, '$').is_some());
        assert!(lookup_address(D, 'G').is_none());
    }
}
