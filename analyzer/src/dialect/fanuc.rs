//! The FANUC Series 30i (machining-centre system) code and address tables, from
//! the fanuc spec digest (§1.9 addresses, §2.3 G-code table, §3 seed functions,
//! §4.5–§4.8 macro and program codes, §3.5 rigid tapping).
//!
//! Group numbers follow the digest's reconstruction of Table 2(a). Defaults are the
//! ▼ marks the digest infers; parameter-selectable ones say so in their doc. One
//! deliberate deviation: the extracted table prints group 19 for both G25/G26 and
//! G40.1–G42.1, and the digest asks for two independent states, so G25/G26 get
//! their own number ([`G25_GROUP`]).

use super::{variants, AddressInfo, CodeInfo, CodeKind, CodeNum, Param};

use CodeKind::{AxisConsumer, Misc, Modal, Motion, OneShot};

const FS: u8 = variants::FANUC30I;

/// Group number used for G25/G26 so that they do not share a modal state with
/// normal direction control (G40.1–G42.1, group 19). The manual prints 19 for both.
pub const G25_GROUP: u8 = 25;

const fn g(
    tenths: u32,
    group: Option<u8>,
    kind: CodeKind,
    summary: &'static str,
    doc: &'static str,
    params: &'static [Param],
) -> CodeInfo {
    CodeInfo::new('G', CodeNum(tenths), group, kind, FS, summary, doc, params)
}

const fn m(n: u32, summary: &'static str, doc: &'static str, params: &'static [Param]) -> CodeInfo {
    CodeInfo::new('M', CodeNum::whole(n), None, Misc, FS, summary, doc, params)
}

const fn o(letter: char, doc: &'static str) -> Param {
    Param::opt(letter, doc)
}

const fn r(letter: char, doc: &'static str) -> Param {
    Param::req(letter, doc)
}

const NONE: &[Param] = &[];

const AXES: &[Param] = &[
    o('X', "X end point (absolute or incremental per G90/G91)"),
    o('Y', "Y end point"),
    o('Z', "Z end point"),
    o('A', "A-axis end point"),
    o('B', "B-axis end point"),
    o('C', "C-axis end point"),
    o('U', "U (parallel-axis) end point"),
    o('V', "V (parallel-axis) end point"),
    o('W', "W (parallel-axis) end point"),
];

const FEED_AXES: &[Param] = &[
    o('X', "X end point (absolute or incremental per G90/G91)"),
    o('Y', "Y end point"),
    o('Z', "Z end point"),
    o('A', "A-axis end point"),
    o('B', "B-axis end point"),
    o('C', "C-axis end point"),
    o('U', "U (parallel-axis) end point"),
    o('V', "V (parallel-axis) end point"),
    o('W', "W (parallel-axis) end point"),
    o('F', "feedrate (modal)"),
];

const ARC: &[Param] = &[
    o('X', "end point X (plane axis under G17/G18)"),
    o('Y', "end point Y (plane axis under G17/G19)"),
    o(
        'Z',
        "end point Z (plane axis under G18/G19; helical axis under G17)",
    ),
    o('A', "additional helical axis"),
    o('B', "additional helical axis"),
    o('C', "additional helical axis"),
    o(
        'I',
        "centre offset along X from the start point (always incremental)",
    ),
    o(
        'J',
        "centre offset along Y from the start point (always incremental)",
    ),
    o(
        'K',
        "centre offset along Z from the start point (always incremental)",
    ),
    o(
        'R',
        "radius: positive = up to 180°, negative = more than 180°; wins over I/J/K",
    ),
    o('F', "feedrate along the arc"),
];

const INVOLUTE: &[Param] = &[
    o('X', "end point X"),
    o('Y', "end point Y"),
    o('Z', "end point Z"),
    o(
        'I',
        "X component of the vector start point → base-circle centre (incremental)",
    ),
    o(
        'J',
        "Y component of the vector start point → base-circle centre (incremental)",
    ),
    o(
        'K',
        "Z component of the vector start point → base-circle centre (incremental)",
    ),
    r('R', "base-circle radius (omitted: PS0241, zero: PS0242)"),
    o('F', "feedrate along the involute"),
];

const REF_AXES: &[Param] = &[
    o('X', "intermediate point X"),
    o('Y', "intermediate point Y"),
    o('Z', "intermediate point Z"),
    o('A', "intermediate point A"),
    o('B', "intermediate point B"),
    o('C', "intermediate point C"),
];

const SET_AXES: &[Param] = &[
    o('X', "value for X"),
    o('Y', "value for Y"),
    o('Z', "value for Z"),
    o('A', "value for A"),
    o('B', "value for B"),
    o('C', "value for C"),
];

const CYC_X: Param = o('X', "hole position X");
const CYC_Y: Param = o('Y', "hole position Y");
const CYC_Z: Param = o(
    'Z',
    "point Z, hole bottom (G90 absolute; G91 distance from point R); modal drilling data",
);
const CYC_R: Param = o(
    'R',
    "point R (G90 absolute; G91 distance from the initial level); modal drilling data",
);
const CYC_F: Param = o('F', "cutting feedrate");
const CYC_K: Param = o(
    'K',
    "number of repeats in this block only (0–9999; K0 stores data only)",
);
const CYC_P: Param = o(
    'P',
    "dwell at the hole bottom in ms (integer); store it in a drilling block",
);

const DRILL: &[Param] = &[CYC_X, CYC_Y, CYC_Z, CYC_R, CYC_F, CYC_K];
const DRILL_DWELL: &[Param] = &[CYC_X, CYC_Y, CYC_Z, CYC_R, CYC_P, CYC_F, CYC_K];
const PECK73: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o('Q', "depth per peck, positive (Q missing or 0: PS0045)"),
    CYC_F,
    CYC_K,
];
const PECK83: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o(
        'Q',
        "depth per peck, incremental and positive (Q missing or 0: PS0045)",
    ),
    CYC_F,
    o('I', "small-hole mode: advance/retract speed (format of F)"),
    CYC_P,
    CYC_K,
];
const SHIFT: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o(
        'Q',
        "shift after the oriented stop (sign ignored); same modal Q as the peck depth",
    ),
    CYC_P,
    CYC_F,
    CYC_K,
];
const TAP: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o(
        'P',
        "dwell in ms at the bottom (rigid: also at point R on the way back)",
    ),
    o('Q', "rigid peck tapping: depth of each cut"),
    CYC_F,
    CYC_K,
];
const TAP15: &[Param] = &[
    CYC_X,
    CYC_Y,
    CYC_Z,
    CYC_R,
    o('P', "dwell in ms at the bottom and at point R"),
    CYC_F,
    o('L', "number of repeats (FS15 format)"),
];

const TOOL_OFS: &[Param] = &[
    o(
        'X',
        "distance along X, lengthened or shortened by the offset",
    ),
    o('Y', "distance along Y"),
    o('Z', "distance along Z"),
    o('D', "tool offset number"),
    o('H', "tool offset number (alternative address)"),
];

