//! Hover: the word under the cursor explained for the file's dialect and
//! variant, the rule behind a diagnostic there, and what a name refers to.

use analyzer::dialect::{self, CodeInfo, CodeNum, Dialect, Variant};
use analyzer::rules::context::collect_codes;
use analyzer::rules::registry;
use analyzer::syntax::{Expr, Item, ItemKind, Program, TokenKind, Word};
use analyzer::Span;

use analyzer::names::{self as nav, Sym};

use super::{keywords, lens, values, Analysis};

/// The item of the block at `offset` whose span holds it (a cursor just after
/// a word still counts as on it).
pub fn item_at(program: &Program, offset: u32) -> Option<(usize, &Item)> {
    let bi = program.block_at(offset)?;
    let items = program.items_of(&program.blocks[bi]);
    items
        .iter()
        .find(|it| it.span.contains(offset))
        .or_else(|| items.iter().find(|it| it.span.end == offset))
        .map(|it| (bi, it))
}

/// The table entry of a literal G/M word.
pub fn code_of(w: &Word) -> Option<(char, CodeNum)> {
    if !(w.letter == b'G' || w.letter == b'M') || w.comma {
        return None;
    }
    let n = w.num()?;
    Some((w.letter as char, CodeNum::from_value(n.value)?)).filter(|_| !(n.signed && n.value < 0.0))
}

/// Markdown for one code, as hover and completion documentation show it:
/// the dialect table's own hover text, plus a warning when the file's variant
/// lacks the code.
pub fn code_markdown(info: &CodeInfo, variant: Variant) -> String {
    let mut s = info.hover(variant.dialect());
    if !info.on_variant(variant) {
        s.push_str(&format!("\n\n⚠ Not available on {}.", variant.as_str()));
    }
    s
}

fn unknown_code(letter: char, num: CodeNum, dialect: Dialect) -> String {
    // FANUC hands M codes it does not know to the machine (PMC): they are
    // the machine builder's, and a few mean the same on nearly every machine.
    if dialect == Dialect::Fanuc && letter == 'M' {
        let usual = match num.0 {
            70 => " On most machines: mist coolant on.",
            80 => " On most machines: flood coolant on.",
            90 => " On most machines: coolant off.",
            190 => " On most machines: oriented spindle stop (spindle orientation).",
            _ => "",
        };
        // As FANUC writes it: two digits at least (`M08`).
        return format!(
            "**M{:0>2}** — machine M code: the control passes it to the machine (PMC), whose builder defines it.{usual}",
            num.display()
        );
    }
    format!(
        "**{letter}{}** — not a code of {}.",
        num.display(),
        dialect.as_str()
    )
}

fn word_markdown(a: &Analysis<'_>, bi: usize, item: &Item, w: &Word) -> Option<String> {
    let program = a.program;
    let settings = a.settings;
    if let Some((letter, num)) = code_of(w) {
        return Some(match dialect::lookup(settings.dialect, letter, num) {
            Some(info) => code_markdown(info, settings.variant),
            None => unknown_code(letter, num, settings.dialect),
        });
    }
    let letter = w.letter as char;
    let mut s = String::new();
    let label = if w.comma {
        format!(",{letter}")
    } else {
        letter.to_string()
    };
    match dialect::lookup_address(settings.dialect, letter) {
        Some(a) => s.push_str(&format!("**{label}** — {}", a.doc)),
        None => s.push_str(&format!("**{label}**")),
    }
    // What this word means to the G codes of its block.
    let mut codes = Vec::new();
    collect_codes(program, &program.blocks[bi], &mut codes);
    for c in codes.iter().filter(|c| c.span != item.span) {
        if let Some(p) = c.info.and_then(|i| i.param(letter)) {
            s.push_str(&format!(
                "\n\nIn **{}**: {}",
                c.info.map(|i| i.name()).unwrap_or_default(),
                p.doc
            ));
        }
    }
    // A macro call's argument letter sets a local variable of the macro.
    let macro_call = codes.iter().find_map(|c| {
        let i = c.info?;
        (i.letter == 'G' && matches!(i.num.0, 650 | 660 | 661))
            .then(|| i.display_name(settings.dialect))
    });
    if let (Some(call), Some(n), false) = (
        macro_call,
        values::argument_variable(w.letter),
        w.comma || settings.dialect == Dialect::Rs274ngc,
    ) {
        s.push_str(&format!(
            "\n\nArgument of **{call}**: sets local variable **#{n}** of the macro (Argument Specification I)."
        ));
    }
    // The value the word's expression had in the dry run.
    if let (ItemKind::Word(_), analyzer::syntax::WordValue::Expr(id)) = (&item.kind, w.value) {
        if let Some(v) = a
            .run
            .clone()
            .and_then(|r| r.values.clone())
            .and_then(|rec| values::recorded(program, &rec, bi, program.expr(id).span))
        {
            s.push_str(&format!("\n\n{v}"));
        }
    }
    Some(s)
}

