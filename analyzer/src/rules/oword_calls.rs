//! P008: RS274/NGC subroutine calls and O labels.

use crate::declare_rule;
use crate::diagnostic::Diagnostic;
use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{BlockKind, Expr, ItemKind, OKeyword, OLabel, OWord, Program};

use super::util::{block_exprs, expr_nodes, is_emc2, lit};
use super::{Interest, ProgramCx, Rule, RuleMeta};

declare_rule! {
    /// ## What it does
    /// Checks RS274/NGC subroutine calls and labels: a call with more than 30 arguments;
    /// a call to a subroutine defined further down the file; a subroutine that calls
    /// itself unconditionally, directly or through others; a label opened by two blocks of
    /// the same subroutine (or two subroutines); an `o… sub` ended by `M99` (the two
    /// subroutine styles mixed in one definition); and a line that
    /// starts with the digit `0` where the letter `O` was meant (`0100 sub`). Only calls
    /// outside any `if` or loop count for recursion; labels repeat freely across
    /// subroutines. Info notes: a subroutine that writes a global parameter (#31 and up,
    /// `#<_name>`), or reads an argument that some call does not pass.
    ///
    /// ## Why is this bad?
    /// Subroutines take at most 30 arguments (#1–#30). The documentation requires a
    /// definition before its call (the interpreter searches forward, slowly). Recursion
    /// exceeds the 10 call levels unless it is bounded. Reused labels make `endwhile`,
    /// `break` and friends ambiguous. LinuxCNC 2.9 accepts `M98`/`M99` programs next to
    /// `o… sub` ones, but not a definition that starts as one and ends as the other.
    /// `0100` is a number, not a label.
    ///
    /// ## Example
    /// ```ngc
    /// o100 call
    /// M2
    /// o100 sub
    /// G0 X1
    /// o100 endsub
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// o100 sub
    /// G0 X1
    /// o100 endsub
    /// o100 call
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC: error for too many arguments and for M99 in an `o… sub` (`linuxcnc`),
    /// warnings otherwise, info for the notes. Calls to subroutines in other files are resolved when the program runs.
    ///
    /// Reported by this rule, not L005, when both see an O-word label written with the digit 0 on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not L003, when both see an O-word label written with the digit 0 (its keyword read as words) on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC606, NGC607, NGC608, NGC610, NGC613, NGC614, NGC617, NGC618
    pub static OWORD_CALLS = {
        code: "P008",
        name: "oword-calls",
        summary: "Subroutine calls and O labels",
        implements: &["NGC606", "NGC607", "NGC608", "NGC610", "NGC613", "NGC614", "NGC617", "NGC618"],
        origin: Static,
        default_enabled: true,
    }
}

pub struct OwordCalls;

fn label(p: &Program, ow: &OWord) -> Option<String> {
    match ow.label {
        OLabel::Number(n) => Some(n.to_string()),
        OLabel::Name => Some(format!(
            "<{}>",
            p.str_of(ow.name_span()).to_ascii_lowercase()
        )),
        _ => None,
    }
}

