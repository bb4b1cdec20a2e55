//! Machine profile: the controller and machine parameters that the planner and the
//! interpreter need (axes, limits, tolerances, non-motion times).
//!
//! The profile is the `[machine]` section of `partscope.toml`. Every field has a
//! default, so a profile only needs to state what differs from
//! [`MachineProfile::default_for`]. For the `rs274ngc` dialect a LinuxCNC `.ini`
//! file can be read directly with [`MachineProfile::from_linuxcnc_ini`].
//!
//! All lengths are millimetres and all times seconds, whatever the machine's own
//! units: the `.ini` reader converts inch machines on the way in.

use analyzer::Dialect;
use serde::{Deserialize, Serialize};

use analyzer::config::{AxisConfig, MachineConfig};
pub use analyzer::config::{AxisKind, PlannerModel, RapidPositioning};

/// One machine axis. Velocities are units/s, accelerations units/s², jerk units/s³,
/// where units are mm for linear and degrees for rotary axes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Axis {
    /// Axis letter as used in programs (`X`, `Y`, `Z`, `A`, `B`, `C`, …).
    pub letter: char,
    pub kind: AxisKind,
    pub min_travel: f64,
    pub max_travel: f64,
    /// Highest speed of this axis in coordinated (feed) motion.
    pub max_velocity: f64,
    /// Rapid (G0) rate of this axis; LinuxCNC uses `max_velocity` for both.
    pub rapid_rate: f64,
    pub max_acceleration: f64,
    /// Jerk limit, used only by the S-curve planner model.
    pub jerk: f64,
    /// Least input increment (ServoWorks "machine unit").
    pub machine_unit: f64,
}

impl Default for Axis {
    fn default() -> Self {
        Axis {
            letter: 'X',
            kind: AxisKind::Linear,
            min_travel: -1.0e9,
            max_travel: 1.0e9,
            max_velocity: 100.0,
            rapid_rate: 100.0,
            max_acceleration: 1000.0,
            jerk: 10_000.0,
            machine_unit: 0.001,
        }
    }
}

impl Axis {
    /// This axis as a `machine.axes` entry that gives every field.
    pub fn as_config(&self) -> AxisConfig {
        AxisConfig {
            letter: Some(self.letter),
            kind: Some(self.kind),
            min_travel: Some(self.min_travel),
            max_travel: Some(self.max_travel),
            max_velocity: Some(self.max_velocity),
            rapid_rate: Some(self.rapid_rate),
            max_acceleration: Some(self.max_acceleration),
            jerk: Some(self.jerk),
            machine_unit: Some(self.machine_unit),
        }
    }

    /// A linear axis with the given letter and limits (rapid rate = max velocity).
    pub fn linear(letter: char, max_velocity: f64, max_acceleration: f64) -> Axis {
        Axis {
            letter,
            max_velocity,
            rapid_rate: max_velocity,
            max_acceleration,
            ..Axis::default()
        }
    }

    /// A rotary axis (degrees) with the given letter and limits.
    pub fn rotary(letter: char, max_velocity: f64, max_acceleration: f64) -> Axis {
        Axis {
            letter,
            kind: AxisKind::Rotary,
            max_velocity,
            rapid_rate: max_velocity,
            max_acceleration,
            jerk: max_acceleration * 10.0,
            ..Axis::default()
        }
    }
}

/// The controller a model reproduces, as measured (`tests/cycle_time`).
pub fn model_reference(model: PlannerModel) -> Option<&'static str> {
    match model {
        PlannerModel::Linuxcnc => Some(LINUXCNC_REFERENCE),
        PlannerModel::Trapezoid | PlannerModel::Scurve => None,
    }
}

/// The LinuxCNC the `linuxcnc` model was measured against: Debian's
/// `linuxcnc-uspace` package, its trajectory planner module and servo period.
pub const LINUXCNC_REFERENCE: &str =
    "LinuxCNC 2.9.0~pre1+git20230208.f1270d6ed7 (commit f1270d6ed715), tpmod, servo period 1 ms";

