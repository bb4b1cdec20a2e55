//! Dialects: the three control languages, their variants/profiles, and the
//! tables of G and M codes each one knows.
//!
//! A dialect is data plus a thin layer of code. The tables live in one file per
//! dialect ([`servoworks`], [`rs274ngc`], [`fanuc`]) and are consulted by the
//! static rules, the interpreter and the language server's hover/completion.

pub mod fanuc;
pub mod rs274ngc;
pub mod servoworks;

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    Servoworks,
    #[default]
    Rs274ngc,
    Fanuc,
}

impl Dialect {
    pub const ALL: [Dialect; 3] = [Dialect::Servoworks, Dialect::Rs274ngc, Dialect::Fanuc];

    pub fn as_str(self) -> &'static str {
        match self {
            Dialect::Servoworks => "servoworks",
            Dialect::Rs274ngc => "rs274ngc",
            Dialect::Fanuc => "fanuc",
        }
    }

    pub fn parse(s: &str) -> Option<Dialect> {
        Some(match s.trim().to_ascii_lowercase().as_str() {
            "servoworks" | "sw" => Dialect::Servoworks,
            "rs274ngc" | "ngc" | "linuxcnc" | "rs274" | "emc2" => Dialect::Rs274ngc,
            "fanuc" => Dialect::Fanuc,
            _ => return None,
        })
    }

    /// The code table of this dialect.
    pub fn codes(self) -> &'static [CodeInfo] {
        match self {
            Dialect::Servoworks => servoworks::CODES,
            Dialect::Rs274ngc => rs274ngc::CODES,
            Dialect::Fanuc => fanuc::CODES,
        }
    }

    /// The default variant/profile of this dialect.
    pub fn default_variant(self) -> Variant {
        match self {
            Dialect::Servoworks => Variant::S140M,
            Dialect::Rs274ngc => Variant::Linuxcnc,
            Dialect::Fanuc => Variant::Fanuc30i,
        }
    }
}

/// A product variant (ServoWorks) or language profile (RS274/NGC).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Variant {
    /// ServoWorks S-100M: 3 coordinated axes, no G02.3/G03.3, no G43.2.
    #[serde(rename = "S-100M", alias = "s100m", alias = "S100M")]
    S100M,
    /// ServoWorks S-120M: 4 axes, G02.3/G03.3, no G43.2.
    #[serde(rename = "S-120M", alias = "s120m", alias = "S120M")]
    S120M,
    /// ServoWorks S-140M: 5 axes, everything including G43.2 TCP.
    #[serde(rename = "S-140M", alias = "s140m", alias = "S140M")]
    S140M,
    /// LinuxCNC 2.9 semantics.
    Linuxcnc,
    /// The 2007 EMC2 seed's semantics.
    Emc2,
    /// FANUC Series 30i (M system).
    #[serde(rename = "30i", alias = "fanuc30i")]
    Fanuc30i,
}

impl Variant {
    pub fn as_str(self) -> &'static str {
        match self {
            Variant::S100M => "S-100M",
            Variant::S120M => "S-120M",
            Variant::S140M => "S-140M",
            Variant::Linuxcnc => "linuxcnc",
            Variant::Emc2 => "emc2",
            Variant::Fanuc30i => "30i",
        }
    }

    pub fn parse(s: &str) -> Option<Variant> {
        let k: String = s
            .chars()
            .filter(|c| *c != '-' && *c != '_')
            .collect::<String>()
            .to_ascii_lowercase();
        Some(match k.as_str() {
            "s100m" => Variant::S100M,
            "s120m" => Variant::S120M,
            "s140m" => Variant::S140M,
            "linuxcnc" | "linuxcnc29" => Variant::Linuxcnc,
            "emc2" => Variant::Emc2,
            "30i" | "fanuc30i" => Variant::Fanuc30i,
            _ => return None,
        })
    }

    /// The bit of this variant in a [`CodeInfo::variants`] mask.
    pub const fn bit(self) -> u8 {
        match self {
            Variant::S100M => 1,
            Variant::S120M => 2,
            Variant::S140M => 4,
            Variant::Linuxcnc => 8,
            Variant::Emc2 => 16,
            Variant::Fanuc30i => 32,
        }
    }

    pub fn dialect(self) -> Dialect {
        match self {
            Variant::S100M | Variant::S120M | Variant::S140M => Dialect::Servoworks,
            Variant::Linuxcnc | Variant::Emc2 => Dialect::Rs274ngc,
            Variant::Fanuc30i => Dialect::Fanuc,
        }
    }
}