/// Every G and M code of the FANUC 30i machining-centre system.
pub static CODES: &[CodeInfo] = &[
    // Group 01.
    g(
        0,
        Some(1),
        Motion,
        "Positioning (rapid traverse)",
        "Moves to the end point at rapid. By default each axis runs at its own rapid rate \
         (dog-leg path); with linear-interpolation-type positioning (No. 1401#1) the path is \
         straight. Always decelerates at the end. Power-on default (G01 by parameter 3402#0); a \
         group-01 code also cancels a canned cycle.",
        AXES,
    )
    .dflt(),
    g(
        10,
        Some(1),
        Motion,
        "Linear interpolation",
        "Straight move at the modal feedrate F (G94 per minute, G95 per revolution, G93 inverse \
         time). A cutting move with no F ever set, or F0, raises PS0011. Can be the power-on mode \
         through parameter 3402#0.",
        FEED_AXES,
    ),
    g(
        20,
        Some(1),
        Motion,
        "Circular / helical interpolation CW",
        "Clockwise arc in the G17/G18/G19 plane, centre by I/J/K (incremental from the start) or \
         radius R; if both are given R wins. Full circles need I/J/K: with R and end = start nothing \
         moves. A start/end radius difference above parameter 3410 raises PS0020; neither R nor \
         I/J/K raises PS0022. A linear axis outside the plane makes a helix. In G16 use R.",
        ARC,
    ),
    g(
        30,
        Some(1),
        Motion,
        "Circular / helical interpolation CCW",
        "Counter-clockwise arc; same words and alarms as G02 (R wins over I/J/K, R cannot make a \
         full circle, radius mismatch beyond No. 3410 is PS0020, missing centre is PS0022).",
        ARC,
    ),
    g(
        22,
        Some(1),
        Motion,
        "Involute interpolation CW",
        "Clockwise involute of the base circle whose centre is I/J/K from the start point and whose \
         radius is R; the tangential feed is held at F. End point and R are required; points inside \
         the base circle, I/J/K all zero or more than 100 turns raise PS0242, an end point off the \
         start involute beyond No. 5610 raises PS0243. Up to four extra axes move linearly.",
        INVOLUTE,
    ),
    g(
        32,
        Some(1),
        Motion,
        "Involute interpolation CCW",
        "Counter-clockwise involute; words and alarms as G02.2. Cutter compensation must be started \
         before and cancelled after involute mode; only G04, G10, G17–G19, G65–G67, G90 and G91 may \
         be given in it.",
        INVOLUTE,
    ),
    g(
        23,
        Some(1),
        Motion,
        "Exponential interpolation CW",
        "Rotary axis turns exponentially with the travel of a linear axis (tapered helical grooves). \
         Option; details are in the common manual, not the seed.",
        FEED_AXES,
    ),
    g(
        33,
        Some(1),
        Motion,
        "Exponential interpolation CCW",
        "Exponential interpolation with the rotary axis turning the other way. Option; details are \
         in the common manual.",
        FEED_AXES,
    ),
    g(
        24,
        Some(1),
        Motion,
        "3-D circular interpolation CW",
        "The table labels it 'three-dimensional coordinate conversion CW', which looks misplaced; it \
         is most likely 3-D circular interpolation through an intermediate point. Option; not \
         described in the seed.",
        FEED_AXES,
    ),
    g(
        34,
        Some(1),
        Motion,
        "3-D circular interpolation CCW",
        "Counterpart of G02.4 (the table's label reads 'three-dimensional coordinate conversion \
         CCW'). Option; not described in the seed.",
        FEED_AXES,
    ),
    g(
        62,
        Some(1),
        Motion,
        "NURBS interpolation",
        "Moves along a NURBS curve defined by control points, weights and knots on the following \
         lines. Option; not described in the seed.",
        FEED_AXES,
    ),
    g(
        330,
        Some(1),
        Motion,
        "Threading",
        "Constant-lead thread synchronised with the spindle position coder; F is the lead along the \
         long axis (IS-B metric F1–F50000 = 0.01–500 mm, or with a decimal point). Starts on the \
         one-revolution signal. Feed override is fixed at 100% and feed hold only stops after the \
         next block. Keep S within (max feed)/lead.",
        &[
            o('X', "end point X"),
            o('Y', "end point Y"),
            o('Z', "end point Z"),
            o('F', "thread lead"),
        ],
    ),
    g(
        340,
        Some(1),
        Motion,
        "Variable lead threading",
        "Thread whose lead changes by a fixed amount per revolution. Not described in the seed.",
        FEED_AXES,
    ),
    g(
        350,
        Some(1),
        Motion,
        "Circular threading CW",
        "Thread cut along a clockwise arc. Not described in the seed.",
        ARC,
    ),
    g(
        360,
        Some(1),
        Motion,
        "Circular threading CCW",
        "Thread cut along a counter-clockwise arc. Not described in the seed.",
        ARC,
    ),
    // Group 00.
    g(
        40,
        Some(0),
        OneShot,
        "Dwell",
        "Waits before the next block. X is seconds (decimal point allowed); P is an integer in \
         milliseconds (P1000 = 1 s) and a decimal point in P is an error. In G95 mode the dwell can \
         be in spindle revolutions by parameter. Its X is never polar.",
        &[
            o('X', "dwell in seconds"),
            o('P', "dwell in milliseconds, integer"),
        ],
    ),
    g(
        50,
        Some(0),
        OneShot,
        "AI contour control (high-precision compatible)",
        "Look-ahead control command compatible with high-precision contour control. Option.",
        &[o('P', "mode selection")],
    ),
    g(
        51,
        Some(0),
        OneShot,
        "AI contour control / nano smoothing",
        "G05.1 Q1 turns look-ahead acceleration before interpolation on, Q0 off (also used for nano \
         smoothing and smooth interpolation). Feed per minute only; rapid becomes \
         linear-interpolation type.",
        &[o('Q', "1 = on, 0 = off")],
    ),
    g(
        54,
        Some(0),
        OneShot,
        "HRV3/4 on/off",
        "Switches high-response servo control mode 3/4 on or off. Option.",
        &[o('Q', "on/off selection")],
    ),
    g(
        70,
        Some(0),
        AxisConsumer,
        "Hypothetical axis interpolation",
        "Declares an axis as hypothetical so that helical-style interpolation can be used for \
         sine-like paths. Option; not described in the seed.",
        SET_AXES,
    ),
    g(
        71,
        Some(0),
        AxisConsumer,
        "Cylindrical interpolation",
        "G07.1 with a rotary axis word and the cylinder radius turns cylindrical interpolation on; \
         the same with radius 0 turns it off. Involute interpolation is not allowed in this mode. \
         G107 is the same code.",
        &[o('C', "rotary axis: cylinder radius (0 = cancel)"), o('A', "rotary axis: cylinder radius"), o('B', "rotary axis: cylinder radius")],
    ),
    g(
        80,
        Some(0),
        OneShot,
        "AI contour control (advanced preview compatible)",
        "Look-ahead command compatible with advanced preview control. Option.",
        &[o('P', "1 = on, 0 = off")],
    ),
    g(
        90,
        Some(0),
        OneShot,
        "Exact stop (one block)",
        "The move in this block decelerates to a stop and the in-position check is made before the \
         next block starts.",
        NONE,
    ),
    g(
        100,
        Some(0),
        AxisConsumer,
        "Programmable data input",
        "Writes offsets, work offsets or parameters from the program; L selects the kind of data and \
         P the number. An illegal L/P or missing data address raises PS0031; excessive values \
         PS0032. Between G10 L… and G11 the data-input mode stays on.",
        &[
            o('L', "data kind (e.g. work offset, tool offset, parameter)"),
            o('P', "offset or work-system number"),
            o('R', "offset value"),
            o('X', "value for X"),
            o('Y', "value for Y"),
            o('Z', "value for Z"),
            o('A', "value for A"),
            o('B', "value for B"),
            o('C', "value for C"),
        ],
    ),
    g(
        106,
        Some(0),
        AxisConsumer,
        "Tool retract and recover",
        "Stores a retract amount; on the retract signal the tool backs off by it and can later \
         return. Not described in the seed.",
        SET_AXES,
    ),
    g(
        109,
        Some(0),
        AxisConsumer,
        "Diameter/radius programming switch",
        "Switches an axis between diameter and radius specification by program. Not described in \
         the seed.",
        SET_AXES,
    ),
    g(
        110,
        Some(0),
        OneShot,
        "Programmable data input mode cancel",
        "Ends the data-input mode opened by G10 L… (e.g. for parameter blocks).",
        NONE,
    ),
    g(
        270,
        Some(0),
        AxisConsumer,
        "Reference position return check",
        "Moves to the given position at rapid and checks that it is the reference position. Not \
         allowed while a canned cycle is modal (PS0044).",
        REF_AXES,
    ),
    g(
        280,
        Some(0),
        AxisConsumer,
        "Automatic return to reference position",
        "Rapids via the intermediate point to the reference position for the named axes; the \
         intermediate point is remembered for G29. Not allowed while a canned cycle is modal \
         (PS0044); `G80 G28 G91 X0 Y0 Z0` is the usual way to finish.",
        REF_AXES,
    ),
    g(
        290,
        Some(0),
        AxisConsumer,
        "Movement from reference position",
        "Moves from the reference position through the intermediate point stored by G28/G30 to the \
         given point. Not allowed while a canned cycle is modal.",
        REF_AXES,
    ),
    g(
        300,
        Some(0),
        AxisConsumer,
        "2nd/3rd/4th reference position return",
        "As G28 but to reference position P2, P3 or P4 (P2 if omitted). Not allowed while a canned \
         cycle is modal.",
        &[
            o('P', "reference position 2, 3 or 4"),
            o('X', "intermediate point X"),
            o('Y', "intermediate point Y"),
            o('Z', "intermediate point Z"),
            o('A', "intermediate point A"),
            o('B', "intermediate point B"),
            o('C', "intermediate point C"),
        ],
    ),
    g(
        301,
        Some(0),
        AxisConsumer,
        "Floating reference position return",
        "Returns via the intermediate point to the floating reference position.",
        REF_AXES,
    ),
    g(
        310,
        Some(0),
        AxisConsumer,
        "Skip function",
        "Linear move at F that is interrupted by the skip signal; the position at the skip is stored \
         in system variables and the next block starts from there.",
        FEED_AXES,
    ),
    g(
        318,
        Some(0),
        AxisConsumer,
        "EGB-axis skip",
        "Skip function for an electronic-gear-box axis. Not described in the seed.",
        FEED_AXES,
    ),
    g(
        370,
        Some(0),
        AxisConsumer,
        "Automatic tool length measurement",
        "Moves toward the measuring position until the sensor signal arrives and sets the tool \
         length offset from the difference. Not described in the seed.",
        &[o('Z', "measuring position"), o('X', "measuring position"), o('Y', "measuring position")],
    ),
    g(
        380,
        Some(0),
        OneShot,
        "Cutter compensation: preserve vector",
        "In cutter compensation, keeps the offset vector of the previous block at the end of this \
         block (no intersection calculation).",
        &[
            o('I', "vector direction X"),
            o('J', "vector direction Y"),
            o('K', "vector direction Z"),
        ],
    ),
    g(
        390,
        Some(0),
        OneShot,
        "Cutter compensation: corner arc",
        "In cutter compensation, inserts an arc of the cutter radius at the corner instead of \
         extending the offset lines.",
        &[
            o('I', "direction X"),
            o('J', "direction Y"),
            o('K', "direction Z"),
        ],
    ),
    g(
        450,
        Some(0),
        AxisConsumer,
        "Tool offset increase",
        "Lengthens the programmed move by the tool offset value. Ignored in canned-cycle mode; not \
         allowed during cutter compensation (PS0042).",
        TOOL_OFS,
    ),
    g(
        460,
        Some(0),
        AxisConsumer,
        "Tool offset decrease",
        "Shortens the programmed move by the tool offset value. Ignored in canned cycles; not with \
         cutter compensation (PS0042).",
        TOOL_OFS,
    ),
    g(
        470,
        Some(0),
        AxisConsumer,
        "Tool offset double increase",
        "Lengthens the move by twice the offset value. Ignored in canned cycles; not with cutter \
         compensation (PS0042).",
        TOOL_OFS,
    ),
    g(
        480,
        Some(0),
        AxisConsumer,
        "Tool offset double decrease",
        "Shortens the move by twice the offset value. Ignored in canned cycles; not with cutter \
         compensation (PS0042).",
        TOOL_OFS,
    ),
    g(
        520,
        Some(0),
        AxisConsumer,
        "Local coordinate system",
        "Shifts the zero of every work coordinate system by the given amounts; G52 with zeros \
         cancels it. With G16 active its axis words are Cartesian; the polar origin follows the \
         local origin.",
        SET_AXES,
    ),
    g(
        530,
        Some(0),
        AxisConsumer,
        "Machine coordinate system selection",
        "Moves to the given machine coordinates at rapid in this block only. Its axis words are not \
         polar under G16.",
        AXES,
    ),
    g(
        531,
        Some(0),
        OneShot,
        "Tool axis direction control",
        "Turns the rotary axes so that the tool points along the Z axis of the feature coordinate \
         system set by G68.2. Not described in the seed.",
        NONE,
    ),
    g(
        600,
        Some(0),
        AxisConsumer,
        "Single direction positioning",
        "Positions always approaching from the same direction to remove backlash. One-shot (group \
         00) normally; modal in group 01 when parameter MDL (No. 5431#0) = 1.",
        AXES,
    ),
    g(
        650,
        Some(0),
        AxisConsumer,
        "Macro call (simple)",
        "Calls macro program O<P> L times, passing the other words as arguments into the local \
         variables of a new level (specification I: A→#1, B→#2, …; II: A B C plus up to ten I/J/K \
         sets). G, L, N, O, P cannot be arguments. Give G65 before its arguments; use decimal \
         points in arguments.",
        &[r('P', "program number of the macro"), o('L', "repeat count (default 1)")],
    ),
    g(
        721,
        Some(0),
        AxisConsumer,
        "Figure copy (rotation)",
        "Repeats a subprogram figure rotated about a centre. Not described in the seed.",
        &[
            o('P', "subprogram number"),
            o('L', "number of copies"),
            o('X', "rotation centre X"),
            o('Y', "rotation centre Y"),
            o('R', "angle increment"),
        ],
    ),
    g(
        722,
        Some(0),
        AxisConsumer,
        "Figure copy (linear)",
        "Repeats a subprogram figure shifted by a constant amount. Not described in the seed.",
        &[
            o('P', "subprogram number"),
            o('L', "number of copies"),
            o('I', "shift along X"),
            o('J', "shift along Y"),
        ],
    ),
    g(
        811,
        Some(0),
        AxisConsumer,
        "Chopping",
        "Oscillates the chopping axis between an upper and a lower dead point (grinding). Not \
         described in the seed.",
        &[
            o('Z', "upper dead point"),
            o('Q', "distance to the lower dead point"),
            o('R', "distance to point R"),
            o('F', "chopping feedrate"),
        ],
    ),
    g(
        911,
        Some(0),
        OneShot,
        "Maximum incremental amount check",
        "Checks that incremental commands do not exceed a set maximum amount. Not described in the \
         seed.",
        SET_AXES,
    ),
    g(
        920,
        Some(0),
        AxisConsumer,
        "Workpiece coordinate system setting / spindle clamp",
        "With axis words, defines the work coordinate system so that the current tool position has \
         the given coordinates (no motion). Its axis words are not polar under G16. (Also clamps the \
         maximum spindle speed with S when used that way.)",
        &[
            o('X', "coordinate of the current position in X"),
            o('Y', "coordinate in Y"),
            o('Z', "coordinate in Z"),
            o('A', "coordinate in A"),
            o('B', "coordinate in B"),
            o('C', "coordinate in C"),
            o('S', "maximum spindle speed clamp"),
        ],
    ),
    g(
        921,
        Some(0),
        AxisConsumer,
        "Workpiece coordinate system preset",
        "Resets a work coordinate system shifted by manual intervention or G92 back to its preset \
         position (IP0 for the axes to preset).",
        SET_AXES,
    ),
    g(
        1070,
        Some(0),
        AxisConsumer,
        "Cylindrical interpolation (alternative code)",
        "Same as G07.1: rotary axis word with the cylinder radius turns cylindrical interpolation on, \
         radius 0 turns it off.",
        &[o('C', "rotary axis: cylinder radius (0 = cancel)"), o('A', "rotary axis: cylinder radius"), o('B', "rotary axis: cylinder radius")],
    ),
    // Group 02.
    g(
        170,
        Some(2),
        Modal,
        "XpYp plane",
        "Selects the plane of X (or a parallel axis) and Y; drilling axis Z. Power-on default \
         unless parameters 3402#1/#2 choose G18/G19. Do not change planes during cutter compensation \
         (PS0037) or rotation (PS0144), nor while a canned cycle is active.",
        NONE,
    )
    .dflt(),
    g(
        180,
        Some(2),
        Modal,
        "ZpXp plane",
        "Selects the Z–X plane (arcs use K and I); drilling axis Y. Not during compensation, \
         rotation or an active canned cycle.",
        NONE,
    ),
    g(
        190,
        Some(2),
        Modal,
        "YpZp plane",
        "Selects the Y–Z plane (arcs use J and K); drilling axis X. Not during compensation, \
         rotation or an active canned cycle.",
        NONE,
    ),
    // Group 03.
    g(
        900,
        Some(3),
        Modal,
        "Absolute programming",
        "Axis words are positions in the work coordinate system; canned-cycle R and Z are absolute \
         levels. Power-on default unless parameter 3402#3 selects G91.",
        NONE,
    )
    .dflt(),
    g(
        910,
        Some(3),
        Modal,
        "Incremental programming",
        "Axis words are distances from the current position; canned-cycle R is measured from the \
         initial level and Z from point R. In G16 an incremental radius puts the polar origin at \
         the current position.",
        NONE,
    ),
    // Group 04.
    g(
        220,
        Some(4),
        Modal,
        "Stored stroke check on",
        "Enables the programmable stroke limit. Which of G22/G23 is on at power-up is chosen by \
         parameter 3402#7 (G22 normally); reset does not change it. Its axis words are not polar.",
        &[
            o('X', "limit X"),
            o('Y', "limit Y"),
            o('Z', "limit Z"),
            o('I', "second limit X"),
            o('J', "second limit Y"),
            o('K', "second limit Z"),
        ],
    )
    .dflt(),
    g(
        230,
        Some(4),
        Modal,
        "Stored stroke check off",
        "Disables the programmable stroke limit.",
        NONE,
    ),
    // Group 05.
    g(
        930,
        Some(5),
        Modal,
        "Inverse time feed",
        "F gives the reciprocal of the move time instead of a speed.",
        NONE,
    ),
    g(
        940,
        Some(5),
        Modal,
        "Feed per minute",
        "F is mm/min (or inch/min, deg/min). Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        950,
        Some(5),
        Modal,
        "Feed per revolution",
        "F is mm (or inch) per spindle revolution, so speed = F × S. In rigid tapping the lead is F.",
        NONE,
    ),
    // Group 06 (kept through reset; no fixed default).
    g(
        200,
        Some(6),
        Modal,
        "Inch input",
        "Input unit inches. Not changed by the clear state.",
        NONE,
    ),
    g(
        210,
        Some(6),
        Modal,
        "Metric input",
        "Input unit millimetres. Not changed by the clear state.",
        NONE,
    ),
    g(
        700,
        Some(6),
        Modal,
        "Inch input (alternative code)",
        "Alternative code for G20 on controls set up for it.",
        NONE,
    ),
    g(
        710,
        Some(6),
        Modal,
        "Metric input (alternative code)",
        "Alternative code for G21 on controls set up for it.",
        NONE,
    ),
    // Group 07.
    g(
        400,
        Some(7),
        Modal,
        "Cutter compensation cancel",
        "Cancels cutter (and 3-D cutter) radius compensation. Power-on default. Cancelling in a \
         G02/G03 block raises PS0034; not allowed in involute mode.",
        NONE,
    )
    .dflt(),
    g(
        410,
        Some(7),
        Modal,
        "Cutter compensation left",
        "Offsets the tool to the left of the path by the value of offset D (3-D comp with I/J/K). \
         Start-up in a G02/G03 block raises PS0034; no plane change while active (PS0037).",
        &[o('D', "cutter radius offset number")],
    ),
    g(
        420,
        Some(7),
        Modal,
        "Cutter compensation right",
        "Offsets the tool to the right of the path by offset D. Same restrictions as G41.",
        &[o('D', "cutter radius offset number")],
    ),
    g(412, Some(7), Modal, "5-axis cutter compensation left (type 1)", "Cutter compensation for 5-axis machining, tool on the left. Option; not described in the seed.", &[o('D', "offset number")]),
    g(413, Some(7), Modal, "5-axis leading-edge offset", "Leading-edge offset for 5-axis machining. Option; not described in the seed.", &[o('D', "offset number")]),
    g(414, Some(7), Modal, "5-axis cutter compensation (FS16i-compatible)", "FS16i-compatible 5-axis cutter compensation command. Option; not described in the seed.", &[o('D', "offset number")]),
    g(415, Some(7), Modal, "5-axis cutter compensation (FS16i-compatible)", "FS16i-compatible 5-axis cutter compensation command. Option; not described in the seed.", &[o('D', "offset number")]),
    g(416, Some(7), Modal, "5-axis cutter compensation left (type 2)", "Cutter compensation for 5-axis machining, tool on the left, type 2. Option; not described in the seed.", &[o('D', "offset number")]),
    g(422, Some(7), Modal, "5-axis cutter compensation right (type 1)", "Cutter compensation for 5-axis machining, tool on the right. Option; not described in the seed.", &[o('D', "offset number")]),
    g(424, Some(7), Modal, "5-axis cutter compensation right (FS16i-compatible)", "FS16i-compatible 5-axis cutter compensation command. Option; not described in the seed.", &[o('D', "offset number")]),
    g(425, Some(7), Modal, "5-axis cutter compensation right (FS16i-compatible)", "FS16i-compatible 5-axis cutter compensation command. Option; not described in the seed.", &[o('D', "offset number")]),
    g(426, Some(7), Modal, "5-axis cutter compensation right (type 2)", "Cutter compensation for 5-axis machining, tool on the right, type 2. Option; not described in the seed.", &[o('D', "offset number")]),
    // Group 08.
    g(
        430,
        Some(8),
        Modal,
        "Tool length compensation +",
        "Adds the value of offset H to the Z end positions. Given in a canned cycle, it takes effect \
         from the positioning to point R on.",
        &[o('H', "tool length offset number"), o('Z', "Z end point")],
    ),
    g(
        431,
        Some(8),
        Modal,
        "Tool length compensation in tool axis direction",
        "Applies the length offset along the tool axis as set by the rotary axes. Option.",
        &[o('H', "tool length offset number")],
    ),
    g(
        434,
        Some(8),
        Modal,
        "Tool centre point control type 1",
        "Keeps the programmed point at the tool tip while rotary axes move (type 1: rotary axes \
         programmed directly). Option; not described in the seed.",
        &[o('H', "tool length offset number")],
    ),
    g(
        435,
        Some(8),
        Modal,
        "Tool centre point control type 2",
        "Tool centre point control with the tool direction given by a vector (type 2). Option; not \
         described in the seed.",
        &[o('H', "tool length offset number")],
    ),
    g(
        440,
        Some(8),
        Modal,
        "Tool length compensation −",
        "Subtracts the value of offset H from the Z end positions.",
        &[o('H', "tool length offset number"), o('Z', "Z end point")],
    ),
    g(
        490,
        Some(8),
        Modal,
        "Tool length compensation cancel",
        "Cancels tool length compensation. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        491,
        Some(8),
        Modal,
        "Tool length compensation cancel (alternative code)",
        "Alternative code for G49.",
        NONE,
    ),
    // Group 09: canned cycles.
    g(
        730,
        Some(9),
        Motion,
        "High-speed peck drilling cycle",
        "Rapid to R, then feeds down by Q per peck, backing off by d (No. 5114) after each, until Z; \
         rapid return to the initial level (G98) or R (G99). Q must be positive (PS0045 if missing or \
         0); Q is shared with G76/G87 as the shift amount.",
        PECK73,
    ),
    g(
        740,
        Some(9),
        Motion,
        "Left-handed tapping cycle",
        "Spindle counter-clockwise (M04 first): feed R → Z, dwell P, spindle clockwise, feed back to \
         R. Override is ignored and feed hold waits for the return. Rigid after M29 S… (or parameter \
         No. 5200#0).",
        TAP,
    ),
    g(
        760,
        Some(9),
        Motion,
        "Fine boring cycle",
        "Feed to Z, dwell P, oriented spindle stop, shift Q away from the tool nose (direction No. \
         5148), rapid out, shift back, spindle on. A negative Q is taken as positive.",
        SHIFT,
    ),
    g(
        800,
        Some(9),
        Modal,
        "Canned cycle cancel",
        "Cancels every drilling cycle and clears point R, point Z and all other drilling data; also \
         ends rigid tapping (S is cleared to 0). Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        810,
        Some(9),
        Motion,
        "Drilling / spot drilling cycle",
        "Rapid to R, feed to Z, rapid return (G98 initial level, G99 point R). Give all drilling \
         data in the first block; a block with no axis or R word does not drill.",
        DRILL,
    ),
    g(
        820,
        Some(9),
        Motion,
        "Drilling / counter boring cycle",
        "As G81 with a dwell of P ms at the bottom.",
        DRILL_DWELL,
    ),
    g(
        830,
        Some(9),
        Motion,
        "Peck drilling cycle",
        "Feeds Q, rapids back to R, rapids down to d (No. 5115) above the previous bottom and feeds \
         Q + d, until Z. Q must be positive. After the small-hole M code (No. 5163) it runs as the \
         small-hole peck cycle with I (advance/retract speed) and P (dwell).",
        PECK83,
    ),
    g(
        840,
        Some(9),
        Motion,
        "Tapping cycle",
        "Spindle clockwise (M03 first): feed to Z, dwell P, spindle reverses, feed back to R. \
         Override ignored. Rigid tapping after M29 S…: lead = F/S in G94 or F in G95, dwell also \
         at R; with Q it pecks.",
        TAP,
    ),
    g(
        842,
        Some(9),
        Motion,
        "Rigid tapping (FS15 format)",
        "Rigid tapping written in the FS15 format; L is the repeat count.",
        TAP15,
    ),
    g(
        843,
        Some(9),
        Motion,
        "Left-handed rigid tapping (FS15 format)",
        "Left-handed rigid tapping in the FS15 format; L is the repeat count.",
        TAP15,
    ),
    g(
        850,
        Some(9),
        Motion,
        "Boring cycle",
        "Feed to Z and feed back up to R; rapid to the initial level under G98.",
        DRILL,
    ),
    g(
        860,
        Some(9),
        Motion,
        "Boring cycle, spindle stop",
        "Feed to Z, stop the spindle, rapid return, spindle restarts.",
        DRILL,
    ),
    g(
        870,
        Some(9),
        Motion,
        "Back boring cycle",
        "Oriented stop and shift Q, rapid to point R below the hole, shift back and start the \
         spindle, feed upward to Z, dwell P, oriented stop, shift and rapid to the initial level. \
         Always returns to the initial level (G99 is not used).",
        SHIFT,
    ),
    g(
        880,
        Some(9),
        Motion,
        "Boring cycle, manual retract",
        "Feed to Z, dwell P, spindle stop and hold for manual operation; after cycle start the tool \
         returns and the spindle restarts. Cycle time includes operator time.",
        DRILL_DWELL,
    ),
    g(
        890,
        Some(9),
        Motion,
        "Boring cycle with dwell",
        "As G85 with a dwell of P ms at the bottom: feed to Z, dwell, feed back to R.",
        DRILL_DWELL,
    ),
    // Group 10.
    g(
        980,
        Some(10),
        Modal,
        "Canned cycle return to initial level",
        "After each hole the tool returns to the initial level. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        990,
        Some(10),
        Modal,
        "Canned cycle return to R level",
        "After each hole the tool returns to point R; the initial level is kept. G87 ignores it.",
        NONE,
    ),
    // Group 11.
    g(
        500,
        Some(11),
        Modal,
        "Scaling cancel",
        "Cancels scaling. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        510,
        Some(11),
        Modal,
        "Scaling",
        "Scales later coordinates about the centre X/Y/Z by P (all axes) or I/J/K (per axis). A \
         magnification of 0 or 10000 and above raises PS0142. Its axis words are not polar.",
        &[
            o('X', "scaling centre X"),
            o('Y', "scaling centre Y"),
            o('Z', "scaling centre Z"),
            o('P', "magnification for all axes"),
            o('I', "magnification X"),
            o('J', "magnification Y"),
            o('K', "magnification Z"),
        ],
    ),
    // Group 12.
    g(
        660,
        Some(12),
        Modal,
        "Macro modal call A",
        "Registers macro O<P>: it is called with the registered arguments after every later block \
         that moves an axis, until G67. Arguments are only taken from the G66 block.",
        &[r('P', "program number of the macro"), o('L', "repeat count (default 1)")],
    ),
    g(
        661,
        Some(12),
        Modal,
        "Macro modal call B",
        "Every following block calls macro O<P>, its own words becoming the arguments (G allowed), \
         until G67.",
        &[r('P', "program number of the macro"), o('L', "repeat count (default 1)")],
    ),
    g(
        670,
        Some(12),
        Modal,
        "Macro modal call cancel",
        "Cancels G66/G66.1. Power-on default.",
        NONE,
    )
    .dflt(),
    // Group 13.
    g(
        960,
        Some(13),
        Modal,
        "Constant surface speed control",
        "S is a surface speed and the spindle rpm follows the tool position.",
        &[o('S', "surface speed")],
    ),
    g(
        970,
        Some(13),
        Modal,
        "Constant surface speed cancel",
        "S is a spindle speed in min⁻¹. Power-on default.",
        NONE,
    )
    .dflt(),
    // Group 14.
    g(
        540,
        Some(14),
        Modal,
        "Workpiece coordinate system 1",
        "Selects work coordinate system 1. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        541,
        Some(14),
        Modal,
        "Additional workpiece coordinate system",
        "G54.1 Pn selects additional work coordinate system n (count depends on the option).",
        &[r('P', "additional system number")],
    ),
    g(550, Some(14), Modal, "Workpiece coordinate system 2", "Selects work coordinate system 2.", NONE),
    g(560, Some(14), Modal, "Workpiece coordinate system 3", "Selects work coordinate system 3.", NONE),
    g(570, Some(14), Modal, "Workpiece coordinate system 4", "Selects work coordinate system 4.", NONE),
    g(580, Some(14), Modal, "Workpiece coordinate system 5", "Selects work coordinate system 5.", NONE),
    g(590, Some(14), Modal, "Workpiece coordinate system 6", "Selects work coordinate system 6.", NONE),
    // Group 15.
    g(
        610,
        Some(15),
        Modal,
        "Exact stop mode",
        "Every cutting block ends with a stop and an in-position check.",
        NONE,
    ),
    g(
        620,
        Some(15),
        Modal,
        "Automatic corner override",
        "Lowers the feed at inner corners during cutter compensation.",
        NONE,
    ),
    g(
        630,
        Some(15),
        Modal,
        "Tapping mode",
        "Feed override fixed at 100% and no in-position check at block ends.",
        NONE,
    ),
    g(
        640,
        Some(15),
        Modal,
        "Cutting mode",
        "Consecutive cutting blocks blend without stopping; corners are rounded by acceleration. \
         Power-on default.",
        NONE,
    )
    .dflt(),
    // Group 16.
    g(
        680,
        Some(16),
        Modal,
        "Coordinate system rotation / 3-D conversion",
        "Rotates later coordinates in the active plane by R degrees about the given centre (R \
         omitted: parameter 5410; absolute/incremental angle by 5400#0). The plane cannot change \
         while it is on (PS0144). Its axis words are not polar.",
        &[
            o('X', "centre of rotation X"),
            o('Y', "centre of rotation Y"),
            o('Z', "centre of rotation Z"),
            o('R', "rotation angle in degrees"),
            o('I', "3-D conversion axis vector X"),
            o('J', "3-D conversion axis vector Y"),
            o('K', "3-D conversion axis vector Z"),
        ],
    ),
    g(
        682,
        Some(16),
        Modal,
        "Feature coordinate system selection",
        "Defines a tilted working plane (feature coordinate system). Option; not described in the \
         seed.",
        &[
            o('X', "origin X"),
            o('Y', "origin Y"),
            o('Z', "origin Z"),
            o('I', "first Euler angle"),
            o('J', "second Euler angle"),
            o('K', "third Euler angle"),
        ],
    ),
    g(
        690,
        Some(16),
        Modal,
        "Rotation / 3-D conversion cancel",
        "Cancels G68/G68.2. Power-on default; may share a block with other commands.",
        NONE,
    )
    .dflt(),
    // Group 17.
    g(
        150,
        Some(17),
        Modal,
        "Polar coordinate command cancel",
        "Axis words are Cartesian again. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        160,
        Some(17),
        Modal,
        "Polar coordinate command",
        "The first plane axis word is a radius and the second an angle in degrees (CCW positive). \
         G90 radius: origin at the work (or local) zero; G91 radius: origin at the current position. \
         Arcs need R, and G04, G10, G52, G53, G92, G22, G68, G51 keep Cartesian words.",
        NONE,
    ),
    // Group 19.
    g(
        401,
        Some(19),
        Modal,
        "Normal direction control cancel",
        "Ends normal direction control. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        411,
        Some(19),
        Modal,
        "Normal direction control left",
        "Keeps the rotary axis perpendicular to the direction of travel, tool on the left.",
        NONE,
    ),
    g(
        421,
        Some(19),
        Modal,
        "Normal direction control right",
        "Keeps the rotary axis perpendicular to the direction of travel, tool on the right.",
        NONE,
    ),
    // G25/G26: printed as group 19; kept as a separate state (see module docs).
    g(
        250,
        Some(G25_GROUP),
        Modal,
        "Spindle speed fluctuation detection off",
        "Turns off the alarm on spindle speed deviation. Power-on default. The manual prints group \
         19 (the same as normal direction control); the two are treated as independent states.",
        NONE,
    )
    .dflt(),
    g(
        260,
        Some(G25_GROUP),
        Modal,
        "Spindle speed fluctuation detection on",
        "Raises an alarm when the actual spindle speed departs from the commanded one. The manual \
         prints group 19; treated independently of G40.1–G42.1.",
        &[
            o('P', "time before checking starts"),
            o('Q', "tolerance ratio"),
            o('R', "fluctuation ratio"),
            o('I', "fluctuation width"),
        ],
    ),
    // Group 21.
    g(
        121,
        Some(21),
        Modal,
        "Polar coordinate interpolation mode",
        "Converts X/C-type commands into linear-axis and rotary-axis motion (e.g. milling on a \
         turned part); involute on a linear and a rotary axis runs in this mode. G112 is the same \
         code.",
        NONE,
    ),
    g(
        131,
        Some(21),
        Modal,
        "Polar coordinate interpolation cancel",
        "Ends polar coordinate interpolation. Power-on default; G113 is the same code.",
        NONE,
    )
    .dflt(),
    g(
        1120,
        Some(21),
        Modal,
        "Polar coordinate interpolation mode (alternative code)",
        "Same as G12.1.",
        NONE,
    ),
    g(
        1130,
        Some(21),
        Modal,
        "Polar coordinate interpolation cancel (alternative code)",
        "Same as G13.1.",
        NONE,
    ),
    // Group 22.
    g(
        501,
        Some(22),
        Modal,
        "Programmable mirror image cancel",
        "Cancels mirroring for the axes named. Power-on default.",
        &[o('X', "axis to un-mirror"), o('Y', "axis to un-mirror"), o('Z', "axis to un-mirror")],
    )
    .dflt(),
    g(
        511,
        Some(22),
        Modal,
        "Programmable mirror image",
        "Mirrors the named axes about the given positions; mirroring one plane axis reverses arc \
         and compensation directions.",
        &[o('X', "mirror position X"), o('Y', "mirror position Y"), o('Z', "mirror position Z")],
    ),
    // Group 24.
    g(
        805,
        Some(24),
        Modal,
        "EGB 2-pair synchronisation cancel",
        "Ends electronic gear box synchronisation (2-pair). Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        815,
        Some(24),
        Modal,
        "EGB 2-pair synchronisation start",
        "Starts electronic gear box synchronisation (2-pair). Option; not described in the seed.",
        NONE,
    ),
    // Group 31.
    g(
        502,
        Some(31),
        Modal,
        "Polygon turning cancel",
        "Ends polygon turning. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        512,
        Some(31),
        Modal,
        "Polygon turning",
        "Synchronises a tool rotary axis with the spindle at a set ratio to cut polygons. Option.",
        &[o('P', "spindle ratio"), o('Q', "tool axis ratio")],
    ),
    // Group 34.
    g(
        808,
        Some(34),
        Modal,
        "EGB synchronisation cancel",
        "Ends electronic gear box synchronisation. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        818,
        Some(34),
        Modal,
        "EGB synchronisation start",
        "Starts electronic gear box synchronisation. Option; not described in the seed.",
        NONE,
    ),
    // M codes (no modal groups on this control; most are carried out by the machine's PMC).
    m(
        0,
        "Program stop",
        "Stops the program; cycle start continues with the next block.",
        NONE,
    ),
    m(
        1,
        "Optional stop",
        "Stops like M00 only when the optional-stop switch is on.",
        NONE,
    ),
    m(
        2,
        "End of program",
        "Ends the main program. A program should end with M02, M30 or M99 before the closing %.",
        NONE,
    ),
    m(
        3,
        "Spindle clockwise",
        "Starts the spindle clockwise; needed before G84 and most other cycles.",
        NONE,
    ),
    m(
        4,
        "Spindle counter-clockwise",
        "Starts the spindle counter-clockwise; needed before G74.",
        NONE,
    ),
    m(5, "Spindle stop", "Stops the spindle.", NONE),
    m(
        6,
        "Tool change",
        "Changes to the tool selected by T (machine-builder function; used in the seed's example \
         program).",
        NONE,
    ),
    m(
        29,
        "Rigid tapping mode",
        "Given as M29 S… before or in the G84/G74 block, it makes the next tapping cycle rigid. An S \
         or axis move between M29 and the tap raises PS0203; M29 inside the cycle raises PS0204. The \
         M code number is a parameter (29 by default).",
        &[o('S', "spindle speed for tapping")],
    ),
    m(
        30,
        "End of program and rewind",
        "Ends the main program and returns to its start.",
        NONE,
    ),
    m(
        98,
        "Subprogram call",
        "Calls subprogram O<P> L times; without L the digits beyond the last four of P are the \
         repeat count (P50010 = O0010 five times, max 9999). The subprogram shares the caller's \
         local variables. In canned-cycle mode it must be in its own block. Program not found: \
         PS0076.",
        &[r('P', "program number (optionally preceded by the repeat count)"), o('L', "repeat count")],
    ),
    m(
        99,
        "Subprogram end / return",
        "Returns to the block after the call; with P to sequence number P of the caller. In a main \
         program it jumps back to the start (endless unless block delete is used).",
        &[o('P', "sequence number to return to")],
    ),
    m(
        198,
        "External subprogram call",
        "Calls a subprogram stored on an external device or memory card.",
        &[r('P', "program or file number"), o('L', "repeat count")],
    ),
];

