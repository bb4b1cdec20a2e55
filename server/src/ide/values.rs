//! Values on hover: what a variable, parameter or word expression evaluated
//! to in the latest dry run (`runtime::ValueRecord`), the meaning of system
//! variables per dialect, and the G65/G66 argument a letter sets.

use analyzer::dialect::{self, Dialect};
use analyzer::syntax::{Expr, ExprId, Program};
use analyzer::Span;
use runtime::{ValueRecord, ValueSeries};

/// A number as a programmer writes it: at most six decimals, no trailing zeros.
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn value(v: Option<f64>) -> String {
    v.map_or_else(|| "vacant".to_string(), number)
}

/// The markdown of one series: the last value, and each execution's value
/// when the expression ran more than once.
pub fn series_markdown(s: &ValueSeries) -> String {
    if s.count == 1 {
        return format!("Value in the dry run: `{}`", value(s.last));
    }
    let list: Vec<String> = s.first.iter().map(|v| format!("`{}`", value(*v))).collect();
    let more = if s.count > s.first.len() as u64 {
        ", …"
    } else {
        ""
    };
    format!(
        "Value in the dry run: `{}` (last of {} executions)  \nEach execution: {}{more}",
        value(s.last),
        s.count,
        list.join(", ")
    )
}

/// The values the expression at `span` of block `bi` took, as markdown; a
/// note when the block ran but was not recorded.
pub fn recorded(program: &Program, rec: &ValueRecord, bi: usize, span: Span) -> Option<String> {
    let base = program.blocks.get(bi)?.span.start;
    let (start, end) = (span.start.checked_sub(base)?, span.end.checked_sub(base)?);
    if let Some(s) = rec.at(bi as u32, start, end) {
        return Some(series_markdown(s));
    }
    None
}

/// The innermost variable or named parameter expression of block `bi`
/// whose span holds `offset`.
pub fn variable_at(program: &Program, bi: usize, offset: u32) -> Option<(ExprId, Span)> {
    let span = program.blocks.get(bi)?.span;
    // The parser writes each block's expression nodes after the previous
    // block's, so they start at the first node that starts in the block.
    let first = program.exprs.partition_point(|n| n.span.start < span.start);
    let mut best: Option<(ExprId, Span)> = None;
    for (i, n) in program.exprs.iter().enumerate().skip(first) {
        if n.span.start >= span.end {
            break;
        }
        if !matches!(n.expr, Expr::Var { .. } | Expr::Named { .. }) {
            continue;
        }
        if !(n.span.contains(offset) || n.span.end == offset) {
            continue;
        }
        if best.is_none_or(|(_, s)| n.span.len() < s.len()) {
            best = Some((ExprId(i as u32), n.span));
        }
    }
    best
}

/// The number of a `#n` whose index is a literal.
pub fn literal_number(program: &Program, id: ExprId) -> Option<i64> {
    match program.expr(id).expr {
        Expr::Var { index } => match program.expr(index).expr {
            Expr::Num(n) if n.value.fract() == 0.0 && n.value >= 0.0 => Some(n.value as i64),
            _ => None,
        },
        _ => None,
    }
}

const FANUC_AXES: [&str; 8] = ["1 (X)", "2 (Y)", "3 (Z)", "4", "5", "6", "7", "8"];
const NGC_AXES: [char; 9] = ['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'];

/// G65/G66 Argument Specification I: the local variable each letter sets.
pub fn argument_variable(letter: u8) -> Option<u32> {
    runtime::interp::macro_argument_variable(letter).map(|n| n as u32)
}

fn fanuc_group(g: u8) -> String {
    let codes: Vec<String> = dialect::codes_in_group(Dialect::Fanuc, g)
        .filter(|c| c.letter == 'G')
        .take(8)
        .map(|c| c.display_name(Dialect::Fanuc))
        .collect();
    if codes.is_empty() {
        format!("modal G code of group {g:02}")
    } else {
        format!("modal G code of group {g:02} ({})", codes.join(" "))
    }
}