/// A keyword (macro statement, operator, function, O-word keyword) under the cursor.
fn keyword_at(a: &Analysis<'_>, offset: u32) -> Option<(String, Span)> {
    let program = a.program;
    let i = program
        .tokens
        .partition_point(|t| t.start <= offset)
        .checked_sub(1)?;
    // A cursor just after a keyword still counts as on it.
    let candidates = [Some(i), i.checked_sub(1)];
    for ti in candidates.into_iter().flatten() {
        let tok = program.tokens.get(ti)?;
        let span = program.token_span(ti);
        if tok.kind != TokenKind::Keyword || !(span.contains(offset) || span.end == offset) {
            continue;
        }
        let text = program.str_of(span);
        let kw = keywords::lookup(a.settings.dialect, text.trim())?;
        return Some((keywords::markdown(kw), span));
    }
    None
}

/// The values of the innermost recorded expression around `offset` (an
/// `IF`/`WHILE` condition, a function's value).
fn expression_value(a: &Analysis<'_>, offset: u32) -> Option<String> {
    let run = a.run.clone()?;
    let rec = run.values.as_deref()?;
    let program = a.program;
    let bi = program.block_at(offset)?;
    let base = program.blocks.get(bi)?.span.start;
    let rel = offset.checked_sub(base)?;
    let s = rec
        .block(bi as u32)
        .iter()
        .filter(|s| s.start <= rel && rel < s.end)
        .min_by_key(|s| s.end - s.start)?;
    Some(values::series_markdown(s))
}

/// Meaning and dry-run values of the variable under the cursor (`#101`,
/// `#[#1+2]`, `#<_x>`).
fn variable_details(a: &Analysis<'_>, offset: u32) -> Option<(String, Span)> {
    let program = a.program;
    let bi = program.block_at(offset)?;
    let (id, span) = values::variable_at(program, bi, offset)?;
    let dialect = a.settings.dialect;
    let mut lines = Vec::new();
    let meaning = match program.expr(id).expr {
        Expr::Named { name } => {
            let text = program.str_of(name);
            let key = text
                .trim_start_matches('#')
                .trim_matches(['<', '>'])
                .trim()
                .to_string();
            values::named_meaning(dialect, &key)
        }
        _ => values::literal_number(program, id).and_then(|n| values::variable_meaning(dialect, n)),
    };
    if let Some(m) = meaning {
        lines.push(format!("*{m}*"));
    }
    let run = a.run.clone();
    if let Some((run, rec)) = run.as_ref().and_then(|r| Some((r, r.values.as_deref()?))) {
        lines.push(match values::recorded(program, rec, bi, span) {
            Some(v) => v,
            // The block ran but the record was full.
            None if rec.truncated && run.block_state(bi).is_some() => format!(
                "Not recorded: the dry run keeps values for its first {} blocks.",
                rec.limits().blocks
            ),
            None => "Not evaluated in the dry run.".into(),
        });
    }
    (!lines.is_empty()).then(|| (lines.join("\n\n"), span))
}

fn sym_markdown(a: &Analysis<'_>, sym: &Sym) -> String {
    let program = a.program;
    let kind = match sym {
        Sym::OLabel(_) => "O-word label",
        Sym::Program(_) => "program",
        Sym::Seq(_) => "sequence number",
        Sym::Var(_) => "variable",
    };
    let mut s = format!("**{}** — {kind}", sym.display());
    if let Some(def) = nav::definition(program, sym) {
        let line = a.lines.line_of(def.start as usize) + 1;
        let verb = if matches!(sym, Sym::Var(_)) {
            "first assigned"
        } else {
            "defined"
        };
        s.push_str(&format!(", {verb} on line {line}"));
    }
    s
}

/// A hover: Markdown, and the span it is about.
#[derive(Debug, Clone, PartialEq)]
pub struct HoverResult {
    pub markdown: String,
    pub span: Span,
}