/// Meanings of the FANUC address letters (M system).
pub static ADDRESSES: &[AddressInfo] = &[
    AddressInfo {
        letter: 'A',
        doc: "A-axis coordinate (rotary, degrees)",
    },
    AddressInfo {
        letter: 'B',
        doc: "B-axis coordinate",
    },
    AddressInfo {
        letter: 'C',
        doc: "C-axis coordinate",
    },
    AddressInfo {
        letter: 'D',
        doc: "cutter radius offset number (0–999, integer)",
    },
    AddressInfo {
        letter: 'F',
        doc: "feedrate (G94 mm/min, G95 mm/rev); thread lead for G33; without a decimal point \
              in the least input increment",
    },
    AddressInfo {
        letter: 'H',
        doc: "tool length offset number (0–999, integer)",
    },
    AddressInfo {
        letter: 'I',
        doc: "arc centre offset along X from the start; involute base-circle centre; G76/G87 \
              shift (option); G65 argument (specification II)",
    },
    AddressInfo {
        letter: 'J',
        doc: "arc centre offset along Y from the start; involute base-circle centre; G65 argument",
    },
    AddressInfo {
        letter: 'K',
        doc: "arc centre offset along Z from the start; canned-cycle repeat count (0–9999, this \
              block only)",
    },
    AddressInfo {
        letter: 'L',
        doc: "repeat count for M98/G65; G10 data kind; G84.2 repeats (integer)",
    },
    AddressInfo {
        letter: 'N',
        doc: "sequence number 1–99999 (target of GOTO and M99 P)",
    },
    AddressInfo {
        letter: 'O',
        doc: "program number 1–9999",
    },
    AddressInfo {
        letter: 'P',
        doc: "dwell in ms (integer); program number for M98/G65/G66; sequence number for M99; \
              G10 and parameter numbers",
    },
    AddressInfo {
        letter: 'Q',
        doc: "peck depth (G73/G83, rigid peck tapping) or shift amount (G76/G87); one modal Q is \
              shared by all cycles",
    },
    AddressInfo {
        letter: 'R',
        doc: "arc radius; involute base-circle radius; canned-cycle point R; G68 rotation angle",
    },
    AddressInfo {
        letter: 'S',
        doc: "spindle speed in min⁻¹ (0–99999, integer)",
    },
    AddressInfo {
        letter: 'T',
        doc: "tool number (up to 8 digits)",
    },
    AddressInfo {
        letter: 'U',
        doc: "U-axis coordinate (axis parallel to X)",
    },
    AddressInfo {
        letter: 'V',
        doc: "V-axis coordinate (axis parallel to Y)",
    },
    AddressInfo {
        letter: 'W',
        doc: "W-axis coordinate (axis parallel to Z)",
    },
    AddressInfo {
        letter: 'X',
        doc: "X coordinate; G04 dwell in seconds",
    },
    AddressInfo {
        letter: 'Y',
        doc: "Y coordinate",
    },
    AddressInfo {
        letter: 'Z',
        doc: "Z coordinate; canned-cycle point Z (hole bottom)",
    },
    AddressInfo {
        letter: ',',
        doc: "',C' optional chamfer or ',R' corner rounding at the end of the block",
    },
    AddressInfo {
        letter: '#',
        doc: "macro variable: #0 vacant, #1–#33 local, #100–#199 and #500–#999 common, #1000+ \
              system",
    },
];

