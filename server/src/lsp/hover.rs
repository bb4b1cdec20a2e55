//! Hover: the word under the cursor explained for the file's dialect and
//! variant, the rule behind a diagnostic there, and what a name refers to.

use analyzer::dialect::{self, CodeInfo, CodeNum, Dialect, Variant};
use analyzer::rules::context::collect_codes;
use analyzer::rules::registry;
use analyzer::syntax::{Item, ItemKind, Program, Word};
use analyzer::Span;

use super::nav::{self, Sym};
use super::snapshot::Snapshot;

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
    format!(
        "**{letter}{}** — not a code of {}.",
        num.display(),
        dialect.as_str()
    )
}

fn word_markdown(snap: &Snapshot, bi: usize, item: &Item, w: &Word) -> Option<String> {
    let program = snap.program();
    let settings = &snap.doc.settings;
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
    Some(s)
}

fn sym_markdown(snap: &Snapshot, sym: &Sym) -> String {
    let program = snap.program();
    let kind = match sym {
        Sym::OLabel(_) => "O-word label",
        Sym::Program(_) => "program",
        Sym::Seq(_) => "sequence number",
        Sym::Var(_) => "variable",
    };
    let mut s = format!("**{}** — {kind}", sym.display());
    if let Some(def) = nav::definition(program, sym) {
        let line = super::position::offset_to_position(&snap.rope, def.start as usize).line + 1;
        let verb = if matches!(sym, Sym::Var(_)) {
            "first assigned"
        } else {
            "defined"
        };
        s.push_str(&format!(", {verb} on line {line}"));
    }
    s
}

/// The hover text at `offset` and the span it is about.
pub fn hover(snap: &Snapshot, offset: u32) -> Option<(String, Span)> {
    let program = snap.program();
    let mut parts = Vec::new();
    let mut span = None;
    for d in snap
        .diagnostics()
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
    if let Some(occ) =
        nav::occurrence_at(program, offset).filter(|o| !matches!(o.sym, Sym::Seq(_)) || !o.def)
    {
        if !matches!(occ.sym, Sym::Program(_)) || occ.def {
            parts.push(sym_markdown(snap, &occ.sym));
            span = Some(occ.span);
        }
    }
    if let Some((bi, item)) = item_at(program, offset) {
        if let ItemKind::Word(w) = &item.kind {
            if let Some(s) = word_markdown(snap, bi, item, w) {
                parts.push(s);
                span = Some(item.span);
            }
        }
    }
    if let Some(state) = block_state(snap, offset) {
        parts.push(state);
    }
    if parts.is_empty() {
        return None;
    }
    Some((
        parts.join("\n\n---\n\n"),
        span.unwrap_or(Span::new(offset, offset)),
    ))
}

/// The machine state after the block under the cursor, from the interpreter's
/// run when the analysis made one.
fn block_state(snap: &Snapshot, offset: u32) -> Option<String> {
    let report = snap.cached_run()?;
    let program = snap.program();
    let bi = program.block_at(offset)?;
    if program.blocks[bi].items.0 == program.blocks[bi].items.1 {
        return None;
    }
    let s = report.block_state(bi)?;
    let axes = ['X', 'Y', 'Z', 'A', 'B', 'C'];
    let pos: Vec<String> = axes
        .iter()
        .zip(s.position.iter())
        .filter(|(a, _)| snap.doc.settings.axes.contains(a))
        .map(|(a, v)| format!("{a}{v:.3}"))
        .collect();
    Some(format!(
        "After this block: `{}`  \nPosition: `{}`  \nF{} S{} T{}",
        s.modal.join(" "),
        pos.join(" "),
        s.feed,
        s.spindle,
        s.tool
    ))
}
