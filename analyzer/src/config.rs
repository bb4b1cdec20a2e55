//! The `partscope.toml` configuration: one typed struct per table, each key
//! declared once with its values, default and meaning.
//!
//! [`Config::load`] never fails: a syntax error, an unknown key or a value of
//! the wrong type or range becomes a [`ConfigIssue`] located at the key (with the
//! nearest valid key for a typo), and the key keeps its default. The same
//! declarations generate `docs/configuration.md` ([`reference_markdown`]), so
//! the reference cannot drift from what is read. Finding and reading the file
//! is the host's job.

use std::collections::BTreeMap;
use std::ops::Range;

use crate::diagnostic::Severity;
use crate::dialect::{Dialect, Variant};

/// Documentation of one key, for messages and the generated reference.
#[derive(Debug, Clone, Copy)]
pub struct KeyDoc {
    pub name: &'static str,
    /// What may be written (`mm`, `bool`, `linear`, `independent`, …).
    pub values: &'static str,
    /// The default, in words.
    pub default: &'static str,
    pub meaning: &'static str,
}

/// A problem in a configuration: where it is and what was done instead.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigIssue {
    /// Dotted key path (`machine.lookahead`); empty for a syntax error.
    pub key: String,
    /// Byte range in the configuration text (of the key, or of the value when
    /// the value is wrong), when the configuration came from text.
    pub span: Option<Range<usize>>,
    pub message: String,
    pub severity: Severity,
}

impl ConfigIssue {
    /// The issue as a finding of rule L016 in the configuration file itself (at
    /// the start of the file when the issue has no place in it).
    pub fn diagnostic(&self) -> crate::Diagnostic {
        let span = self.span.clone().unwrap_or(0..0);
        let at = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
        crate::rules::CONFIG_ISSUE.diagnostic(
            self.severity,
            crate::Span::new(at(span.start), at(span.end)),
            self.message.clone(),
        )
    }
}

/// A table read key by key: unknown keys and bad values are issues, the rest is read.
trait KeyTable: Default {
    /// Every key of the table, in declaration order.
    const KEYS: &'static [KeyDoc];

    /// Reads one key: `None` when the table has no such key, else whether the
    /// value was taken.
    fn set(&mut self, key: &str, v: &toml::Value) -> Option<Result<(), String>>;
}

/// Declares a table's struct (every key an `Option`), its key documentation and
/// the reading of one key, so a key is named exactly once.
macro_rules! table {
    (
        $(#[$meta:meta])* $vis:vis struct $name:ident {
            $( $key:ident : $ty:ty = $parse:expr,
               values $values:literal, default $default:literal, $meaning:literal; )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Default, PartialEq)]
        $vis struct $name {
            $( #[doc = $meaning] pub $key: Option<$ty>, )*
        }

        impl $name {
            /// Every key of this table, in declaration order.
            pub const KEYS: &'static [KeyDoc] = &[
                $( KeyDoc {
                    name: stringify!($key),
                    values: $values,
                    default: $default,
                    meaning: $meaning,
                }, )*
            ];
        }

        impl KeyTable for $name {
            const KEYS: &'static [KeyDoc] = $name::KEYS;

            fn set(&mut self, key: &str, v: &toml::Value) -> Option<Result<(), String>> {
                match key {
                    $( stringify!($key) => {
                        let parse: fn(&toml::Value) -> Result<$ty, String> = $parse;
                        Some(parse(v).map(|x| self.$key = Some(x)))
                    } )*
                    _ => None,
                }
            }
        }
    };
}

table! {
    /// The top level of a `partscope.toml` (besides its tables).
    struct TopKeys {
        dialect: Dialect = dialect,
            values "`servoworks`, `rs274ngc`, `fanuc`",
            default "from a `(partscope: dialect=…)` first-line comment, the extension, or `rs274ngc`",
            "language of the programs under this config";
        variant: Variant = variant,
            values "`S-100M`, `S-120M`, `S-140M`, `linuxcnc`, `emc2`, `30i`",
            default "`S-140M`, `linuxcnc`, `30i`",
            "control model / profile: gates variant-only codes (G02.3 not on S-100M, G43.2 only on S-140M) and the 2007 `emc2` semantics";
        tool_table: String = string,
            values "path", default "none",
            "LinuxCNC `.tbl` (relative to this file); read by `check`, `run` and the LSP";
        var_file: String = string,
            values "path", default "none",
            "LinuxCNC `.var` parameter file";
        ini: String = string,
            values "path", default "none",
            "LinuxCNC `.ini`: its `[TRAJ]`/`[AXIS_*]`/`[JOINT_*]` limits become the machine, its `TOOL_TABLE` and `PARAMETER_FILE` are used unless `tool_table`/`var_file` are given (`check`, `run` and the language server, whose cycle time is the same machine's)";
    }
}

table! {
    /// The `[rules]` table.
    pub struct RulesConfig {
        select: Vec<String> = strings,
            values "codes, prefixes (`\"S\"`), `\"ALL\"`", default "the default-enabled rules",
            "rules to enable; off-by-default rules (style `S…`, `F015`) must be selected";
        ignore: Vec<String> = strings,
            values "codes or prefixes", default "none",
            "rules to disable";
        fail_level: Severity = severity,
            values "`error`, `warning`, `info`, `hint`", default "`warning`",
            "lowest severity that makes `partscope check` exit 1";
        custom_codes: Vec<String> = strings,
            values "e.g. `[\"G100\", \"M150\"]`", default "none",
            "codes your control defines as macro calls (no \"unknown code\" report)";
        max_runtime_errors: usize = |v| integer_in(v, 1, 1 << 32).map(|n| n as usize),
            values "a number ≥ 1", default "`100`",
            "runtime errors the dry run reports and recovers from per file before it stops with one F004 (`--max-runtime-errors`)";
    }
}

