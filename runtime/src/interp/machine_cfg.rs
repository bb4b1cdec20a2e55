//! The `[machine]` keys the interpreter reads, with their defaults.

use std::collections::HashMap;

use analyzer::Dialect;

/// One tool: length and diameter in mm.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Tool {
    pub length: f64,
    pub diameter: f64,
    pub x_offset: f64,
    pub y_offset: f64,
    /// LinuxCNC lathe tool orientation (the tool table's Q, 0-9; 0 is a mill cutter).
    pub orientation: u8,
}

#[derive(Debug, Clone, PartialEq)]
pub struct MachineCfg {
    /// ServoWorks circle error allowance (mm), default 0.
    pub circle_error_allowance: f64,
    /// FANUC parameter 3410 (mm), default 0.02.
    pub arc_radius_tolerance: f64,
    /// ServoWorks integer programming with machine unit.
    pub integer_machine_unit: bool,
    /// Machine unit (mm), default 0.001.
    pub machine_unit: f64,
    /// Block skip switch on.
    pub block_skip: bool,
    /// mm per unit of tool-table, `.var` and offset parameters. The
    /// standalone LinuxCNC `rs274` is an inch machine (25.4); everything else mm.
    pub param_unit: f64,
    /// FANUC pocket-calculator decimal input (DPI = 1).
    pub decimal_point_input: bool,
    /// FANUC G73 retract (No. 5114) and G83 clearance (No. 5115), mm.
    pub g73_retract: f64,
    pub g83_clearance: f64,
    pub tools: HashMap<u32, Tool>,
    /// Tool numbers in tool-table order (LinuxCNC slots).
    pub tool_order: Vec<u32>,
    /// Work offsets from the profile: (origin index 1..=9, values in mm).
    pub work_offsets: Vec<(usize, [f64; 6])>,
    /// FANUC/ServoWorks reference positions 1-4 in machine coordinates, mm (G28 goes to
    /// the first, G30 P2-P4 to the others; FANUC parameters No. 1240-1243). Key
    /// `reference_positions = { 2 = [x, y, z, a, b, c], … }`; machine zero by default.
    pub reference_positions: [[f64; 6]; 4],
    /// Maximum subprogram/macro nesting.
    pub max_depth: usize,
    /// Travel limits per axis index (X Y Z A B C), machine frame.
    pub limits: [Option<(f64, f64)>; 6],
    /// `trc_g41_side = "right"`: G41 puts the tool right of the path. The ServoWorks
    /// manual says so (§6.2, §6.3.15) against ISO practice and its own G41.1; the
    /// digest recommends `left` (ambiguity A1), the default.
    pub g41_right: bool,
    /// Optional stop switch: M1 stops (and costs `program_stop_time`) only when on.
    pub optional_stop: bool,
    /// G76/G87 shift: (plane axis 0 = first, 1 = second, sign), or `None` for no shift
    /// (ServoWorks "No Shift"). Key `drill_shift = "+X" | "-X" | "+Y" | "-Y" | "none"`,
    /// default `+X` (ServoWorks digest recommendation; FANUC No. 5101 RD1/RD2 = 0).
    pub drill_shift: Option<(usize, f64)>,
    /// ServoWorks normal direction control parameters.
    pub ndc: super::ndc::NdcConfig,
    /// ServoWorks G37 ratio, speed, limit and the simulated measurement.
    pub(super) g37: super::exec::G37Cfg,
    /// ServoWorks TCP Arm Length (mm): pivot to tool holder.
    pub tcp_arm_length: f64,
}

/// Reads `drill_shift`: the letter names the first (X) or second (Y) axis of the
/// G17 plane; in G18/G19 the same plane position is used.
fn drill_shift(v: Option<&toml::Value>) -> Option<(usize, f64)> {
    let s = match v.and_then(|v| v.as_str()) {
        Some(s) => s.trim().to_ascii_uppercase(),
        None => return Some((0, 1.0)),
    };
    match s.as_str() {
        "NONE" | "OFF" | "0" => None,
        "-X" => Some((0, -1.0)),
        "+Y" | "Y" => Some((1, 1.0)),
        "-Y" => Some((1, -1.0)),
        _ => Some((0, 1.0)),
    }
}

