//! Checks for the spec ledger's runtime ids (issue 3). They sit in their own
//! module, reached through a handful of hook calls, so that the interpreter's
//! semantics and these diagnostics can change independently.

use analyzer::syntax::{BinOp, Expr, Item};

use super::*;
use crate::rules::check::AXES;

impl Interp<'_, '_> {
    /// Runs once before the first block: the tool table and `.var` file the host read.
    pub(super) fn spec_input_files(&mut self) {
        if let Some(t) = self.input.tool_table {
            for (line, msg) in lint_tool_table(t) {
                self.diag(
                    codes::TOOL_TABLE,
                    if msg.1 {
                        Severity::Error
                    } else {
                        Severity::Warning
                    },
                    Span::default(),
                    format!("tool table line {line}: {}", msg.0),
                );
            }
        }
        if let Some(v) = self.input.var_file {
            for (line, msg) in lint_var_file(v) {
                self.diag(
                    codes::VAR_FILE,
                    Severity::Error,
                    Span::default(),
                    format!("parameter file line {line}: {msg}"),
                );
            }
        }
    }

    /// ServoWorks: a subprogram file that was just loaded for `M98 P<name>`.
    pub(super) fn spec_file_loaded(&mut self, idx: usize, name: &str) {
        if self.dialect != Dialect::Servoworks {
            return;
        }
        let Some(file) = self.files.get(idx) else {
            return;
        };
        let prog = file.prog.clone();
        let id = file.id;
        let mut head: Option<(String, Span)> = None;
        let mut first_code: Option<Span> = None;
        let mut last_block: Option<(Span, bool)> = None;
        for b in &prog.blocks {
            let items = prog.items_of(b);
            if items.is_empty() || !matches!(b.kind, analyzer::syntax::BlockKind::Normal) {
                continue;
            }
            let mut has_code = false;
            let mut m99 = false;
            for it in items {
                match &it.kind {
                    ItemKind::ProgramHead { name, .. } if first_code.is_none() => {
                        head = Some((prog.str_of(*name).into_owned(), it.span));
                        has_code = true;
                    }
                    ItemKind::Word(wd) => {
                        has_code = true;
                        if wd.letter == b'M' && wd.num().is_some_and(|n| n.value == 99.0) {
                            m99 = true;
                        }
                    }
                    ItemKind::Assign { .. } | ItemKind::Macro(_) => has_code = true,
                    _ => {}
                }
            }
            if has_code {
                first_code.get_or_insert(b.span);
                last_block = Some((b.span, m99));
            }
        }
        let Some((last_span, ends_m99)) = last_block else {
            return;
        };
        if !ends_m99 {
            let d = Diagnostic::new(codes::SUBPROGRAM_FILE, Severity::Warning, last_span, format!("subprogram O{name} does not end with M99: a ServoWorks subprogram returns to its caller only at M99; end it with M99")).in_file(id);
            self.out.diagnostics.push(d);
        }
        match head {
            Some((n, s)) if !n.eq_ignore_ascii_case(name) => {
                let d = Diagnostic::new(codes::SUBPROGRAM_FILE, Severity::Info, s, format!("the O line names O{n} but the file was called as O{name}: name the subprogram after its file")).in_file(id);
                self.out.diagnostics.push(d);
            }
            None => {
                let d = Diagnostic::new(codes::SUBPROGRAM_FILE, Severity::Info, first_code.unwrap_or_default(), format!("subprogram O{name} has no O{name} line: a ServoWorks subprogram starts with its name")).in_file(id);
                self.out.diagnostics.push(d);
            }
            _ => {}
        }
    }