/// Variant masks for [`CodeInfo::variants`].
pub mod variants {
    pub const S100M: u8 = 1;
    pub const S120M: u8 = 2;
    pub const S140M: u8 = 4;
    pub const ALL_SW: u8 = S100M | S120M | S140M;
    pub const LINUXCNC: u8 = 8;
    pub const EMC2: u8 = 16;
    pub const ALL_NGC: u8 = LINUXCNC | EMC2;
    pub const FANUC30I: u8 = 32;
}

/// A G or M code number in tenths: `G2.3` is `CodeNum(23)`, `G54.1` is
/// `CodeNum(541)`, `M30` is `CodeNum(300)`. Tenths make decimal G codes exact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CodeNum(pub u32);

impl CodeNum {
    /// The code for a programmed value, when it is within 0.001 of a tenth
    /// (the RS274/NGC rule; FANUC and ServoWorks literals are exact anyway).
    pub fn from_value(v: f64) -> Option<CodeNum> {
        if !v.is_finite() || !(0.0..=400_000_000.0).contains(&v) {
            return None;
        }
        let t = v * 10.0;
        let r = t.round();
        if (t - r).abs() > 0.001 * 10.0 {
            return None;
        }
        Some(CodeNum(r as u32))
    }

    pub const fn whole(n: u32) -> CodeNum {
        CodeNum(n * 10)
    }

    /// Formats as the dialect writes it: `2`, `2.3`, `54.1`.
    pub fn display(self) -> String {
        if self.0.is_multiple_of(10) {
            format!("{}", self.0 / 10)
        } else {
            format!("{}.{}", self.0 / 10, self.0 % 10)
        }
    }
}

/// What a code does, for the rules that need to know (axis-word consumers,
/// motion, one-shot).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CodeKind {
    /// Group-1 style motion (G0, G1, G2, cycles…): consumes axis words.
    /// The cycle cancel G80 is [`CodeKind::Modal`], because it takes no axis words.
    Motion,
    /// Non-modal code that consumes axis words (G10, G28, G92, G52, G53…).
    /// RS274/NGC's G53 is [`CodeKind::OneShot`] there: it only modifies the
    /// G0/G1 on its line, which keeps the axis words.
    AxisConsumer,
    /// Modal setting (plane, units, distance mode, …).
    Modal,
    /// Non-modal code that does not use axis words (G4 dwell, …).
    OneShot,
    /// An M code.
    Misc,
}

/// A word a code takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Param {
    /// The address letter, upper case.
    pub letter: char,
    /// Meaning in our own words.
    pub doc: &'static str,
    pub required: bool,
}

/// One G or M code of one dialect.
#[derive(Debug, Clone, Copy)]
pub struct CodeInfo {
    /// `'G'` or `'M'`.
    pub letter: char,
    pub num: CodeNum,
    /// Modal group as the dialect's manual numbers it (`0` = non-modal / group 00).
    /// `None` for codes outside every group. M-code groups (RS274/NGC only) are a
    /// separate numbering from G-code groups: compare with [`CodeInfo::same_group`].
    pub group: Option<u8>,
    pub kind: CodeKind,
    /// Variants that have this code (a [`variants`] mask).
    pub variants: u8,
    /// Whether this is the power-on default of its group.
    pub default: bool,
    /// One-line summary in our own words.
    pub summary: &'static str,
    /// Longer description in our own words (hover text).
    pub doc: &'static str,
    pub params: &'static [Param],
}

impl CodeInfo {
    pub fn name(&self) -> String {
        format!("{}{}", self.letter, self.num.display())
    }

    /// The name as the dialect's manual writes it: `G04`, `G02.3`, `M03` for
    /// ServoWorks and FANUC; `G4`, `M3` for RS274/NGC.
    pub fn display_name(&self, dialect: Dialect) -> String {
        match dialect {
            Dialect::Rs274ngc => self.name(),
            Dialect::Servoworks | Dialect::Fanuc => {
                let whole = self.num.0 / 10;
                let tenth = self.num.0 % 10;
                if tenth == 0 {
                    format!("{}{:02}", self.letter, whole)
                } else {
                    format!("{}{:02}.{}", self.letter, whole, tenth)
                }
            }
        }
    }

