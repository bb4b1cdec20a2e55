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
mod block_too_long;
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
mod sequence_number;
mod style_decimals;
mod style_g92;
mod style_line_numbers;
mod style_lowercase_o;
mod style_number_whitespace;
mod style_order_of_execution;
mod style_preamble;
mod style_radius_arc;
mod style_start_with_g40;
mod style_units;
mod subprogram_name_glued;
mod syntax_rules;
mod too_many_m_words;
mod unknown_address;
mod unknown_code;
mod unreachable_after_end;
pub(crate) mod util;
mod word_value_range;

pub use context::{AxisFeedWords, BlockCode, BlockCx, ProgramCx, Seg};

// Declared apart from the sorted list above so that branches adding rules merge cleanly.
mod word_without_user;

use crate::diagnostic::Diagnostic;

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

/// A static rule: checks one block at a time, or the whole file.
pub trait Rule: Sync {
    fn meta(&self) -> &'static RuleMeta;

    fn check_block(&self, _cx: &BlockCx<'_>, _out: &mut Vec<Diagnostic>) {}

    fn check_program(&self, _cx: &ProgramCx<'_>, _out: &mut Vec<Diagnostic>) {}

    /// Whether `check_block` can report anything on an axis/feed block (see
    /// [`context::is_axis_feed_block`]): only literal X/Y/Z/A/B/C/U/V/W, I/J/K, R
    /// and F words. Most of a CAM program is such blocks, so rules that need a
    /// G/M code, an expression, a comment or another letter say `false` and are
    /// not called on them. The default is the safe answer.
    fn reports_on_axis_feed_blocks(&self) -> bool {
        true
    }

    /// Whether the rule has a `check_block` at all. Whole-file rules say `false`
    /// and are not called once per block (half a million no-op calls on a large
    /// CAM program).
    fn has_block_check(&self) -> bool {
        true
    }

    /// Whether `check_block` is certain to report nothing on an axis/feed block
    /// with these words, told from one summary the block rules share instead of
    /// each walking the words. `false` (the default) means "call me"; a rule that
    /// answers `true` must be silent then (`rules::tests` checks it on random
    /// blocks).
    fn silent_on_axis_feed(&self, _cx: &BlockCx<'_>, _words: &AxisFeedWords) -> bool {
        false
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

/// Runs every enabled static rule over a parsed program.
/// Blocks with more items than this are only checked for their length.
pub const MAX_ITEMS_PER_BLOCK: usize = 512;

pub fn check(cx: &ProgramCx<'_>, out: &mut Vec<Diagnostic>) {
    let enabled = enabled_rules(cx.settings);
    if enabled.is_empty() {
        return;
    }
    let mut codes = Vec::new();
    // The stretches are needed by the whole-file rules too; computing them once
    // here saves a second pass over every block.
    let skipped = skipped_blocks_in(cx.program, cx.segments());
    let block_rules: Vec<&'static dyn Rule> = enabled
        .iter()
        .copied()
        .filter(|r| r.has_block_check())
        .collect();
    // The rules that can report on an axis/feed block, chosen once for the whole file.
    let axis_feed: Vec<&'static dyn Rule> = block_rules
        .iter()
        .copied()
        .filter(|r| r.reports_on_axis_feed_blocks())
        .collect();
    for (i, block) in cx.program.blocks.iter().enumerate() {
        if skipped.get(i).copied().unwrap_or(false) {
            continue;
        }
        if let Some(words) = context::axis_feed_words(cx.program, block) {
            // No G or M word, so the block has no codes to collect.
            codes.clear();
            run_axis_feed_rules(cx, &axis_feed, i, block, &words, out);
        } else {
            check_block_at(cx, &block_rules, i, &mut codes, out);
        }
    }
    check_whole_program(cx, &enabled, out);
}

/// Calls the rules `rules` on the axis/feed block `i` with the words `words`,
/// except those that can tell from `words` alone that they would be silent.
fn run_axis_feed_rules(
    cx: &ProgramCx<'_>,
    rules: &[&'static dyn Rule],
    i: usize,
    block: &crate::syntax::Block,
    words: &AxisFeedWords,
    out: &mut Vec<Diagnostic>,
) {
    // As in `check_block_at`: a pathological block is checked on its first items.
    let head = huge_block_head(block, out);
    let block = head.as_ref().unwrap_or(block);
    let bcx = BlockCx {
        program: cx.program,
        block,
        index: i,
        settings: cx.settings,
        codes: &[],
    };
    for r in rules {
        if !r.silent_on_axis_feed(&bcx, words) {
            r.check_block(&bcx, out);
        }
    }
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
    enabled: &[&'static dyn Rule],
    i: usize,
    codes: &mut Vec<BlockCode>,
    out: &mut Vec<Diagnostic>,
) {
    let Some(full) = cx.program.blocks.get(i) else {
        return;
    };
    codes.clear();
    let first = huge_block_head(full, out);
    let block = first.as_ref().unwrap_or(full);
    if context::is_axis_feed_block(cx.program, block) {
        // Same verdict as a full check: the skipped rules cannot report on this block.
        for r in enabled.iter().filter(|r| r.reports_on_axis_feed_blocks()) {
            run_block_rules(cx, std::slice::from_ref(r), i, block, codes, out);
        }
        return;
    }
    context::collect_codes(cx.program, block, codes);
    run_block_rules(cx, enabled, i, block, codes, out);
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
    out.push(Diagnostic::warning(
        "L015",
        block.span,
        format!("this block has {n} words and other items; the block rules check the first {MAX_ITEMS_PER_BLOCK} only (no control reads a block this long): split it"),
    ));
    Some(head)
}

/// Calls the block rules `rules` on block `i` whose codes are `codes`.
fn run_block_rules(
    cx: &ProgramCx<'_>,
    rules: &[&'static dyn Rule],
    i: usize,
    block: &crate::syntax::Block,
    codes: &[BlockCode],
    out: &mut Vec<Diagnostic>,
) {
    let bcx = BlockCx {
        program: cx.program,
        block,
        index: i,
        settings: cx.settings,
        codes,
    };
    // Some block rules compare words pairwise: a pathological block (thousands of
    // words on one line) comes here cut to its first items (`huge_block_head`), so
    // analysis stays linear.
    for r in rules {
        r.check_block(&bcx, out);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::Dialect;
    use crate::syntax::{parse, ParseOptions};

    /// [`check`] skips the block call of rules without a block check; calling it
    /// anyway must report nothing on any kind of block.
    #[test]
    fn rules_without_a_block_check_report_nothing_per_block() {
        let text = "%\nO1000 (PART)\nN10 G21 G17 G90 G40 G49 G80\nT1 M6\nG43 H1 Z50.\n\
            G0 X0 Y0 S1200 M3\n#1 = 2\n#<a> = [#1 * 3]\nIF [#1 GT 1] GOTO 20\nWHILE [#1 LT 3] DO1\n\
            #1 = [#1 + 1]\nEND1\nN20 G1 X1.5 Y2 F300\nX2 Y3 Z4\nG2 X1 Y1 R5\nG81 Z-1 R1 F100\n\
            G80\nG4 P1\n/ M1\no100 sub\no100 endsub\no100 call [1]\nG92 X0\nG65 P9000 A1 B2\n\
            M98 P1000 L2\nM99\n(partscope: allow W001)\nG10 L2 P1 X0\nM30\nX1\n%\n";
        let mut calls = 0;
        for dialect in [Dialect::Rs274ngc, Dialect::Fanuc, Dialect::Servoworks] {
            let program = parse(ParseOptions::new(dialect), text.as_bytes().to_vec());
            let settings = crate::Settings::new(dialect);
            for (i, block) in program.blocks.iter().enumerate() {
                let mut codes = Vec::new();
                context::collect_codes(&program, block, &mut codes);
                let cx = BlockCx {
                    program: &program,
                    block,
                    index: i,
                    settings: &settings,
                    codes: &codes,
                };
                for rule in registry::STATIC_RULES
                    .iter()
                    .filter(|r| !r.has_block_check())
                {
                    let mut out = Vec::new();
                    rule.check_block(&cx, &mut out);
                    assert!(out.is_empty(), "{} reported {out:?}", rule.meta().code);
                    calls += 1;
                }
            }
        }
        // The seventeen whole-file rules, on every block of three parses.
        assert!(calls >= 17 * 3 * 30, "{calls}");
    }

    /// A rule that claims from the shared summary that it is silent on an
    /// axis/feed block really reports nothing there, in every dialect, variant
    /// and axis configuration; and the claim is made often enough to matter.
    #[test]
    fn rules_silent_by_summary_report_nothing() {
        use crate::dialect::Variant;
        const VALUES: &[&str] = &[
            "0",
            "1",
            "-1",
            "0.",
            "-0",
            "+2",
            ".5",
            "-.5",
            "1.5",
            "-12.3456",
            "100000",
            "123456789",
            "1234567890",
            "-1234567890123",
            "0.0001",
            "2 5.4",
            "-3 .25",
        ];
        let letters = b"XYZABCUVWIJKRFE";
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = |n: usize| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % n as u64) as usize
        };
        let mut text = String::new();
        for _ in 0..4000 {
            for w in 0..1 + next(5) {
                if w > 0 && next(2) == 0 {
                    text.push(' ');
                }
                text.push(letters[next(letters.len())] as char);
                text.push_str(VALUES[next(VALUES.len())]);
            }
            text.push('\n');
        }
        let variants = [
            (Dialect::Rs274ngc, Variant::Linuxcnc),
            (Dialect::Rs274ngc, Variant::Emc2),
            (Dialect::Servoworks, Variant::S100M),
            (Dialect::Fanuc, Dialect::Fanuc.default_variant()),
        ];
        let (mut silent, mut checked) = (0, 0);
        for (dialect, variant) in variants {
            let program = parse(ParseOptions::new(dialect), text.as_bytes().to_vec());
            for axes in [
                &['X', 'Y', 'Z'][..],
                &['X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W', 'E'],
            ] {
                for imu in [false, true] {
                    let mut settings = crate::Settings::new(dialect);
                    settings.variant = variant;
                    settings.axes = axes.to_vec();
                    settings.integer_machine_unit = imu;
                    for (i, block) in program.blocks.iter().enumerate() {
                        let words = context::axis_feed_words(&program, block);
                        assert_eq!(
                            words.is_some(),
                            context::is_axis_feed_block(&program, block)
                        );
                        let Some(words) = words else {
                            continue;
                        };
                        let cx = BlockCx {
                            program: &program,
                            block,
                            index: i,
                            settings: &settings,
                            codes: &[],
                        };
                        for rule in registry::STATIC_RULES {
                            checked += 1;
                            if !rule.silent_on_axis_feed(&cx, &words) {
                                continue;
                            }
                            silent += 1;
                            let mut out = Vec::new();
                            rule.check_block(&cx, &mut out);
                            assert!(
                                out.is_empty(),
                                "{} claimed silence but reported {out:?} on {:?} ({dialect:?})",
                                rule.meta().code,
                                program.str_of(block.span)
                            );
                        }
                    }
                }
            }
        }
        assert!(silent > 50_000, "{silent} silent of {checked}");
    }
}
