//! Static (block-local and whole-file, no execution) rules, and the rule
//! metadata type shared with the runtime's flow-sensitive rules.
//!
//! Shape (after ruff and Biome): one file per rule, named for what it flags,
//! declared with [`declare_rule!`]; its doc comment (`## What it does`,
//! `## Why is this bad?`, `## Example`, `Use instead:`, `## Dialects`,
//! `Implements: …`) is the text of `partscope rule CODE`, of the LSP hover on a
//! diagnostic and of the generated docs, and its examples are tested.
//!
//! Code letters: `L` lexical/format (emitted by the parser), `G` G/M code
//! tables, `W` words of a block, `P` program structure, `S` style (off by
//! default). The runtime uses `A` arcs, `C` canned cycles, `T` tool
//! compensation, `K` coordinates/kinematics/limits, `D` look-ahead modes,
//! `F` flow/subprograms/feed, `X` execution.

mod axis_word_conflict;
pub mod block_too_long;
mod bracket_nesting;
mod code_not_on_variant;
mod comment_use;
mod conflicting_words;
mod constant_expression;
pub mod context;
mod control_notes;
mod cycle_words;
mod dlacc_form;
mod duplicate_word;
mod endless_loop;
mod eq_non_integer;
mod expression_form;
mod g54_with_words;
mod goto_target;
mod integer_machine_unit;
mod integer_word;
mod m98_with_motion;
mod m_group_conflict;
mod macro_call_arguments;
mod macro_loop_structure;
mod macro_with_nc_words;
mod missing_required_word;
mod modal_group_conflict;
mod oword_calls;
mod oword_structure;
mod parameter_number;
mod parameter_same_line;
mod program_end;
pub mod registry;
pub(crate) mod sequence_number;
mod style_decimals;
mod style_g92;
pub(crate) mod style_line_numbers;
mod style_lowercase_o;
mod style_number_whitespace;
mod style_order_of_execution;
mod style_preamble;
mod style_radius_arc;
mod style_start_with_g40;
mod style_units;
mod subprogram_name_glued;
pub(crate) mod syntax_rules;
mod too_many_m_words;
pub(crate) mod unknown_address;
mod unknown_code;
mod unreachable_after_end;
pub(crate) mod util;
mod word_value_range;

pub use context::{BlockCode, BlockCx, BlockWords, Interest, ProgramCx, Seg};
pub use syntax_rules::{BAD_EXPRESSION, CONFIG_ISSUE, IO_ERROR, NOT_TEXT};

// Declared apart from the sorted list above so that branches adding rules merge cleanly.
pub(crate) mod control_mismatch;
mod word_without_user;

use crate::diagnostic::{Diagnostic, Severity};
use crate::span::Span;

/// Where a rule's check runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// Emitted by the parser.
    Syntax,
    /// A static rule in `analyzer::rules`.
    Static,
    /// A flow-sensitive rule in `runtime`.
    Runtime,
}

/// Metadata of one rule. The `doc` is the rule's doc comment.
#[derive(Debug)]
pub struct RuleMeta {
    pub code: &'static str,
    /// kebab-case name, e.g. `modal-group-conflict`.
    pub name: &'static str,
    pub summary: &'static str,
    pub doc: &'static str,
    /// Spec catalogue ids this rule implements (`SW006`, `NGC105`, `FAN020`).
    pub implements: &'static [&'static str],
    pub origin: Origin,
    /// Style advice is off unless selected.
    pub default_enabled: bool,
}

/// A rule's diagnostics are made from its metadata, so the code they carry is the one
/// the rule declares and documents: no site writes a code as a string
/// (`analyzer/tests/rule_codes.rs` checks).
impl RuleMeta {
    pub fn diagnostic(
        &self,
        severity: Severity,
        span: Span,
        message: impl Into<String>,
    ) -> Diagnostic {
        Diagnostic::new(self.code, severity, span, message)
    }

    pub fn error(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.diagnostic(Severity::Error, span, message)
    }

    pub fn warning(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.diagnostic(Severity::Warning, span, message)
    }

    pub fn info(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.diagnostic(Severity::Info, span, message)
    }
}

/// A static rule: checks one block at a time, or the whole file.
pub trait Rule: Sync {
    fn meta(&self) -> &'static RuleMeta;