    /// Runs on the items of a block before any of it executes: variable reads.
    pub(super) fn spec_items(&mut self, prog: &Program, items: &[Item]) {
        self.items.dollar.clear();
        self.items.bare_axes.clear();
        for it in items {
            match &it.kind {
                ItemKind::Word(wd) => {
                    if wd.letter == b'$' {
                        let v = match wd.value {
                            WordValue::Num(n) => n.value,
                            _ => 0.0,
                        };
                        self.items.dollar.push((v, it.span));
                    }
                    if matches!(wd.value, WordValue::Missing) && AXES.contains(&wd.letter) {
                        self.items.bare_axes.push((wd.letter, it.span));
                    }
                    if let WordValue::Expr(e) = wd.value {
                        self.vacant_reads(prog, e, false);
                    }
                }
                // A plain copy (`#10 = #1`) passes the vacancy on and computes nothing.
                ItemKind::Assign { value, .. } if plain_var(prog, *value) => {}
                ItemKind::Assign { value, .. } => self.vacant_reads(prog, *value, false),
                _ => {}
            }
        }
        self.spec_comma_words(items);
    }

    /// Reports reads of vacant variables in `e` (FANUC locals #1–#33 and, in
    /// ServoWorks, any variable). Operands of EQ/NE are exempt: comparing with
    /// a vacant value is how macros test whether an argument was given.
    fn vacant_reads(&mut self, prog: &Program, e: ExprId, in_compare: bool) {
        let node = *prog.expr(e);
        match node.expr {
            Expr::Var { index } => {
                if let Expr::Num(n) = prog.expr(index).expr {
                    let k = n.value;
                    let fanuc_local = self.dialect == Dialect::Fanuc && (1.0..=33.0).contains(&k);
                    let sw = self.dialect == Dialect::Servoworks && (1.0..1000.0).contains(&k);
                    let vacant = self.st.params.get(k as usize).copied().flatten().is_none();
                    // Set from a machine value the dry run does not know (`#24 = #516`):
                    // not read before it is assigned.
                    let machine_value = self
                        .machine_vars
                        .unknown_origin(k as usize, false)
                        .is_some();
                    // In a G65/G66 macro a local is an argument the caller may leave
                    // out: it reads as 0 in arithmetic, which macros rely on.
                    let macro_level = self.frames.last().is_some_and(|f| f.saved.is_some())
                        // A main program that returns with M99 is a macro checked alone.
                        || (self.frames.iter().all(|f| f.saved.is_none())
                            && self.files.first().is_some_and(|f| f.returns));
                    if !in_compare && (fanuc_local || sw) && vacant && !machine_value {
                        let (sev, why) = if fanuc_local && macro_level {
                            (Severity::Info, "an argument the caller did not pass is vacant and reads as 0 in arithmetic")
                        } else if fanuc_local {
                            (Severity::Warning, "a local variable that was not assigned at this level (nor passed as an argument) is vacant")
                        } else {
                            (
                                Severity::Info,
                                "the variable has not been assigned yet, so its value is vacant",
                            )
                        };
                        self.diag(
                            codes::VACANT_READ,
                            sev,
                            node.span,
                            format!(
                                "#{} is read before it is assigned: {why}; assign it first",
                                k as i64
                            ),
                        );
                    }
                } else {
                    self.vacant_reads(prog, index, in_compare);
                }
            }
            Expr::Neg { arg } | Expr::Plus { arg } => self.vacant_reads(prog, arg, in_compare),
            Expr::Group { inner } => self.vacant_reads(prog, inner, in_compare),
            Expr::Binary { op, lhs, rhs } => {
                let cmp = in_compare || matches!(op, BinOp::Eq | BinOp::Ne);
                self.vacant_reads(prog, lhs, cmp);
                self.vacant_reads(prog, rhs, cmp);
            }
            Expr::Call { arg, arg2, .. } => {
                self.vacant_reads(prog, arg, in_compare);
                if let Some(a) = arg2 {
                    self.vacant_reads(prog, a, in_compare);
                }
            }
            _ => {}
        }
    }