table! {
    /// The `[machine]` table: the machine profile the interpreter, the planner and
    /// the host read. Every key is optional; the readers apply the dialect's
    /// defaults to the keys left out.
    pub struct MachineConfig {
        circle_error_allowance: f64 = non_negative,
            values "mm", default "0",
            "ServoWorks *Circle Error Allowance*; the tolerance is max(allowance, √(m1² + m2²)) with the machine unit m (§6.3.3)";
        arc_radius_tolerance: f64 = non_negative,
            values "mm", default "0.02",
            "FANUC parameter No. 3410 (PS0020). LinuxCNC's own rule is built in (profile `linuxcnc` / `emc2`)";
        machine_unit: f64 = |v| number_in(v, 1e-9, 1.0),
            values "mm", default "0.001",
            "least input increment (ServoWorks *Machine Unit*); also `axes[0].machine_unit`";
        integer_machine_unit: bool = boolean,
            values "bool", default "false",
            "ServoWorks integer programming with machine unit (`X100` = 100 machine units)";
        decimal_point_input: bool = boolean,
            values "bool", default "false",
            "FANUC pocket-calculator input (`X1` = 1 mm rather than 1 µm)";
        block_skip: bool = boolean,
            values "bool", default "false",
            "optional block skip switch: `/` blocks are skipped when on. LinuxCNC's task (the real machine) starts with block delete on, its standalone `rs274` with it off: set `block_skip = true` to time a program as LinuxCNC runs it";
        optional_stop: bool = boolean,
            values "bool", default "false",
            "optional stop switch: M1 stops (and costs `program_stop_time`) only when on";
        machine_units: Units = |v| choice(v, &[("mm", Units::Mm), ("inch", Units::Inch)]),
            values "`mm`, `inch`",
            default "`inch` for `rs274ngc` (the standalone rs274 is an inch machine), else `mm`",
            "units of tool-table, `.var` and offset values";
        tools: BTreeMap<u32, ToolConfig> = tools,
            values "table `T1 = { length = …, diameter = … }` (or `radius`)", default "none",
            "tool table in mm; with a table, unknown T/H numbers are reported (`T001`)";
        work_offsets: BTreeMap<usize, [f64; 6]> = work_offsets,
            values "table `G54 = [x, y, z, a, b, c]` … `G59.3`", default "zeros",
            "work offsets at power-on";
        reference_positions: BTreeMap<usize, [f64; 6]> = reference_positions,
            values "table `2 = [x, y, z, a, b, c]` … `4 = […]` (1 too), machine coordinates, mm",
            default "machine zero",
            "FANUC/ServoWorks reference positions: G28 returns to the first, G30 P2 (default), P3, P4 to the others (FANUC No. 1240–1243). RS274/NGC uses `#5161`… and `#5181`… instead";
        max_call_depth: usize = |v| integer_in(v, 1, 10_000).map(|n| n as usize),
            values "integer", default "ServoWorks 8, FANUC 15, RS274/NGC 10",
            "subprogram/macro nesting limit";
        g73_retract: f64 = number,
            values "mm", default "1.0",
            "FANUC No. 5114 and the ServoWorks *Retract Vector* d (G73)";
        g83_clearance: f64 = number,
            values "mm", default "1.0",
            "FANUC No. 5115 and the ServoWorks *Retract Vector* d (G83)";
        tlc_type: i64 = |v| integer_in(v, 0, 2),
            values "0, 1, 2", default "0",
            "ServoWorks Tool Length Compensation Type: 0 = A (Z only), 1 = B (axis normal to the plane), 2 = C (any axis; G49 and H0 both needed to cancel; no G37)";
        servo_rate_khz: f64 = positive,
            values "1, 2, 4", default "1",
            "ServoWorks servo rate: limits G10 L108 smoothing time to 5000 / 2500 / 1250 ms";
        spindles: f64 = |v| integer_in(v, 1, 64).map(|n| n as f64),
            values "integer", default "1",
            "number of spindles (ServoWorks `S2_1500` needs 2)";
        user_m_codes: Vec<i64> = integers,
            values "list of integers", default "none",
            "LinuxCNC M100–M199 programs that exist (others stop rs274: \"Unknown m code\")";
        subroutine_path: Vec<String> = path_list,
            values "path, `:`-separated paths, or a list", default "none",
            "LinuxCNC `SUBROUTINE_PATH` folders (relative to this file) searched for `o<name> call` files, by `check`, `run` and the LSP";
        max_cutting_feed: f64 = positive,
            values "mm/min", default "none (checks skipped)",
            "FANUC cutting-feed upper limit, for rigid tapping and threading checks";
        offset_count: f64 = |v| integer_in(v, 0, 100_000).map(|n| n as f64),
            values "integer", default "400",
            "number of H/D offsets the FANUC control has";
        involute_tolerance: f64 = non_negative,
            values "mm", default "0.01",
            "FANUC parameter No. 5610: end point off the involute";
        sequence_number_digits: u8 = |v| one_of_integers(v, &[5, 8]),
            values "5, 8", default "5",
            "FANUC sequence-number digits: 8 with the 8-digit sequence number option";
        program_number_digits: u8 = |v| one_of_integers(v, &[4, 8]),
            values "4, 8", default "not set: a program number beyond 4 digits is taken as the option's and said once",
            "FANUC program-number digits: 8 with the 8-digit program number option";
        common_variables: u16 = |v| one_of_integers(v, &[199, 499]),
            values "199, 499", default "not set: a use of #200–#499 is taken as the option's and said once",
            "FANUC: the last common variable of the #100 range, 199 (standard) or 499 (additional common variables option)";
        trc_g41_side: G41Side = |v| choice(v, &[("left", G41Side::Left), ("right", G41Side::Right)]),
            values "`left`, `right`", default "`left`",
            "which side G41 puts the tool. The ServoWorks manual says *right* (ambiguity A1 of the digest); ISO practice and the digest's recommendation say *left*";
        drill_shift: DrillShift = drill_shift,
            values "`+X`, `-X`, `+Y`, `-Y`, `none`", default "`+X`",
            "G76/G87 shift direction after the oriented spindle stop (ServoWorks *Shift Direction*, FANUC No. 5101 RD1/RD2); the letter is the first/second axis of the plane";
        ndc_axis: NdcAxis = |v| choice(v, &[("a", NdcAxis::A), ("b", NdcAxis::B), ("c", NdcAxis::C)]),
            values "`A`, `B`, `C`", default "`C`",
            "ServoWorks normal direction control (G41.1/G42.1): the rotary axis kept normal to the XY direction of motion";
        ndc_rotation_feed: f64 = number,
            values "deg/min", default "1000",
            "ServoWorks NDC *Rotation Feedrate*: speed of the in-place turns at corners (1000 is the manual's screenshot value)";
        ndc_angle_limit: f64 = number,
            values "degrees", default "0",
            "ServoWorks NDC *Angle Limit*: turns smaller than this are skipped (and add up until they reach it)";
        ndc_length_limit: f64 = number,
            values "mm", default "0",
            "ServoWorks NDC *Length Limit*: blocks shorter than this turn nothing";
        g37_ratio: f64 = |v| number_in(v, 0.0, 1.0),
            values "0…1", default "0",
            "ServoWorks *G37 Ratio*: the share of the distance to the surface position run at rapid";
        g37_speed: f64 = positive,
            values "mm/min", default "100",
            "ServoWorks *G37 Speed*: the feed of the rest of the G37 approach (no documented default)";
        g37_limit: f64 = number,
            values "mm", default "none (no check)",
            "ServoWorks *G37 Limit*: a calibration of this size or more stops the program (T005)";
        g37_measured: f64 = number,
            values "mm", default "0",
            "where the dry run's G37 sensor triggers, relative to the surface position (the calibration it yields)";
        tcp_arm_length: f64 = number,
            values "mm", default "0",
            "ServoWorks TCP *Arm Length*: with the H tool length, the distance from the programmed tip to the tool base point that the travel limits check under G43.2";
        axes: Vec<AxisConfig> = axes,
            values "array of `{ letter, kind = \"linear\"/\"rotary\", min_travel, max_travel, max_velocity, rapid_rate, max_acceleration, jerk, machine_unit }`, or of letters",
            default "X, Y, Z: 100 mm/s, 1000 mm/s², no travel limits",
            "per-axis limits (units/s, units/s², units/s³); travel limits also drive the out-of-travel check, the letters the unknown-axis check";
        traj_max_velocity: f64 = positive,
            values "mm/s", default "100",
            "Cartesian speed cap (LinuxCNC `[TRAJ]MAX_LINEAR_VELOCITY`)";
        traj_max_acceleration: f64 = positive,
            values "mm/s²", default "1000",
            "path acceleration cap (generic models)";
        planner: PlannerModel = |v| choice(v, &[("linuxcnc", PlannerModel::Linuxcnc), ("trapezoid", PlannerModel::Trapezoid), ("scurve", PlannerModel::Scurve)]),
            values "`linuxcnc`, `trapezoid`, `scurve`", default "`linuxcnc` for `rs274ngc`, else `trapezoid`",
            "velocity-planning model";
        lookahead: u32 = |v| integer_in(v, 0, 100_000).map(|n| n as u32),
            values "segments (at most 100000)", default "50 (`rs274ngc`), 40 (`fanuc`), 100 (`servoworks`)",
            "look-ahead window";
        default_blend_tolerance: f64 = non_negative,
            values "mm", default "0 (as large as the geometry allows)",
            "G64 without P";
        tangent_kink_ratio: f64 = |v| number_in(v, 0.0, 1.0),
            values "0–1", default "0.1",
            "LinuxCNC `ARC_BLEND_KINK_RATIO`";
        servo_period: f64 = |v| number_in(v, 1e-5, 1.0),
            values "s (0.00001 to 1)", default "0.001",
            "interpolation period";
        servo_simulation: bool = boolean,
            values "bool", default "true",
            "`linuxcnc` model: execute period by period (exact to the period) rather than closed-form; long jobs switch to closed form automatically";
        feed_override: f64 = |v| number_in(v, 1e-3, 10.0),
            values "factor (0.001 to 10)", default "1.0",
            "feed override (`partscope run --feed-override 80%`)";
        rapid_override: f64 = |v| number_in(v, 1e-3, 10.0),
            values "factor (0.001 to 10)", default "1.0",
            "rapid override";
        block_processing_time: f64 = non_negative,
            values "s", default "0",
            "minimum time per motion block";
        rapid_positioning: RapidPositioning = |v| choice(v, &[("linear", RapidPositioning::Linear), ("independent", RapidPositioning::Independent)]),
            values "`linear`, `independent`", default "`independent` for `fanuc` and `servoworks`, `linear` for `rs274ngc`",
            "G0 path. `independent`: each axis at its own `rapid_rate` and acceleration, all starting together (the dog-leg): timed by the slowest axis, drawn as the path the axes make, `distance_mm` its length, no `traj_max_velocity` cap. `linear`: a straight line at the speed no axis's rate forbids. FANUC parameter No. 1401#1 LRP: 0 (the default) = non-linear positioning, 1 = linear interpolation positioning (spec/fanuc.md §5.1, [R10] sheet 9, [R11] sheet 16). ServoWorks *G00 Perform Linear Interpolation* (manual §6.3.1, p. 6-7; Reference Manual §3.4.2): the manual gives no default and calls the disabled state \"normal rapid traverse\"";
        lrp: RapidPositioning = |v| match integer_in(v, 0, 1)? { 1 => Ok(RapidPositioning::Linear), _ => Ok(RapidPositioning::Independent) },
            values "0, 1", default "0",
            "FANUC's name for the same switch: `lrp = 1` is `rapid_positioning = \"linear\"` (`rapid_positioning` wins when both are given)";
        g00_linear_interpolation: RapidPositioning = |v| Ok(if boolean(v)? { RapidPositioning::Linear } else { RapidPositioning::Independent }),
            values "bool", default "false",
            "ServoWorks's name for the same switch: `true` is `rapid_positioning = \"linear\"` (`rapid_positioning` and `lrp` win when given)";
        tool_change_time: f64 = non_negative,
            values "s", default "0",
            "per M6 (ServoWorks: per T)";
        tool_select_time: f64 = non_negative,
            values "s", default "0",
            "per T word that only selects a tool (FANUC, RS274/NGC); 0 = selected while cutting, no stop";
        spindle_ramp_time: f64 = non_negative,
            values "s", default "0",
            "fixed part of every spindle start (M3/M4), stop (M5) and S change while turning";
        spindle_ramp_per_1000rpm: f64 = non_negative,
            values "s", default "0",
            "plus this per 1000 rpm of speed change (a reversal runs through 0; M5 at rest costs nothing)";
        spindle_orient_time: f64 = non_negative,
            values "s", default "0",
            "per M19";
        coolant_time: f64 = non_negative,
            values "s", default "0",
            "per block switching coolant (M7, M8, M9)";
        pallet_change_time: f64 = non_negative,
            values "s", default "0",
            "per pallet change";
        pallet_change_m: u32 = |v| integer_in(v, 0, 9999).map(|n| n as u32),
            values "integer", default "60",
            "M code of the pallet change: LinuxCNC M60 (pallet shuttle, then a program stop); on FANUC/ServoWorks the builder's code, which stops nothing";
        m_code_time: f64 = non_negative,
            values "s", default "0",
            "per other M code (a machine-builder code that waits for its handshake)";
        m_code_times: BTreeMap<String, f64> = m_code_times,
            values "table `{ M10 = 0.5, M11 = 0.5 }`", default "none",
            "times of particular M codes, instead of `m_code_time`";
        program_stop_time: f64 = non_negative,
            values "s", default "0",
            "per M0 (and M1 with `optional_stop`): operator time, reported on its own line (`stops`, JSON `auxiliary.program_stop_s`)";
        in_position_time: f64 = non_negative,
            values "s", default "0",
            "settling time at every exact stop";
    }
}