/// Machine and controller parameters used by the interpreter and the planner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MachineProfile {
    pub axes: Vec<Axis>,
    /// Cap on the Cartesian (XYZ) path speed, mm/s (LinuxCNC `[TRAJ]MAX_LINEAR_VELOCITY`).
    pub traj_max_velocity: f64,
    /// Cap on the path acceleration, mm/s². LinuxCNC does not apply it to
    /// coordinated moves (measured), so the `linuxcnc` model ignores it.
    pub traj_max_acceleration: f64,
    /// Minimum time the control spends per motion block, s (0 = none): shorter
    /// moves are slowed down to take this long.
    pub block_processing_time: f64,
    /// G0 path: `linear` or `independent` (dog-leg). FANUC: parameter No. 1401#1
    /// LRP, 0 (the default) = non-linear positioning, each axis at its own rapid
    /// rate, 1 = linear interpolation positioning (spec/fanuc.md §5.1 from [R10]
    /// sheet 9 and [R11] sheet 16; the 30i manual's safety precautions warn that
    /// non-linear positioning leaves the line between the end points).
    /// ServoWorks: *G00 Perform Linear Interpolation* (manual §6.3.1, p. 6-7;
    /// Reference Manual §3.4.2); the manual gives no default and calls the
    /// disabled state "normal rapid traverse", so `independent` is the default.
    /// RS274/NGC (LinuxCNC): `linear`. Also set by `lrp = 0 | 1` (FANUC) and
    /// `g00_linear_interpolation = true | false` (ServoWorks).
    pub rapid_positioning: RapidPositioning,
    /// Duration of a tool change (M6; ServoWorks: the T word), s.
    pub tool_change_time: f64,
    /// Tool pre-selection (a T word without M6: FANUC, RS274/NGC), s. Counted only
    /// when the control waits for it; 0 for a changer that selects while cutting.
    pub tool_select_time: f64,
    /// Fixed part of every spindle start (M3/M4), stop (M5) and speed change, s.
    pub spindle_ramp_time: f64,
    /// Spindle acceleration: seconds per 1000 rpm of speed change (a start from
    /// rest to S, a stop from S, an S change while turning, a reversal through 0).
    pub spindle_ramp_per_1000rpm: f64,
    /// Spindle orientation (M19), s.
    pub spindle_orient_time: f64,
    /// Coolant switching (M7, M8, M9), s.
    pub coolant_time: f64,
    /// Pallet change, s (the M code `pallet_change_m`).
    pub pallet_change_time: f64,
    /// M code number of the pallet change: LinuxCNC M60 (pallet shuttle, then a
    /// program stop); on FANUC and ServoWorks the machine builder chooses it.
    pub pallet_change_m: u32,
    /// Time for any other M code (one that waits for a machine handshake), s.
    pub m_code_time: f64,
    /// Times of particular M codes, s: `m_code_times = { M10 = 0.5, M11 = 0.5 }`;
    /// codes not listed take `m_code_time`.
    pub m_code_times: std::collections::BTreeMap<String, f64>,
    /// Time charged for a program stop (M0) or optional stop (M1), s: operator
    /// time, reported apart from the machine's own auxiliary time.
    pub program_stop_time: f64,
    /// Settling time added at every exact stop (FANUC in-position check), s.
    /// Applied by the generic models and the closed-form `linuxcnc` execution.
    pub in_position_time: f64,
    pub planner: PlannerModel,
    /// Number of segments the planner looks ahead (LinuxCNC
    /// `[TRAJ]ARC_BLEND_OPTIMIZATION_DEPTH`).
    pub lookahead: u32,
    /// Blend tolerance used for G64 without P, mm (0 = as large as the geometry allows).
    pub default_blend_tolerance: f64,
    /// Servo / interpolation period, s.
    pub servo_period: f64,
    /// Feed override applied to feed moves (1.0 = 100 %).
    pub feed_override: f64,
    /// Override applied to rapid moves (1.0 = 100 %).
    pub rapid_override: f64,
    /// LinuxCNC `[TRAJ]ARC_BLEND_KINK_RATIO`: acceleration share given up at
    /// corners that are not blended.
    pub tangent_kink_ratio: f64,
    /// `linuxcnc` model: execute period by period like LinuxCNC's servo thread
    /// (default; matches LinuxCNC to the period, cost proportional to machine time)
    /// instead of with closed-form profiles (cost proportional to the number of
    /// moves; up to 0.5 % off where short moves sit at the ramp threshold).
    pub servo_simulation: bool,
}

impl Default for MachineProfile {
    fn default() -> Self {
        MachineProfile::default_for(Dialect::Rs274ngc)
    }
}