/// What a numbered variable is in FANUC Custom Macro B (ServoWorks numbers
/// its macro variables the same way).
fn fanuc_variable(n: i64) -> Option<String> {
    let axis = |base: i64| FANUC_AXES[(n - base) as usize];
    Some(match n {
        0 => "always vacant (#0 cannot be written)".into(),
        1..=33 => {
            let arg = (b'A'..=b'Z')
                .find(|l| argument_variable(*l) == Some(n as u32))
                .map(|l| {
                    format!(
                        "; G65/G66 argument {} (Argument Specification I)",
                        l as char
                    )
                })
                .unwrap_or_default();
            format!("local variable of the current macro level{arg}")
        }
        100..=199 => "common variable, cleared at power-off".into(),
        500..=999 => "common variable, kept at power-off".into(),
        1000..=1015 | 1032 => "interface input signal (read only)".into(),
        1100..=1115 | 1132 | 1133 => "interface output signal".into(),
        2001..=2999 => {
            "tool compensation value (the layout depends on the offset memory type)".into()
        }
        3000 => "macro alarm: writing `#3000 = n (MESSAGE)` stops with an alarm".into(),
        3001 => "millisecond timer".into(),
        3002 => "hour timer".into(),
        3003 => "single-block stop and FIN-wait suppression".into(),
        3004 => "feed hold, feed override and exact-stop suppression".into(),
        3005 => "settings".into(),
        3006 => "stop with message: `#3006 = 1 (MESSAGE)` stops until cycle start".into(),
        3011 => "date (YYYYMMDD, read only)".into(),
        3012 => "time (HHMMSS, read only)".into(),
        3901 => "parts machined".into(),
        3902 => "parts required".into(),
        4001..=4030 => format!(
            "{} in force in the preceding block (read only)",
            fanuc_group((n - 4000) as u8)
        ),
        4201..=4230 => format!(
            "{} of the block now executing (read only)",
            fanuc_group((n - 4200) as u8)
        ),
        4102 | 4107 | 4108 | 4109 | 4111 | 4113 | 4114 | 4115 | 4119 | 4120 | 4130 => {
            let what = match n {
                4102 => "B code",
                4107 => "D code (cutter compensation number)",
                4108 => "E code",
                4109 => "F code (feed)",
                4111 => "H code (tool length offset number)",
                4113 => "M code",
                4114 => "sequence number N",
                4115 => "program number O",
                4119 => "S code (spindle speed)",
                4120 => "T code (tool)",
                _ => "P code (additional work offset number)",
            };
            format!("{what} in force in the preceding block (read only)")
        }
        4302 | 4307 | 4308 | 4309 | 4311 | 4313 | 4314 | 4315 | 4319 | 4320 | 4330 => {
            "modal information of the block now executing (as #4102… for the preceding block)"
                .into()
        }
        5001..=5008 => format!(
            "end point of the preceding block, axis {}, workpiece coordinates (read only)",
            axis(5001)
        ),
        5021..=5028 => format!(
            "machine position, axis {} (read after motion stops; read only)",
            axis(5021)
        ),
        5041..=5048 => format!("workpiece position, axis {} (read only)", axis(5041)),
        5061..=5068 => format!(
            "skip-signal (G31) position, axis {} (read only)",
            axis(5061)
        ),
        5081..=5088 => format!(
            "tool length offset in effect, axis {} (read only)",
            axis(5081)
        ),
        5101..=5108 => format!("servo position deviation, axis {} (read only)", axis(5101)),
        5201..=5208 => format!("external workpiece zero offset, axis {}", axis(5201)),
        5221..=5328 if (n - 5201) % 20 < 8 => {
            let k = (n - 5201) / 20;
            let a = ((n - 5201) % 20) as usize;
            format!("work offset G{}, axis {}", 53 + k, FANUC_AXES[a])
        }
        7001..=7960 if (n - 7001) % 20 < 8 => {
            let p = (n - 7001) / 20 + 1;
            let a = ((n - 7001) % 20) as usize;
            format!("additional work offset G54.1 P{p}, axis {}", FANUC_AXES[a])
        }
        _ => return None,
    })
}