/// Keys the planner reads; the rest of [`MachineConfig`] is the interpreter's
/// and the host's (the reference lists them in two sections).
const PLANNER_KEYS_FROM: &str = "axes";

/// Units of tool-table, `.var` and offset values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    Mm,
    Inch,
}

/// The side G41 puts the tool on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum G41Side {
    Left,
    Right,
}

/// G76/G87 shift after the oriented spindle stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrillShift {
    PlusX,
    MinusX,
    PlusY,
    MinusY,
    None,
}

/// The rotary axis of ServoWorks normal direction control.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NdcAxis {
    A,
    B,
    C,
}

/// Whether an axis moves along a line (mm) or turns (degrees).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum AxisKind {
    #[default]
    Linear,
    Rotary,
}

/// Which velocity-planning model the cycle-time estimator uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PlannerModel {
    /// Reproduces LinuxCNC 2.9's trajectory planner: trapezoidal profiles, arcs at
    /// half the tangential acceleration, 10 % acceleration cut at G61 corners, blend
    /// arcs for G64, a 1 ms servo period.
    #[default]
    Linuxcnc,
    /// Generic look-ahead planner with trapezoidal (constant acceleration) profiles.
    Trapezoid,
    /// Generic look-ahead planner with jerk-limited (S-curve) profiles.
    Scurve,
}

