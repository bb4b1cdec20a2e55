//! The `[machine]` keys the interpreter reads, with their defaults.

use std::collections::HashMap;

use analyzer::config::{DrillShift, G41Side, MachineConfig, Units};
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

/// `drill_shift` as (plane axis, sign): the letter names the first (X) or second
/// (Y) axis of the G17 plane; in G18/G19 the same plane position is used.
fn drill_shift(v: Option<DrillShift>) -> Option<(usize, f64)> {
    match v.unwrap_or(DrillShift::PlusX) {
        DrillShift::None => None,
        DrillShift::PlusX => Some((0, 1.0)),
        DrillShift::MinusX => Some((0, -1.0)),
        DrillShift::PlusY => Some((1, 1.0)),
        DrillShift::MinusY => Some((1, -1.0)),
    }
}

impl MachineCfg {
    pub fn read(m: &MachineConfig, dialect: Dialect) -> MachineCfg {
        let param_unit = match m.machine_units {
            Some(Units::Mm) => 1.0,
            Some(Units::Inch) => 25.4,
            None if dialect == Dialect::Rs274ngc => 25.4,
            None => 1.0,
        };
        let mut tools = HashMap::new();
        for (n, t) in m.tools.iter().flatten() {
            let diameter = t.diameter.or(t.radius.map(|r| 2.0 * r)).unwrap_or(0.0);
            // Profile tools are in mm; tools are kept in parameter units.
            tools.insert(
                *n,
                Tool {
                    length: t.length.unwrap_or(0.0) / param_unit,
                    diameter: diameter / param_unit,
                    x_offset: 0.0,
                    y_offset: 0.0,
                    orientation: 0,
                },
            );
        }
        let work_offsets = m
            .work_offsets
            .iter()
            .flatten()
            .map(|(i, v)| (*i, *v))
            .collect();
        let mut reference_positions = [[0.0; 6]; 4];
        for (n, v) in m.reference_positions.iter().flatten() {
            if let Some(slot) = n
                .checked_sub(1)
                .and_then(|i| reference_positions.get_mut(i))
            {
                *slot = *v;
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
        for a in m.axes.iter().flatten() {
            let Some(i) = a.letter.and_then(|l| "XYZABC".find(l)) else {
                continue;
            };
            if let (Some(lo), Some(hi)) = (a.min_travel, a.max_travel) {
                limits[i] = Some((lo, hi));
            }
            if i == 0 {
                axis_unit = a.machine_unit;
            }
        }
        MachineCfg {
            limits,
            g41_right: m.trc_g41_side == Some(G41Side::Right),
            drill_shift: drill_shift(m.drill_shift),
            ndc: super::ndc::NdcConfig::read(m),
            g37: super::exec::G37Cfg::read(m),
            tcp_arm_length: m.tcp_arm_length.unwrap_or(0.0),
            optional_stop: m.optional_stop.unwrap_or(false),
            circle_error_allowance: m.circle_error_allowance.unwrap_or(0.0),
            arc_radius_tolerance: m.arc_radius_tolerance.unwrap_or(0.02),
            integer_machine_unit: m.integer_machine_unit.unwrap_or(false),
            machine_unit: m.machine_unit.or(axis_unit).unwrap_or(0.001),
            // Off, as in the standalone rs274 (`-b` toggles) that `--emit canon` is
            // checked against; LinuxCNC's task starts with it on (its canonical
            // layer's default), which a LinuxCNC machine profile sets.
            block_skip: m.block_skip.unwrap_or(false),
            param_unit,
            decimal_point_input: m.decimal_point_input.unwrap_or(false),
            g73_retract: m.g73_retract.unwrap_or(1.0),
            g83_clearance: m.g83_clearance.unwrap_or(1.0),
            tools,
            tool_order: Vec::new(),
            work_offsets,
            reference_positions,
            max_depth: m.max_call_depth.unwrap_or(max_default),
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