/// FANUC G65/G66 Argument Specification I: the local variable a letter sets
/// (`X` → #24). I, J and K give their first set (#4–#6); the interpreter reads
/// later sets by Argument Specification II.
pub fn macro_argument_variable(letter: u8) -> Option<u32> {
    Some(match letter {
        b'A' => 1,
        b'B' => 2,
        b'C' => 3,
        b'I' => 4,
        b'J' => 5,
        b'K' => 6,
        b'D' => 7,
        b'E' => 8,
        b'F' => 9,
        b'H' => 11,
        b'M' => 13,
        b'Q' => 17,
        b'R' => 18,
        b'S' => 19,
        b'T' => 20,
        b'U' => 21,
        b'V' => 22,
        b'W' => 23,
        b'X' => 24,
        b'Y' => 25,
        b'Z' => 26,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::super::{
        assert_all_present, check_table_invariants, codes_in_group, default_codes, lookup,
        lookup_address, Dialect, Variant,
    };
    use super::*;

    const D: Dialect = Dialect::Fanuc;

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
    fn every_code_of_table_2a_is_present() {
        // Digest §2.3 rows (alternative codes in parentheses included) and §4.7/§4.8/§3.5 M codes.
        assert_all_present(
            D,
            &[
                "G0", "G1", "G2", "G3", "G2.2", "G3.2", "G2.3", "G3.3", "G2.4", "G3.4", "G4", "G5",
                "G5.1", "G5.4", "G6.2", "G7", "G7.1", "G107", "G8", "G9", "G10", "G10.6", "G10.9",
                "G11", "G12.1", "G13.1", "G15", "G16", "G17", "G18", "G19", "G20", "G70", "G21",
                "G71", "G22", "G23", "G25", "G26", "G27", "G28", "G29", "G30", "G30.1", "G31",
                "G31.8", "G33", "G34", "G35", "G36", "G37", "G38", "G39", "G40", "G41", "G42",
                "G41.2", "G41.3", "G41.4", "G41.5", "G41.6", "G42.2", "G42.4", "G42.5", "G42.6",
                "G40.1", "G41.1", "G42.1", "G43", "G44", "G43.1", "G43.4", "G43.5", "G45", "G46",
                "G47", "G48", "G49", "G49.1", "G50", "G51", "G50.1", "G51.1", "G50.2", "G51.2",
                "G52", "G53", "G53.1", "G54", "G54.1", "G55", "G56", "G57", "G58", "G59", "G60",
                "G61", "G62", "G63", "G64", "G65", "G66", "G66.1", "G67", "G68", "G69", "G68.2",
                "G72.1", "G72.2", "G73", "G74", "G76", "G80", "G80.5", "G81.5", "G80.8", "G81.8",
                "G81", "G81.1", "G82", "G83", "G84", "G84.2", "G84.3", "G85", "G86", "G87", "G88",
                "G89", "G90", "G91", "G91.1", "G92", "G92.1", "G93", "G94", "G95", "G96", "G97",
                "G98", "G99", "G112", "G113", "M0", "M1", "M2", "M3", "M4", "M5", "M6", "M29",
                "M30", "M98", "M99", "M198",
            ],
        );
    }

    #[test]
    fn groups_and_defaults() {
        let g00 = get('G', 0);
        assert_eq!(g00.group, Some(1));
        assert!(g00.default);
        assert_eq!(get('G', 150).group, Some(17));
        assert_eq!(get('G', 160).group, Some(17));
        assert!(get('G', 150).default);
        assert_eq!(get('G', 650).group, Some(0));
        assert_eq!(get('G', 661).group, Some(12));
        assert_eq!(get('G', 121).group, Some(21));
        assert_eq!(get('G', 502).group, Some(31));
        assert_eq!(get('G', 818).group, Some(34));
        assert_eq!(get('G', 842).group, Some(9));
        assert_eq!(get('G', 411).group, Some(19));
        assert_eq!(get('G', 260).group, Some(G25_GROUP));
        assert_ne!(G25_GROUP, 19);
        assert_eq!(names(codes_in_group(D, 17)), ["G15", "G16"]);
        assert_eq!(
            names(default_codes(D)),
            [
                "G0", "G17", "G90", "G22", "G94", "G40", "G49", "G80", "G98", "G50", "G67", "G97",
                "G54", "G64", "G69", "G15", "G40.1", "G25", "G13.1", "G50.1", "G80.5", "G50.2",
                "G80.8"
            ]
        );
        // Units are kept through reset: no default in group 06.
        assert!(codes_in_group(D, 6).all(|c| !c.default));
        assert!(get('M', 980).group.is_none());
    }

    #[test]
    fn kinds_params_variants() {
        assert!(CODES.iter().all(|c| c.on_variant(Variant::Fanuc30i)));
        assert_eq!(get('G', 810).kind, CodeKind::Motion);
        assert_eq!(get('G', 22).kind, CodeKind::Motion);
        assert_eq!(get('G', 280).kind, CodeKind::AxisConsumer);
        assert_eq!(get('G', 920).kind, CodeKind::AxisConsumer);
        assert_eq!(get('G', 90).kind, CodeKind::OneShot);
        assert_eq!(get('G', 800).kind, CodeKind::Modal);
        assert!(get('G', 650).param('P').is_some_and(|p| p.required));
        assert!(get('M', 980).param('P').is_some_and(|p| p.required));
        assert!(get('G', 22).param('R').is_some_and(|p| p.required));
        let g04 = get('G', 40);
        assert!(g04.params.iter().all(|p| !p.required));
        assert!(get('G', 730).param('Q').is_some());
        assert!(get('G', 810).param('Q').is_none());
    }

    #[test]
    fn addresses() {
        assert!(lookup_address(D, 'k').is_some_and(|a| a.doc.contains("9999")));
        assert!(lookup_address(D, ',').is_some());
        assert!(lookup_address(D, 'E').is_none());
    }
}