/// How G0 moves several axes at once.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum RapidPositioning {
    /// Straight line at the highest speed no axis's rapid rate forbids (LinuxCNC;
    /// FANUC LRP No. 1401#1 = 1; ServoWorks *G00 Perform Linear Interpolation* on).
    #[default]
    Linear,
    /// Each axis at its own rapid rate and acceleration, all starting together and
    /// each stopping when it arrives: the dog-leg path (FANUC non-linear
    /// positioning, LRP = 0; ServoWorks *G00 Perform Linear Interpolation* off).
    Independent,
}

table! {
    /// One entry of `machine.axes`: the keys it gives; the rest comes from the
    /// default axis.
    pub struct AxisConfig {
        letter: char = |v| {
            let s = string(v)?;
            let mut c = s.chars();
            match (c.next(), c.next()) {
                (Some(l), None) if l.is_ascii_alphabetic() => Ok(l.to_ascii_uppercase()),
                _ => Err(format!("`{s}` is not an axis letter")),
            }
        },
            values "`X`, `Y`, `Z`, `A`, …", default "`X`", "axis letter as used in programs";
        kind: AxisKind = |v| choice(v, &[("linear", AxisKind::Linear), ("rotary", AxisKind::Rotary)]),
            values "`linear`, `rotary`", default "`linear`", "whether the axis moves along a line (mm) or turns (degrees)";
        min_travel: f64 = number, values "mm or degrees", default "no limit", "lower travel limit, machine coordinates";
        max_travel: f64 = number, values "mm or degrees", default "no limit", "upper travel limit, machine coordinates";
        max_velocity: f64 = positive, values "units/s", default "100", "highest speed in coordinated (feed) motion";
        rapid_rate: f64 = positive, values "units/s", default "100", "rapid (G0) rate; LinuxCNC uses `max_velocity` for both";
        max_acceleration: f64 = positive, values "units/s²", default "1000", "acceleration limit";
        jerk: f64 = positive, values "units/s³", default "10000", "jerk limit, used only by the S-curve planner model";
        machine_unit: f64 = |v| number_in(v, 1e-9, 1.0), values "mm", default "0.001", "least input increment (ServoWorks machine unit)";
    }
}

table! {
    /// One entry of `machine.tools`, in mm.
    pub struct ToolConfig {
        length: f64 = number, values "mm", default "0", "tool length offset";
        diameter: f64 = non_negative, values "mm", default "0", "cutter diameter";
        radius: f64 = non_negative, values "mm", default "0", "cutter radius (instead of `diameter`)";
    }
}

/// The contents of a `partscope.toml`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Config {
    pub dialect: Option<Dialect>,
    /// Variant or profile: `S-100M`, `S-120M`, `S-140M`, `linuxcnc`, `emc2`, `30i`.
    pub variant: Option<Variant>,
    pub rules: RulesConfig,
    pub machine: MachineConfig,
    /// LinuxCNC files for the `rs274ngc` dialect (paths relative to the config file).
    pub ini: Option<String>,
    pub tool_table: Option<String>,
    pub var_file: Option<String>,
}

impl Config {
    /// Reads a configuration text. Never fails: every problem is an issue and the
    /// key it concerns keeps its default.
    pub fn load(text: &str) -> (Config, Vec<ConfigIssue>) {
        let table = match toml::from_str::<toml::Table>(text) {
            Ok(t) => t,
            Err(e) => {
                let issue = ConfigIssue {
                    key: String::new(),
                    span: e.span(),
                    message: format!(
                        "{}; the whole file is ignored",
                        e.message().trim_end_matches('\n')
                    ),
                    severity: Severity::Error,
                };
                return (Config::default(), vec![issue]);
            }
        };
        let spans = Spans::new(text);
        let mut issues = Vec::new();
        let config = Config::from_table(&table, &spans, &mut issues);
        // In the order of the file (tables iterate by key).
        issues.sort_by_key(|i| i.span.as_ref().map(|s| s.start));
        (config, issues)
    }

    /// Reads a configuration and refuses it on the first problem (tests and
    /// tools that want a strict reading).
    pub fn from_toml(text: &str) -> Result<Config, String> {
        let (config, issues) = Config::load(text);
        match issues.into_iter().next() {
            Some(i) => Err(i.message),
            None => Ok(config),
        }
    }

    fn from_table(table: &toml::Table, spans: &Spans, issues: &mut Vec<ConfigIssue>) -> Config {
        let mut top = TopKeys::default();
        let mut config = Config::default();
        for (key, value) in table {
            match key.as_str() {
                "rules" => {
                    config.rules = read_table(&["rules"], value, spans, issues).unwrap_or_default()
                }
                "machine" => {
                    config.machine =
                        read_table(&["machine"], value, spans, issues).unwrap_or_default()
                }
                _ => match top.set(key, value) {
                    Some(Ok(())) => {}
                    Some(Err(e)) => issues.push(bad_value(&[key], e, spans)),
                    None => {
                        // A machine key at the top level is a missing `[machine]` header.
                        let message = if MachineConfig::KEYS.iter().any(|k| k.name == key) {
                            format!("unknown key `{key}`: it belongs in the `[machine]` table (`machine.{key}`); ignored")
                        } else {
                            unknown_message(key, &top_level_names())
                        };
                        issues.push(ConfigIssue {
                            key: key.clone(),
                            span: spans.key(&[key]),
                            message,
                            severity: Severity::Warning,
                        });
                    }
                },
            }
        }
        config.dialect = top.dialect;
        config.variant = top.variant;
        config.ini = top.ini;
        config.tool_table = top.tool_table;
        config.var_file = top.var_file;
        config
    }
}