/// Values of a LinuxCNC `.ini` that the host must resolve (paths are as written,
/// relative to the `.ini` file's directory).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct IniExtras {
    /// `[EMCIO]TOOL_TABLE`.
    pub tool_table: Option<String>,
    /// `[RS274NGC]PARAMETER_FILE`.
    pub parameter_file: Option<String>,
    /// `[TRAJ]LINEAR_UNITS` as written (`mm`, `inch`, …).
    pub linear_units: Option<String>,
}

impl MachineProfile {
    /// The documented default machine for a dialect: a 3-axis mill with 100 mm/s and
    /// 1000 mm/s² per axis (the LinuxCNC oracle's default machine), planner model
    /// and tolerances as the dialect's control behaves.
    pub fn default_for(dialect: Dialect) -> MachineProfile {
        let axes = vec![
            Axis::linear('X', 100.0, 1000.0),
            Axis::linear('Y', 100.0, 1000.0),
            Axis::linear('Z', 100.0, 1000.0),
        ];
        let base = MachineProfile {
            axes,
            traj_max_velocity: 100.0,
            traj_max_acceleration: 1000.0,
            block_processing_time: 0.0,
            rapid_positioning: RapidPositioning::Linear,
            tool_change_time: 0.0,
            tool_select_time: 0.0,
            spindle_ramp_time: 0.0,
            spindle_ramp_per_1000rpm: 0.0,
            spindle_orient_time: 0.0,
            coolant_time: 0.0,
            pallet_change_time: 0.0,
            pallet_change_m: 60,
            m_code_time: 0.0,
            m_code_times: std::collections::BTreeMap::new(),
            program_stop_time: 0.0,
            in_position_time: 0.0,
            planner: PlannerModel::Trapezoid,
            lookahead: 50,
            default_blend_tolerance: 0.0,
            servo_period: 0.001,
            feed_override: 1.0,
            rapid_override: 1.0,
            tangent_kink_ratio: 0.1,
            servo_simulation: true,
        };
        match dialect {
            // LinuxCNC 2.9: the optimisation depth default is 50 segments.
            Dialect::Rs274ngc => MachineProfile {
                planner: PlannerModel::Linuxcnc,
                ..base
            },
            // FANUC AI contour control looks 40 blocks ahead; LRP (No. 1401#1) is 0.
            Dialect::Fanuc => MachineProfile {
                lookahead: 40,
                rapid_positioning: RapidPositioning::Independent,
                ..base
            },
            // ServoWorks TRC/DLACC buffers 100 blocks; G00 is "normal rapid
            // traverse" unless linear interpolation is enabled.
            Dialect::Servoworks => MachineProfile {
                lookahead: 100,
                rapid_positioning: RapidPositioning::Independent,
                ..base
            },
        }
    }

    /// Reads a machine profile text (a `[machine]` table, or its keys alone)
    /// over the dialect's defaults, refusing it on the first problem (tests and
    /// tools; hosts read the configuration with [`analyzer::Config::load`]).
    pub fn from_toml(text: &str, dialect: Dialect) -> Result<MachineProfile, String> {
        let (m, issues) = MachineConfig::load(text);
        if let Some(i) = issues.into_iter().next() {
            return Err(i.message);
        }
        let profile = MachineProfile::default_for(dialect).with(&m);
        profile.check_ranges()?;
        Ok(profile)
    }

    /// This profile with the planner keys a `[machine]` table gives: a LinuxCNC
    /// `.ini`'s limits with the configuration's tool-change and spindle times,
    /// for example. Axis entries give only some fields (`letter`, travel
    /// limits…); the rest comes from this profile's first axis.
    pub fn with(&self, m: &MachineConfig) -> MachineProfile {
        let mut p = self.clone();
        if let Some(axes) = &m.axes {
            let base = self.axes.first().cloned().unwrap_or_default();
            p.axes = axes.iter().map(|a| axis_over(&base, a)).collect();
        }
        macro_rules! take {
            ($($key:ident),*) => {$( if let Some(v) = m.$key.clone() { p.$key = v; } )*};
        }
        take!(
            traj_max_velocity,
            traj_max_acceleration,
            block_processing_time,
            tool_change_time,
            tool_select_time,
            spindle_ramp_time,
            spindle_ramp_per_1000rpm,
            spindle_orient_time,
            coolant_time,
            pallet_change_time,
            pallet_change_m,
            m_code_time,
            m_code_times,
            program_stop_time,
            in_position_time,
            planner,
            lookahead,
            default_blend_tolerance,
            servo_period,
            feed_override,
            rapid_override,
            tangent_kink_ratio,
            servo_simulation
        );
        if let Some(r) = m.rapid() {
            p.rapid_positioning = r;
        }
        p
    }