    /// Whether `self` and `other` are in the same modal group (G and M groups
    /// are separate numberings, so the letters must match too).
    pub fn same_group(&self, other: &CodeInfo) -> bool {
        self.letter == other.letter && self.group.is_some() && self.group == other.group
    }

    pub fn on_variant(&self, v: Variant) -> bool {
        self.variants & v.bit() != 0
    }
}

/// Looks a code up in a dialect's table.
pub fn lookup(dialect: Dialect, letter: char, num: CodeNum) -> Option<&'static CodeInfo> {
    let codes = dialect.codes();
    match CodeIndex::of(dialect).position(letter, num) {
        Some(Some(i)) => codes.get(i),
        Some(None) => None,
        None => codes.iter().find(|c| c.letter == letter && c.num == num),
    }
}

/// G and M codes (tenths) below this are found through [`CodeIndex`].
const INDEXED_CODES: usize = 1024;

/// Where each G and M code below [`INDEXED_CODES`] is in a dialect's table (its
/// first entry), so that the lookup every block makes is one load, not a scan of
/// a table of a few hundred codes.
struct CodeIndex {
    g: Vec<u16>,
    m: Vec<u16>,
}

impl CodeIndex {
    /// Marks a code the table does not have.
    const NONE: u16 = u16::MAX;

    fn of(dialect: Dialect) -> &'static CodeIndex {
        static INDEX: [std::sync::OnceLock<CodeIndex>; 3] = [
            std::sync::OnceLock::new(),
            std::sync::OnceLock::new(),
            std::sync::OnceLock::new(),
        ];
        let slot = match dialect {
            Dialect::Servoworks => &INDEX[0],
            Dialect::Rs274ngc => &INDEX[1],
            Dialect::Fanuc => &INDEX[2],
        };
        slot.get_or_init(|| CodeIndex::build(dialect.codes()))
    }

    fn build(codes: &[CodeInfo]) -> CodeIndex {
        let mut index = CodeIndex {
            g: vec![Self::NONE; INDEXED_CODES],
            m: vec![Self::NONE; INDEXED_CODES],
        };
        for (i, c) in codes.iter().enumerate().rev() {
            let list = match c.letter {
                'G' => &mut index.g,
                'M' => &mut index.m,
                _ => continue,
            };
            if let (Some(slot), Ok(i)) = (list.get_mut(c.num.0 as usize), u16::try_from(i)) {
                *slot = i;
            }
        }
        index
    }

    /// `Some(position)` for an indexed code (`Some(None)`: not in the table);
    /// `None` when the code is not indexed and the table must be searched.
    fn position(&self, letter: char, num: CodeNum) -> Option<Option<usize>> {
        let list = match letter {
            'G' => &self.g,
            'M' => &self.m,
            _ => return None,
        };
        let at = *list.get(num.0 as usize)?;
        Some((at != Self::NONE).then_some(usize::from(at)))
    }
}

/// The meaning of one address letter (a non-G/M word) in a dialect, for hover.
#[derive(Debug, Clone, Copy)]
pub struct AddressInfo {
    /// The address letter, upper case (`'#'` for macro variables where a dialect has them).
    pub letter: char,
    /// Meaning(s) in our own words; several meanings are separated by "; ".
    pub doc: &'static str,
}

impl Dialect {
    /// The address-letter table of this dialect (meanings of non-G/M words).
    pub fn addresses(self) -> &'static [AddressInfo] {
        match self {
            Dialect::Servoworks => servoworks::ADDRESSES,
            Dialect::Rs274ngc => rs274ngc::ADDRESSES,
            Dialect::Fanuc => fanuc::ADDRESSES,
        }
    }
}

/// Looks a code up for one variant/profile: `None` when the dialect lacks the
/// code or the variant does not have it (e.g. G43.2 on ServoWorks S-120M).
pub fn lookup_variant(variant: Variant, letter: char, num: CodeNum) -> Option<&'static CodeInfo> {
    lookup(variant.dialect(), letter, num).filter(|c| c.on_variant(variant))
}