fn read_table<T: KeyTable>(
    path: &[&str],
    value: &toml::Value,
    spans: &Spans,
    issues: &mut Vec<ConfigIssue>,
) -> Option<T> {
    let Some(table) = value.as_table() else {
        issues.push(bad_value(path, "must be a table".into(), spans));
        return None;
    };
    let mut out = T::default();
    for (key, v) in table {
        let mut at: Vec<&str> = path.to_vec();
        at.push(key);
        match out.set(key, v) {
            Some(Ok(())) => {}
            Some(Err(e)) => issues.push(bad_value(&at, e, spans)),
            None => {
                let names: Vec<&str> = T::KEYS.iter().map(|k| k.name).collect();
                issues.push(ConfigIssue {
                    key: at.join("."),
                    span: spans.key(&at),
                    message: unknown_message(key, &names),
                    severity: Severity::Warning,
                })
            }
        }
    }
    Some(out)
}

impl MachineConfig {
    /// A `[machine]` table read alone (a machine profile file, an editor's
    /// inline table), with its issues.
    pub fn from_toml_table(table: &toml::Table) -> (MachineConfig, Vec<ConfigIssue>) {
        let mut issues = Vec::new();
        let value = toml::Value::Table(table.clone());
        let m = read_table(&["machine"], &value, &Spans::none(), &mut issues).unwrap_or_default();
        (m, issues)
    }

    /// A machine profile text: a `[machine]` table, or the keys alone.
    pub fn load(text: &str) -> (MachineConfig, Vec<ConfigIssue>) {
        match toml::from_str::<toml::Table>(text) {
            Ok(t) if t.contains_key("machine") => {
                let (c, issues) = Config::load(text);
                (c.machine, issues)
            }
            Ok(t) => {
                let mut issues = Vec::new();
                let spans = Spans::new(text);
                let value = toml::Value::Table(t);
                let m = read_table(&[], &value, &spans, &mut issues).unwrap_or_default();
                issues.sort_by_key(|i| i.span.as_ref().map(|s| s.start));
                (m, issues)
            }
            Err(_) => {
                let (c, issues) = Config::load(text);
                (c.machine, issues)
            }
        }
    }

    /// Reads a machine profile text and refuses it on the first problem (tests
    /// and tools that want a strict reading).
    pub fn from_toml(text: &str) -> Result<MachineConfig, String> {
        let (m, issues) = MachineConfig::load(text);
        match issues.into_iter().next() {
            Some(i) => Err(i.message),
            None => Ok(m),
        }
    }

    /// The G0 switch by whichever of its three names is given.
    pub fn rapid(&self) -> Option<RapidPositioning> {
        self.rapid_positioning
            .or(self.lrp)
            .or(self.g00_linear_interpolation)
    }

    /// Whether the table sets nothing.
    pub fn is_empty(&self) -> bool {
        *self == MachineConfig::default()
    }

    /// The keys the planner reads (the machine profile); the keys before them are
    /// the interpreter's and the host's.
    pub fn planner_keys() -> &'static [KeyDoc] {
        let split = MachineConfig::KEYS
            .iter()
            .position(|k| k.name == PLANNER_KEYS_FROM)
            .unwrap_or(MachineConfig::KEYS.len());
        &MachineConfig::KEYS[split..]
    }

    /// The axis letters the machine has, when the table lists axes.
    pub fn axis_letters(&self) -> Option<Vec<char>> {
        let axes = self.axes.as_ref()?;
        let letters: Vec<char> = axes.iter().filter_map(|a| a.letter).collect();
        (!letters.is_empty()).then_some(letters)
    }
}

/// The lowest severity that fails `check`, by the config.
pub fn fail_level(config: &Config) -> Severity {
    config.rules.fail_level.unwrap_or(Severity::Warning)
}

fn top_level_names() -> Vec<&'static str> {
    let mut names: Vec<&str> = TopKeys::KEYS.iter().map(|k| k.name).collect();
    names.extend(["rules", "machine"]);
    names
}

fn unknown_message(key: &str, names: &[&str]) -> String {
    format!("{} (ignored)", unknown_phrase(key, names))
}

fn unknown_phrase(key: &str, names: &[&str]) -> String {
    match nearest(key, names) {
        Some(n) => format!("unknown key `{key}`: did you mean `{n}`?"),
        None => format!("unknown key `{key}`; known keys: {}", names.join(", ")),
    }
}

/// The valid key closest to a typo, when it is close enough to be the intent.
fn nearest<'a>(key: &str, names: &[&'a str]) -> Option<&'a str> {
    let key = key.to_ascii_lowercase();
    names
        .iter()
        .map(|n| (strsim::damerau_levenshtein(&key, n), *n))
        .filter(|(d, n)| *d <= (n.len() / 3).max(2))
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n)
}

fn bad_value(path: &[&str], message: String, spans: &Spans) -> ConfigIssue {
    ConfigIssue {
        key: path.join("."),
        span: spans.value(path).or_else(|| spans.key(path)),
        message: format!("`{}`: {message} (the default is used)", path.join(".")),
        severity: Severity::Warning,
    }
}

type KeyValueSpans = (Option<Range<usize>>, Option<Range<usize>>);

/// Where keys and values are in the configuration text.
struct Spans(Option<toml_edit::ImDocument<String>>);

impl Spans {
    fn new(text: &str) -> Spans {
        Spans(toml_edit::ImDocument::parse(text.to_string()).ok())
    }

    fn none() -> Spans {
        Spans(None)
    }

    /// The spans of a key and of its value.
    fn lookup(&self, path: &[&str]) -> Option<KeyValueSpans> {
        let doc = self.0.as_ref()?;
        let mut table: &dyn toml_edit::TableLike = doc.as_table();
        let (last, parents) = path.split_last()?;
        for p in parents {
            table = table.get(p)?.as_table_like()?;
        }
        let (key, item) = table.get_key_value(last)?;
        // An array of tables (`[[machine.axes]]`) has no span of its own: its
        // first header stands for it.
        let value = item.span().or_else(|| {
            item.as_array_of_tables()?
                .iter()
                .next()
                .and_then(toml_edit::Table::span)
        });
        Some((key.span(), value))
    }

    fn key(&self, path: &[&str]) -> Option<Range<usize>> {
        self.lookup(path)?.0
    }

    fn value(&self, path: &[&str]) -> Option<Range<usize>> {
        self.lookup(path)?.1
    }
}

// Value readers: each says what it expected.

fn kind(v: &toml::Value) -> &'static str {
    v.type_str()
}