    /// Seconds an M code (`tenths`: its number × 10, 190 for M19) takes by
    /// `m_code_times`, else `m_code_time`.
    pub fn m_code_seconds(&self, tenths: u32) -> f64 {
        let number = f64::from(tenths) / 10.0;
        self.m_code_times
            .iter()
            .find(|(k, _)| {
                k.trim()
                    .trim_start_matches(['M', 'm'])
                    .parse::<f64>()
                    .is_ok_and(|n| (n - number).abs() < 1e-6)
            })
            .map(|(_, v)| *v)
            .unwrap_or(self.m_code_time)
    }

    /// The axis with this letter (case-insensitive).
    pub fn axis(&self, letter: char) -> Option<&Axis> {
        let l = letter.to_ascii_uppercase();
        self.axes
            .iter()
            .find(|a| a.letter.to_ascii_uppercase() == l)
    }

    /// Velocity, acceleration limits of the six program axes X Y Z A B C; an axis
    /// the machine lacks gets 0 (meaning "not present").
    /// Every value outside the range the planner can use, each named by its key
    /// (`Err` lists them all, `; `-separated). A negative feed cap or a NaN time
    /// would make every cycle time meaningless rather than fail visibly.
    pub fn check_ranges(&self) -> Result<(), String> {
        fn positive(bad: &mut Vec<String>, key: &str, v: f64) {
            if v.is_nan() || v <= 0.0 {
                bad.push(format!("`{key}` = {v} must be greater than 0"));
            }
        }
        fn in_range(bad: &mut Vec<String>, key: &str, v: f64, (lo, hi): (f64, f64), what: &str) {
            if !(lo..=hi).contains(&v) {
                bad.push(format!("`{key}` = {v} must be {what}"));
            }
        }
        const TIME: (f64, f64) = (0.0, f64::MAX);
        const OVERRIDE: (f64, f64) = (1e-3, 10.0);
        let mut bad = Vec::new();
        positive(&mut bad, "traj_max_velocity", self.traj_max_velocity);
        positive(
            &mut bad,
            "traj_max_acceleration",
            self.traj_max_acceleration,
        );
        for (key, v) in [
            ("tool_change_time", self.tool_change_time),
            ("tool_select_time", self.tool_select_time),
            ("spindle_ramp_time", self.spindle_ramp_time),
            ("spindle_ramp_per_1000rpm", self.spindle_ramp_per_1000rpm),
            ("spindle_orient_time", self.spindle_orient_time),
            ("coolant_time", self.coolant_time),
            ("pallet_change_time", self.pallet_change_time),
            ("m_code_time", self.m_code_time),
            ("program_stop_time", self.program_stop_time),
            ("in_position_time", self.in_position_time),
            ("block_processing_time", self.block_processing_time),
            ("default_blend_tolerance", self.default_blend_tolerance),
        ] {
            in_range(&mut bad, key, v, TIME, "0 or more (and finite)");
        }
        for (code, v) in &self.m_code_times {
            let key = format!("m_code_times.{code}");
            in_range(&mut bad, &key, *v, TIME, "0 or more (and finite)");
        }
        // The servo simulation costs one step per period of machine time.
        let (period, fo, ro) = (self.servo_period, self.feed_override, self.rapid_override);
        in_range(
            &mut bad,
            "servo_period",
            period,
            (1e-5, 1.0),
            "between 0.00001 and 1 s",
        );
        in_range(
            &mut bad,
            "feed_override",
            fo,
            OVERRIDE,
            "between 0.001 and 10 (1 = 100 %)",
        );
        in_range(
            &mut bad,
            "rapid_override",
            ro,
            OVERRIDE,
            "between 0.001 and 10 (1 = 100 %)",
        );
        let kink = self.tangent_kink_ratio;
        in_range(
            &mut bad,
            "tangent_kink_ratio",
            kink,
            (0.0, 1.0),
            "between 0 and 1",
        );
        if self.lookahead > 100_000 {
            bad.push(format!(
                "`lookahead` = {} must be at most 100000 segments",
                self.lookahead
            ));
        }
        for a in &self.axes {
            let l = a.letter;
            positive(&mut bad, &format!("axes.{l}.max_velocity"), a.max_velocity);
            positive(&mut bad, &format!("axes.{l}.rapid_rate"), a.rapid_rate);
            positive(
                &mut bad,
                &format!("axes.{l}.max_acceleration"),
                a.max_acceleration,
            );
            positive(&mut bad, &format!("axes.{l}.jerk"), a.jerk);
            let key = format!("axes.{l}.machine_unit");
            in_range(
                &mut bad,
                &key,
                a.machine_unit,
                (1e-9, 1.0),
                "between 0.000000001 and 1",
            );
            if a.min_travel.is_nan() || a.max_travel.is_nan() || a.min_travel > a.max_travel {
                bad.push(format!(
                    "axes.{l}: `min_travel` = {} must not exceed `max_travel` = {}",
                    a.min_travel, a.max_travel
                ));
            }
        }
        if bad.is_empty() {
            Ok(())
        } else {
            Err(bad.join("; "))
        }
    }