/// The variants of `dialect`, in [`Variant::bit`] order.
pub fn variants_of(dialect: Dialect) -> &'static [Variant] {
    match dialect {
        Dialect::Servoworks => &[Variant::S100M, Variant::S120M, Variant::S140M],
        Dialect::Rs274ngc => &[Variant::Linuxcnc, Variant::Emc2],
        Dialect::Fanuc => &[Variant::Fanuc30i],
    }
}

/// Looks an address letter up in a dialect's address table (case-insensitive).
pub fn lookup_address(dialect: Dialect, letter: char) -> Option<&'static AddressInfo> {
    let up = letter.to_ascii_uppercase();
    dialect.addresses().iter().find(|a| a.letter == up)
}

/// Every G code of `dialect` in modal group `group`, in table order. G and M
/// groups are numbered separately (RS274/NGC's M groups 4–10 are not G groups
/// 4–10); use [`codes_in_letter_group`] for M-code groups.
pub fn codes_in_group(dialect: Dialect, group: u8) -> impl Iterator<Item = &'static CodeInfo> {
    codes_in_letter_group(dialect, 'G', group)
}

/// Every code with `letter` (`'G'` or `'M'`) of `dialect` in modal group `group`.
pub fn codes_in_letter_group(
    dialect: Dialect,
    letter: char,
    group: u8,
) -> impl Iterator<Item = &'static CodeInfo> {
    dialect
        .codes()
        .iter()
        .filter(move |c| c.letter == letter && c.group == Some(group))
}

/// The power-on default codes of `dialect` (at most one per group), in table order.
pub fn default_codes(dialect: Dialect) -> impl Iterator<Item = &'static CodeInfo> {
    dialect.codes().iter().filter(|c| c.default)
}

/// The distinct modal groups of `letter` codes in `dialect`'s table, ascending.
pub fn groups(dialect: Dialect, letter: char) -> Vec<u8> {
    let mut g: Vec<u8> = dialect
        .codes()
        .iter()
        .filter(|c| c.letter == letter)
        .filter_map(|c| c.group)
        .collect();
    g.sort_unstable();
    g.dedup();
    g
}

/// Checks shared by every dialect's table tests: no duplicate (letter, num), at
/// most one default per group, non-empty texts, upper-case params without repeats.
#[cfg(test)]
pub(crate) fn check_table_invariants(dialect: Dialect) {
    let codes = dialect.codes();
    for (i, a) in codes.iter().enumerate() {
        for b in &codes[i + 1..] {
            assert!(
                !(a.letter == b.letter && a.num == b.num),
                "{}: duplicate {}",
                dialect.as_str(),
                a.name()
            );
        }
        assert!(
            a.letter == 'G' || a.letter == 'M',
            "{}: bad letter in {}",
            dialect.as_str(),
            a.name()
        );
        assert!(
            !a.summary.is_empty() && !a.doc.is_empty(),
            "{}: empty text for {}",
            dialect.as_str(),
            a.name()
        );
        assert!(
            a.variants != 0,
            "{}: {} on no variant",
            dialect.as_str(),
            a.name()
        );
        if a.letter == 'M' {
            assert_eq!(
                a.kind,
                CodeKind::Misc,
                "{}: {} kind",
                dialect.as_str(),
                a.name()
            );
        }
        if a.default {
            assert!(
                a.group.is_some_and(|g| g != 0),
                "{}: default {} outside a modal group",
                dialect.as_str(),
                a.name()
            );
        }
        for (j, p) in a.params.iter().enumerate() {
            assert!(
                p.letter.is_ascii_uppercase(),
                "{}: {} param {:?}",
                dialect.as_str(),
                a.name(),
                p.letter
            );
            assert!(
                !p.doc.is_empty(),
                "{}: {} param {} undocumented",
                dialect.as_str(),
                a.name(),
                p.letter
            );
            assert!(
                a.params[j + 1..].iter().all(|q| q.letter != p.letter),
                "{}: {} repeats param {}",
                dialect.as_str(),
                a.name(),
                p.letter
            );
        }
    }
    for letter in ['G', 'M'] {
        for g in groups(dialect, letter) {
            let n = codes_in_letter_group(dialect, letter, g)
                .filter(|c| c.default)
                .count();
            assert!(
                n <= 1,
                "{}: {letter} group {} has {} defaults",
                dialect.as_str(),
                g,
                n
            );
        }
    }
    let letters: Vec<char> = dialect.addresses().iter().map(|a| a.letter).collect();
    for (i, l) in letters.iter().enumerate() {
        assert!(
            !letters[i + 1..].contains(l),
            "{}: address {} twice",
            dialect.as_str(),
            l
        );
    }
    assert!(dialect.addresses().iter().all(|a| !a.doc.is_empty()));
}