/// What a numbered parameter is in RS274/NGC (LinuxCNC).
fn ngc_parameter(n: i64) -> Option<String> {
    let axis = |base: i64| NGC_AXES[(n - base) as usize];
    Some(match n {
        1..=30 => "subroutine argument / local parameter: `call` sets #1…#n, and they get the caller's values back on return".into(),
        31..=5000 => "global parameter".into(),
        5021..=5029 => format!("machine position {} (read only)", axis(5021)),
        5061..=5069 => format!("probe (G38) result {} in the work frame", axis(5061)),
        5070 => "probe result: 1 when the probe tripped, 0 when not".into(),
        5161..=5169 => format!("G28 home position {} (machine coordinates)", axis(5161)),
        5181..=5189 => format!("G30 home position {} (machine coordinates)", axis(5181)),
        5210 => "1 while G92 offsets are applied".into(),
        5211..=5219 => format!("G92/G52 offset {}", axis(5211)),
        5220 => "coordinate system in use: 1 = G54 … 9 = G59.3".into(),
        5221..=5390 if (n - 5221) % 20 < 10 => {
            let k = ((n - 5221) / 20) as usize;
            let names = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"];
            let i = ((n - 5221) % 20) as usize;
            let what = NGC_AXES.get(i).map_or("rotation R".to_string(), |a| a.to_string());
            format!("work offset {} {what}", names[k])
        }
        5399 => "result of the last M66 wait (−1 on time-out)".into(),
        5400 => "tool in the spindle (read only)".into(),
        5401..=5409 => format!("tool-table offset {} of the tool in the spindle (read only)", axis(5401)),
        5410 => "tool diameter of the tool in the spindle (read only)".into(),
        5411 => "tool front angle (read only)".into(),
        5412 => "tool back angle (read only)".into(),
        5413 => "tool orientation (read only)".into(),
        5420..=5428 => format!("current position {} in the work frame (read only)", axis(5420)),
        5599 => "DEBUG output: 1 prints (DEBUG,…) comments, 0 does not".into(),
        5600 => "tool changer fault flag".into(),
        5601 => "tool changer fault code".into(),
        _ => return None,
    })
}

