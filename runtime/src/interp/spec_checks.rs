//! Checks for the spec ledger's runtime ids (issue 3). They sit in their own
//! module, reached through a handful of hook calls, so that the interpreter's
//! semantics and these diagnostics can change independently.

use analyzer::syntax::{BinOp, Expr, Item};

use super::*;

/// What these checks remember between blocks.
#[derive(Debug, Default, Clone, PartialEq)]
pub(super) struct SpecMem {
    /// RS274/NGC: user M codes already noted as unconfigured.
    pub(super) user_m_noted: Vec<i64>,
    /// ServoWorks: G311 (feed excludes rotary axes) is in force.
    g311: bool,
    /// RS274/NGC: a UVW plane (G17.1/G18.1/G19.1) is selected.
    uvw_plane: bool,
    /// FANUC: polar coordinate interpolation (G12.1) is on.
    polar_interp: bool,
    /// FANUC: cylindrical interpolation (G07.1) is on.
    cylindrical: bool,
    /// ServoWorks: a G43/G44 with a non-zero H has been given and not cancelled.
    tlc_h: bool,
    /// Blocks since the last motion while radius compensation is on.
    blocks_without_motion: u32,
    motions_seen: usize,
    /// RS274/NGC: call levels (frame depth) at which M70/M73 saved the modal state.
    saved_levels: Vec<usize>,
    /// `$` words of the current block (value, span), and bare axis letters.
    dollar: Vec<(f64, Span)>,
    bare_axes: Vec<(u8, Span)>,
    /// Whether the optional rule F015 is selected, looked up once: the registry
    /// search costs more than the rest of a motion block's checks.
    feed_spindle_off: Option<bool>,
    /// Rapid blocks (file, block) that have moved the tool at least once, and
    /// those that carry an F014 note: a rapid in a subprogram or loop is a
    /// no-op on some passes only, and the note is for rapids that never move.
    rapid_moved: std::collections::HashSet<(usize, u32)>,
    rapid_noted: std::collections::HashSet<(usize, u32)>,
    /// Every block runs at most once (a program without calls, loops or jumps):
    /// the per-block rapid bookkeeping above is not needed.
    pub(super) single_pass: bool,
}

const AXES: &[u8; 6] = b"XYZABC";

impl SpecMem {
    /// Applies `f` to the source spans remembered (a rerun moves them).
    pub(super) fn shift_spans(&mut self, f: impl Fn(Span) -> Span) {
        for (_, s) in &mut self.dollar {
            *s = f(*s);
        }
        for (_, s) in &mut self.bare_axes {
            *s = f(*s);
        }
    }

    /// Moves the remembered motion count (a rerun changes how many motions
    /// came before).
    pub(super) fn shift_motion_count(&mut self, d: i64) {
        self.motions_seen = (self.motions_seen as i64 + d).max(0) as usize;
    }
}