/// Asserts that every name in `names` (like `"G2.3"`, `"M30"`) is in the table.
#[cfg(test)]
pub(crate) fn assert_all_present(dialect: Dialect, names: &[&str]) {
    for n in names {
        let (letter, rest) = n.split_at(1);
        let letter = letter.chars().next().unwrap_or('?');
        let v: f64 = rest.parse().unwrap_or(-1.0);
        let num = CodeNum::from_value(v).unwrap_or(CodeNum(u32::MAX));
        assert!(
            lookup(dialect, letter, num).is_some(),
            "{}: {} missing",
            dialect.as_str(),
            n
        );
    }
}

impl Param {
    /// An optional word.
    pub const fn opt(letter: char, doc: &'static str) -> Param {
        Param {
            letter,
            doc,
            required: false,
        }
    }

    /// A word without which the code is an error.
    pub const fn req(letter: char, doc: &'static str) -> Param {
        Param {
            letter,
            doc,
            required: true,
        }
    }

    /// Looks a word up in a code's parameter list.
    pub fn find(params: &'static [Param], letter: char) -> Option<&'static Param> {
        let up = letter.to_ascii_uppercase();
        params.iter().find(|p| p.letter == up)
    }
}

impl CodeInfo {
    /// A table row; `default` starts false (see [`CodeInfo::dflt`]).
    #[allow(clippy::too_many_arguments)]
    pub const fn new(
        letter: char,
        num: CodeNum,
        group: Option<u8>,
        kind: CodeKind,
        variants: u8,
        summary: &'static str,
        doc: &'static str,
        params: &'static [Param],
    ) -> CodeInfo {
        CodeInfo {
            letter,
            num,
            group,
            kind,
            variants,
            default: false,
            summary,
            doc,
            params,
        }
    }

    /// The same row marked as its group's power-on default.
    pub const fn dflt(self) -> CodeInfo {
        let mut c = self;
        c.default = true;
        c
    }

    /// The same row restricted to the variants in `mask`.
    pub const fn only(self, mask: u8) -> CodeInfo {
        let mut c = self;
        c.variants = mask;
        c
    }

    /// The parameter entry for `letter`, if this code documents one.
    pub fn param(&self, letter: char) -> Option<&'static Param> {
        Param::find(self.params, letter)
    }

    /// The group as the dialect's manual writes it: `"00"`, `"01"` for
    /// ServoWorks and FANUC, `"0"`, `"1"` for RS274/NGC (M groups prefixed `M`).
    pub fn group_label(&self, dialect: Dialect) -> Option<String> {
        let g = self.group?;
        let prefix = if self.letter == 'M' { "M" } else { "" };
        Some(match dialect {
            Dialect::Rs274ngc => format!("{prefix}{g}"),
            Dialect::Servoworks | Dialect::Fanuc => format!("{prefix}{g:02}"),
        })
    }