/// What a predefined named parameter of LinuxCNC is.
fn ngc_named(name: &str) -> Option<String> {
    let name = name.to_ascii_lowercase();
    for a in ["x", "y", "z", "a", "b", "c", "u", "v", "w"] {
        if name.strip_prefix('_') == Some(a) {
            return Some(format!(
                "current position {} in the work frame",
                a.to_uppercase()
            ));
        }
        if name == format!("_abs_{a}") {
            return Some(format!("machine position {}", a.to_uppercase()));
        }
    }
    Some(
        match name.as_str() {
            "_vmajor" | "_vminor" => "LinuxCNC version",
            "_line" => "current line number",
            "_motion_mode" => "motion mode × 10 (G1 → 10, G81 → 810)",
            "_plane" => "plane: 170, 180 or 190",
            "_ccomp" => "cutter compensation: 400, 410, 411, 420 or 421",
            "_metric" => "1 when G21 is in force",
            "_imperial" => "1 when G20 is in force",
            "_absolute" => "1 when G90 is in force",
            "_incremental" => "1 when G91 is in force",
            "_inverse_time" => "1 when G93 is in force",
            "_units_per_minute" => "1 when G94 is in force",
            "_units_per_rev" => "1 when G95 is in force",
            "_coord_system" => "coordinate system × 10: 540 … 593",
            "_tool_offset" => "1 while G43 is on",
            "_retract_r_plane" => "1 when G99 (retract to R) is in force",
            "_retract_old_z" => "1 when G98 (retract to the old Z) is in force",
            "_spindle_rpm_mode" => "1 when G97 is in force",
            "_spindle_css_mode" => "1 when G96 is in force",
            "_ijk_absolute_mode" => "1 when G90.1 is in force",
            "_lathe_diameter_mode" => "1 when G7 is in force",
            "_lathe_radius_mode" => "1 when G8 is in force",
            "_spindle_on" => "1 while the spindle turns",
            "_spindle_cw" => "1 when the spindle turns clockwise",
            "_mist" => "1 while mist coolant is on",
            "_flood" => "1 while flood coolant is on",
            "_speed_override" | "_feed_override" | "_adaptive_feed" | "_feed_hold" => {
                "override switch state"
            }
            "_feed" => "programmed feed F",
            "_rpm" => "programmed spindle speed S",
            "_current_tool" => "tool in the spindle (= #5400)",
            "_current_pocket" => "pocket of the tool in the spindle",
            "_selected_tool" => "tool selected by T (−1 when none)",
            "_selected_pocket" => "pocket of the selected tool",
            "_value" => "value returned by the last subroutine (`return [v]`, `endsub [v]`)",
            "_value_returned" => "1 when the last subroutine returned a value",
            "_task" => "1 in the machine's interpreter, 0 in the preview",
            "_call_level" => "subroutine nesting level",
            "_remap_level" => "remap nesting level",
            _ if name.starts_with("_ini[") => "a value from the machine's INI file (read only)",
            _ if name.starts_with("_hal[") => "a HAL pin's value (read only)",
            _ if name.starts_with('_') => "global named parameter",
            _ => "named parameter, local to the subroutine (or the main program) that sets it",
        }
        .to_string(),
    )
}

/// The meaning of variable `#n` in `dialect`.
pub fn variable_meaning(dialect: Dialect, n: i64) -> Option<String> {
    match dialect {
        Dialect::Rs274ngc => ngc_parameter(n),
        Dialect::Fanuc | Dialect::Servoworks => fanuc_variable(n),
    }
}

/// The meaning of named parameter `#<name>` (RS274/NGC only).
pub fn named_meaning(dialect: Dialect, name: &str) -> Option<String> {
    (dialect == Dialect::Rs274ngc)
        .then(|| ngc_named(name))
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(number(12.5), "12.5");
        assert_eq!(number(3.0), "3");
        assert_eq!(number(0.1 + 0.2), "0.3");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(-1.25), "-1.25");
    }

    #[test]
    fn system_variables_have_their_meaning() {
        let f = |n| variable_meaning(Dialect::Fanuc, n).unwrap();
        assert!(f(4119).starts_with("S code"), "{}", f(4119));
        assert!(f(5001).contains("axis 1 (X)"));
        assert_eq!(f(5243), "work offset G55, axis 3 (Z)");
        assert_eq!(f(7021), "additional work offset G54.1 P2, axis 1 (X)");
        assert!(f(4003).contains("G90"), "{}", f(4003));
        assert!(f(24).contains("argument X"));
        let n = |n| variable_meaning(Dialect::Rs274ngc, n).unwrap();
        assert_eq!(n(5223), "work offset G54 Z");
        assert_eq!(n(5230), "work offset G54 rotation R");
        assert_eq!(n(5383), "work offset G59.3 Z");
        assert!(n(5063).starts_with("probe (G38) result Z"));
        assert!(variable_meaning(Dialect::Rs274ngc, 5231).is_none());
        assert_eq!(
            named_meaning(Dialect::Rs274ngc, "_x").unwrap(),
            "current position X in the work frame"
        );
        assert!(named_meaning(Dialect::Fanuc, "_x").is_none());
    }

    #[test]
    fn argument_specification_one() {
        assert_eq!(argument_variable(b'X'), Some(24));
        assert_eq!(argument_variable(b'H'), Some(11));
        assert_eq!(argument_variable(b'P'), None);
        assert_eq!(argument_variable(b'G'), None);
    }
}