    pub fn xyzabc_limits(&self) -> ([f64; 6], [f64; 6]) {
        let mut v = [0.0; 6];
        let mut a = [0.0; 6];
        for (i, l) in ['X', 'Y', 'Z', 'A', 'B', 'C'].iter().enumerate() {
            if let Some(ax) = self.axis(*l) {
                v[i] = ax.max_velocity;
                a[i] = ax.max_acceleration;
            }
        }
        (v, a)
    }

    /// Builds a profile from the text of a LinuxCNC `.ini` file.
    ///
    /// Reads `[TRAJ]` `COORDINATES`, `LINEAR_UNITS`, `MAX_LINEAR_VELOCITY` (or the older
    /// `MAX_VELOCITY`), `MAX_LINEAR_ACCELERATION`, `ARC_BLEND_OPTIMIZATION_DEPTH`,
    /// `ARC_BLEND_KINK_RATIO`, `[EMCMOT]SERVO_PERIOD`, and per axis
    /// `[AXIS_<L>]` `MAX_VELOCITY`, `MAX_ACCELERATION`, `MIN_LIMIT`, `MAX_LIMIT`,
    /// falling back to the `[JOINT_<n>]` (or 2.7-style `[AXIS_<n>]`) section of the
    /// joint that drives the letter under trivkins. Inch machines are converted to mm.
    pub fn from_linuxcnc_ini(text: &str) -> Result<(MachineProfile, IniExtras), String> {
        let ini = Ini::parse(text);
        let mut p = MachineProfile::default_for(Dialect::Rs274ngc);
        let mut extras = IniExtras {
            tool_table: ini.get("EMCIO", "TOOL_TABLE").map(str::to_string),
            parameter_file: ini.get("RS274NGC", "PARAMETER_FILE").map(str::to_string),
            linear_units: ini.get("TRAJ", "LINEAR_UNITS").map(str::to_string),
        };
        let scale = match extras.linear_units.as_deref().map(str::to_ascii_lowercase) {
            None => 1.0,
            Some(u) => match u.as_str() {
                "mm" | "metric" => 1.0,
                "inch" | "imperial" | "in" => 25.4,
                "cm" => 10.0,
                other => other
                    .parse::<f64>()
                    // A number is "machine units per mm".
                    .ok()
                    .filter(|f| *f > 0.0)
                    .map(|f| 1.0 / f)
                    .ok_or_else(|| format!("unknown [TRAJ]LINEAR_UNITS `{other}`"))?,
            },
        };
        let num = |sec: &str, key: &str| -> Result<Option<f64>, String> {
            match ini.get(sec, key) {
                None => Ok(None),
                Some(s) => s
                    .parse::<f64>()
                    .map(Some)
                    .map_err(|_| format!("[{sec}]{key} = `{s}` is not a number")),
            }
        };
        let coords: Vec<char> = match ini.get("TRAJ", "COORDINATES") {
            Some(c) => c
                .chars()
                .filter(|c| c.is_ascii_alphabetic())
                .map(|c| c.to_ascii_uppercase())
                .collect(),
            None => match ini
                .get("KINS", "KINEMATICS")
                .and_then(|k| k.split("coordinates=").nth(1))
            {
                Some(c) => c
                    .chars()
                    .take_while(|c| c.is_ascii_alphabetic())
                    .map(|c| c.to_ascii_uppercase())
                    .collect(),
                None => vec!['X', 'Y', 'Z'],
            },
        };
        if coords.is_empty() {
            return Err("[TRAJ]COORDINATES names no axes".to_string());
        }
        let traj_v = num("TRAJ", "MAX_LINEAR_VELOCITY")?.or(num("TRAJ", "MAX_VELOCITY")?);
        let traj_a = num("TRAJ", "MAX_LINEAR_ACCELERATION")?.or(num("TRAJ", "MAX_ACCELERATION")?);
        let mut axes = Vec::new();
        let mut seen = String::new();
        for (joint, letter) in coords.iter().enumerate() {
            if seen.contains(*letter) {
                // Gantry: a second joint for the same letter adds no axis.
                continue;
            }
            seen.push(*letter);
            let rotary = matches!(letter, 'A' | 'B' | 'C');
            let unit = if rotary { 1.0 } else { scale };
            let axis_sec = format!("AXIS_{letter}");
            let joint_secs = [format!("JOINT_{joint}"), format!("AXIS_{joint}")];
            let get = |key: &str| -> Result<Option<f64>, String> {
                if let Some(v) = num(&axis_sec, key)? {
                    return Ok(Some(v));
                }
                for s in &joint_secs {
                    if let Some(v) = num(s, key)? {
                        return Ok(Some(v));
                    }
                }
                Ok(None)
            };
            let mut ax = if rotary {
                Axis::rotary(*letter, 360.0, 3600.0)
            } else {
                Axis::linear(*letter, 100.0, 1000.0)
            };
            if let Some(v) = get("MAX_VELOCITY")? {
                ax.max_velocity = v * unit;
                ax.rapid_rate = v * unit;
            }
            if let Some(a) = get("MAX_ACCELERATION")? {
                ax.max_acceleration = a * unit;
                ax.jerk = a * unit * 10.0;
            }
            if let Some(v) = get("MIN_LIMIT")? {
                ax.min_travel = v * unit;
            }
            if let Some(v) = get("MAX_LIMIT")? {
                ax.max_travel = v * unit;
            }
            axes.push(ax);
        }
        p.axes = axes;
        // Without a TRAJ cap LinuxCNC lets the axes decide; model that as "no cap".
        p.traj_max_velocity = traj_v.map(|v| v * scale).unwrap_or(f64::INFINITY);
        p.traj_max_acceleration = traj_a.map(|a| a * scale).unwrap_or(f64::INFINITY);
        if let Some(d) = num("TRAJ", "ARC_BLEND_OPTIMIZATION_DEPTH")? {
            p.lookahead = d.max(0.0) as u32;
        }
        if let Some(k) = num("TRAJ", "ARC_BLEND_KINK_RATIO")? {
            p.tangent_kink_ratio = k;
        }
        if let Some(ns) = num("EMCMOT", "SERVO_PERIOD")? {
            if ns > 0.0 {
                p.servo_period = ns * 1e-9;
            }
        }
        if extras.linear_units.is_none() {
            extras.linear_units = Some("mm".to_string());
        }
        p.check_ranges()?;
        Ok((p, extras))
    }
}

