//! P008: RS274/NGC subroutine calls and O labels.

use std::collections::{HashMap, HashSet};

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
        let mut written: HashSet<(String, String)> = HashSet::new();
        // Per subroutine: the highest local parameter #1–#30 it reads, with its span.
        let mut reads: Vec<(String, u32, Span)> = Vec::new();
        let mut read_at: HashMap<String, usize> = HashMap::new();
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
                        out.push(OWORD_CALLS.warning(
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
                            match read_at.get(sub).and_then(|&i| reads.get_mut(i)) {
                                Some(r) if r.1 >= v => {}
                                Some(r) => *r = (sub.clone(), v, p.expr(id).span),
                                None => {
                                    read_at.insert(sub.clone(), reads.len());
                                    reads.push((sub.clone(), v, p.expr(id).span));
                                }
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
                                    out.push(OWORD_CALLS.error(
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
                        out.push(OWORD_CALLS.error(
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
                        if global && written.insert(key) {
                            out.push(OWORD_CALLS.info(
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
        // Fewest arguments any call passes, per subroutine.
        let mut fewest_args: HashMap<&str, usize> = HashMap::new();
        for (l, n) in &arg_counts {
            let e = fewest_args.entry(l.as_str()).or_insert(*n);
            *e = (*e).min(*n);
        }
        for (sub, highest, span) in &reads {
            if let Some(&fewest) = fewest_args.get(sub.as_str()) {
                if (*highest as usize) > fewest {
                    out.push(OWORD_CALLS.info(
                        *span,
                        format!(
                            "o{sub} reads #{highest}, but a call passes only {fewest} argument{}: the parameter keeps whatever value it had.",
                            if fewest == 1 { "" } else { "s" }
                        ),
                    ));
                }
            }
        }
        let mut first_opener: HashMap<(&str, &str), Span> = HashMap::new();
        for (scope, l, span) in &openers {
            match first_opener.entry((scope.as_str(), l.as_str())) {
                std::collections::hash_map::Entry::Occupied(first) => out.push(
                    OWORD_CALLS.warning(*span, format!("Label o{l} already names another block; give every sub, loop and if its own label."))
                        .with_related(*first.get(), "first use of the label"),
                ),
                std::collections::hash_map::Entry::Vacant(v) => {
                    v.insert(*span);
                }
            }
        }
        let mut first_def: HashMap<&str, (u32, Span)> = HashMap::new();
        for (l, pos, span) in &defs {
            first_def.entry(l.as_str()).or_insert((*pos, *span));
        }
        for (l, pos, span, _) in &calls {
            if let Some(&(dpos, dspan)) = first_def.get(l.as_str()) {
                if dpos > *pos {
                    out.push(
                        OWORD_CALLS.warning(*span, format!("o{l} is called before its definition; define subroutines above their first call."))
                            .with_related(dspan, "definition"),
                    );
                }
            }
        }
        // Recursion in the static call graph: a definition on a cycle of
        // unconditional calls (strongly connected components, linear time).
        let on_cycle = recursive_subs(&calls);
        for (name, _, dspan) in &defs {
            if on_cycle.contains(name.as_str()) {
                out.push(OWORD_CALLS.warning(
                    *dspan,
                    format!("o{name} calls itself unconditionally (directly or through other subroutines): the recursion never stops and exceeds LinuxCNC's 10 call levels."),
                ));
            }
        }
    }
}

/// The subroutines on a cycle of the call graph whose edges are the
/// unconditional calls `(callee, _, _, Some(caller))`: Tarjan's algorithm with
/// an explicit stack, so deep call chains cost neither time nor native stack.
fn recursive_subs(calls: &[(String, u32, Span, Option<String>)]) -> HashSet<&str> {
    let mut id: HashMap<&str, usize> = HashMap::new();
    let mut names: Vec<&str> = Vec::new();
    let mut edges: Vec<Vec<usize>> = Vec::new();
    let mut self_loop: Vec<bool> = Vec::new();
    for (callee, _, _, caller) in calls {
        let Some(caller) = caller.as_deref() else {
            continue;
        };
        let a = *id.entry(caller).or_insert_with(|| {
            names.push(caller);
            edges.push(Vec::new());
            self_loop.push(false);
            names.len() - 1
        });
        let b = *id.entry(callee.as_str()).or_insert_with(|| {
            names.push(callee.as_str());
            edges.push(Vec::new());
            self_loop.push(false);
            names.len() - 1
        });
        if a == b {
            self_loop[a] = true;
        }
        edges[a].push(b);
    }
    let n = names.len();
    let mut index = vec![usize::MAX; n];
    let mut low = vec![0usize; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<usize> = Vec::new();
    let mut next = 0usize;
    let mut out = HashSet::new();
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        // (node, next edge to look at)
        let mut work: Vec<(usize, usize)> = vec![(root, 0)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (v, ref mut e)) = work.last_mut() {
            if let Some(&w) = edges[v].get(*e) {
                *e += 1;
                if index[w] == usize::MAX {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(u, _)) = work.last() {
                low[u] = low[u].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 || self_loop[v] {
                    out.extend(component.into_iter().map(|w| names[w]));
                }
            }
        }
    }
    out
}
