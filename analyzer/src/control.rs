//! Recognises programs written for a control Partscope does not model (a FANUC or
//! Haas lathe, a Haas mill) when they are checked in the `fanuc` dialect, which
//! models the FANUC 30i mill. Checked as a mill, such a program gets a flood of
//! findings and a meaningless cycle time; one clear diagnostic (P010) is more use.
//!
//! One sign is never enough: each sign alone also occurs in ordinary mill
//! programs (a `T101` tool number, a `G99` return level, a 5-digit O number on a
//! control with the 8-digit option). A signature needs two signs of different kinds.

use crate::dialect::Dialect;
use crate::span::Span;
use crate::syntax::{Block, ItemKind, Program, Word};

/// The control a program looks written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// A lathe (T system): FANUC, or Haas when `haas` (a Haas-only sign is present too).
    Lathe { haas: bool },
    /// A Haas mill.
    HaasMill,
    /// A program in another control's macro language (LNC, Syntec, Fadal).
    OtherMacro,
}

impl Control {
    /// How the diagnostic names the program.
    pub fn name(self) -> &'static str {
        match self {
            Control::Lathe { haas: true } => "a Haas lathe program",
            Control::Lathe { haas: false } => "a FANUC or Haas lathe program",
            Control::HaasMill => "a Haas mill program",
            Control::OtherMacro => {
                "a program in another control's language (LNC, Syntec, Fadal, LinuxCNC, …)"
            }
        }
    }
}

/// One piece of evidence: what was written, and where.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Evidence {
    pub span: Span,
    /// 0-based line.
    pub line: u32,
    /// The words as written, e.g. `G71 P10 Q20`.
    pub text: String,
}

/// What a program looks written for, with the first evidence of each kind in file order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signature {
    pub control: Control,
    pub evidence: Vec<Evidence>,
}