fn num(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

impl MachineCfg {
    pub fn read(t: &toml::Table, dialect: Dialect) -> MachineCfg {
        let f = |k: &str, d: f64| t.get(k).and_then(num).unwrap_or(d);
        let b = |k: &str, d: bool| t.get(k).and_then(|v| v.as_bool()).unwrap_or(d);
        let default_param_unit = if dialect == Dialect::Rs274ngc {
            25.4
        } else {
            1.0
        };
        let param_unit = match t.get("machine_units").and_then(|v| v.as_str()) {
            Some(s) if s.eq_ignore_ascii_case("mm") => 1.0,
            Some(s) if s.eq_ignore_ascii_case("inch") => 25.4,
            _ => default_param_unit,
        };
        let mut tools = HashMap::new();
        if let Some(toml::Value::Table(tt)) = t.get("tools") {
            for (k, v) in tt {
                let Ok(n) = k.trim_start_matches(['T', 't']).parse::<u32>() else {
                    continue;
                };
                let Some(v) = v.as_table() else { continue };
                let length = v.get("length").and_then(num).unwrap_or(0.0);
                let diameter = v
                    .get("diameter")
                    .and_then(num)
                    .or_else(|| v.get("radius").and_then(num).map(|r| 2.0 * r))
                    .unwrap_or(0.0);
                // Profile tools are in mm; tools are kept in parameter units.
                tools.insert(
                    n,
                    Tool {
                        length: length / param_unit,
                        diameter: diameter / param_unit,
                        x_offset: 0.0,
                        y_offset: 0.0,
                        orientation: 0,
                    },
                );
            }
        }
        let mut work_offsets = Vec::new();
        if let Some(toml::Value::Table(w)) = t.get("work_offsets") {
            for (k, v) in w {
                let key = k.to_ascii_uppercase();
                let idx = match key.as_str() {
                    "G54" => 1,
                    "G55" => 2,
                    "G56" => 3,
                    "G57" => 4,
                    "G58" => 5,
                    "G59" => 6,
                    "G59.1" => 7,
                    "G59.2" => 8,
                    "G59.3" => 9,
                    _ => continue,
                };
                let mut vals = [0.0; 6];
                if let Some(arr) = v.as_array() {
                    for (i, x) in arr.iter().take(6).enumerate() {
                        vals[i] = num(x).unwrap_or(0.0);
                    }
                }
                work_offsets.push((idx, vals));
            }
        }
        let mut reference_positions = [[0.0; 6]; 4];
        if let Some(toml::Value::Table(r)) = t.get("reference_positions") {
            for (k, v) in r {
                let Some(slot) = k
                    .trim()
                    .parse::<usize>()
                    .ok()
                    .and_then(|n| n.checked_sub(1))
                    .and_then(|i| reference_positions.get_mut(i))
                else {
                    continue;
                };
                if let Some(arr) = v.as_array() {
                    for (i, x) in arr.iter().take(6).enumerate() {
                        slot[i] = num(x).unwrap_or(0.0);
                    }
                }
            }
        }
        let max_default = match dialect {
            Dialect::Servoworks => 8,
            Dialect::Fanuc => 15,
            // rs274ngc.md TV-O4: LinuxCNC stops beyond 10 nested calls.
            Dialect::Rs274ngc => 10,
        };
        let mut limits = [None; 6];
        let mut axis_unit = None;
        if let Some(toml::Value::Array(axes)) = t.get("axes") {
            for a in axes.iter().filter_map(|a| a.as_table()) {
                let Some(letter) = a
                    .get("letter")
                    .and_then(|l| l.as_str())
                    .and_then(|s| s.chars().next())
                else {
                    continue;
                };
                let Some(i) = "XYZABC".find(letter.to_ascii_uppercase()) else {
                    continue;
                };
                let lo = a.get("min_travel").and_then(num);
                let hi = a.get("max_travel").and_then(num);
                if let (Some(lo), Some(hi)) = (lo, hi) {
                    limits[i] = Some((lo, hi));
                }
                if i == 0 {
                    axis_unit = a.get("machine_unit").and_then(num);
                }
            }
        }
        MachineCfg {
            limits,
            g41_right: t
                .get("trc_g41_side")
                .and_then(|v| v.as_str())
                .is_some_and(|s| s.eq_ignore_ascii_case("right")),
            drill_shift: drill_shift(t.get("drill_shift")),
            ndc: super::ndc::NdcConfig::read(t),
            g37: super::exec::G37Cfg::read(t),
            tcp_arm_length: f("tcp_arm_length", 0.0),
            optional_stop: b("optional_stop", false),
            circle_error_allowance: f("circle_error_allowance", 0.0),
            arc_radius_tolerance: f("arc_radius_tolerance", 0.02),
            integer_machine_unit: b("integer_machine_unit", false),
            machine_unit: t
                .get("machine_unit")
                .and_then(num)
                .or(axis_unit)
                .unwrap_or(0.001),
            // Off, as in the standalone rs274 (`-b` toggles) that `--emit canon` is
            // checked against; LinuxCNC's task starts with it on (its canonical
            // layer's default), which a LinuxCNC machine profile sets.
            block_skip: b("block_skip", false),
            param_unit,
            decimal_point_input: b("decimal_point_input", false),
            g73_retract: f("g73_retract", 1.0),
            g83_clearance: f("g83_clearance", 1.0),
            tools,
            tool_order: Vec::new(),
            work_offsets,
            reference_positions,
            max_depth: t
                .get("max_call_depth")
                .and_then(|v| v.as_integer())
                .map(|v| v.max(1) as usize)
                .unwrap_or(max_default),
        }
    }
}

/// Reads a LinuxCNC tool table (`T1 P1 D0.125 Z+0.511 ;comment`); values in
/// machine units, scaled by `unit` to mm.
pub fn parse_tool_table(
    text: &str,
    unit: f64,
    into: &mut HashMap<u32, Tool>,
    order: &mut Vec<u32>,
) {
    for line in text.lines() {
        let body = line.split(';').next().unwrap_or("");
        let mut n = None;
        let mut tool = Tool::default();
        for word in body.split_whitespace() {
            let mut chars = word.chars();
            let Some(letter) = chars.next() else { continue };
            let Ok(v) = chars.as_str().parse::<f64>() else {
                continue;
            };
            match letter.to_ascii_uppercase() {
                'T' => n = Some(v as u32),
                'Z' => tool.length = v * unit,
                'D' => tool.diameter = v * unit,
                'X' => tool.x_offset = v * unit,
                'Y' => tool.y_offset = v * unit,
                'Q' if (0.0..=9.0).contains(&v) => tool.orientation = v as u8,
                _ => {}
            }
        }
        if let Some(n) = n {
            into.insert(n, tool);
            order.push(n);
        }
    }
}

/// Reads a LinuxCNC `.var` file: `number value` per line.
pub fn parse_var_file(text: &str) -> Vec<(usize, f64)> {
    text.lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            let n = it.next()?.parse::<usize>().ok()?;
            let v = it.next()?.parse::<f64>().ok()?;
            Some((n, v))
        })
        .collect()
}