fn number(v: &toml::Value) -> Result<f64, String> {
    let n = match v {
        toml::Value::Float(f) => *f,
        toml::Value::Integer(i) => *i as f64,
        other => return Err(format!("expected a number, found {}", kind(other))),
    };
    if n.is_finite() {
        Ok(n)
    } else {
        Err(format!("{n} is not a finite number"))
    }
}

fn number_in(v: &toml::Value, lo: f64, hi: f64) -> Result<f64, String> {
    let n = number(v)?;
    if (lo..=hi).contains(&n) {
        Ok(n)
    } else {
        Err(format!("{n} must be between {lo} and {hi}"))
    }
}

fn non_negative(v: &toml::Value) -> Result<f64, String> {
    let n = number(v)?;
    if n >= 0.0 {
        Ok(n)
    } else {
        Err(format!("{n} must be 0 or more"))
    }
}

fn positive(v: &toml::Value) -> Result<f64, String> {
    let n = number(v)?;
    if n > 0.0 {
        Ok(n)
    } else {
        Err(format!("{n} must be greater than 0"))
    }
}

fn integer_in(v: &toml::Value, lo: i64, hi: i64) -> Result<i64, String> {
    match v {
        toml::Value::Integer(i) if (lo..=hi).contains(i) => Ok(*i),
        toml::Value::Integer(i) => Err(format!("{i} must be between {lo} and {hi}")),
        other => Err(format!("expected an integer, found {}", kind(other))),
    }
}

fn one_of_integers<T: TryFrom<i64>>(v: &toml::Value, allowed: &[i64]) -> Result<T, String> {
    let n = integer_in(v, i64::MIN, i64::MAX)?;
    match T::try_from(n) {
        Ok(t) if allowed.contains(&n) => Ok(t),
        _ => {
            let list: Vec<String> = allowed.iter().map(i64::to_string).collect();
            Err(format!("{n} is not one of {}", list.join(", ")))
        }
    }
}

fn boolean(v: &toml::Value) -> Result<bool, String> {
    v.as_bool()
        .ok_or_else(|| format!("expected true or false, found {}", kind(v)))
}

fn string(v: &toml::Value) -> Result<String, String> {
    v.as_str()
        .map(str::to_string)
        .ok_or_else(|| format!("expected a string, found {}", kind(v)))
}

fn strings(v: &toml::Value) -> Result<Vec<String>, String> {
    let a = v
        .as_array()
        .ok_or_else(|| format!("expected a list of strings, found {}", kind(v)))?;
    a.iter().map(string).collect()
}

fn integers(v: &toml::Value) -> Result<Vec<i64>, String> {
    let a = v
        .as_array()
        .ok_or_else(|| format!("expected a list of integers, found {}", kind(v)))?;
    a.iter()
        .map(|x| integer_in(x, i64::MIN, i64::MAX))
        .collect()
}

fn path_list(v: &toml::Value) -> Result<Vec<String>, String> {
    match v {
        toml::Value::String(s) => Ok(s.split(':').map(str::to_string).collect()),
        toml::Value::Array(_) => strings(v),
        other => Err(format!(
            "expected a path or a list of paths, found {}",
            kind(other)
        )),
    }
}

/// A case-insensitive choice among named values.
fn choice<T: Copy>(v: &toml::Value, names: &[(&str, T)]) -> Result<T, String> {
    let s = string(v)?;
    names
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(s.trim()))
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            let list: Vec<String> = names.iter().map(|(n, _)| format!("`{n}`")).collect();
            format!("`{s}` is not one of {}", list.join(", "))
        })
}

fn dialect(v: &toml::Value) -> Result<Dialect, String> {
    let s = string(v)?;
    Dialect::parse(&s).ok_or_else(|| format!("unknown dialect `{s}` (servoworks, rs274ngc, fanuc)"))
}

fn variant(v: &toml::Value) -> Result<Variant, String> {
    let s = string(v)?;
    Variant::parse(&s).ok_or_else(|| {
        format!("unknown variant `{s}` (S-100M, S-120M, S-140M, linuxcnc, emc2, 30i)")
    })
}

fn severity(v: &toml::Value) -> Result<Severity, String> {
    let s = string(v)?;
    Severity::parse(&s).ok_or_else(|| format!("`{s}` is not one of error, warning, info, hint"))
}

fn drill_shift(v: &toml::Value) -> Result<DrillShift, String> {
    choice(
        v,
        &[
            ("+x", DrillShift::PlusX),
            ("x", DrillShift::PlusX),
            ("-x", DrillShift::MinusX),
            ("+y", DrillShift::PlusY),
            ("y", DrillShift::PlusY),
            ("-y", DrillShift::MinusY),
            ("none", DrillShift::None),
            ("off", DrillShift::None),
            ("0", DrillShift::None),
        ],
    )
}

/// Reads the entries of a nested table; a bad entry is an error for the whole key.
fn nested<T: KeyTable>(v: &toml::Value) -> Result<T, String> {
    let t = v
        .as_table()
        .ok_or_else(|| format!("expected a table, found {}", kind(v)))?;
    let mut out = T::default();
    for (k, x) in t {
        match out.set(k, x) {
            Some(Ok(())) => {}
            Some(Err(e)) => return Err(format!("`{k}`: {e}")),
            None => {
                let names: Vec<&str> = T::KEYS.iter().map(|k| k.name).collect();
                return Err(unknown_phrase(k, &names));
            }
        }
    }
    Ok(out)
}

fn axes(v: &toml::Value) -> Result<Vec<AxisConfig>, String> {
    let a = v
        .as_array()
        .ok_or_else(|| format!("expected an array of axes, found {}", kind(v)))?;
    let one = |entry: &toml::Value| match entry {
        toml::Value::String(_) => {
            let mut axis = AxisConfig::default();
            axis.set("letter", entry).transpose()?;
            Ok(axis)
        }
        _ => {
            let axis = nested::<AxisConfig>(entry)?;
            match (axis.min_travel, axis.max_travel) {
                (Some(lo), Some(hi)) if lo > hi => Err(format!(
                    "`min_travel` = {lo} must not exceed `max_travel` = {hi}"
                )),
                _ => Ok(axis),
            }
        }
    };
    a.iter()
        .enumerate()
        .map(|(i, entry)| one(entry).map_err(|e| format!("axis {}: {e}", i + 1)))
        .collect()
}

fn six(v: &toml::Value) -> Result<[f64; 6], String> {
    let a = v
        .as_array()
        .ok_or_else(|| format!("expected an array of up to six numbers, found {}", kind(v)))?;
    if a.len() > 6 {
        return Err(format!("{} values for six axes (X Y Z A B C)", a.len()));
    }
    let mut out = [0.0; 6];
    for (slot, x) in out.iter_mut().zip(a) {
        *slot = number(x)?;
    }
    Ok(out)
}

