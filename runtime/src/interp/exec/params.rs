//! Parameters: the numbered and named parameter tables, the read-only system
//! variables computed from the state (FANUC `#4001…`, `#5001…`; LinuxCNC `#5420…`,
//! `#<_x>` …), expression evaluation against them, and assignment.

use super::*;
use crate::rules::{expression::EXPRESSION, macro_alarm::MACRO_ALARM};

impl Interp<'_, '_> {
    pub(super) fn param(&self, n: usize) -> f64 {
        self.st.params.get(n).copied().flatten().unwrap_or(0.0)
    }

    pub(super) fn set_param(&mut self, n: usize, v: Option<f64>) {
        if n < NUM_PARAMS {
            Arc::make_mut(&mut self.st.params)[n] = v;
        }
    }

    pub(super) fn eval_err(&self, e: EvalError) -> Diagnostic {
        self.err(e.rule, e.span, e.message)
    }

    /// Evaluates an expression. While recovering (`recover.rs`), a failed one is
    /// reported and yields an unknown value (0), and one that reads a parameter an
    /// earlier error left unknown is unknown too: `taint.last` says which.
    pub(super) fn eval(&self, p: &Program, id: ExprId) -> Result<Val, Diagnostic> {
        self.eval_reading(p, id).0
    }

    /// [`Self::eval`], and the first variables it read that only the machine
    /// knows and that the machine may change (`machine_vars.rs`).
    pub(super) fn eval_reading(
        &self,
        p: &Program,
        id: ExprId,
    ) -> (Result<Val, Diagnostic>, (Option<usize>, Option<usize>)) {
        let locals = self
            .frames
            .last()
            .map(|f| &f.named_locals)
            .or(Some(&self.main_locals));
        let hit = std::cell::Cell::new(false);
        let mut vars = self.vars(locals);
        vars.tainted = Some(&hit);
        self.taint.last.set(false);
        let v = match self.eval_recorded(p, id, &vars) {
            Ok(v) => {
                if hit.get() {
                    self.taint.last.set(true);
                    self.taint.block.set(true);
                }
                Ok(v)
            }
            // A failure that follows from an unknown value is not reported again.
            Err(e) if self.recovering() => {
                Ok(self.taint_failed(Some(self.eval_err(e)).filter(|_| !hit.get())))
            }
            Err(e) => Err(self.eval_err(e)),
        };
        (v, (vars.machine_read.get(), vars.shared_read.get()))
    }

    /// What expressions read: the state, the named locals in scope and the
    /// current tool's offsets in parameter units.
    pub(super) fn vars<'s>(&'s self, locals: Option<&'s HashMap<String, f64>>) -> Vars<'s> {
        let t = self
            .cfg
            .tools
            .get(&self.st.tool)
            .copied()
            .unwrap_or_default();
        // LinuxCNC reads #5401-#5410 straight from its tool table, in the machine's
        // units whatever G20/G21 says.
        Vars {
            st: &self.st,
            locals,
            dialect: self.dialect,
            tool: [t.x_offset, t.y_offset, t.length, t.diameter],
            machine: &self.machine_vars,
            machine_read: std::cell::Cell::new(None),
            shared_read: std::cell::Cell::new(None),
            tainted: None,
        }
    }

    /// A numbered parameter as an expression would read it (system values included).
    pub(super) fn read_param(&self, n: i64) -> f64 {
        self.vars(None)
            .get_num(n, Span::default())
            .ok()
            .flatten()
            .unwrap_or(0.0)
    }

    pub(super) fn eval_num(&self, p: &Program, id: ExprId) -> Result<f64, Diagnostic> {
        Ok(self.eval(p, id)?.unwrap_or(0.0))
    }