impl Rule for OwordCalls {
    fn meta(&self) -> &'static RuleMeta {
        &OWORD_CALLS
    }

    fn interest(&self, _: &crate::Settings) -> Interest {
        Interest::NONE
    }

    fn check_program(&self, cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
        let p = cx.program;
        if p.dialect != Dialect::Rs274ngc {
            return;
        }
        // Definitions: label → (position, span).
        let mut defs: Vec<(String, u32, Span)> = Vec::new();
        // Calls: (label, position, span, enclosing sub).
        let mut calls: Vec<(String, u32, Span, Option<String>)> = Vec::new();
        // Labels of blocks: (scope, label, span). Subroutines share one scope; the loops
        // and ifs of each subroutine (and of the main program) have their own.
        let mut openers: Vec<(String, String, Span)> = Vec::new();
        // Open control-flow blocks in the current scope; a call inside one is conditional.
        let mut depth = 0usize;
        let mut open_do: Vec<String> = Vec::new();
        let mut current_sub: Option<String> = None;
        // Global writes already reported, per subroutine (once each).
        let mut written: Vec<(String, String)> = Vec::new();
        // Per subroutine: the highest local parameter #1–#30 it reads, with its span.
        let mut reads: Vec<(String, u32, Span)> = Vec::new();
        // Per call: (label, number of arguments).
        let mut arg_counts: Vec<(String, usize)> = Vec::new();
        // Plain blocks start with a letter and hold no O-word, M99, expression
        // or assignment: nothing here looks at them.
        for b in cx.non_plain_blocks() {
            if b.kind == BlockKind::Normal {
                let text = p.str_of(b.span);
                let t = text.trim_start().trim_start_matches('/').trim_start();
                let digits = t.bytes().take_while(|c| c.is_ascii_digit()).count();
                if digits > 1 && t.starts_with('0') {
                    let rest = t[digits..].trim_start().to_ascii_lowercase();
                    let word = rest
                        .split(|c: char| !c.is_ascii_alphabetic())
                        .next()
                        .unwrap_or("");
                    if OKeyword::from_name(word).is_some() {
                        out.push(Diagnostic::warning(
                            "P008",
                            b.span,
                            format!("`{}` starts with the digit 0; an O-word label starts with the letter o, as in `o{}`.", &t[..digits], &t[1..digits]),
                        ));
                    }
                }
            }
            if let Some(sub) = &current_sub {
                let items = p.items_of(b);
                for root in block_exprs(p, items) {
                    for id in expr_nodes(p, root) {
                        let Expr::Var { index } = p.expr(id).expr else {
                            continue;
                        };
                        let Expr::Num(n) = p.expr(index).expr else {
                            continue;
                        };
                        if (1.0..=30.0).contains(&n.value) && n.value.fract() == 0.0 {
                            let v = n.value as u32;
                            match reads.iter_mut().find(|(s, _, _)| s == sub) {
                                Some(r) if r.1 >= v => {}
                                Some(r) => *r = (sub.clone(), v, p.expr(id).span),
                                None => reads.push((sub.clone(), v, p.expr(id).span)),
                            }
                        }
                    }
                }
            }
            for item in p.items_of(b) {
                match item.kind {
                    ItemKind::OWord(o) => {
                        let Some(l) = label(p, &o) else { continue };
                        match o.keyword {
                            Some(OKeyword::Sub) => {
                                defs.push((l.clone(), item.span.start, item.span));
                                current_sub = Some(l.clone());
                                depth = 0;
                                openers.push(("sub".into(), l, item.span));
                            }
                            Some(OKeyword::Endsub) => {
                                current_sub = None;
                                depth = 0;
                            }
                            Some(OKeyword::Call) => {
                                let n = p.expr_list(o.args()).len();
                                if n > 30 {
                                    out.push(Diagnostic::error(
                                        "P008",
                                        item.span,
                                        format!("{n} call arguments: a subroutine receives at most 30 (#1–#30)."),
                                    ));
                                }
                                // A call inside an if or loop may be the bounded case of a recursion.
                                let caller = current_sub.clone().filter(|_| depth == 0);
                                arg_counts.push((l.clone(), n));
                                calls.push((l, item.span.start, item.span, caller));
                            }
                            Some(OKeyword::While) if open_do.last() == Some(&l) => {
                                // `o1 do … o1 while` is one block: the closing while reuses the label.
                                open_do.pop();
                                depth = depth.saturating_sub(1);
                            }
                            Some(OKeyword::Endwhile)
                            | Some(OKeyword::Endif)
                            | Some(OKeyword::Endrepeat) => {
                                depth = depth.saturating_sub(1);
                            }
                            Some(OKeyword::While)
                            | Some(OKeyword::Do)
                            | Some(OKeyword::If)
                            | Some(OKeyword::Repeat) => {
                                if o.keyword == Some(OKeyword::Do) {
                                    open_do.push(l.clone());
                                }
                                depth += 1;
                                let scope = current_sub.clone().unwrap_or_default();
                                openers.push((scope, l, item.span));
                            }
                            _ => {}
                        }
                    }
                    ItemKind::Word(w)
                        if w.letter == b'M'
                            && lit(&w) == Some(99.0)
                            && current_sub.is_some()
                            && !is_emc2(cx.settings) =>
                    {
                        // An `o… sub` must end with `endsub`; M99 belongs to Fanuc-style `O…` programs.
                        out.push(Diagnostic::error(
                            "P008",
                            item.span,
                            "M99 inside an `o… sub` subroutine: LinuxCNC does not mix the two subroutine styles in one definition. End it with `o… endsub`, or write it as a Fanuc-style `O…` program ending in M99.",
                        ));
                    }
                    ItemKind::Assign { target, .. } if current_sub.is_some() => {
                        let global = match p.expr(target).expr {
                            Expr::Var { index } => {
                                matches!(p.expr(index).expr, Expr::Num(n) if n.value >= 31.0)
                            }
                            Expr::Named { name } => p.str_of(name).trim_start().starts_with('_'),
                            _ => false,
                        };
                        let key = (
                            current_sub.clone().unwrap_or_default(),
                            p.str_of(p.expr(target).span).to_ascii_lowercase(),
                        );
                        if global && !written.contains(&key) {
                            written.push(key);
                            out.push(Diagnostic::info(
                                "P008",
                                p.expr(target).span,
                                format!(
                                    "The subroutine writes the global parameter `{}`; the caller sees the change after the call returns.",
                                    p.str_of(p.expr(target).span)
                                ),
                            ));
                        }
                    }
                    _ => {}
                }
            }
        }
        for (sub, highest, span) in &reads {
            let passed: Vec<usize> = arg_counts
                .iter()
                .filter(|(l, _)| l == sub)
                .map(|(_, n)| *n)
                .collect();
            if let Some(fewest) = passed.iter().min() {
                if (*highest as usize) > *fewest {
                    out.push(Diagnostic::info(
                        "P008",
                        *span,
                        format!(
                            "o{sub} reads #{highest}, but a call passes only {fewest} argument{}: the parameter keeps whatever value it had.",
                            if *fewest == 1 { "" } else { "s" }
                        ),
                    ));
                }
            }
        }
        for (j, (scope, l, span)) in openers.iter().enumerate() {
            if let Some((_, _, first)) = openers[..j]
                .iter()
                .find(|(os, ol, _)| ol == l && os == scope)
            {
                out.push(
                    Diagnostic::warning("P008", *span, format!("Label o{l} already names another block; give every sub, loop and if its own label."))
                        .with_related(*first, "first use of the label"),
                );
            }
        }
        for (l, pos, span, _) in &calls {
            if let Some((_, dpos, dspan)) = defs.iter().find(|(dl, _, _)| dl == l) {
                if dpos > pos {
                    out.push(
                        Diagnostic::warning("P008", *span, format!("o{l} is called before its definition; define subroutines above their first call."))
                            .with_related(*dspan, "definition"),
                    );
                }
            }
        }
        // Recursion in the static call graph.
        for (name, _, dspan) in &defs {
            let mut seen = vec![name.clone()];
            let mut frontier = vec![name.clone()];
            let mut recursive = false;
            while let Some(f) = frontier.pop() {
                for (callee, _, _, caller) in &calls {
                    if caller.as_ref() != Some(&f) {
                        continue;
                    }
                    if callee == name {
                        recursive = true;
                    } else if !seen.contains(callee) {
                        seen.push(callee.clone());
                        frontier.push(callee.clone());
                    }
                }
            }
            if recursive {
                out.push(Diagnostic::warning(
                    "P008",
                    *dspan,
                    format!("o{name} calls itself unconditionally (directly or through other subroutines): the recursion never stops and exceeds LinuxCNC's 10 call levels."),
                ));
            }
        }
    }
}