fn work_offsets(v: &toml::Value) -> Result<BTreeMap<usize, [f64; 6]>, String> {
    const NAMES: [&str; 9] = [
        "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3",
    ];
    let t = v
        .as_table()
        .ok_or_else(|| format!("expected a table, found {}", kind(v)))?;
    let mut out = BTreeMap::new();
    for (k, x) in t {
        let Some(i) = NAMES.iter().position(|n| n.eq_ignore_ascii_case(k)) else {
            return Err(unknown_phrase(k, &NAMES));
        };
        out.insert(i + 1, six(x).map_err(|e| format!("`{k}`: {e}"))?);
    }
    Ok(out)
}

fn reference_positions(v: &toml::Value) -> Result<BTreeMap<usize, [f64; 6]>, String> {
    let t = v
        .as_table()
        .ok_or_else(|| format!("expected a table, found {}", kind(v)))?;
    let mut out = BTreeMap::new();
    for (k, x) in t {
        match k.trim().parse::<usize>() {
            Ok(n @ 1..=4) => {
                out.insert(n, six(x).map_err(|e| format!("`{k}`: {e}"))?);
            }
            _ => return Err(format!("`{k}` is not a reference position (1 to 4)")),
        }
    }
    Ok(out)
}

fn tools(v: &toml::Value) -> Result<BTreeMap<u32, ToolConfig>, String> {
    let t = v
        .as_table()
        .ok_or_else(|| format!("expected a table, found {}", kind(v)))?;
    let mut out = BTreeMap::new();
    for (k, x) in t {
        let n = k
            .trim_start_matches(['T', 't'])
            .parse::<u32>()
            .map_err(|_| format!("`{k}` is not a tool (`T1`, `T2`, …)"))?;
        let tool = nested::<ToolConfig>(x).map_err(|e| format!("`{k}`: {e}"))?;
        out.insert(n, tool);
    }
    Ok(out)
}

fn m_code_times(v: &toml::Value) -> Result<BTreeMap<String, f64>, String> {
    let t = v
        .as_table()
        .ok_or_else(|| format!("expected a table, found {}", kind(v)))?;
    let mut out = BTreeMap::new();
    for (k, x) in t {
        let is_code = k
            .trim()
            .trim_start_matches(['M', 'm'])
            .parse::<f64>()
            .is_ok();
        if !is_code {
            return Err(format!("`{k}` is not an M code (`M10`, `M19.1`, …)"));
        }
        out.insert(
            k.clone(),
            non_negative(x).map_err(|e| format!("`{k}`: {e}"))?,
        );
    }
    Ok(out)
}

/// `docs/configuration.md`, generated from the declarations above; a test keeps
/// the committed file equal to it.
pub fn reference_markdown() -> String {
    let mut out = String::from(REFERENCE_HEAD);
    let table =
        |out: &mut String, title: &str, header: &str, keys: &mut dyn Iterator<Item = &KeyDoc>| {
            out.push_str(&format!(
                "## {title}\n\n| key | values | default{header} | meaning |\n|---|---|---|---|\n"
            ));
            for k in keys {
                out.push_str(&format!(
                    "| `{}` | {} | {} | {} |\n",
                    k.name, k.values, k.default, k.meaning
                ));
            }
            out.push('\n');
        };
    table(&mut out, "Top level", "", &mut TopKeys::KEYS.iter());
    table(&mut out, "`[rules]`", "", &mut RulesConfig::KEYS.iter());
    out.push_str(REFERENCE_RULES_TAIL);
    let planner = MachineConfig::planner_keys();
    let interp = &MachineConfig::KEYS[..MachineConfig::KEYS.len() - planner.len()];
    table(
        &mut out,
        "`[machine]`: what the interpreter and the host read",
        "",
        &mut interp.iter(),
    );
    table(
        &mut out,
        "`[machine]`: what the planner reads (cycle time)",
        " (all dialects unless noted)",
        &mut planner.iter(),
    );
    table(
        &mut out,
        "`[[machine.axes]]` entries",
        "",
        &mut AxisConfig::KEYS.iter(),
    );
    table(
        &mut out,
        "`[machine.tools]` entries",
        "",
        &mut ToolConfig::KEYS.iter(),
    );
    out.push_str(REFERENCE_TAIL);
    out
}

const REFERENCE_HEAD: &str = "# `partscope.toml` reference

<!-- Generated from analyzer/src/config.rs: edit the declarations there, then run
     PARTSCOPE_UPDATE_DOCS=1 cargo test -p analyzer --test config_docs -->

`partscope check`, `partscope run` and `partscope lsp` read the nearest `partscope.toml`,
searched upward from each program (or the file given with `--config`). Every key is
optional; a missing key keeps the default shown here. Lengths are millimetres, times seconds,
angles degrees, unless the table says otherwise.

An unknown key (with the nearest valid key when it looks like a typo), a machine key outside
`[machine]`, or a value of the wrong type or outside its range is reported at the key or value,
and the key keeps its default. `partscope check` reports these as warnings of rule L016 in the
configuration file itself, once, in every output format (`--ignore L016` or `[rules] ignore`
turns them off); `partscope run` prints them on stderr, located (`partscope.toml:LINE:COL`); the
language server shows them once, as a message. A file that is not TOML at all stops `check`
and `run` with exit status 2, located.

";

const REFERENCE_RULES_TAIL: &str =
    "Per block: `(partscope: allow CODE, CODE)`; per file: `(partscope: allow-file CODE)`.\n\n";

const REFERENCE_TAIL: &str = "An auxiliary event whose time is 0 does not stop the motion (the spindle, tool change and stop
events stop it whatever their time, as before). G31 (FANUC/ServoWorks skip) and G38.x are timed
as feed moves at F. Beside a LinuxCNC `ini`, the config's own `[machine]` keys other than `axes`
(times, overrides, `planner`) apply over the `ini`'s limits.

Example profiles with typical, non-zero times: `examples/machines/vmc.toml` (a small FANUC
VMC), `examples/machines/router.toml` (a ServoWorks gantry router) and
`examples/machines/linuxcnc-mill/` (a LinuxCNC `mill.ini` with the shop's times in its
`partscope.toml`, used with `--config`). `partscope run` names the profile it used (`machine`
line, JSON `machine_profile`); without one it says `built-in <dialect> default (no tool-change
or spindle times)`.

## Language server options