    pub(super) fn assign(
        &mut self,
        p: &Program,
        target: ExprId,
        v: Val,
        span: Span,
        tainted: bool,
        machine_value: Option<usize>,
    ) -> Result<(), Diagnostic> {
        self.record_assigned(p, target, v);
        match p.expr(target).expr {
            Expr::Var { index } => {
                let n = self.eval_num(p, index)?.round();
                if self.dialect == Dialect::Fanuc && machine_vars::UNMODELLED.contains(&(n as i64))
                {
                    // The control's extended ranges (options): the machine keeps the
                    // value; the dry run says once that it does not follow them.
                    if !self.machine_vars.unmodelled_noted {
                        self.machine_vars.unmodelled_noted = true;
                        self.diag(&EXPRESSION, Severity::Info, span, format!("#{n} is in a variable range of a control option this dry run does not model (#20000 and above): its value is left to the machine, and reads of such variables are unknown"));
                    }
                    return Ok(());
                }
                if n < 0.0 || n as usize >= NUM_PARAMS {
                    return Err(self.err(
                        &EXPRESSION,
                        span,
                        format!("parameter number #{n} out of range"),
                    ));
                }
                if n == 0.0 && !self.ngc() {
                    return Err(self.err(&EXPRESSION, span, "#0 is read-only (PS0116)"));
                }
                let v = if self.ngc() {
                    Some(v.unwrap_or(0.0))
                } else {
                    v
                };
                if self.dialect == Dialect::Fanuc && (n as usize == 3000 || n as usize == 3006) {
                    let stop = n as usize == 3000;
                    self.event(EventKind::Message(format!("#{} = {}", n, v.unwrap_or(0.0))));
                    if stop {
                        let alarm = format!("macro alarm #3000 = {}", v.unwrap_or(0.0));
                        let mut d = self.err(&MACRO_ALARM, span, &alarm);
                        // Reached only because a machine value was read as vacant.
                        if let Some(why) = self.machine_dependence() {
                            d.severity = Severity::Info;
                            d.message = format!("{alarm} may not fire on the machine: {why}");
                        }
                        return Err(d);
                    }
                }
                self.machine_vars.assigned(n as usize);
                // The target now stands for the machine value it was computed from.
                self.machine_vars.derive(n as usize, machine_value);
                self.set_param(n as usize, v);
                self.mark_taint(|| format!("#{}", n as usize), tainted);
                Ok(())
            }
            Expr::Named { name } => {
                let key = expr::named_key(&p.str_of(name));
                let v = v.unwrap_or(0.0);
                self.mark_taint(|| key.clone(), tainted);
                if key.starts_with('_') {
                    Arc::make_mut(&mut self.st.named).insert(key, v);
                } else if let Some(f) = self.frames.last_mut() {
                    f.named_locals.insert(key, v);
                } else {
                    self.main_locals.insert(key, v);
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
}

pub(super) struct Vars<'s> {
    st: &'s State,
    locals: Option<&'s HashMap<String, f64>>,
    dialect: Dialect,
    /// Tool-table offsets (X Y Z) and diameter of the tool in the spindle, in the tool
    /// table's units.
    tool: [f64; 4],
    machine: &'s machine_vars::MachineVars,
    /// The first variable read whose value only the machine knows.
    pub(super) machine_read: std::cell::Cell<Option<usize>>,
    /// The first variable read that the machine may change while the program runs.
    pub(super) shared_read: std::cell::Cell<Option<usize>>,
    /// Set when a read hits a parameter an earlier error left unknown.
    tainted: Option<&'s std::cell::Cell<bool>>,
}

impl Vars<'_> {
    /// Notes a read of `key` when it is tainted (the list is empty unless an
    /// error happened, so the key is only built then).
    fn read(&self, key: impl FnOnce() -> String) {
        if let Some(hit) = self.tainted {
            if !self.st.tainted.is_empty() && self.st.tainted.contains(&key()) {
                hit.set(true);
            }
        }
    }
}

impl VarSource for Vars<'_> {
    fn get_num(&self, n: i64, span: Span) -> Result<Val, EvalError> {
        if self.dialect == Dialect::Fanuc && machine_vars::UNMODELLED.contains(&n) {
            if self.machine_read.get().is_none() {
                self.machine_read.set(Some(n as usize));
            }
            return Ok(None);
        }
        if n < 0 || n as usize >= NUM_PARAMS {
            return Err(EvalError {
                span,
                message: format!("parameter number #{n} out of range"),
                rule: &EXPRESSION,
            });
        }
        if self.dialect == Dialect::Rs274ngc && (5401..=5403).contains(&n) {
            return Ok(Some(self.tool[(n - 5401) as usize]));
        }
        if self.dialect == Dialect::Rs274ngc && n == 5410 {
            return Ok(Some(self.tool[3]));
        }
        if let Some(v) = system_var(self.st, self.dialect, n) {
            return Ok(Some(v));
        }
        self.read(|| format!("#{n}"));
        let v = self.st.params.get(n as usize).copied().flatten();
        if self.dialect == Dialect::Fanuc {
            let n = n as usize;
            if self.machine_read.get().is_none() {
                if let Some(origin) = self.machine.unknown_origin(n, v.is_none()) {
                    self.machine_read.set(Some(origin));
                }
            }
            if machine_vars::shared(n) && self.shared_read.get().is_none() {
                self.shared_read.set(Some(n));
            }
        }
        Ok(if self.dialect == Dialect::Rs274ngc {
            Some(v.unwrap_or(0.0))
        } else {
            v
        })
    }
    fn get_named(&self, name: &str, span: Span) -> Result<Val, EvalError> {
        self.read(|| name.to_string());
        if let Some(v) = self.locals.and_then(|l| l.get(name)) {
            return Ok(Some(*v));
        }
        if let Some(v) = self.st.named.get(name) {
            return Ok(Some(*v));
        }
        if let Some(v) = predefined(self.st, name) {
            return Ok(Some(v));
        }
        // A global the skipped call would have set: unknown, and what it feeds
        // reports nothing more.
        if self.st.skipped_call && name.starts_with('_') {
            if let Some(hit) = self.tainted {
                hit.set(true);
                return Ok(Some(0.0));
            }
        }
        Err(EvalError {
            span,
            message: format!("named parameter #<{name}> not defined"),
            rule: &EXPRESSION,
        })
    }
    fn named_exists(&self, name: &str) -> bool {
        self.locals.is_some_and(|l| l.contains_key(name))
            || self.st.named.contains_key(name)
            || predefined(self.st, name).is_some()
    }
}

/// Read-only system variables computed from the state: FANUC/ServoWorks
/// #4001… modal codes, #5001… end point, #5021… machine, #5041… work
/// position; LinuxCNC #5420… current position.
fn system_var(st: &State, d: Dialect, n: i64) -> Option<f64> {
    // RS274/NGC keeps lengths in program units already.
    let u = if st.modal.inch && d != Dialect::Rs274ngc {
        25.4
    } else {
        1.0
    };
    let axis = |v: &[f64; 6], i: usize| if i < 3 { v[i] / u } else { v[i] };
    match d {
        Dialect::Rs274ngc => match n {
            5420..=5425 => Some(axis(&st.pos, (n - 5420) as usize)),
            5400 => Some(f64::from(st.tool)),
            _ => None,
        },
        _ => match n {
            4001 => Some(f64::from(st.modal.motion) / 10.0),
            4002 => Some(f64::from(st.modal.plane) / 10.0),
            4003 => Some(if st.modal.incremental { 91.0 } else { 90.0 }),
            4005 => Some(f64::from(st.modal.feed_mode) / 10.0),
            4006 => Some(if st.modal.inch { 20.0 } else { 21.0 }),
            4007 => Some(f64::from(st.modal.comp) / 10.0),
            4008 => Some(f64::from(st.modal.tlo_mode) / 10.0),
            4009 => Some(if st.modal.modal_cycle() {
                f64::from(st.modal.motion) / 10.0
            } else {
                80.0
            }),
            4010 => Some(if st.modal.retract_old_z { 98.0 } else { 99.0 }),
            4014 => Some(match st.modal.origin {
                o @ 1..=6 => 53.0 + o as f64,
                _ => 54.1,
            }),
            4109 => Some(st.feed / u),
            4119 => Some(st.spindle),
            4120 => Some(f64::from(st.tool)),
            5001..=5006 | 5041..=5046 => Some(axis(&st.pos, ((n - 1) % 20) as usize)),
            5021..=5026 => Some(axis(&st.mpos, (n - 5021) as usize)),
            5081..=5086 => Some(axis(&st.tlo, (n - 5081) as usize)),
            _ => None,
        },
    }
}

/// LinuxCNC read-only named parameters, in program units.
pub(super) fn predefined(st: &State, name: &str) -> Option<f64> {
    // Only RS274/NGC has named parameters, and it keeps program units.
    let u = 1.0;
    let axes = ["x", "y", "z", "a", "b", "c"];
    for (i, a) in axes.iter().enumerate() {
        if name.strip_prefix('_') == Some(a) {
            return Some(if i < 3 { st.pos[i] / u } else { st.pos[i] });
        }
        if name == format!("_abs_{a}") {
            return Some(if i < 3 { st.mpos[i] / u } else { st.mpos[i] });
        }
    }
    Some(match name {
        "_metric" => f64::from(u8::from(!st.modal.inch)),
        "_imperial" => f64::from(u8::from(st.modal.inch)),
        "_lathe_diameter_mode" => f64::from(u8::from(st.modal.diameter)),
        "_lathe_radius_mode" => f64::from(u8::from(!st.modal.diameter)),
        "_absolute" => f64::from(u8::from(!st.modal.incremental)),
        "_incremental" => f64::from(u8::from(st.modal.incremental)),
        "_feed" => st.feed / u,
        "_rpm" => st.spindle,
        "_current_tool" => f64::from(st.tool),
        "_selected_tool" => f64::from(st.next_tool),
        "_coord_system" => 530.0 + 10.0 * st.modal.origin as f64,
        "_motion_mode" => f64::from(st.modal.motion),
        "_plane" => f64::from(st.modal.plane),
        "_value" | "_value_returned" => 0.0,
        "_line" => f64::from(st.line),
        "_ccomp" => f64::from(st.modal.comp),
        "_inverse_time" => f64::from(u8::from(st.modal.feed_mode == 930)),
        "_units_per_minute" => f64::from(u8::from(st.modal.feed_mode == 940)),
        "_units_per_rev" => f64::from(u8::from(st.modal.feed_mode == 950)),
        "_tool_offset" => f64::from(u8::from(st.tlo.iter().any(|v| *v != 0.0))),
        // G98 retracts to the old Z, G99 to the R plane.
        "_retract_old_z" => f64::from(u8::from(st.modal.retract_old_z)),
        "_retract_r_plane" => f64::from(u8::from(!st.modal.retract_old_z)),
        "_spindle_rpm_mode" => f64::from(u8::from(!st.modal.css)),
        "_spindle_css_mode" => f64::from(u8::from(st.modal.css)),
        "_ijk_absolute_mode" => f64::from(u8::from(st.modal.ijk_abs)),
        "_spindle_on" => f64::from(u8::from(st.spindle_dir != 0)),
        "_spindle_cw" => f64::from(u8::from(st.spindle_dir > 0)),
        "_mist" => f64::from(u8::from(st.mist)),
        "_flood" => f64::from(u8::from(st.flood)),
        // A dry run sees the overrides at 100 % and no feed hold input, as `rs274` does.
        "_speed_override" | "_feed_override" | "_feed_hold" => 1.0,
        "_adaptive_feed" | "_remap_level" | "_task" => 0.0,
        "_vmajor" => 2.9,
        "_vminor" => 0.0,
        "_u" | "_v" | "_w" => 0.0,
        _ => return None,
    })
}