impl Interp<'_, '_> {
    /// Removes the F014 note of a rapid block that has now moved the tool.
    fn withdraw_rapid_note(&mut self, here: (usize, u32), span: Span) {
        if !self.spec.rapid_noted.remove(&here) {
            return;
        }
        let file = self.file_id();
        if let Some(j) = self
            .out
            .diagnostics
            .iter()
            .rposition(|d| d.code == codes::RAPID_NO_MOTION && d.span == span && d.file == file)
        {
            self.out.diagnostics.remove(j);
        }
    }

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
        self.spec.dollar.clear();
        self.spec.bare_axes.clear();
        for it in items {
            match &it.kind {
                ItemKind::Word(wd) => {
                    if wd.letter == b'$' {
                        let v = match wd.value {
                            WordValue::Num(n) => n.value,
                            _ => 0.0,
                        };
                        self.spec.dollar.push((v, it.span));
                    }
                    if matches!(wd.value, WordValue::Missing) && AXES.contains(&wd.letter) {
                        self.spec.bare_axes.push((wd.letter, it.span));
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

    /// Checks of a block against the state before it runs.
    pub(super) fn spec_checks(
        &mut self,
        w: &Words,
        bspan: Span,
        motion: Option<(u32, Span)>,
    ) -> Result<(), Diagnostic> {
        match self.dialect {
            Dialect::Rs274ngc => self.ngc_spec_checks(w, bspan, motion)?,
            Dialect::Servoworks => self.sw_spec_checks(w, bspan, motion),
            Dialect::Fanuc => self.fanuc_spec_checks(w, bspan, motion),
        }
        // The look-ahead of ServoWorks radius compensation counts blocks between motions.
        let n = self.out.motions.len();
        if n > self.spec.motions_seen || self.st.modal.comp == 400 {
            self.spec.blocks_without_motion = 0;
        } else {
            self.spec.blocks_without_motion += 1;
            if self.dialect == Dialect::Servoworks && self.spec.blocks_without_motion == 101 {
                self.diag(codes::TRC_LOOKAHEAD, Severity::Info, bspan, "more than 100 blocks without motion in tool radius compensation: the look-ahead buffer holds 100 blocks, so the offset at the next corner cannot see the next move; keep blocks without motion few");
            }
        }
        self.spec.motions_seen = n;
        Ok(())
    }

    /// What `spec_checks` does for a plain motion line of the fast path (see
    /// `plain_motion_checks`): the M70/M73 levels, feed with the spindle stopped,
    /// and the look-ahead count.
    pub(super) fn plain_spec_checks(&mut self, m: u32, s: Span, bspan: Span) {
        self.spec.dollar.clear();
        self.spec.bare_axes.clear();
        if !self.spec.saved_levels.is_empty() {
            let level = self.frames.len();
            self.spec.saved_levels.retain(|l| *l <= level);
        }
        if m == 10 && self.feed_spindle_off_wanted() && self.st.spindle_dir == 0 {
            self.diag(codes::FEED_SPINDLE_OFF, Severity::Warning, s, "feed move with the spindle stopped: the tool would rub or break; start the spindle (M3/M4) first");
        }
        let _ = bspan;
        // Compensation is off on the fast path, so the count restarts.
        self.spec.blocks_without_motion = 0;
        self.spec.motions_seen = self.out.motions.len();
    }

    /// Whether the optional rule for feed moves with the spindle stopped is selected
    /// (looked up once).
    fn feed_spindle_off_wanted(&mut self) -> bool {
        match self.spec.feed_spindle_off {
            Some(w) => w,
            None => {
                let w = crate::rules::lookup(codes::FEED_SPINDLE_OFF)
                    .is_some_and(|meta| self.input.settings.rule_enabled(meta));
                self.spec.feed_spindle_off = Some(w);
                w
            }
        }
    }

    fn ngc_spec_checks(
        &mut self,
        w: &Words,
        bspan: Span,
        motion: Option<(u32, Span)>,
    ) -> Result<(), Diagnostic> {
        let modal = self.st.modal.motion;
        let gm = |codes: &[u32]| codes.iter().any(|c| w.has_g(*c));
        // Axis words with no motion code in the line while the modal motion is G80
        // (also at power on): LinuxCNC has nothing to give them to (enhance_block).
        // G10, G28, G30, G52 and G92 use them themselves; G43.1/G43.2 take them
        // as the offset.
        let group_1 = w.g.iter().any(|(g, _)| is_group_1(*g));
        if modal == 800
            && motion.is_none()
            && !group_1
            && w.any_axis()
            && !gm(&[100, 280, 300, 520, 920, 431, 432])
        {
            let span = b"XYZABCUVW"
                .iter()
                .find(|c| w.has(**c))
                .map(|c| w.sp(*c))
                .unwrap_or(bspan);
            return Err(self.err(
                codes::WORD_UNUSED,
                span,
                "cannot use axis values without a g code that uses them: no motion mode is active \
                 (G80, or none yet since the program start), so LinuxCNC stops here; give G0 or G1 \
                 on this line",
            ));
        }
        let mm = |codes: &[u32]| codes.iter().any(|c| w.has_m(*c));
        let user_m = w.m.iter().any(|(m, _)| (1000..=1990).contains(m));
        // Splines and NURBS are not in the checks' motion list: an explicit code wins.
        let mode =
            w.g.iter()
                .find(|g| matches!(g.0, 50..=52))
                .map(|g| g.0)
                .or(motion.map(|m| m.0))
                .unwrap_or(modal);
        let lathe_cycle = gm(&[700, 710, 711, 712, 720, 721, 722]);
        let cycle = is_cycle(mode);
        // Words that no code of the line uses (LinuxCNC's check of other codes).
        let unused: [(u8, bool, &str); 8] = [
            (b'D', gm(&[410, 411, 420, 421, 960]) || lathe_cycle, "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it"),
            (b'H', gm(&[430, 432, 760]), "H word with no G43 or G76 to use it"),
            (b'I', matches!(mode, 20 | 30 | 50 | 51 | 870 | 331 | 760) || gm(&[100, 710, 711, 712, 720, 721, 722]), "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it"),
            (b'J', matches!(mode, 20 | 30 | 50 | 51 | 870 | 331 | 760) || gm(&[100]), "J word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it"),
            (b'L', cycle || matches!(mode, 20 | 30 | 52 | 760) || gm(&[100, 410, 411, 420, 421]) || mm(&[660, 980]) || lathe_cycle, "L word with no G10, cutter compensation, canned cycle, digital/analog input, M98 or NURBS code"),
            (b'P', cycle || matches!(mode, 20 | 30 | 50 | 52 | 760) || gm(&[40, 100, 640]) || mm(&[190, 500, 510, 520, 530, 620, 630, 640, 650, 660, 980]) || user_m || lathe_cycle, "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 M53 M62 M63 M64 M65 M66 M98 or user M code to use it"),
            (b'Q', cycle || matches!(mode, 50 | 760) || gm(&[100, 640]) || mm(&[190, 610, 660, 670, 680]) || user_m || lathe_cycle, "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses it"),
            (b'R', cycle || matches!(mode, 20 | 30 | 760) || gm(&[100]) || mm(&[190]) || lathe_cycle, "R word with no g code that uses it"),
        ];
        for (c, used, msg) in unused {
            if w.has(c) && !used {
                return Err(self.err(
                    codes::WORD_UNUSED,
                    w.sp(c),
                    format!(
                        "{msg}: LinuxCNC stops here; remove the word or add the code it belongs to"
                    ),
                ));
            }
        }
        if let Some(&(v, s)) = self.spec.dollar.first() {
            let takes = mm(&[30, 40, 50, 190, 510]) || gm(&[330, 331, 760, 950, 960, 970]);
            if !takes {
                return Err(self.err(codes::WORD_UNUSED, s, "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, G76, G95, G96 or G97 to use it: LinuxCNC stops here"));
            }
            let spindles = self.input.machine.spindles.unwrap_or(1.0);
            if v != -1.0 && (v < 0.0 || v >= spindles || v.fract() != 0.0) {
                return Err(self.err(codes::WORD_UNUSED, s, format!("${v} selects a spindle this machine does not have (spindles 0 to {}, or $-1 for all): LinuxCNC stops here", spindles - 1.0)));
            }
        }
        // User M codes M100–M199 run a program from the configured list.
        if let Some(&(m, s)) = w.m.iter().find(|(m, _)| (1000..=1990).contains(m)) {
            let n = i64::from(m / 10);
            let listed = self.input.machine.user_m_codes.as_ref();
            let known = listed.is_some_and(|a| a.contains(&n));
            // Without a list and without the machine's search path the program file
            // M<n> may well exist on the machine: say so once per code, go on.
            if !known && listed.is_none() && !self.input.resolver.searches_like_the_control() {
                if !self.spec.user_m_noted.contains(&n) {
                    self.spec.user_m_noted.push(n);
                    self.diag(codes::UNKNOWN_USER_M, Severity::Info, s, format!("M{n} is a user M code: LinuxCNC runs the program file M{n} from its USER_M_PATH. None is configured here, so the dry run takes it as doing nothing; list the codes the machine has in `machine.user_m_codes` to have the others reported"));
                }
            } else if !known {
                return Err(self.err(codes::UNKNOWN_USER_M, s, format!("Unknown m code used: M{n}: no user M-code program M{n} is configured; list it in `machine.user_m_codes` or remove it")));
            }
        }
        // M70/M73 save the modal state of this call level; M72 restores it.
        let level = self.frames.len();
        if (w.has_m(700) || w.has_m(730)) && !self.spec.saved_levels.contains(&level) {
            self.spec.saved_levels.push(level);
        }
        if w.has_m(720) && !self.spec.saved_levels.contains(&level) {
            return Err(self.err(codes::CONTEXT_RESTORE, Self::m_span(w, 720), "M72 restores a modal state that no M70 or M73 saved at this call level: LinuxCNC stops (missing M70/M73?)"));
        }
        self.spec.saved_levels.retain(|l| *l <= level);
        // NURBS blocks.
        if w.has_g(53) && modal != 52 {
            return Err(self.err(
                codes::NURBS_BLOCK,
                w.g_span(53),
                "Cannot use G5.3 without G5.2 first",
            ));
        }
        if mode == 52 && (w.has_g(52) || w.any_axis()) {
            if let Some(p) = w.get(b'P').filter(|p| *p <= 0.0) {
                return Err(self.err(
                    codes::NURBS_BLOCK,
                    w.sp(b'P'),
                    format!("NURBS weight P{p} must be positive"),
                ));
            }
            // The first control point may leave out X and Y (it is where the
            // tool is); any other needs both, and one without the other is
            // always an error.
            let span = motion.map(|m| m.1).unwrap_or(bspan);
            if w.has(b'X') != w.has(b'Y') {
                return Err(self.err(
                    codes::NURBS_BLOCK,
                    span,
                    "You must specify both X and Y coordinates for Control Points",
                ));
            }
            if !w.has(b'X') && w.get(b'P').is_some_and(|p| p > 0.0) && !self.nurbs.is_empty() {
                return Err(self.err(
                    codes::NURBS_BLOCK,
                    span,
                    "Can specify P without X and Y only for the first control point",
                ));
            }
        }
        // Lathe roughing/finishing cycles, checked in LinuxCNC's order and words.
        if let Some(&(g, s)) =
            w.g.iter()
                .find(|(g, _)| matches!(g, 700 | 710 | 711 | 712 | 720 | 721 | 722))
        {
            let name = format!("G{}.{}", g / 10, g % 10);
            if !w.has(b'Q') {
                return Err(self.err(codes::LATHE_CYCLE, s, "G7x.x  requires a Q word"));
            }
            if g != 700 && self.st.modal.comp != 400 {
                return Err(self.err(
                    codes::LATHE_CYCLE,
                    s,
                    format!("{name} cannot be used with cutter compensation enabled"),
                ));
            }
            if self.st.modal.plane != 180 && !w.has_g(180) {
                return Err(self.err(
                    codes::LATHE_CYCLE,
                    s,
                    format!("{name} can only be used in XZ plane (G18)"),
                ));
            }
        }
        // Plane selection for arcs in UVW planes.
        if let Some(&(g, s)) = motion.as_ref().filter(|m| matches!(m.0, 20 | 30)) {
            if self.spec.uvw_plane && !gm(&[170, 180, 190]) {
                return Err(self.err(codes::ARC_UVW_PLANE, s, format!("G{} in a UVW plane (G17.1/G18.1/G19.1): LinuxCNC cannot make arcs there; select G17, G18 or G19", g / 10)));
            }
        }
        if gm(&[171, 181, 191]) {
            self.spec.uvw_plane = true;
        } else if gm(&[170, 180, 190]) {
            self.spec.uvw_plane = false;
        }
        if let Some((m, s)) = motion {
            // A rapid to where the tool already is.
            if m == 0 && w.has_g(0) && w.any_axis() && self.any_motion() {
                let t = self.target(w);
                let here = self.cur;
                // A subprogram's first motion positions the tool for each call: that
                // a caller is already there does not make it useless.
                let made = self.motions_drained + self.out.motions.len();
                let positions_call = self
                    .frames
                    .last()
                    .is_some_and(|f| f.motions_at_call == made);
                if positions_call {
                    if self.spec.rapid_moved.insert(here) {
                        self.withdraw_rapid_note(here, s);
                    }
                } else if dist(&t, &self.st.pos) < 1e-9 {
                    if self.spec.single_pass {
                        self.diag(codes::RAPID_NO_MOTION, Severity::Info, s, "this rapid goes to where the tool already is: it does nothing but costs a block; remove it or check the coordinates");
                    } else if !self.spec.rapid_moved.contains(&here)
                        && !self.spec.rapid_noted.contains(&here)
                    {
                        self.spec.rapid_noted.insert(here);
                        self.diag(codes::RAPID_NO_MOTION, Severity::Info, s, "this rapid goes to where the tool already is: it does nothing but costs a block; remove it or check the coordinates");
                    }
                } else if !self.spec.single_pass && self.spec.rapid_moved.insert(here) {
                    self.withdraw_rapid_note(here, s);
                }
            }
            // Feed moves with the spindle off (optional rule).
            // Off by default, so it is computed only when selected.
            let wanted = self.feed_spindle_off_wanted();
            if wanted && (matches!(m, 10 | 20 | 30) || is_cycle(m)) && self.st.spindle_dir == 0 {
                self.diag(codes::FEED_SPINDLE_OFF, Severity::Warning, s, "feed move with the spindle stopped: the tool would rub or break; start the spindle (M3/M4) first");
            }
            // A cycle repeated by a line that moves only the drilling axis.
            if motion_is_modal(w, m) && is_cycle(m) {
                let n = b"ZYX"[match self.st.modal.plane {
                    180 => 1,
                    190 => 2,
                    _ => 0,
                }];
                let plane_word = b"XYZ".iter().any(|c| *c != n && w.has(*c));
                if w.has(n) && !plane_word {
                    self.diag(codes::CYCLE_STILL_ACTIVE, Severity::Info, s, format!("the canned cycle G{} is still active: this {} move drills again at the same hole instead of moving; give G80 before leaving the holes", m / 10, n as char));
                }
            }
        }
        Ok(())
    }

    fn sw_spec_checks(&mut self, w: &Words, _bspan: Span, motion: Option<(u32, Span)>) {
        let tlc_type = self.input.machine.tlc_type.unwrap_or(0);
        // A plane code in the block applies before its G43/G37.
        let plane =
            w.g.iter()
                .find(|g| matches!(g.0, 170 | 180 | 190))
                .map_or(self.st.modal.plane, |g| g.0);
        let perpendicular = match plane {
            180 => 1usize,
            190 => 0,
            _ => 2,
        };
        let axis_words: Vec<(usize, Span)> = AXES
            .iter()
            .enumerate()
            .filter(|(_, c)| w.has(**c))
            .map(|(i, c)| (i, w.sp(*c)))
            .chain(
                self.spec
                    .bare_axes
                    .iter()
                    .filter_map(|(c, s)| AXES.iter().position(|a| a == c).map(|i| (i, *s))),
            )
            .collect();
        // G43/G44: which axis the length offset goes to, by TLC type.
        if let Some(&(g, _)) = w.g.iter().find(|(g, _)| matches!(g, 430 | 440)) {
            let h = w.get(b'H').map(|h| h.round() as i64);
            let allowed = if tlc_type == 1 { perpendicular } else { 2 };
            let has_allowed = axis_words.iter().any(|a| a.0 == allowed);
            for &(i, s) in axis_words
                .iter()
                .filter(|_| tlc_type != 2 && !has_allowed)
                .take(1)
            {
                let letter = AXES[i] as char;
                match tlc_type {
                    0 if i != 2 => self.diag(codes::TLC_TYPE, Severity::Error, s, format!("tool length compensation type 0 (A) compensates only Z: G{} {letter} raises an alarm; use Z or set machine.tlc_type", g / 10)),
                    1 if i != perpendicular => self.diag(codes::TLC_TYPE, Severity::Error, s, format!("tool length compensation type 1 (B) compensates the axis perpendicular to the plane ({}): G{} {letter} raises an alarm; select the matching plane first", AXES[perpendicular] as char, g / 10)),
                    _ => {}
                }
            }
            match h {
                Some(0) => self.spec.tlc_h = false,
                Some(_) => self.spec.tlc_h = true,
                None => {}
            }
        }
        if w.has_g(490) {
            self.spec.tlc_h = false;
            // Type C cancels only with G49 and H0 in the same block.
            if tlc_type == 2 && w.get(b'H') != Some(0.0) {
                self.diag(codes::TLC_TYPE, Severity::Error, w.g_span(490), "with tool length compensation type 2 (C) the cancel needs both G49 and H0: G49 alone raises an alarm; write G49 H0");
            }
        }
        // G37 automatic tool length calibration.
        if w.has_g(370) {
            let s = w.g_span(370);
            if tlc_type == 2 {
                self.diag(codes::TLC_TYPE, Severity::Error, s, "G37 is not supported with tool length compensation type 2 (C): the control raises an error");
            } else if !self.spec.tlc_h {
                self.diag(codes::TLC_TYPE, Severity::Error, s, "G37 needs a preceding G43 or G44 with a non-zero H: the calibrated offset has no tool to go to");
            }
            let allowed = if tlc_type == 1 { perpendicular } else { 2 };
            if tlc_type != 2 {
                if let Some(&(i, ws)) = axis_words.iter().find(|(i, _)| *i != allowed) {
                    self.diag(codes::TLC_TYPE, Severity::Error, ws, format!("G37 with {} is not allowed: with tool length compensation type {tlc_type} only {} can be calibrated", AXES[i] as char, AXES[allowed] as char));
                }
            }
        }
        // Smoothing time by servo rate (G10 L108).
        if w.has_g(100) && w.get(b'L').map(|l| l.round() as i64) == Some(108) {
            let khz = self.input.machine.servo_rate_khz.unwrap_or(1.0);
            let max = if khz <= 1.0 {
                5000.0
            } else if khz <= 2.0 {
                2500.0
            } else {
                1250.0
            };
            for c in [b'R', b'X', b'Y', b'Z', b'A', b'B', b'C'] {
                if let Some(v) = w.get(c).filter(|v| *v < 0.0 || *v > max) {
                    self.diag(codes::SMOOTHING_TIME, Severity::Error, w.sp(c), format!("smoothing time {v} ms is out of range: at a {khz} kHz servo rate G10 L108 accepts 0 to {max} ms"));
                }
            }
        }
        // G311: rotary axes are not part of the feed; a block moving only rotary axes has none.
        if w.has_g(3110) {
            self.spec.g311 = true;
        } else if w.has_g(3100) {
            self.spec.g311 = false;
        }
        if let Some((m, s)) = motion {
            let rotary = b"ABC".iter().any(|c| w.has(*c));
            let linear = b"XYZ".iter().any(|c| w.has(*c));
            if self.spec.g311 && matches!(m, 10 | 20 | 30) && rotary && !linear {
                self.diag(codes::ROTARY_ONLY_FEED, Severity::Warning, s, "G311 leaves rotary axes out of the feed, and this block moves only rotary axes: the feed has no basis; use G310 for this block");
            }
        }
    }

    fn fanuc_spec_checks(&mut self, w: &Words, _bspan: Span, motion: Option<(u32, Span)>) {
        let involute_mode = matches!(self.st.modal.motion, 22 | 32);
        // Modes that switch for the following blocks.
        if w.has_g(71) {
            self.spec.cylindrical = true;
        }
        if w.has_g(121) {
            self.spec.polar_interp = true;
        } else if w.has_g(131) {
            self.spec.polar_interp = false;
        }
        // Involute mode restrictions.
        // Involute codes are not in the checks' motion list: find them here.
        let invol: Option<(u32, Span)> =
            w.g.iter()
                .find(|g| matches!(g.0, 22 | 32))
                .copied()
                .or_else(|| {
                    (involute_mode
                        && w.any_axis()
                        && !w.g.iter().any(|g| matches!(g.0, 0 | 10 | 20 | 30)))
                    .then(|| {
                        (
                            self.st.modal.motion,
                            w.g.first().map(|g| g.1).unwrap_or(_bspan),
                        )
                    })
                });
        let invol_block = invol.is_some();
        let motion = invol.or(motion);
        if involute_mode || invol_block {
            for &(g, s) in &w.g {
                if matches!(g, 400 | 410 | 420) && involute_mode {
                    self.diag(codes::INVOLUTE, Severity::Error, s, format!("G{} cannot be commanded in involute interpolation mode: give G41/G42 before G02.2/G03.2 and G40 after leaving it", g / 10));
                } else if involute_mode
                    && !matches!(
                        g,
                        22 | 32
                            | 40
                            | 100
                            | 170
                            | 180
                            | 190
                            | 650
                            | 660
                            | 670
                            | 900
                            | 910
                            | 0
                            | 10
                            | 20
                            | 30
                    )
                {
                    self.diag(codes::INVOLUTE, Severity::Error, s, format!("G{} is not allowed in involute interpolation mode (only G04, G10, G17–G19, G65–G67, G90, G91)", analyzer::dialect::CodeNum(g).display()));
                }
            }
        }
        if let Some((m, s)) = motion {
            if matches!(m, 22 | 32) {
                if self.spec.cylindrical {
                    self.diag(codes::INVOLUTE, Severity::Error, s, "involute interpolation is not allowed in cylindrical interpolation (G07.1) mode");
                }
                self.involute_geometry(w, m == 32, s);
            }
            if self.spec.polar_interp && m == 0 {
                self.diag(codes::POLAR_INTERP, Severity::Warning, s, "G00 in polar coordinate interpolation (G12.1): only G01, G02, G03, G02.2 and G03.2 are allowed there; cancel with G13.1 before rapids");
            }
            if matches!(m, 330) {
                self.thread_checks(w, s);
            }
            if is_cycle(m) && matches!(m, 840 | 740) && self.st.modal.rigid_tap {
                if let Some(f) = w.get(b'F') {
                    if f == 0.0 {
                        self.diag(codes::RIGID_TAP_FEED, Severity::Error, w.sp(b'F'), "rigid tapping with F0: the lead is zero, so the tap cannot advance (PS0201); give F = lead × S");
                    } else if let Some(max) = self.input.machine.max_cutting_feed {
                        let f_mm = if self.st.modal.feed_mode == 950 {
                            f * self.st.spindle
                        } else {
                            f
                        } * if self.st.modal.inch { 25.4 } else { 1.0 };
                        if f_mm > max {
                            self.diag(codes::RIGID_TAP_FEED, Severity::Error, w.sp(b'F'), format!("rigid tapping feed {f_mm} mm/min is above the cutting-feed upper limit {max} mm/min: the control alarms; lower S or the lead"));
                        }
                    }
                }
            }
        }
        // Offset numbers and G10 data.
        let count = self.input.machine.offset_count.unwrap_or(400.0);
        for c in [b'H', b'D'] {
            if let Some(v) = w.get(c) {
                let uses = if c == b'H' {
                    w.g.iter().any(|g| matches!(g.0, 430 | 440 | 490))
                } else {
                    w.g.iter().any(|g| matches!(g.0, 410 | 420))
                };
                if uses && (v < 0.0 || v > count) {
                    self.diag(codes::OFFSET_NUMBER, Severity::Error, w.sp(c), format!("offset number {}{v} is beyond the {count} offsets of this control (PS0030): use 0 to {count}", c as char));
                }
            }
        }
        if w.has_g(100) {
            let l = w.get(b'L').map(|l| l.round() as i64);
            let ok_l = matches!(l, Some(1 | 2 | 3 | 10 | 11 | 12 | 13 | 20 | 50 | 52));
            if !ok_l {
                let span = if w.has(b'L') {
                    w.sp(b'L')
                } else {
                    w.g_span(100)
                };
                self.diag(codes::OFFSET_NUMBER, Severity::Error, span, format!("G10 {}: the data kind L is missing or not one the control knows (PS0031); use L1/L10–L13 tool offsets, L2/L20 work offsets", l.map(|l| format!("L{l}")).unwrap_or_else(|| "without L".into())));
            } else if matches!(l, Some(1 | 10 | 11 | 12 | 13)) && !w.has(b'P') {
                self.diag(codes::OFFSET_NUMBER, Severity::Error, w.g_span(100), "G10 tool offset data without P (the offset number): the control alarms (PS0031)");
            } else if l == Some(2) && w.get(b'P').is_some_and(|p| !(0.0..=6.0).contains(&p)) {
                self.diag(
                    codes::OFFSET_NUMBER,
                    Severity::Error,
                    w.sp(b'P'),
                    "G10 L2 takes P0 (external) to P6 (G59): other P values are illegal (PS0031)",
                );
            }
        }
        // Scaling magnification.
        if w.has_g(510) {
            if let Some(p) = w.get(b'P') {
                let m = if w.point[(b'P' - b'A') as usize] {
                    p
                } else {
                    p * 0.001
                };
                if m <= 0.0 || m >= 10.0 {
                    self.diag(codes::SCALING_MAGNIFICATION, Severity::Error, w.sp(b'P'), format!("scaling magnification {m} is out of range (PS0142): it must be above 0 and below 10 (P1 to P9999)"));
                }
            }
        }
    }

    /// G33 lead and spindle speed limits (FANUC).
    fn thread_checks(&mut self, w: &Words, s: Span) {
        let Some(f) = w.get(b'F') else { return };
        let point = w.point[(b'F' - b'A') as usize];
        let inch = self.st.modal.inch;
        let lead = if point {
            f
        } else if inch {
            f * 0.0001
        } else {
            f * 0.01
        };
        let (lo, hi, unit) = if inch {
            (0.0001, 9.9999, "in")
        } else {
            (0.01, 500.0, "mm")
        };
        if lead < lo - 1e-12 || lead > hi + 1e-9 {
            self.diag(codes::THREAD_LEAD, Severity::Error, w.sp(b'F'), format!("G33 lead {lead} {unit} is out of range: the control accepts {lo} to {hi} {unit}"));
            return;
        }
        let lead_mm = if inch { lead * 25.4 } else { lead };
        if let Some(fmax) = self.input.machine.max_cutting_feed {
            let smax = fmax / lead_mm;
            if self.st.spindle > smax + 1e-9 {
                self.diag(codes::THREAD_LEAD, Severity::Warning, s, format!("spindle speed S{} exceeds the threading limit {:.1} min⁻¹ (maximum feed {fmax} mm/min ÷ lead {lead_mm} mm): the axis cannot follow the spindle; lower S", self.st.spindle, smax));
            }
        }
    }

    /// FANUC involute interpolation (G02.2/G03.2) in the XY plane: the start
    /// and end must lie outside the base circle, on one involute, within 100 turns.
    fn involute_geometry(&mut self, w: &Words, ccw: bool, s: Span) {
        let (a, b) = self.plane_axes();
        let (ia, ib) = (b"IJK"[a.min(2)], b"IJK"[b.min(2)]);
        let (Some(i), Some(j), Some(r)) = (w.get(ia), w.get(ib), w.get(b'R')) else {
            return;
        };
        let u = if self.st.modal.inch { 25.4 } else { 1.0 };
        let (i, j, r) = (i * u, j * u, r.abs() * u);
        if r <= 0.0 {
            return;
        }
        let start = [self.st.pos[a], self.st.pos[b]];
        let t = self.target(w);
        let end = [t[a], t[b]];
        let c = [start[0] + i, start[1] + j];
        let rho = |p: [f64; 2]| (p[0] - c[0]).hypot(p[1] - c[1]);
        let (rs, re) = (rho(start), rho(end));
        let tol = 1e-6;
        if rs < r - tol || re < r - tol {
            let which = if rs < r - tol { "start" } else { "end" };
            self.diag(codes::INVOLUTE, Severity::Error, s, format!("the involute's {which} point lies inside the base circle (radius {r}): the control alarms (PS0242)"));
            return;
        }
        // Unwinding angle of each point and the angle where its involute leaves the circle.
        let phi = |rr: f64| ((rr / r).powi(2) - 1.0).max(0.0).sqrt();
        let (ps, pe) = (phi(rs), phi(re));
        if ps.max(pe) > 100.0 * std::f64::consts::TAU {
            self.diag(codes::INVOLUTE, Severity::Error, s, "the involute's start or end point is more than 100 turns from where the involute leaves the base circle: the control alarms (PS0242)");
            return;
        }
        // G03.2 turns counter-clockwise: outward the involute unwinds with the turn, inward against it.
        let dir = if ccw { 1.0 } else { -1.0 };
        let sense = if re >= rs { dir } else { -dir };
        let ang = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
        let base = |p: [f64; 2], f: f64| ang(p) - sense * (f - f.atan());
        let mut d = base(end, pe) - base(start, ps);
        d = (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
        let dev = 2.0 * re * (d.abs() / 2.0).sin();
        let limit = self.input.machine.involute_tolerance.unwrap_or(0.01);
        if dev > limit {
            self.diag(codes::INVOLUTE, Severity::Error, s, format!("the end point is {dev:.4} mm off the involute through the start point, more than the allowed {limit} mm (parameter 5610): the control alarms (PS0243)"));
        }
        // Cutter compensation on the concave side shortens the unwound string by the radius.
        let inner = matches!((self.st.modal.comp, ccw), (410, true) | (420, false));
        let rc = self.st.comp_radius;
        if inner && rc > 0.0 && rc > r * ps.min(pe) {
            self.diag(codes::INVOLUTE, Severity::Warning, s, format!("with cutter compensation (radius {rc}) the tool-centre involute enters the base circle near the start: the control alarms (PS0242); start farther from the base circle or use a smaller tool"));
        }
        let extra = b"XYZABCUVW"
            .iter()
            .enumerate()
            .filter(|(k, c)| *k != a && *k != b && w.has(**c))
            .count();
        if extra > 4 {
            self.diag(codes::INVOLUTE, Severity::Error, s, format!("a helical involute moves at most four additional axes; this block moves {extra}"));
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
            } else if self.spec.polar_interp || self.st.modal.polar {
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

/// Whether the motion of the block comes from the modal state (no group-01 code written).
fn motion_is_modal(w: &Words, m: u32) -> bool {
    !w.has_g(m)
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