`initializationOptions` or the `partscope` section of `workspace/configuration`:
`dialect`, `machine` (an inline table or a path to a TOML profile), `select`, `ignore`,
`maxFileSize` (bytes; above it a document is only parsed, default 64 MB), `maxRunFileSize`
(bytes; above it the interpreter runs only on request, default 32 MB: a diagnostic at the top
of the file and the lens say so), `maxToolpathPoints` (the most toolpath points a
`partscope/dryRun` answer holds, default 100 000; `editors/README.md`) and
`blockTimes` (`block`, the default: an inlay hint with each block's own time, its causes as
the tooltip; `cumulative`: the program time when the block ends; `off`).
`format` sets the defaults of document formatting: `numbers` (`keep`, `renumber`, `add`,
`remove`; default `keep`), `start` and `step` (10, 10), `spacing` (`keep`, `one`, `none`;
default `one`) and `uppercase` (default true; never applied to ServoWorks, which ignores
lower-case words). A formatting request's `partscope.numbers`, `partscope.start`, … properties
override them. Formatting never changes what the control runs: comments and the inside of
every word stay as written, FANUC `GOTO` targets are renumbered with their blocks (and kept
when numbers are removed), and it refuses, saying why, where it cannot be sure (a computed
`GOTO #1`, an `M99 P` return, a block number past five digits).
For the files below it, a `partscope.toml` in the workspace takes precedence: its `dialect` over the client's, its `[machine]` table over the client's `machine`; `select`/`ignore` add to its own.

The environment variable `PARTSCOPE_LSP_MAX_MESSAGE_BYTES` caps the size of one message body
the server accepts (default 256 MiB; the limit applies before any option arrives). A larger
message is skipped as it streams in and, when it is a request, answered with error -32600.

`PARTSCOPE_LSP_TIMING=1` is a diagnostic aid: the server then writes to its standard error
how long each analysis, interpreter run and planner took, the process's memory (`VmRSS`,
`VmHWM`) and each publish. It changes nothing else; `scripts/lsp_edit_runs.py` reads these
lines.
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_keys_are_read() {
        let (c, issues) = Config::load(
            "dialect = \"servoworks\"\nvariant = \"S-100M\"\n[machine]\ncircle_error_allowance = 0.01\nlookahead = 40\naxes = [\"X\", { letter = \"a\", kind = \"rotary\" }]\n[rules]\nignore = [\"L008\"]\nfail_level = \"error\"\n",
        );
        assert_eq!(issues, vec![]);
        assert_eq!(c.dialect, Some(Dialect::Servoworks));
        assert_eq!(c.variant, Some(Variant::S100M));
        assert_eq!(c.machine.circle_error_allowance, Some(0.01));
        assert_eq!(c.machine.lookahead, Some(40));
        assert_eq!(c.machine.axis_letters(), Some(vec!['X', 'A']));
        assert_eq!(
            c.machine.axes.as_ref().and_then(|a| a[1].kind),
            Some(AxisKind::Rotary)
        );
        assert_eq!(c.rules.ignore, Some(vec!["L008".to_string()]));
        assert_eq!(fail_level(&c), Severity::Error);
    }

    #[test]
    fn a_typo_names_the_nearest_key_at_its_place() {
        let text = "[machine]\nlookahaed = 40\ntool_change_time = 2\n";
        let (c, issues) = Config::load(text);
        assert_eq!(issues.len(), 1);
        let i = &issues[0];
        assert_eq!(i.key, "machine.lookahaed");
        assert_eq!(
            i.message,
            "unknown key `lookahaed`: did you mean `lookahead`? (ignored)"
        );
        assert_eq!(i.span.clone().map(|s| &text[s]), Some("lookahaed"));
        // The rest of the table still applies.
        assert_eq!(c.machine.tool_change_time, Some(2.0));
    }

    #[test]
    fn every_bad_value_is_reported_and_keeps_its_default() {
        let text = "[machine]\nfeed_override = 20\nlookahead = \"many\"\nplanner = \"fast\"\ncoolant_time = 1.5\n";
        let (c, issues) = Config::load(text);
        let got: Vec<(&str, &str)> = issues
            .iter()
            .map(|i| (i.key.as_str(), &text[i.span.clone().unwrap_or(0..0)]))
            .collect();
        assert_eq!(
            got,
            vec![
                ("machine.feed_override", "20"),
                ("machine.lookahead", "\"many\""),
                ("machine.planner", "\"fast\""),
            ]
        );
        assert_eq!(
            issues[0].message,
            "`machine.feed_override`: 20 must be between 0.001 and 10 (the default is used)"
        );
        assert_eq!(c.machine.feed_override, None);
        assert_eq!(c.machine.coolant_time, Some(1.5));
    }

    #[test]
    fn a_machine_key_at_the_top_level_points_at_the_table() {
        let (_, issues) = Config::load("lookahead = 40\n");
        assert_eq!(
            issues[0].message,
            "unknown key `lookahead`: it belongs in the `[machine]` table (`machine.lookahead`); ignored"
        );
    }

    #[test]
    fn a_syntax_error_is_located_and_ignores_the_file() {
        let text = "dialect = \"fanuc\"\n[machine\n";
        let (c, issues) = Config::load(text);
        assert_eq!(c, Config::default());
        assert_eq!(issues.len(), 1);
        assert_eq!(issues[0].severity, Severity::Error);
        let at = issues[0].span.clone().map(|s| s.start);
        assert!(at.is_some_and(|s| s >= text.find("[machine").unwrap_or(0)));
    }

    #[test]
    fn the_g0_switch_has_three_names_in_order() {
        let (c, _) = Config::load("[machine]\nlrp = 1\ng00_linear_interpolation = false\n");
        assert_eq!(c.machine.rapid(), Some(RapidPositioning::Linear));
        let (c, _) = Config::load("[machine]\nlrp = 1\nrapid_positioning = \"independent\"\n");
        assert_eq!(c.machine.rapid(), Some(RapidPositioning::Independent));
    }

    #[test]
    fn nested_entries_are_checked() {
        let (c, issues) = Config::load(
            "[machine]\ntools = { T1 = { length = 10, diamter = 6 } }\nwork_offsets = { G54 = [1, 2, 3] }\n",
        );
        assert_eq!(issues.len(), 1);
        assert_eq!(
            issues[0].message,
            "`machine.tools`: `T1`: unknown key `diamter`: did you mean `diameter`? (the default is used)"
        );
        assert_eq!(c.machine.tools, None);
        assert_eq!(
            c.machine.work_offsets.as_ref().and_then(|w| w.get(&1)),
            Some(&[1.0, 2.0, 3.0, 0.0, 0.0, 0.0])
        );
    }

    #[test]
    fn editor_tables_are_read_without_spans() {
        let mut t = toml::Table::new();
        t.insert("lookahead".into(), toml::Value::Integer(-1));
        let (m, issues) = MachineConfig::from_toml_table(&t);
        assert_eq!(m.lookahead, None);
        assert_eq!(issues.len(), 1);
        assert_eq!(issues[0].span, None);
    }
}