/// The hover text at `offset` and the span it is about.
pub fn hover(a: &Analysis<'_>, offset: u32) -> Option<HoverResult> {
    let program = a.program;
    let mut parts = Vec::new();
    let mut span = None;
    for d in a
        .diagnostics
        .iter()
        .filter(|d| d.file == analyzer::FileId(0))
    {
        let on = d.span.contains(offset) || (d.span.is_empty() && d.span.start == offset);
        if !on {
            continue;
        }
        let mut s = format!("**{}** ({}): {}", d.code, d.severity.as_str(), d.message);
        if let Some(meta) = registry::lookup(d.code).or_else(|| runtime::rules::lookup(d.code)) {
            s.push_str(&format!(
                "\n\n*{}* — {}\n\n{}",
                meta.name,
                meta.summary,
                meta.doc.trim()
            ));
        }
        parts.push(s);
        span.get_or_insert(d.span);
    }
    let variable = variable_details(a, offset);
    let mut variable_shown = false;
    if let Some(occ) =
        nav::occurrence_at(program, offset).filter(|o| !matches!(o.sym, Sym::Seq(_)) || !o.def)
    {
        if !matches!(occ.sym, Sym::Program(_)) || occ.def {
            let mut md = sym_markdown(a, &occ.sym);
            if let (Sym::Var(_), Some((v, _))) = (&occ.sym, &variable) {
                md.push_str("\n\n");
                md.push_str(v);
                variable_shown = true;
            }
            parts.push(md);
            span = Some(occ.span);
        }
    }
    if let (Some((v, vspan)), false) = (&variable, variable_shown) {
        let text = program.str_of(*vspan);
        parts.push(format!("**{}** — variable\n\n{v}", text.trim()));
        span = Some(*vspan);
    }
    if let Some((mut md, kspan)) = keyword_at(a, offset) {
        // An operator or function: the value of the expression it is in.
        if variable.is_none() {
            if let Some(v) = expression_value(a, offset) {
                md.push_str("\n\n");
                md.push_str(&v);
            }
        }
        parts.push(md);
        span = Some(kspan);
    }
    if let Some((bi, item)) = item_at(program, offset).filter(|_| variable.is_none()) {
        if let ItemKind::Word(w) = &item.kind {
            if let Some(s) = word_markdown(a, bi, item, w) {
                parts.push(s);
                span = Some(item.span);
            }
        }
    }
    if let Some(state) = block_state(a, offset) {
        parts.push(state);
    }
    // On the first line: which dialect the file is read in, and why, so that a
    // wrong guess is visible.
    if a.on_first_line(offset as usize) {
        parts.push(format!(
            "*Checked as {}: {}*",
            program.dialect.as_str(),
            a.dialect_reason
        ));
        // The cycle-time lens sits on this line: where its time goes.
        if let Some(b) = a.run.clone().and_then(|r| r.breakdown.clone()) {
            parts.push(b.markdown());
        }
        span.get_or_insert(Span::new(offset, offset));
    }
    if parts.is_empty() {
        return None;
    }
    Some(HoverResult {
        markdown: parts.join("\n\n---\n\n"),
        span: span.unwrap_or(Span::new(offset, offset)),
    })
}

/// The machine state after the block under the cursor, from the interpreter's
/// run when the analysis made one.
fn block_state(a: &Analysis<'_>, offset: u32) -> Option<String> {
    let report = a.run.clone()?;
    let program = a.program;
    let bi = program.block_at(offset)?;
    if program.blocks[bi].items.0 == program.blocks[bi].items.1 {
        return None;
    }
    let s = report.block_state(bi)?;
    let axes = ['X', 'Y', 'Z', 'A', 'B', 'C'];
    let pos: Vec<String> = axes
        .iter()
        .zip(s.position.iter())
        .filter(|(axis, _)| a.settings.axes.contains(axis))
        .map(|(a, v)| format!("{a}{v:.3}"))
        .collect();
    let mut md = format!(
        "After this block: `{}`  \nPosition: `{}`  \nF{} S{} T{}",
        s.modal.join(" "),
        pos.join(" "),
        s.feed,
        s.spindle,
        s.tool
    );
    // The block's planned time, summed over its executions, and its causes.
    if offset as usize > program.text.len() {
        return None;
    }
    let line = a.lines.line_of(offset as usize) as u32;
    if let Some(b) = report
        .blocks
        .iter()
        .find(|b| b.line == line && b.time_s > 0.0)
    {
        md.push_str(&format!(
            "  \nTime: {} ({}), ends at {}",
            lens::block_seconds(b.time_s),
            crate::document::run::Breakdown::of_block(b),
            lens::format_duration(b.end_s)
        ));
    }
    Some(md)
}