    /// Markdown hover text: name, summary, group/default, variants, doc and words.
    pub fn hover(&self, dialect: Dialect) -> String {
        let mut out = format!("**{}** — {}\n\n", self.display_name(dialect), self.summary);
        match (self.group, self.group_label(dialect)) {
            (Some(0), Some(l)) => out.push_str(&format!("Group {l} (non-modal)")),
            (Some(_), Some(l)) => out.push_str(&format!("Modal group {l}")),
            _ => out.push_str("No modal group"),
        }
        if self.default {
            out.push_str(", power-on default");
        }
        let all = variants_of(dialect);
        if all.iter().any(|v| !self.on_variant(*v)) {
            let on: Vec<&str> = all
                .iter()
                .filter(|v| self.on_variant(**v))
                .map(|v| v.as_str())
                .collect();
            out.push_str(&format!(". Only on: {}", on.join(", ")));
        }
        out.push_str(".\n\n");
        out.push_str(self.doc);
        if !self.params.is_empty() {
            out.push_str("\n\n");
            for p in self.params {
                let req = if p.required { " (required)" } else { "" };
                out.push_str(&format!("- `{}` {}{}\n", p.letter, p.doc, req));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_num_from_value_and_display() {
        assert_eq!(CodeNum::from_value(2.3), Some(CodeNum(23)));
        assert_eq!(CodeNum::from_value(54.1), Some(CodeNum(541)));
        assert_eq!(CodeNum::from_value(2.35), None);
        assert_eq!(CodeNum(3100).display(), "310");
        assert_eq!(CodeNum(592).display(), "59.2");
    }

    #[test]
    fn variant_lookup() {
        let g432 = CodeNum(432);
        assert!(lookup_variant(Variant::S140M, 'G', g432).is_some());
        assert!(lookup_variant(Variant::S120M, 'G', g432).is_none());
        assert!(lookup_variant(Variant::S100M, 'G', CodeNum(23)).is_none());
        assert!(lookup_variant(Variant::S120M, 'G', CodeNum(23)).is_some());
        assert!(lookup_variant(Variant::Emc2, 'G', CodeNum(520)).is_none());
        assert!(lookup_variant(Variant::Linuxcnc, 'G', CodeNum(520)).is_some());
        assert!(lookup_variant(Variant::Fanuc30i, 'G', CodeNum(650)).is_some());
        for d in Dialect::ALL {
            assert!(variants_of(d).iter().all(|v| v.dialect() == d));
            assert!(variants_of(d).contains(&d.default_variant()));
        }
    }

    #[test]
    fn address_lookup_is_case_insensitive() {
        for d in Dialect::ALL {
            assert!(lookup_address(d, 'x').is_some(), "{}", d.as_str());
            assert!(lookup_address(d, 'F').is_some(), "{}", d.as_str());
        }
    }

    #[test]
    fn hover_text() {
        let g04 =
            lookup(Dialect::Servoworks, 'G', CodeNum(40)).map(|c| c.hover(Dialect::Servoworks));
        let g04 = g04.unwrap_or_default();
        assert!(
            g04.starts_with("**G04** — Dwell\n\nGroup 00 (non-modal)."),
            "{g04}"
        );
        assert!(g04.contains("- `P` dwell in milliseconds, integer\n"));
        let g432 =
            lookup(Dialect::Servoworks, 'G', CodeNum(432)).map(|c| c.hover(Dialect::Servoworks));
        assert!(g432
            .unwrap_or_default()
            .contains("Modal group 08. Only on: S-140M."));
        let m8 = lookup(Dialect::Rs274ngc, 'M', CodeNum(90)).map(|c| c.hover(Dialect::Rs274ngc));
        assert!(m8
            .unwrap_or_default()
            .contains("Modal group M8, power-on default."));
        let g80 =
            lookup(Dialect::Fanuc, 'G', CodeNum(800)).and_then(|c| c.group_label(Dialect::Fanuc));
        assert_eq!(g80.as_deref(), Some("09"));
        let m30 = lookup(Dialect::Fanuc, 'M', CodeNum(300)).map(|c| c.hover(Dialect::Fanuc));
        assert!(m30.unwrap_or_default().contains("No modal group."));
    }
}

#[cfg(test)]
mod index_tests {
    use super::*;

    /// The index finds exactly what a scan of the table finds: every code of every
    /// table, the numbers between them, and letters and numbers it does not index.
    #[test]
    fn lookup_agrees_with_a_scan_of_the_table() {
        for dialect in [Dialect::Servoworks, Dialect::Rs274ngc, Dialect::Fanuc] {
            let scan = |letter: char, num: CodeNum| {
                dialect
                    .codes()
                    .iter()
                    .find(|c| c.letter == letter && c.num == num)
            };
            for letter in ['G', 'M', 'T', 'D'] {
                for n in (0..1100).chain([9999, 10_000, u32::MAX]) {
                    let num = CodeNum(n);
                    let got = lookup(dialect, letter, num).map(|c| (c.letter, c.num));
                    let want = scan(letter, num).map(|c| (c.letter, c.num));
                    assert_eq!(got, want, "{} {letter}{n}", dialect.as_str());
                }
            }
            for c in dialect.codes() {
                assert!(std::ptr::eq(lookup(dialect, c.letter, c.num).unwrap(), c));
            }
        }
    }
}
