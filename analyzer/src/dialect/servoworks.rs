//! The ServoWorks (S-100M / S-120M / S-140M) code and address tables, from the
//! servoworks spec digest (§2 addresses, §3.1/§3.2 G codes, §4 cycles, §8.1 M codes).
//!
//! Group numbers are the manual's (00 = non-modal). Where the manual names no
//! power-on default the digest's recommendation is used (G49, G80, G54, G69).

use super::{variants, AddressInfo, CodeInfo, CodeKind, CodeNum, Param};

use CodeKind::{AxisConsumer, Misc, Modal, Motion, OneShot};

const ALL: u8 = variants::ALL_SW;

const fn g(
    tenths: u32,
    group: Option<u8>,
    kind: CodeKind,
    summary: &'static str,
    doc: &'static str,
    params: &'static [Param],
) -> CodeInfo {
    CodeInfo::new('G', CodeNum(tenths), group, kind, ALL, summary, doc, params)
}

const fn m(n: u32, summary: &'static str, doc: &'static str, params: &'static [Param]) -> CodeInfo {
    CodeInfo::new(
        'M',
        CodeNum::whole(n),
        None,
        Misc,
        ALL,
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

/// End-point words of a positioning or linear move.
const MOVE_AXES: &[Param] = &[
    o('X', "X end point (absolute or incremental per G90/G91)"),
    o('Y', "Y end point"),
    o('Z', "Z end point"),
    o('A', "A-axis end point (degrees when rotary)"),
    o('B', "B-axis end point"),
    o('C', "C-axis end point"),
];

const FEED_AXES: &[Param] = &[
    o('X', "X end point (absolute or incremental per G90/G91)"),
    o('Y', "Y end point"),
    o('Z', "Z end point"),
    o('A', "A-axis end point (degrees when rotary)"),
    o('B', "B-axis end point"),
    o('C', "C-axis end point"),
    o(
        'F',
        "feedrate, modal (G94: mm/min or in/min; G95: per spindle revolution)",
    ),
];

const ARC: &[Param] = &[
    o(
        'X',
        "end point X (plane axis under G17/G18; extra helical axis under G19)",
    ),
    o(
        'Y',
        "end point Y (plane axis under G17/G19; extra helical axis under G18)",
    ),
    o(
        'Z',
        "end point Z (plane axis under G18/G19; extra helical axis under G17)",
    ),
    o('A', "extra axis moved linearly with the arc (helical)"),
    o(
        'I',
        "centre offset along X, incremental from the start point (G17/G18)",
    ),
    o(
        'J',
        "centre offset along Y, incremental from the start point (G17/G19)",
    ),
    o(
        'K',
        "centre offset along Z, incremental from the start point (G18/G19)",
    ),
    o(
        'R',
        "radius instead of I/J/K; positive = arc up to 180°, negative = 180° or more",
    ),
    o('F', "feedrate along the arc in the plane (modal)"),
    o(
        'Q',
        "allowed contour error (mm/inch); the feed is reduced to stay within it",
    ),
];

const EXPO: &[Param] = &[
    o('X', "end point of the linear axis"),
    o('Y', "end point Y"),
    o('Z', "end point Z"),
    o(
        'I',
        "taper angle, 0–89° (Table 2-1 swaps I and J; §6.3.5 is followed)",
    ),
    o('J', "helix angle, 0–89°"),
    o('R', "exponential constant"),
    o('F', "feedrate at the start (includes the rotary component)"),
    o(
        'Q',
        "feedrate at the end point (includes the rotary component)",
    ),
];

const REF_AXES: &[Param] = &[
    o('X', "intermediate point X (absolute or incremental)"),
    o('Y', "intermediate point Y"),
    o('Z', "intermediate point Z"),
    o('A', "intermediate point A"),
    o('B', "intermediate point B"),
    o('C', "intermediate point C"),
];

const CYCLE_XY: [Param; 2] = [
    o('X', "hole position X (absolute or incremental)"),
    o('Y', "hole position Y (absolute or incremental)"),
];
const CYCLE_Z: Param = o(
    'Z',
    "hole bottom (G90: absolute; G91: distance from the R level); needed unless already in effect",
);
const CYCLE_R: Param = o(
    'R',
    "R level (G90: absolute; G91: distance from the initial level); modal",
);
const CYCLE_F: Param = o('F', "cutting feedrate");
const CYCLE_K: Param = o('K', "number of repetitions (integer, default 1)");
const CYCLE_P: Param = o('P', "dwell at the hole bottom in ms (integer)");

const G73_P: &[Param] = &[
    CYCLE_XY[0],
    CYCLE_XY[1],
    CYCLE_Z,
    CYCLE_R,
    o(
        'Q',
        "depth of each peck, incremental and positive (negative Q is ignored)",
    ),
    CYCLE_F,
    CYCLE_K,
];
const G83_P: &[Param] = G73_P;
const TAP_P: &[Param] = &[
    CYCLE_XY[0],
    CYCLE_XY[1],
    CYCLE_Z,
    CYCLE_R,
    CYCLE_P,
    CYCLE_F,
    CYCLE_K,
];
const SHIFT_P: &[Param] = &[
    CYCLE_XY[0],
    CYCLE_XY[1],
    CYCLE_Z,
    CYCLE_R,
    o(
        'Q',
        "tool shift after the oriented stop (sign ignored); shares the modal Q with G73/G83",
    ),
    CYCLE_P,
    CYCLE_F,
    CYCLE_K,
];
const DRILL_P: &[Param] = &[CYCLE_XY[0], CYCLE_XY[1], CYCLE_Z, CYCLE_R, CYCLE_F, CYCLE_K];
const DWELL_P: &[Param] = TAP_P;

const TLC_P: &[Param] = &[
    o(
        'H',
        "tool length offset number (1 = tool 1); H0 cancels on the compensated axis",
    ),
    o(
        'Z',
        "compensated axis (type A/B); with a value the axis also moves there",
    ),
    o(
        'Y',
        "compensated axis under G18 (type B) or any axis (type C)",
    ),
    o(
        'X',
        "compensated axis under G19 (type B) or any axis (type C)",
    ),
    o('A', "compensated axis (type C only)"),
    o('B', "compensated axis (type C only)"),
    o('C', "compensated axis (type C only)"),
];

const TRC_P: &[Param] = &[
    o(
        'D',
        "integer: tool offset number; with a decimal point: nominal tool diameter",
    ),
    o('H', "offset number shown in the manual's format"),
];

const G51_P: &[Param] = &[
    o(
        'X',
        "scaling centre X, absolute (omitted: current position)",
    ),
    o('Y', "scaling centre Y, absolute"),
    o('Z', "scaling centre Z, absolute"),
    o(
        'P',
        "one factor for all axes, 0.001–999.999 (not with I/J/K)",
    ),
    o('I', "X factor, 0.001–999.999 (not with P)"),
    o('J', "Y factor, 0.001–999.999 (not with P)"),
    o('K', "Z factor, 0.001–999.999 (not with P)"),
];

/// Every G and M code of ServoWorks.
pub static CODES: &[CodeInfo] = &[
    // Group 01: interpolation.
    g(
        0,
        Some(1),
        Motion,
        "Rapid positioning",
        "Moves each named axis at its own rapid feedrate; do not cut with it. With the \
         'G00 Perform Linear Interpolation' parameter the path is a straight line at the fastest \
         speed no axis exceeds, otherwise the axes run independently (dog-leg). Acceleration uses \
         the smoothing time; G10 L106 selects the smoothing mode. Power-on default of group 01.",
        MOVE_AXES,
    )
    .dflt(),
    g(
        1,
        Some(1),
        Motion,
        "Rapid positioning, acceleration-limited (undocumented)",
        "Not in the manual's G-code tables: it is only described by a stray paragraph in the G01 \
         section and listed among group-01 codes for canned cycles. Behaves like G00 but \
         accelerates with the maximum acceleration/deceleration rate instead of the smoothing time.",
        MOVE_AXES,
    ),
    g(
        10,
        Some(1),
        Motion,
        "Linear interpolation at feedrate F",
        "Moves all named axes together along a straight line at path speed F (per minute under \
         G94, per revolution under G95). Rotary axes are included in the feed calculation under \
         G310 and excluded under G311. A feedrate must be in effect.",
        FEED_AXES,
    ),
    g(
        20,
        Some(1),
        Motion,
        "Clockwise circular or helical interpolation",
        "Arc in the active plane (G17 XY, G18 ZX, G19 YZ) to the end point, with the centre given \
         incrementally by I/J/K or by radius R, never both. One or two extra axes make a helix; F \
         is then the speed along the arc projected into the plane. R cannot make a full circle \
         (use I/J/K with no end point). Q caps the contour error by lowering the feed.",
        ARC,
    ),
    g(
        30,
        Some(1),
        Motion,
        "Counter-clockwise circular or helical interpolation",
        "As G02 but counter-clockwise: plane from G17/G18/G19, centre by I/J/K or R (not both), \
         optional extra axes for a helix with F measured on the projected arc. Full circles need \
         I/J/K; Q limits the contour error through the feedrate.",
        ARC,
    ),
    g(
        23,
        Some(1),
        Motion,
        "Exponential interpolation, positive rotation (S-120M/S-140M)",
        "Turns the rotary A axis exponentially with the travel of the linear X axis, for tapered \
         grooves with a constant helix angle. I is the taper angle and J the helix angle (0–89°), \
         R the exponential constant; the feed changes linearly from F at the start to Q at the end. \
         Not available on S-100M.",
        EXPO,
    )
    .only(variants::S120M | variants::S140M),
    g(
        33,
        Some(1),
        Motion,
        "Exponential interpolation, negative rotation (S-120M/S-140M)",
        "As G02.3 with the rotary axis turning in the negative direction. I = taper angle, J = helix \
         angle (0–89°), R = exponential constant, F = start feed, Q = end feed. Not available on \
         S-100M.",
        EXPO,
    )
    .only(variants::S120M | variants::S140M),
    // Group 00: one-shot codes.
    g(
        40,
        Some(0),
        OneShot,
        "Dwell",
        "Waits before the next block. P is milliseconds written WITHOUT a decimal point (P5000 = \
         5 s); X is seconds written WITH a decimal point (X3.0 = 3 s). A bare G04 just waits for the \
         previous move to finish (exact stop). The manual's text saying 'minutes' is wrong.",
        &[
            o('P', "dwell in milliseconds, integer"),
            o('X', "dwell in seconds, with a decimal point"),
        ],
    ),
    g(
        50,
        Some(0),
        OneShot,
        "3D Dynamic Look-Ahead Contour Control on/off",
        "G05 P10000 turns look-ahead (acceleration planned along the path) on, G05 P0 turns it off; \
         any other form is ignored. While it is on only a limited set of G codes may be used (no \
         G10, G31, G37, compensation, rotation, canned cycles, G94/G95, G98/G99), and it cannot be \
         combined with TCP (G43.2). The state persists although the code is in group 00.",
        &[o('P', "10000 = on, 0 = off")],
    ),
    g(
        80,
        Some(0),
        OneShot,
        "3D Dynamic Look-Ahead Contour Control on/off",
        "G08 P1 turns look-ahead on, G08 P0 turns it off; other forms are ignored. Same \
         restrictions as G05: while on, only the whitelisted G codes are allowed and TCP (G43.2) \
         cannot be used.",
        &[o('P', "1 = on, 0 = off")],
    ),
    g(
        100,
        Some(0),
        AxisConsumer,
        "Programmable data input",
        "Writes a setting selected by L: L2 work offsets, L10 tool length, L11 tool radius, L20 \
         axis type, L30 in-position width, L106/L107 smoothing mode for rapid/cutting, L108 \
         smoothing time (ms), L10909 position-loop gain (Hz). Either P (axis or index) with R \
         (value), or X/Y/Z values per axis. Put a G04 before L106/L107/L108. Not allowed under \
         look-ahead.",
        &[
            r('L', "data category (2, 10, 11, 20, 30, 106, 107, 108, 10909)"),
            o('P', "axis number or data index"),
            o('R', "value to write"),
            o('X', "value for the X axis"),
            o('Y', "value for the Y axis"),
            o('Z', "value for the Z axis"),
        ],
    ),
    g(
        280,
        Some(0),
        AxisConsumer,
        "Return to reference point",
        "Moves through the intermediate point given by the axis words (absolute or incremental) to \
         reference point 1; the intermediate point is remembered for G29. Must not be used while \
         rotation (G68) is on.",
        REF_AXES,
    ),
    g(
        290,
        Some(0),
        AxisConsumer,
        "Return from reference point",
        "Moves from the reference point through the intermediate point stored by the last G28/G30 \
         to the destination given by the axis words. Needs an earlier G28 or G30; not allowed \
         while G68 is on.",
        &[
            o('X', "destination X"),
            o('Y', "destination Y"),
            o('Z', "destination Z"),
            o('A', "destination A"),
            o('B', "destination B"),
            o('C', "destination C"),
        ],
    ),
    g(
        300,
        Some(0),
        AxisConsumer,
        "Return to 2nd/3rd/4th reference point",
        "Moves through the intermediate point to reference point P2, P3 or P4 (P2 when P is \
         omitted). P must be an integer 2–4. Not allowed while G68 is on.",
        &[
            o('P', "reference point number 2, 3 or 4 (default 2)"),
            o('X', "intermediate point X"),
            o('Y', "intermediate point Y"),
            o('Z', "intermediate point Z"),
            o('A', "intermediate point A"),
            o('B', "intermediate point B"),
            o('C', "intermediate point C"),
        ],
    ),
    g(
        310,
        Some(0),
        AxisConsumer,
        "Skip cutting",
        "Linear move at F that stops as soon as the PLC skip signal G6.6 changes (either edge); the \
         next block starts from wherever the axes stopped, so its incremental moves shift. Applies \
         to its own block only.",
        FEED_AXES,
    ),
    g(
        370,
        Some(0),
        AxisConsumer,
        "Automatic tool length calibration",
        "Moves one axis toward the theoretical surface position and on until the surface signal \
         (G201.4) trips; the difference is added to the active length offset. Needs an earlier \
         G43/G44 with H; not possible with length-compensation type C. Part of the distance runs at \
         rapid (G37 Ratio), the rest at the G37 speed, and a trip outside G37 Limit is an error.",
        &[
            o('Z', "theoretical surface position (type A, or B under G17)"),
            o('Y', "theoretical surface position (type B under G18)"),
            o('X', "theoretical surface position (type B under G19)"),
        ],
    ),
    g(
        520,
        Some(0),
        AxisConsumer,
        "Local coordinate system",
        "Shifts the zero of the current work coordinate system by the given offsets; each work \
         system keeps its own local shift. Cancel with G52 and zero for every shifted axis. \
         Ignored in incremental mode (G91) and forbidden while G68 is on.",
        &[o('X', "local zero offset X"), o('Y', "local zero offset Y"), o('Z', "local zero offset Z")],
    ),
    g(
        530,
        Some(0),
        AxisConsumer,
        "Move in machine coordinates",
        "For this block only the coordinates are machine coordinates and the tool moves there at \
         rapid; later blocks use the previous work system again. Forbidden while G68 is on.",
        MOVE_AXES,
    ),
    g(
        650,
        Some(0),
        AxisConsumer,
        "Simple macro call",
        "Calls macro O<P> L times (default once) passing the other words as arguments. G65 must be \
         written before its arguments and the macro must be in the same file as the caller. In a \
         G65 block L is the repeat count, not a digital output.",
        &[r('P', "macro program number"), o('L', "repeat count (default 1)")],
    ),
    g(
        920,
        Some(0),
        AxisConsumer,
        "Set workpiece coordinates",
        "Defines the work coordinate system so that the current tool position gets the given \
         coordinates; no motion. Allowed under look-ahead.",
        &[
            o('X', "new coordinate of the current position in X"),
            o('Y', "new coordinate in Y"),
            o('Z', "new coordinate in Z"),
            o('A', "new coordinate in A"),
            o('B', "new coordinate in B"),
            o('C', "new coordinate in C"),
        ],
    ),
    // Group 02: plane.
    g(
        170,
        Some(2),
        Modal,
        "XY plane",
        "Selects the XY plane for arcs, exponential interpolation and rotation; drilling is along \
         Z. Power-on default. Must not be changed while G68 rotation or a canned cycle is active.",
        NONE,
    )
    .dflt(),
    g(
        180,
        Some(2),
        Modal,
        "ZX plane",
        "Selects the ZX plane (arcs use K and I). Must not be changed while G68 rotation or a canned \
         cycle is active.",
        NONE,
    ),
    g(
        190,
        Some(2),
        Modal,
        "YZ plane",
        "Selects the YZ plane (arcs use J and K). Must not be changed while G68 rotation or a canned \
         cycle is active.",
        NONE,
    ),
    // Group 06: units.
    g(
        200,
        Some(6),
        Modal,
        "Inch input",
        "Linear distances and feeds are in inches; rotary axes stay in degrees. Normally given at \
         the start of the program.",
        NONE,
    ),
    g(
        210,
        Some(6),
        Modal,
        "Metric input",
        "Linear distances and feeds are in millimetres; rotary axes stay in degrees. Power-on \
         default.",
        NONE,
    )
    .dflt(),
    // Group 07: tool radius compensation.
    g(
        400,
        Some(7),
        Modal,
        "Tool radius compensation off",
        "Cancels cutter radius compensation. Power-on default. The last move in compensation mode \
         must not be an arc.",
        NONE,
    )
    .dflt(),
    g(
        410,
        Some(7),
        Modal,
        "Tool radius compensation (manual: 'right')",
        "Offsets the path by the tool radius. The manual calls G41 'right', the reverse of the usual \
         convention, so the side comes from the machine profile. The radius comes from D (index or \
         diameter), H or the current T. First and last compensated moves cannot be arcs; not with \
         scaling or mirror; only G00–G04, M, S, F allowed while active; 100-block look-ahead.",
        TRC_P,
    ),
    g(
        420,
        Some(7),
        Modal,
        "Tool radius compensation (manual: 'left')",
        "Offsets the path by the tool radius on the side opposite G41. The manual calls G42 'left', \
         the reverse of the usual convention; the side comes from the machine profile. Same limits \
         as G41.",
        TRC_P,
    ),
    // Group 19: normal direction control.
    g(
        401,
        Some(19),
        Modal,
        "Normal direction control off",
        "Stops keeping the rotary tool axis perpendicular to the cutting direction. Power-on \
         default.",
        NONE,
    )
    .dflt(),
    g(
        411,
        Some(19),
        Modal,
        "Normal direction control, tool on the left",
        "Keeps a rotary axis turned normal to the XY direction of travel with the tool on the left \
         of the path (angle = direction − 90°). Rotations at corners happen in place at the Rotation \
         Feedrate; small turns and short blocks are skipped by the Angle and Length limits. The \
         rotary axis must be of type Rotary or Rotary ST. The manual says it takes no parameters.",
        &[o('H', "shown in the manual's format although it lists no parameters")],
    ),
    g(
        421,
        Some(19),
        Modal,
        "Normal direction control, tool on the right",
        "As G41.1 with the tool on the right of the path (angle = direction + 90°). The rotary axis \
         must be of type Rotary or Rotary ST.",
        &[o('H', "shown in the manual's format although it lists no parameters")],
    ),
    // Group 08: tool length compensation / TCP.
    g(
        430,
        Some(8),
        Modal,
        "Tool length compensation +",
        "Adds the length offset of tool H (geometry + wear) to the end position of the compensated \
         axis, whether G90 or G91. Which axis depends on the TLC type: A = Z only, B = the axis \
         normal to the plane, C = the named axis. An axis letter with no value only selects it. Do \
         not use while TCP (G43.2) is on.",
        TLC_P,
    ),
    g(
        432,
        Some(8),
        Modal,
        "Tool centre point control (S-140M)",
        "Keeps the programmed X/Y/Z at the tool tip while Axis 4 and Axis 5 rotate, moving the tip \
         at F along the programmed path. Tool length (H) plus arm length give the pivot distance. \
         Only on S-140M, both rotary axes must be of type Rotary, and it cannot run under look-ahead. \
         Cancel with G49.",
        &[o('H', "tool whose length is added to the arm length")],
    )
    .only(variants::S140M),
    g(
        440,
        Some(8),
        Modal,
        "Tool length compensation −",
        "Subtracts the length offset of tool H from the end position of the compensated axis. Axis \
         selection follows the TLC type as for G43; a negative offset reverses the direction.",
        TLC_P,
    ),
    g(
        490,
        Some(8),
        Modal,
        "Tool length compensation and TCP off",
        "Cancels tool length compensation on all axes and tool centre point control. With TLC type \
         C both G49 and H0 are needed. Default by recommendation (the manual names none).",
        NONE,
    )
    .dflt(),
    // Group 11: scaling.
    g(
        500,
        Some(11),
        Modal,
        "Scaling off",
        "Cancels scaling. Power-on default. When rotation is also used, give G69 before G50.",
        NONE,
    )
    .dflt(),
    g(
        510,
        Some(11),
        Modal,
        "Scaling on",
        "Scales later coordinates about the absolute centre X/Y/Z (current position if omitted) by \
         P for all axes or I/J/K per axis, never both; one of them is required. Factors are \
         0.001–999.999; a missing I/J/K keeps its previous value. Not with radius compensation or \
         mirror image.",
        G51_P,
    ),
    // Group 22: mirror image.
    g(
        501,
        Some(22),
        Modal,
        "Mirror image off",
        "Cancels mirroring only for the axes written in the block (the values do not matter). \
         Without axis words nothing is cancelled. Power-on default.",
        &[o('X', "cancel mirroring of X"), o('Y', "cancel mirroring of Y"), o('Z', "cancel mirroring of Z")],
    )
    .dflt(),
    g(
        511,
        Some(22),
        Modal,
        "Mirror image on",
        "Mirrors each named axis about the given coordinate (absolute or incremental per G90/G91). \
         With exactly one mirrored plane axis, arc directions are reversed. Not with radius \
         compensation or scaling.",
        &[o('X', "mirror centre X"), o('Y', "mirror centre Y"), o('Z', "mirror centre Z")],
    ),
    // Group 14: work coordinate systems.
    g(
        540,
        Some(14),
        Modal,
        "Work coordinate system 1",
        "Selects workpiece zero offset 1. Words in the same block are ignored, so write it alone. \
         Forbidden while G68 is on. Default by recommendation.",
        NONE,
    )
    .dflt(),
    g(
        541,
        Some(14),
        Modal,
        "Additional work coordinate system",
        "G54.1 Pn selects workpiece zero offset n + 6, n = 1–58 (integer). Forbidden while G68 is \
         on.",
        &[r('P', "additional system number 1–58")],
    ),
    g(550, Some(14), Modal, "Work coordinate system 2", "Selects workpiece zero offset 2. Words in the same block are ignored; forbidden while G68 is on.", NONE),
    g(560, Some(14), Modal, "Work coordinate system 3", "Selects workpiece zero offset 3. Words in the same block are ignored; forbidden while G68 is on.", NONE),
    g(570, Some(14), Modal, "Work coordinate system 4", "Selects workpiece zero offset 4. Words in the same block are ignored; forbidden while G68 is on.", NONE),
    g(580, Some(14), Modal, "Work coordinate system 5", "Selects workpiece zero offset 5. Words in the same block are ignored; forbidden while G68 is on.", NONE),
    g(590, Some(14), Modal, "Work coordinate system 6", "Selects workpiece zero offset 6. Words in the same block are ignored; forbidden while G68 is on.", NONE),
    // Group 15: path control.
    g(
        610,
        Some(15),
        Modal,
        "Exact stop mode",
        "Every move decelerates to a stop at its end point and waits for the in-position check \
         before the next block. Gives sharp corners at the cost of time.",
        NONE,
    ),
    g(
        640,
        Some(15),
        Modal,
        "Continuous cutting mode",
        "No in-position check at the end of blocks; execution goes straight on to the next block. \
         Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        641,
        Some(15),
        Modal,
        "Continuous cutting with block rollover",
        "Neither deceleration nor in-position check between blocks, and the leftover of a block that \
         does not fill the last interpolation period is carried into the next block.",
        NONE,
    ),
    // Group 16: rotation.
    g(
        680,
        Some(16),
        Modal,
        "Coordinate system rotation",
        "Rotates later geometry in the active plane by R degrees (positive = counter-clockwise, 0 if \
         omitted) about the absolute centre given by the plane's two axis words (current position if \
         omitted). While on, the plane must not change and G28–G30, G52–G59, G54.1 are forbidden. \
         Order with scaling and compensation: G51, G68, G41 … G69, G50.",
        &[
            o('X', "rotation centre X (absolute)"),
            o('Y', "rotation centre Y (absolute)"),
            o('Z', "rotation centre Z (absolute)"),
            o('R', "rotation angle in degrees, positive counter-clockwise"),
        ],
    ),
    g(
        690,
        Some(16),
        Modal,
        "Coordinate system rotation off",
        "Cancels G68. The manual names G68 as the default, which is almost certainly wrong; G69 is \
         treated as the power-on state.",
        NONE,
    )
    .dflt(),
    // Group 09: canned cycles.
    g(
        730,
        Some(9),
        Motion,
        "High-speed peck drilling cycle",
        "Rapid to the hole position and R level, then feed down in pecks of Q, backing off by the \
         Retract Vector parameter after each, until Z; rapid back to the initial level (G98) or R \
         (G99). Q must be positive; K repeats the cycle. The spindle must be running.",
        G73_P,
    ),
    g(
        740,
        Some(9),
        Motion,
        "Counter (left-hand) tapping cycle",
        "Feeds from R to Z with the spindle counter-clockwise, dwells P ms, reverses and feeds back \
         to R. After M29 S it runs as rigid tapping (dwell also at R). Lead is F/S under G94 or F \
         under G95; feed hold and feed override do not act during the cycle.",
        TAP_P,
    ),
    g(
        760,
        Some(9),
        Motion,
        "Fine boring cycle",
        "Feeds from R to Z, dwells P ms, stops the spindle oriented, shifts the tool away from the \
         wall by Q and rapids out, then shifts back. The shift direction is a machine parameter; Q \
         is the same modal Q as the peck depth of G73/G83.",
        SHIFT_P,
    ),
    g(
        800,
        Some(9),
        Modal,
        "Canned cycle cancel",
        "Ends the active drilling cycle and clears R, Z and the other drilling data (set to zero in \
         incremental mode); rigid tapping returns to velocity control. Default by recommendation.",
        NONE,
    )
    .dflt(),
    g(
        810,
        Some(9),
        Motion,
        "Drilling / spot drilling cycle",
        "Rapid to the hole position and R, feed to Z, rapid out to the initial level (G98) or R \
         (G99). A block with no axis or R word makes no hole; K repeats the cycle.",
        DRILL_P,
    ),
    g(
        820,
        Some(9),
        Motion,
        "Drilling cycle with dwell",
        "As G81 with a dwell of P ms (integer) at the hole bottom before the rapid retract.",
        DWELL_P,
    ),
    g(
        830,
        Some(9),
        Motion,
        "Peck drilling cycle",
        "Feeds down by Q per peck, rapids back to R after each peck and rapids down again to just \
         above the previous depth (Retract Vector clearance) until Z is reached, then returns to the \
         initial level or R. Q must be positive.",
        G83_P,
    ),
    g(
        840,
        Some(9),
        Motion,
        "Tapping cycle",
        "Feeds from R to Z with the spindle clockwise, dwells P ms, reverses and feeds back to R. \
         After M29 S it is rigid tapping (dwell also at R). Lead is F/S under G94 or F under G95; \
         feed hold and feed override do not act.",
        TAP_P,
    ),
    g(
        850,
        Some(9),
        Motion,
        "Boring cycle, feed out",
        "Feeds from R to Z and feeds back up to R, then rapids to the initial level under G98. The \
         manual's format shows Q and P but the cycle uses neither.",
        &[
            CYCLE_XY[0],
            CYCLE_XY[1],
            CYCLE_Z,
            CYCLE_R,
            o('Q', "printed in the format but not used"),
            o('P', "printed in the format but not used"),
            CYCLE_F,
            CYCLE_K,
        ],
    ),
    g(
        860,
        Some(9),
        Motion,
        "Boring cycle, spindle stop at bottom",
        "Feeds from R to Z, stops the spindle, rapids out to the initial level or R, and restarts \
         the spindle before the next block.",
        DRILL_P,
    ),
    g(
        870,
        Some(9),
        Motion,
        "Back boring cycle",
        "Oriented stop and shift by Q, rapid down to R below the part, shift back and start the \
         spindle, feed upward to Z, dwell P, oriented stop, shift and rapid out to the initial level. \
         Works only with G98; G99 is an error.",
        SHIFT_P,
    ),
    g(
        890,
        Some(9),
        Motion,
        "Boring cycle with dwell, feed out",
        "As G85 with a dwell of P ms at the hole bottom: feed to Z, dwell, feed back to R, rapid to \
         the initial level under G98.",
        DWELL_P,
    ),
    // Group 03: distance mode.
    g(
        900,
        Some(3),
        Modal,
        "Absolute programming",
        "Coordinates are positions in the active work system. Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        910,
        Some(3),
        Modal,
        "Incremental programming",
        "Coordinates are distances from the current position. G52 is ignored in this mode, and \
         canned-cycle R and Z become relative distances.",
        NONE,
    ),
    // Group 05: feed mode.
    g(
        940,
        Some(5),
        Modal,
        "Feed per minute",
        "F is mm/min or in/min (deg/min for rotary axes). Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        950,
        Some(5),
        Modal,
        "Feed per revolution",
        "F is mm or inches per spindle revolution, so the path speed is F times the spindle speed; \
         a spindle speed must be in effect.",
        NONE,
    ),
    // Group 10: cycle return level.
    g(
        980,
        Some(10),
        Modal,
        "Cycle return to initial level",
        "Canned cycles retract to the level where the cycle started. Power-on default; the only mode \
         G87 accepts.",
        NONE,
    )
    .dflt(),
    g(
        990,
        Some(10),
        Modal,
        "Cycle return to R level",
        "Canned cycles retract only to the R level between holes. G87 back boring with G99 is an \
         error.",
        NONE,
    ),
    // Group 31: feedrate with rotary axes.
    g(
        3100,
        Some(31),
        Modal,
        "Feedrate includes rotary axes",
        "F is shared over all moving axes, linear and rotary (degrees counted like millimetres). \
         Power-on default.",
        NONE,
    )
    .dflt(),
    g(
        3110,
        Some(31),
        Modal,
        "Feedrate over linear axes only",
        "F is the speed of the linear axes alone; rotary axes are scaled by the same factor. A block \
         that moves only rotary axes has no defined feed basis.",
        NONE,
    ),
    // M codes (Table 7-1 and other chapters); all but M98/M99 are carried out by the PLC ladder.
    m(
        0,
        "Program stop",
        "Stops the program temporarily; the operator restarts it. Like other PLC M codes it acts \
         after the motion in its block has finished.",
        NONE,
    ),
    m(
        1,
        "Optional stop",
        "Stops the program like M00 when the optional-stop switch is on, otherwise it is passed.",
        NONE,
    ),
    m(
        2,
        "Program end",
        "Ends the main program. A program should end with M02 or M30.",
        NONE,
    ),
    m(
        3,
        "Spindle clockwise",
        "Starts the spindle clockwise at the current S speed. Only for inverter-type or single \
         spindles; a servo spindle is started by the sign of S instead.",
        NONE,
    ),
    m(
        4,
        "Spindle counter-clockwise",
        "Starts the spindle counter-clockwise. Only for inverter-type or single spindles.",
        NONE,
    ),
    m(
        5,
        "Spindle stop",
        "Stops the spindle. Only for inverter-type or single spindles; a servo spindle stops with S0.",
        NONE,
    ),
    m(
        8,
        "Coolant on (PLC-defined)",
        "Shown only as an example auxiliary code; its action is whatever the machine's PLC ladder \
         program defines.",
        NONE,
    ),
    m(
        29,
        "Rigid tapping mode",
        "Switches the spindle to position control for rigid tapping with the next G74/G84; write \
         it with S (M29 S…). Needs a servo spindle. Defined by the default LadderWorks PLC program; \
         G80 returns to velocity control.",
        &[o('S', "spindle speed for the tapping")],
    ),
    m(
        30,
        "Program end and rewind",
        "Ends the main program and returns to its start.",
        NONE,
    ),
    m(
        98,
        "Subprogram call",
        "Runs subprogram file O<name>.dat from the caller's folder R times (once if R is omitted, \
         at most 999,999). P is the name without the leading O and may contain letters, digits and \
         _. Up to eight nesting levels. Motion in the same block is ignored.",
        &[
            r('P', "subprogram name without the leading O"),
            o('R', "number of repetitions, integer 1–999,999 (default 1)"),
        ],
    ),
    m(
        99,
        "Subprogram end / return",
        "Returns from a subprogram or G65 macro to the caller. In a main program it jumps back to \
         the program's beginning, which loops forever.",
        NONE,
    ),
];

/// Meanings of the ServoWorks address letters (manual ch. 2).
pub static ADDRESSES: &[AddressInfo] = &[
    AddressInfo {
        letter: 'A',
        doc: "A-axis coordinate (degrees when rotary), absolute or incremental per G90/G91",
    },
    AddressInfo {
        letter: 'B',
        doc: "B-axis coordinate; under TCP (G43.2) the manual's Axis 5 (tilt from −Z)",
    },
    AddressInfo {
        letter: 'C',
        doc: "C-axis coordinate; under TCP (G43.2) the manual's Axis 4 (angle in the XY plane)",
    },
    AddressInfo {
        letter: 'D',
        doc: "integer: tool offset number for radius compensation; with a decimal point: nominal \
              tool diameter; or a D-axis coordinate when configured. May stand alone",
    },
    AddressInfo {
        letter: 'E',
        doc: "E-axis coordinate (only when the machine has such an axis)",
    },
    AddressInfo {
        letter: 'F',
        doc: "modal feedrate (G94: mm/min, in/min or deg/min; G95: per revolution); start feed of \
              G02.3/G03.3; cutting feed of canned cycles. May stand alone",
    },
    AddressInfo {
        letter: 'H',
        doc: "tool length offset number (G43/G44/G43.2/G37, 1–256, integer); H0 cancels on that axis",
    },
    AddressInfo {
        letter: 'I',
        doc: "arc centre offset along X from the start point; G02.3/G03.3 taper angle; G51 X scale factor",
    },
    AddressInfo {
        letter: 'J',
        doc: "arc centre offset along Y from the start point; G02.3/G03.3 helix angle; G51 Y scale factor",
    },
    AddressInfo {
        letter: 'K',
        doc: "arc centre offset along Z from the start point; G51 Z scale factor; canned-cycle \
              repeat count (integer, default 1)",
    },
    AddressInfo {
        letter: 'L',
        doc: "G10 data category; G65 repeat count; in any other block a 16-bit direct digital \
              output 0–65535 applied at the start of the block",
    },
    AddressInfo {
        letter: 'N',
        doc: "sequence (block) number",
    },
    AddressInfo {
        letter: 'O',
        doc: "program, subprogram or macro name at the top of its file (O<name>)",
    },
    AddressInfo {
        letter: 'P',
        doc: "M98 subprogram name; G04 dwell in ms (integer); G05/G08 on/off; G10 axis or index; \
              G30 reference point 2–4; G51 scale factor; G54.1 system 1–58; G65 macro number; \
              canned-cycle dwell in ms",
    },
    AddressInfo {
        letter: 'Q',
        doc: "G02/G03 allowed contour error; G02.3/G03.3 end feed; G73/G83 peck depth; G76/G87 \
              shift amount (one modal Q shared by all cycles)",
    },
    AddressInfo {
        letter: 'R',
        doc: "M98 repetitions; arc radius; G02.3/G03.3 exponential constant; G10 value; G68 angle \
              in degrees; canned-cycle R level",
    },
    AddressInfo {
        letter: 'S',
        doc: "spindle speed, integer of up to 5 digits; S<n>_<speed> addresses spindle n (1–16); on \
              a servo spindle the sign gives the direction and S0 stops it",
    },
    AddressInfo {
        letter: 'T',
        doc: "tool number 1–256 (same as its offset number); the radius offset applies at once, the \
              length offset needs G43/G44 with H; T0 cancels offsets",
    },
    AddressInfo {
        letter: 'U',
        doc: "U-axis coordinate (only when configured)",
    },
    AddressInfo {
        letter: 'V',
        doc: "V-axis coordinate (only when configured)",
    },
    AddressInfo {
        letter: 'W',
        doc: "W-axis coordinate (only when configured)",
    },
    AddressInfo {
        letter: 'X',
        doc: "X coordinate (end point, centre, offset); G04 dwell in seconds with a decimal point; \
              G10 value for X; G37 surface position",
    },
    AddressInfo {
        letter: 'Y',
        doc: "Y coordinate (end point, centre, offset); G10 value for Y; G37 surface position",
    },
    AddressInfo {
        letter: 'Z',
        doc: "Z coordinate; G10 value for Z; G37 surface position; canned cycles: hole bottom \
              (G87: top of the cut)",
    },
    AddressInfo {
        letter: '#',
        doc: "macro variable, e.g. #101 = 1.0 or X#101",
    },
];

#[cfg(test)]
mod tests {
    use super::super::{
        assert_all_present, check_table_invariants, codes_in_group, default_codes, lookup,
        lookup_address, Dialect, Variant,
    };
    use super::*;

    const D: Dialect = Dialect::Servoworks;

    fn get(letter: char, tenths: u32) -> &'static CodeInfo {
        match lookup(D, letter, CodeNum(tenths)) {
            Some(c) => c,
            None => panic!("{letter}{} missing", CodeNum(tenths).display()),
        }
    }

    #[test]
    fn table_invariants() {
        check_table_invariants(D);
    }

    #[test]
    fn every_code_of_the_summary_tables_is_present() {
        // Digest §3.1 / §3.2 rows, expanded (G54…G59, G73…G89 without G88).
        assert_all_present(
            D,
            &[
                "G0", "G0.1", "G1", "G2", "G3", "G2.3", "G3.3", "G4", "G5", "G8", "G10", "G17",
                "G18", "G19", "G20", "G21", "G28", "G29", "G30", "G31", "G37", "G40", "G41", "G42",
                "G40.1", "G41.1", "G42.1", "G43", "G43.2", "G44", "G49", "G50", "G51", "G50.1",
                "G51.1", "G52", "G53", "G54", "G55", "G56", "G57", "G58", "G59", "G54.1", "G61",
                "G64", "G64.1", "G65", "G68", "G69", "G73", "G74", "G76", "G80", "G81", "G82",
                "G83", "G84", "G85", "G86", "G87", "G89", "G90", "G91", "G92", "G94", "G95", "G98",
                "G99", "G310", "G311", "M0", "M1", "M2", "M3", "M4", "M5", "M8", "M29", "M30",
                "M98", "M99",
            ],
        );
        // Codes the digest says do not exist must stay out.
        for t in [880, 960, 970, 120, 130, 150, 160, 412, 431, 434, 811] {
            assert!(
                lookup(D, 'G', CodeNum(t)).is_none(),
                "G{} should not exist",
                CodeNum(t).display()
            );
        }
    }

    #[test]
    fn variant_restrictions() {
        let g023 = get('G', 23);
        assert!(!g023.on_variant(Variant::S100M));
        assert!(g023.on_variant(Variant::S120M) && g023.on_variant(Variant::S140M));
        assert_eq!(get('G', 33).variants, variants::S120M | variants::S140M);
        let g432 = get('G', 432);
        assert_eq!(g432.variants, variants::S140M);
        assert!(!g432.on_variant(Variant::S120M));
        assert_eq!(get('G', 10).variants, variants::ALL_SW);
    }

    #[test]
    fn groups_and_defaults() {
        let defaults: Vec<String> = default_codes(D).map(|c| c.name()).collect();
        assert_eq!(
            defaults,
            [
                "G0", "G17", "G21", "G40", "G40.1", "G49", "G50", "G50.1", "G54", "G64", "G69",
                "G80", "G90", "G94", "G98", "G310"
            ]
        );
        assert_eq!(get('G', 20).group, Some(1));
        assert_eq!(get('G', 23).group, Some(1));
        assert_eq!(get('G', 432).group, Some(8));
        assert_eq!(get('G', 541).group, Some(14));
        assert_eq!(get('G', 641).group, Some(15));
        assert_eq!(get('G', 511).group, Some(22));
        assert_eq!(get('G', 3110).group, Some(31));
        assert_eq!(get('G', 411).group, Some(19));
        let g00: Vec<String> = codes_in_group(D, 0).map(|c| c.name()).collect();
        assert_eq!(
            g00,
            [
                "G4", "G5", "G8", "G10", "G28", "G29", "G30", "G31", "G37", "G52", "G53", "G65",
                "G92"
            ]
        );
        let g09: Vec<String> = codes_in_group(D, 9).map(|c| c.name()).collect();
        assert_eq!(
            g09,
            ["G73", "G74", "G76", "G80", "G81", "G82", "G83", "G84", "G85", "G86", "G87", "G89"]
        );
        assert!(get('M', 30).group.is_none());
    }

    #[test]
    fn kinds_and_params() {
        assert_eq!(get('G', 810).kind, CodeKind::Motion);
        assert_eq!(get('G', 920).kind, CodeKind::AxisConsumer);
        assert_eq!(get('G', 40).kind, CodeKind::OneShot);
        assert_eq!(get('G', 900).kind, CodeKind::Modal);
        let g04 = get('G', 40);
        assert!(g04.param('P').is_some_and(|p| !p.required));
        assert!(g04.param('X').is_some_and(|p| !p.required));
        assert!(get('M', 980).param('P').is_some_and(|p| p.required));
        assert!(get('G', 541).param('P').is_some_and(|p| p.required));
        assert!(get('G', 650).param('P').is_some_and(|p| p.required));
        assert!(get('G', 830).param('Q').is_some());
        assert!(get('G', 810).param('Q').is_none());
        assert!(get('G', 20).param('R').is_some());
    }

    #[test]
    fn addresses() {
        assert!(lookup_address(D, 'l').is_some_and(|a| a.doc.contains("65535")));
        assert!(lookup_address(D, 'P').is_some());
        assert!(lookup_address(D, 'G').is_none());
        assert!(lookup_address(D, 'M').is_none());
    }
}