    fn check_block(&self, _cx: &BlockCx<'_>, _out: &mut Vec<Diagnostic>) {}

    fn check_program(&self, _cx: &ProgramCx<'_>, _out: &mut Vec<Diagnostic>) {}

    /// What a block must hold for `check_block` to report anything on it, for
    /// these settings: the dispatcher reads it once per file and calls the rule
    /// only on blocks that match ([`Interest::matches`]), so the common blocks of
    /// any program shape skip the rules that cannot fire on them. Whole-file
    /// rules say [`Interest::NONE`]. The default is the safe answer;
    /// `rules::tests` checks every rule's claim on random blocks.
    fn interest(&self, _settings: &crate::Settings) -> Interest {
        Interest::ALL
    }
}

/// Declares a rule's metadata from its doc comment.
///
/// ```text
/// declare_rule! {
///     /// ## What it does
///     /// …
///     pub static MODAL_GROUP_CONFLICT = {
///         code: "G001",
///         name: "modal-group-conflict",
///         summary: "Two G codes of one modal group in a block",
///         implements: &["SW006", "NGC020"],
///         origin: Static,
///         default_enabled: true,
///     }
/// }
/// ```
#[macro_export]
macro_rules! declare_rule {
    (
        $(#[doc = $doc:expr])*
        $vis:vis static $ident:ident = {
            code: $code:expr,
            name: $name:expr,
            summary: $summary:expr,
            implements: $implements:expr,
            origin: $origin:ident,
            default_enabled: $enabled:expr $(,)?
        }
    ) => {
        $(#[doc = $doc])*
        $vis static $ident: $crate::rules::RuleMeta = $crate::rules::RuleMeta {
            code: $code,
            name: $name,
            summary: $summary,
            doc: concat!($($doc, "\n"),*),
            implements: $implements,
            origin: $crate::rules::Origin::$origin,
            default_enabled: $enabled,
        };
    };
}

/// Blocks with more items than this are only checked for their length.
pub const MAX_ITEMS_PER_BLOCK: usize = 512;

/// Runs every enabled static rule over a parsed program.
pub fn check(cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
    let enabled = enabled_rules(cx.settings);
    if enabled.is_empty() {
        return;
    }
    let rules = BlockRules::new(&enabled, cx.settings);
    let mut codes = Vec::new();
    // The stretches are needed by the whole-file rules too; computing them once
    // here saves a second pass over every block.
    let skipped = skipped_blocks_in(cx.program, cx.segments());
    for (i, block) in cx.program.blocks.iter().enumerate() {
        if skipped.get(i).copied().unwrap_or(false) {
            continue;
        }
        rules.check(cx, i, block, &mut codes, out);
    }
    check_whole_program(cx, &enabled, out);
}

/// The rules with a block check, each with its [`Interest`] for one file's
/// settings, indexed so that a block finds the rules interested in it with a few
/// table look-ups instead of matching every interest.
pub struct BlockRules {
    rules: Vec<&'static dyn Rule>,
    /// Per letter, the rules (bit `i` for `rules[i]`, the first 128) interested in
    /// a word of it, in two or more words of it, or in a negative literal of it.
    by_letter: Box<[[u128; 3]; 128]>,
    /// The rules interested in anything but literal words.
    other: u128,
    /// The rules interested in literals longer than some number of digits.
    digits: Vec<(usize, u16)>,
    /// Rules past the first 128, matched one by one.
    rest: Vec<(usize, Interest)>,
}

impl BlockRules {
    pub fn new(enabled: &[&'static dyn Rule], settings: &crate::Settings) -> BlockRules {
        let mut rules = Vec::new();
        let mut by_letter = Box::new([[0u128; 3]; 128]);
        let (mut other, mut digits, mut rest) = (0u128, Vec::new(), Vec::new());
        for r in enabled {
            let interest = r.interest(settings);
            if interest == Interest::NONE {
                continue;
            }
            let i = rules.len();
            rules.push(*r);
            if i >= 128 {
                rest.push((i, interest));
                continue;
            }
            let bit = 1u128 << i;
            for (l, masks) in by_letter.iter_mut().enumerate() {
                let l = 1u128 << l;
                for (k, set) in [interest.letters, interest.repeated, interest.negative]
                    .into_iter()
                    .enumerate()
                {
                    if set & l != 0 {
                        masks[k] |= bit;
                    }
                }
            }
            if interest.other {
                other |= bit;
            }
            if interest.digits_over < u16::MAX {
                digits.push((i, interest.digits_over));
            }
        }
        BlockRules {
            rules,
            by_letter,
            other,
            digits,
            rest,
        }
    }

    /// The rules (bits, as in `by_letter`) interested in a block with `contents`.
    fn interested(&self, contents: &BlockWords) -> u128 {
        let mut mask = if contents.other { self.other } else { 0 };
        for (k, mut set) in [contents.letters, contents.repeated, contents.negative]
            .into_iter()
            .enumerate()
        {
            while set != 0 {
                let l = set.trailing_zeros() as usize;
                set &= set - 1;
                if let Some(m) = self.by_letter.get(l) {
                    mask |= m[k];
                }
            }
        }
        for &(i, over) in &self.digits {
            if contents.max_digits > over {
                mask |= 1u128 << i;
            }
        }
        mask
    }

    /// Calls the rules interested in block `i` (`codes` is scratch space).
    fn check(
        &self,
        cx: &ProgramCx<'_>,
        i: usize,
        block: &crate::syntax::Block,
        codes: &mut Vec<BlockCode>,
        out: &mut Vec<Diagnostic>,
    ) {
        // Some block rules compare words pairwise: a pathological block (thousands
        // of words on one line) is checked on its first items, so analysis stays
        // linear.
        let head = huge_block_head(block, out);
        let block = head.as_ref().unwrap_or(block);
        let contents = context::block_words(cx.program, block);
        let mut mask = self.interested(&contents);
        let rest = self.rest.iter().filter(|(_, w)| w.matches(&contents));
        if mask == 0 && self.rest.is_empty() {
            return;
        }
        codes.clear();
        if contents.letters & const { context::letter_set(b"GM") } != 0 {
            context::collect_codes(cx.program, block, codes);
        }
        let bcx = BlockCx {
            program: cx.program,
            block,
            index: i,
            settings: cx.settings,
            codes,
            contents,
            file: cx.file,
        };
        let call = |r: &dyn Rule, out: &mut Vec<Diagnostic>| r.check_block(&bcx, out);
        // In registry order, as the diagnostics of one position are kept in it.
        while mask != 0 {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if let Some(r) = self.rules.get(k) {
                call(*r, out);
            }
        }
        for (k, _) in rest {
            if let Some(r) = self.rules.get(*k) {
                call(*r, out);
            }
        }
    }
}

/// For a block of more than [`MAX_ITEMS_PER_BLOCK`] items: the block cut to its
/// first ones, which the block rules check instead (the span, and so the line
/// length, stays the whole block's), and L015 on the block.
fn huge_block_head(
    block: &crate::syntax::Block,
    out: &mut Vec<Diagnostic>,
) -> Option<crate::syntax::Block> {
    let n = (block.items.1 - block.items.0) as usize;
    if n <= MAX_ITEMS_PER_BLOCK {
        return None;
    }
    let mut head = *block;
    head.items.1 = block.items.0 + MAX_ITEMS_PER_BLOCK as u32;
    out.push(syntax_rules::BLOCK_TOO_MANY_ITEMS.warning(
        block.span,
        format!("this block has {n} words and other items; the block rules check the first {MAX_ITEMS_PER_BLOCK} only (no control reads a block this long): split it"),
    ));
    Some(head)
}

/// The static rules the settings enable, in registry order.
pub fn enabled_rules(settings: &crate::Settings) -> Vec<&'static dyn Rule> {
    registry::STATIC_RULES
        .iter()
        .copied()
        .filter(|r| settings.rule_enabled(r.meta()))
        .collect()
}

/// Blocks the block rules pass over: lines LinuxCNC never reads are only
/// reported as unreachable (P006), and a block the parser could not read is
/// reported by the parser alone (rules would only describe the debris of the
/// syntax error).
pub fn skipped_blocks(program: &crate::syntax::Program) -> Vec<bool> {
    let segs = context::segments_of(program.blocks.iter().map(|b| util::is_plain(program, b)));
    skipped_blocks_in(program, &segs)
}

/// [`skipped_blocks`] over known stretches of the program.
pub fn skipped_blocks_in(program: &crate::syntax::Program, segs: &[Seg]) -> Vec<bool> {
    let mut skipped = util::dead_blocks_in(program, segs);
    for (s, u) in skipped.iter_mut().zip(util::unreadable_blocks(program)) {
        *s |= u;
    }
    skipped
}

/// Runs the block rules on block `i` (`codes` is scratch space).
pub fn check_block_at(
    cx: &ProgramCx<'_>,
    rules: &BlockRules,
    i: usize,
    codes: &mut Vec<BlockCode>,
    out: &mut Vec<Diagnostic>,
) {
    if let Some(block) = cx.program.blocks.get(i) {
        rules.check(cx, i, block, codes, out);
    }
}

/// Whether the block rules' verdict on this block may depend on earlier
/// blocks (a G10 looks back for the last motion and dwell), so an edit
/// anywhere before it calls for a new check.
pub fn block_looks_back(program: &crate::syntax::Program, block: &crate::syntax::Block) -> bool {
    util::block_g_codes(program, block).contains(&100)
}

/// Runs the whole-file rules.
pub fn check_whole_program(
    cx: &ProgramCx<'_>,
    enabled: &[&'static dyn Rule],
    out: &mut Vec<Diagnostic>,
) {
    for r in enabled {
        r.check_program(cx, out);
    }
}