    /// FANUC: optional chamfer / corner R (`,C` `,R`) in involute or polar
    /// interpolation mode, found through the items (the word reader drops them).
    fn spec_comma_words(&mut self, items: &[Item]) {
        if self.dialect != Dialect::Fanuc {
            return;
        }
        let involute = matches!(self.st.modal.motion, 22 | 32);
        for it in items {
            let ItemKind::Word(wd) = &it.kind else {
                continue;
            };
            if !wd.comma {
                continue;
            }
            let g_here: Vec<u32> = items
                .iter()
                .filter_map(|x| match &x.kind {
                    ItemKind::Word(g) if g.letter == b'G' => g
                        .num()
                        .and_then(|n| analyzer::dialect::CodeNum::from_value(n.value))
                        .map(|c| c.0),
                    _ => None,
                })
                .collect();
            let inv_here = involute && !g_here.iter().any(|g| matches!(g, 0 | 10 | 20 | 30))
                || g_here.iter().any(|g| matches!(g, 22 | 32));
            if inv_here {
                self.diag(
                    codes::INVOLUTE,
                    Severity::Error,
                    it.span,
                    "optional chamfering or corner R cannot be used in involute interpolation mode",
                );
            } else if self.rules.polar_interp.on || self.st.modal.polar {
                self.diag(
                    codes::POLAR_INTERP,
                    Severity::Error,
                    it.span,
                    "optional chamfering or corner R cannot be used in polar coordinate mode",
                );
            }
        }
    }
}

/// Problems of a LinuxCNC tool table: (1-based line, (message, is error)).
pub fn lint_tool_table(text: &str) -> Vec<(usize, (String, bool))> {
    let mut out = Vec::new();
    let mut pockets: Vec<(i64, usize)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let body = line.split(';').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let mut t = None;
        let mut p = None;
        for word in body.split_whitespace() {
            let mut chars = word.chars();
            let letter = chars.next().map(|c| c.to_ascii_uppercase());
            let value = chars.as_str().parse::<f64>();
            match (letter, value) {
                (Some('T'), Ok(v)) => t = Some(v),
                (Some('P'), Ok(v)) => p = Some(v as i64),
                (
                    Some(
                        'T' | 'P' | 'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W' | 'D' | 'I'
                        | 'J' | 'Q',
                    ),
                    Err(_),
                )
                | (None, _) => {
                    out.push((
                        k + 1,
                        (
                            format!("`{word}` is not a number: LinuxCNC cannot load this line"),
                            true,
                        ),
                    ));
                }
                (Some(c), _) if !"TPXYZABCUVWDIJQ".contains(c) => {
                    out.push((
                        k + 1,
                        (
                            format!("unknown entry `{word}`: LinuxCNC cannot load this line"),
                            true,
                        ),
                    ));
                }
                _ => {}
            }
        }
        if t.is_none() || p.is_none() {
            out.push((
                k + 1,
                (
                    format!("a tool line needs both T (tool number) and P (pocket): `{body}`"),
                    true,
                ),
            ));
        }
        if let Some(p) = p {
            if let Some((_, first)) = pockets.iter().find(|(q, _)| *q == p) {
                out.push((
                    k + 1,
                    (
                        format!("pocket P{p} is already used on line {first}: the last line wins"),
                        false,
                    ),
                ));
            } else {
                pockets.push((p, k + 1));
            }
        }
    }
    out
}

/// Problems of a LinuxCNC `.var` file: (1-based line, message).
pub fn lint_var_file(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut last: Option<u64> = None;
    for (k, line) in text.lines().enumerate() {
        let mut it = line.split_whitespace();
        let Some(n) = it.next() else { continue };
        let (Ok(n), Some(Ok(_))) = (n.parse::<u64>(), it.next().map(|v| v.parse::<f64>())) else {
            out.push((
                k + 1,
                format!(
                    "`{}` is not `number value`: LinuxCNC cannot read the parameter file",
                    line.trim()
                ),
            ));
            continue;
        };
        if last.is_some_and(|l| n <= l) {
            out.push((k + 1, format!("parameter {n} is out of order (after {}): LinuxCNC requires increasing numbers", last.unwrap_or(0))));
        }
        last = Some(n);
    }
    out
}

/// `#n` with a literal number, in any brackets.
fn plain_var(prog: &Program, e: ExprId) -> bool {
    prog.variable_index(e)
        .is_some_and(|i| matches!(prog.expr(i).expr, Expr::Num(_)))
}