impl Signature {
    /// The evidence in words: "T0101 on line 4, G71 P10 Q20 on line 9".
    pub fn describe(&self) -> String {
        let parts: Vec<String> = self
            .evidence
            .iter()
            .map(|e| format!("{} on line {}", e.text, e.line + 1))
            .collect();
        parts.join(", ")
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Sign {
    // Lathe signs.
    LatheTool,
    SpeedClamp,
    TurningCycle,
    ReferenceUw,
    FeedPerRev,
    // Haas signs.
    Haas187,
    Haas103,
    FiveDigitO,
    DwellSeconds,
    LocalCall,
    Haas154,
    // Signs of another macro language: none is FANUC syntax (a FANUC control
    // alarms on each), and two kinds are needed, so one typo never hides a file.
    SlashComment,
    AtVariable,
    UnderscoreName,
    MacroHeader,
    LetterVariable,
    QuoteComment,
    NotEqual,
    StringLiteral,
}

impl Sign {
    fn lathe(self) -> bool {
        self <= Sign::FeedPerRev
    }

    fn other_macro(self) -> bool {
        self >= Sign::SlashComment
    }
}

/// The other-macro-language signs in one block's text, outside `( )` comments:
/// `//` comments and `@100` variables (LNC, Syntec), names with `_` (`END_IF`,
/// `MSG_OK`), a `%@MACRO` header (Syntec), `#V1`/`#R4` variables and `'`
/// comments (Fadal), `!=`, `"…"` strings (`#PRINT "…"`, `G65 "NAME"`). Each as
/// (sign, byte offset in the block, length).
fn text_signs(text: &[u8]) -> Vec<(Sign, usize, usize)> {
    let mut out = Vec::new();
    let mut depth = 0u32;
    // Every block of a program is read, and most hold none of the bytes a sign or a
    // comment starts with: the loop only visits those bytes.
    let next = |k: usize| {
        text.get(k..)
            .and_then(|rest| rest.iter().position(|&c| SIGN_START[usize::from(c)]))
            .map_or(text.len(), |p| k + p)
    };
    let mut i = next(0);
    let at = |k: usize| text.get(k).copied().unwrap_or(0);
    // `@100`, `#V10`: the mark and the letters and digits after it.
    let name_len = |k: usize| {
        1 + text[k + 1..]
            .iter()
            .take_while(|c| c.is_ascii_alphanumeric())
            .count()
    };
    while i < text.len() {
        let b = text[i];
        match b {
            b'(' => depth += 1,
            b')' => depth = depth.saturating_sub(1),
            _ if depth > 0 => {}
            b'/' if at(i + 1) == b'/' => {
                out.push((Sign::SlashComment, i, 2));
                // The rest of the line is the comment.
                break;
            }
            b'\'' => {
                out.push((Sign::QuoteComment, i, 1));
                break;
            }
            b'%' if text[i..].starts_with(b"%@MACRO") => out.push((Sign::MacroHeader, i, 7)),
            b'@' if at(i + 1).is_ascii_digit() => out.push((Sign::AtVariable, i, name_len(i))),
            b'!' if at(i + 1) == b'=' => out.push((Sign::NotEqual, i, 2)),
            b'"' => {
                let len = text[i + 1..]
                    .iter()
                    .position(|c| *c == b'"')
                    .map_or(text.len() - i, |p| p + 2);
                out.push((Sign::StringLiteral, i, len));
                i += len;
                continue;
            }
            b'#' if at(i + 1).is_ascii_alphabetic() => {
                out.push((Sign::LetterVariable, i, name_len(i)))
            }
            b'_' if i > 0
                && text[i - 1].is_ascii_alphabetic()
                && at(i + 1).is_ascii_alphabetic() =>
            {
                let start = text[..i]
                    .iter()
                    .rposition(|c| !c.is_ascii_alphanumeric())
                    .map_or(0, |p| p + 1);
                // FANUC's own names are `#_…` system variables.
                if start == 0 || text[start - 1] != b'#' {
                    let end = text[i..]
                        .iter()
                        .position(|c| !(c.is_ascii_alphanumeric() || *c == b'_'))
                        .map_or(text.len(), |p| i + p);
                    out.push((Sign::UnderscoreName, start, end - start));
                    i = end;
                    continue;
                }
            }
            _ => {}
        }
        i = next(i + 1);
    }
    out
}

/// The bytes [`text_signs`] acts on: comment brackets and the first byte of every sign.
static SIGN_START: [bool; 256] = {
    let mut t = [false; 256];
    let starts = b"()/'%@!\"#_";
    let mut k = 0;
    while k < starts.len() {
        t[starts[k] as usize] = true;
        k += 1;
    }
    t
};

fn lit_of(w: &Word) -> Option<f64> {
    w.num().map(|n| n.value)
}

fn code_in(program: &Program, b: &Block, letter: u8, v: f64) -> bool {
    program
        .words(b)
        .any(|(_, w)| w.letter == letter && !w.comma && lit_of(w) == Some(v))
}

/// The text of the block's words with these letters, in the order written.
fn words_text(program: &Program, b: &Block, letters: &[u8]) -> (Span, String) {
    let mut span: Option<Span> = None;
    let mut parts = Vec::new();
    for (it, w) in program.words(b) {
        if !w.comma && letters.contains(&w.letter) {
            span = Some(match span {
                Some(s) => Span::new(s.start, it.span.end),
                None => it.span,
            });
            parts.push(program.str_of(it.span).trim().to_string());
        }
    }
    (span.unwrap_or(b.span), parts.join(" "))
}

/// The lathe- or Haas-style signs of one block.
/// `G99` counts as [`Sign::FeedPerRev`] here; the caller drops it when the file
/// has a drilling cycle.
fn block_signs(program: &Program, b: &Block, out: &mut Vec<(Sign, Evidence)>) {
    let mut push = |sign: Sign, (span, text): (Span, String)| {
        out.push((
            sign,
            Evidence {
                span,
                line: b.line,
                text,
            },
        ))
    };
    let has = |letter: u8| {
        program
            .words(b)
            .any(|(_, w)| w.letter == letter && !w.comma)
    };
    for it in program.items_of(b) {
        if let ItemKind::ProgramHead {
            name,
            number: Some(_),
        } = it.kind
        {
            let digits = program.slice(name);
            if digits.len() == 5 && digits.iter().all(u8::is_ascii_digit) {
                push(
                    Sign::FiveDigitO,
                    (it.span, program.str_of(it.span).trim().to_string()),
                );
            }
        }
    }
    let text = program.slice(b.span);
    for (sign, at, len) in text_signs(text) {
        let start = b.span.start + at as u32;
        let span = Span::new(start, start + len as u32);
        push(
            sign,
            (
                span,
                String::from_utf8_lossy(&text[at..at + len]).into_owned(),
            ),
        );
    }
    for (it, w) in program.words(b) {
        let Some(n) = w.num() else { continue };
        if w.comma {
            continue;
        }
        let word = || (it.span, program.str_of(it.span).trim().to_string());
        let v = n.value;
        match w.letter {
            // A lathe T word selects tool and offset together: T0101, T202.
            b'T' if v.fract() == 0.0 && !n.has_point && (101.0..10000.0).contains(&v) => {
                let t = v as u32;
                let written_four = n.digits == 4 && t < 1000;
                if !t.is_multiple_of(100) && (written_four || t / 100 == t % 100) {
                    push(Sign::LatheTool, word());
                }
            }
            b'G' if v == 50.0 && has(b'S') => push(Sign::SpeedClamp, words_text(program, b, b"GS")),
            b'G' if (v == 70.0 || v == 71.0 || v == 72.0) && has(b'P') && has(b'Q') => {
                let (span, text) = words_text(program, b, b"PQ");
                let g = program.str_of(it.span).trim().to_string();
                push(
                    Sign::TurningCycle,
                    (
                        Span::new(it.span.start, span.end.max(it.span.end)),
                        format!("{g} {text}"),
                    ),
                );
            }
            b'G' if v == 28.0 && (has(b'U') || has(b'W')) => {
                push(Sign::ReferenceUw, words_text(program, b, b"GUW"))
            }
            b'G' if v == 99.0 => push(Sign::FeedPerRev, word()),
            b'G' if v == 187.0 => push(Sign::Haas187, word()),
            b'G' if v == 103.0 => push(Sign::Haas103, word()),
            b'G' if v == 154.0 && has(b'P') => push(Sign::Haas154, words_text(program, b, b"GP")),
            b'M' if v == 97.0 && has(b'P') => push(Sign::LocalCall, words_text(program, b, b"MP")),
            // FANUC reads G04 P as whole milliseconds; Haas takes seconds with a point.
            b'P' if n.has_point && code_in(program, b, b'G', 4.0) => {
                push(Sign::DwellSeconds, words_text(program, b, b"GP"))
            }
            _ => {}
        }
    }
}

/// Whether the block uses a drilling canned cycle (G73, G74, G76, G81–G89).
fn block_drills(program: &Program, b: &Block) -> bool {
    program.words(b).any(|(_, w)| {
        w.letter == b'G'
            && !w.comma
            && lit_of(w)
                .is_some_and(|v| matches!(v as i64, 73 | 74 | 76 | 81..=89) && v.fract() == 0.0)
    })
}

/// What a FANUC-dialect program looks written for, if not the FANUC 30i mill:
/// a lathe needs two kinds of lathe sign, a Haas mill two kinds of Haas sign.
/// Other dialects, and programs with fewer signs, give `None`.
pub fn control_signature(program: &Program) -> Option<Signature> {
    let mut scan = SignScan::default();
    scan.add(program);
    scan.finish()
}

/// [`control_signature`] of a file read in parts (windows, in file order).
#[derive(Debug, Default)]
pub struct SignScan {
    fanuc: bool,
    drilling: bool,
    /// The first evidence of each kind, in file order (a FANUC feed per
    /// revolution is kept apart: it counts only in a file without drilling).
    firsts: Vec<(Sign, Evidence)>,
}

impl SignScan {
    /// Reads the signs of one part of the file.
    pub fn add(&mut self, program: &Program) {
        if program.dialect != Dialect::Fanuc {
            return;
        }
        self.fanuc = true;
        // One pass over the blocks (the program is large, its items are read once).
        let mut found = Vec::new();
        for b in &program.blocks {
            self.drilling = self.drilling || block_drills(program, b);
            block_signs(program, b, &mut found);
        }
        for (s, e) in found {
            if !self.firsts.iter().any(|(k, _)| *k == s) {
                self.firsts.push((s, e));
            }
        }
    }

    /// The signature of everything read.
    pub fn finish(mut self) -> Option<Signature> {
        if !self.fanuc {
            return None;
        }
        // On a mill G99 returns a canned cycle to the R level; without any drilling
        // cycle in the file it is a lathe's feed per revolution.
        if self.drilling {
            self.firsts.retain(|(s, _)| *s != Sign::FeedPerRev);
        }
        let firsts = self.firsts;
        let lathe = firsts.iter().filter(|(s, _)| s.lathe()).count();
        let other = firsts.iter().filter(|(s, _)| s.other_macro()).count();
        let haas = firsts.len() - lathe - other;
        let (control, keep): (Control, fn(Sign) -> bool) = if other >= 2 {
            (Control::OtherMacro, |s| s.other_macro())
        } else if lathe >= 2 {
            (Control::Lathe { haas: haas > 0 }, |s| !s.other_macro())
        } else if haas >= 2 {
            (Control::HaasMill, |s| !s.lathe() && !s.other_macro())
        } else {
            return None;
        };
        let evidence = firsts
            .into_iter()
            .filter(|(s, _)| keep(*s))
            .map(|(_, e)| e)
            .collect();
        Some(Signature { control, evidence })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sig(src: &str) -> Option<Signature> {
        let settings = crate::Settings::new(Dialect::Fanuc);
        control_signature(&crate::analyze(src.as_bytes().to_vec(), &settings).program)
    }

    #[test]
    fn a_lathe_program_is_named_with_its_evidence_in_file_order() {
        let s = sig("%\nO10\nG18\nT0101\nG0 X2. Z0.1\nG71 P10 Q20 U0.01 W0 D0.025 F0.02\nN10 G1 X1.\nN20 Z-1.\nM30\n%\n")
            .expect("a lathe");
        assert_eq!(s.control, Control::Lathe { haas: false });
        assert_eq!(s.describe(), "T0101 on line 4, G71 P10 Q20 on line 6");
        assert_eq!(s.evidence[0].line, 3);
    }

    #[test]
    fn a_haas_sign_beside_lathe_signs_names_a_haas_lathe() {
        let s = sig("O58214\nG50 S1600\nT101\nG04 P3.\nM30\n").expect("a lathe");
        assert_eq!(s.control, Control::Lathe { haas: true });
        assert_eq!(
            s.describe(),
            "O58214 on line 1, G50 S1600 on line 2, T101 on line 3, G04 P3. on line 4"
        );
    }

    #[test]
    fn a_haas_mill_needs_two_kinds_of_haas_sign() {
        let s = sig("O01000\nG187 P1\nG0 X0 Y0\nM30\n").expect("a Haas mill");
        assert_eq!(s.control, Control::HaasMill);
        assert_eq!(s.describe(), "O01000 on line 1, G187 on line 2");
        assert_eq!(sig("O01000\nG0 X0 Y0\nM30\n"), None);
        assert_eq!(sig("O1000\nG04 P1.\nG04 P2.\nM30\n"), None);
    }

    #[test]
    fn one_sign_or_one_kind_twice_is_an_ordinary_mill_program() {
        // A tool numbered 101, and G99 among the drilling cycles, are mill usage.
        assert_eq!(sig("O1\nT101 M6\nG0 X0 Y0\nM30\n"), None);
        assert_eq!(sig("O1\nT0101 M6\nT0202 M6\nM30\n"), None);
        assert_eq!(sig("O1\nT0101 M6\nG99 G81 Z-5. R2. F100\nG80\nM30\n"), None);
        assert_eq!(sig("O1\nG50 S2000\nG50 S3000\nM30\n"), None);
        // G99 with no drilling cycle in the file is a lathe's feed per revolution.
        assert!(sig("O1\nT0101\nG99\nG1 X1. F0.01\nM30\n").is_some());
    }

    #[test]
    fn another_macro_language_needs_two_kinds_of_its_signs() {
        // LNC 6800: `//` comments, `@` variables, `END_IF`.
        let s =
            sig("G65 \"PROBECONFIG\"\n// LOAD\n#100 = @100 // TOOL\nIF [#1!=#0]\nEND_IF\nM30\n")
                .expect("LNC");
        assert_eq!(s.control, Control::OtherMacro);
        assert_eq!(
            s.describe(),
            "\"PROBECONFIG\" on line 1, // on line 2, @100 on line 3, != on line 4, END_IF on line 5"
        );
        // Fadal Format 2: `#` statements and strings, `#V` variables and `'` comments.
        let s =
            sig("%\nN0 O9999 (CHOOSER)\n#PRINT \"Select:\"\n#INPUT V10\nM30\n%\n").expect("Fadal");
        assert_eq!(s.describe(), "#PRINT on line 3, \"Select:\" on line 3");
        let s = sig("%\nO9101\n#V10 = 1 'TOOL NUMBER\n#R4 = V12\nM30\n%\n").expect("Fadal");
        assert_eq!(s.control, Control::OtherMacro);
        assert_eq!(s.describe(), "#V10 on line 3, ' on line 3");
        // One kind, however often, is a broken FANUC program, still checked; so are
        // FANUC's `#_` system variable names and anything inside a comment.
        assert_eq!(sig("O1\nG0 X0 // RAPID\nG1 X1 // FEED\nM30\n"), None);
        assert_eq!(sig("O1\n#1=#_UI[1]\n(DON'T // @1 END_IF)\nM30\n"), None);
    }

    #[test]
    fn other_dialects_are_not_examined() {
        let settings = crate::Settings::new(Dialect::Rs274ngc);
        let p = crate::analyze(b"T0101\nG50 S2000\nM2\n".to_vec(), &settings).program;
        assert_eq!(control_signature(&p), None);
    }
}