/// An axis entry of `[machine]` over a base axis.
fn axis_over(base: &Axis, a: &AxisConfig) -> Axis {
    let mut axis = base.clone();
    macro_rules! take {
        ($($key:ident),*) => {$( if let Some(v) = a.$key { axis.$key = v; } )*};
    }
    take!(
        letter,
        kind,
        min_travel,
        max_travel,
        max_velocity,
        rapid_rate,
        max_acceleration,
        jerk,
        machine_unit
    );
    axis
}

/// Minimal `.ini` reader: `[SECTION]` headers, `KEY = VALUE` lines, `#`/`;` comments.
/// The first occurrence of a key wins, as in LinuxCNC's IniFile::Find.
struct Ini {
    entries: Vec<(String, String, String)>,
}

impl Ini {
    fn parse(text: &str) -> Ini {
        let mut entries = Vec::new();
        let mut section = String::new();
        for raw in text.lines() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with(';') {
                continue;
            }
            if let Some(rest) = line.strip_prefix('[') {
                if let Some(end) = rest.find(']') {
                    section = rest[..end].trim().to_ascii_uppercase();
                }
                continue;
            }
            if let Some((k, v)) = line.split_once('=') {
                let v = v.split('#').next().unwrap_or("").trim();
                entries.push((
                    section.clone(),
                    k.trim().to_ascii_uppercase(),
                    v.to_string(),
                ));
            }
        }
        Ini { entries }
    }

    fn get(&self, section: &str, key: &str) -> Option<&str> {
        self.entries
            .iter()
            .find(|(s, k, _)| s == section && k == key)
            .map(|(_, _, v)| v.as_str())
    }
}
