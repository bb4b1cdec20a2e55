//! Documentation of the words of the macro languages: FANUC Custom Macro B
//! statements (FANUC and ServoWorks, whose parser reads the same language),
//! RS274/NGC O-word keywords, the operators and the functions, each only in
//! the dialects that have it. Hover and completion read this one table.

use analyzer::Dialect;

/// What a keyword is, for completion's item kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KwKind {
    Statement,
    Operator,
    Function,
    /// An RS274/NGC O-word keyword (`o100 while`).
    OWord,
}

pub struct Keyword {
    /// As the dialect's manual writes it (upper case, O-words lower case).
    pub name: &'static str,
    pub kind: KwKind,
    /// How it is written, e.g. `WHILE [cond] DO m`.
    pub syntax: &'static str,
    pub doc: &'static str,
}

const MACRO_B: &[Dialect] = &[Dialect::Fanuc, Dialect::Servoworks];
const NGC: &[Dialect] = &[Dialect::Rs274ngc];
const ALL: &[Dialect] = &[Dialect::Fanuc, Dialect::Servoworks, Dialect::Rs274ngc];

/// One entry per dialect group: the same name may mean different things.
struct Entry {
    dialects: &'static [Dialect],
    kw: Keyword,
}

const fn e(
    dialects: &'static [Dialect],
    name: &'static str,
    kind: KwKind,
    syntax: &'static str,
    doc: &'static str,
) -> Entry {
    Entry {
        dialects,
        kw: Keyword {
            name,
            kind,
            syntax,
            doc,
        },
    }
}

use KwKind::{Function as F, OWord as O, Operator as Op, Statement as S};

static TABLE: &[Entry] = &[
    // Custom Macro B statements.
    e(MACRO_B, "IF", S, "IF [cond] GOTO n  /  IF [cond] THEN statement",
      "Conditional branch or execution. With `GOTO n` control jumps to sequence number N n when the condition is true; with `THEN` the one macro statement after it runs only when the condition is true. The condition must be in brackets."),
    e(MACRO_B, "THEN", S, "IF [cond] THEN statement",
      "Introduces the single macro statement (usually an assignment) that `IF` runs when its condition is true."),
    e(MACRO_B, "GOTO", S, "GOTO n",
      "Unconditional branch to the block with sequence number N n (1–99999, may be an expression). The control searches the current program in both directions; a number it cannot find is alarm PS0128. Jumping into a DO–END range is not allowed."),
    e(MACRO_B, "WHILE", S, "WHILE [cond] DO m … END m",
      "Loop: the blocks up to `END m` repeat while the condition is true; the condition is tested before each pass. m is 1, 2 or 3; loops nest at most three deep and must not cross. Branching out of a loop is allowed, into one is not."),
    e(MACRO_B, "DO", S, "WHILE [cond] DO m  /  DO m",
      "Opens loop m (1–3) that ends at `END m`. Without a `WHILE` in front, the loop never ends by itself (leave it with GOTO)."),
    e(MACRO_B, "END", S, "END m",
      "Closes loop m opened by `DO m`: control goes back to the loop's `WHILE` test. A `DO` without its `END` is alarm PS0124."),
    e(MACRO_B, "POPEN", S, "POPEN",
      "Opens the external output device (punch or serial port) for `DPRNT`/`BPRNT`. No effect on motion."),
    e(MACRO_B, "PCLOS", S, "PCLOS",
      "Closes the external output device opened with `POPEN`."),
    e(MACRO_B, "DPRNT", S, "DPRNT [text #var[digits]]",
      "Prints text and variable values in decimal to the device opened with `POPEN`. No effect on motion."),
    e(MACRO_B, "BPRNT", S, "BPRNT [text #var[digits]]",
      "Prints text and variable values in binary to the device opened with `POPEN`. No effect on motion."),
    // Relational operators.
    e(ALL, "EQ", Op, "a EQ b", "Equal: 1 (true) or 0 (false). Compare computed values with a tolerance instead (`ABS[a-b] LT 0.001`): real numbers are rarely exactly equal."),
    e(ALL, "NE", Op, "a NE b", "Not equal: 1 (true) or 0 (false)."),
    e(ALL, "GT", Op, "a GT b", "Greater than: 1 (true) or 0 (false)."),
    e(ALL, "GE", Op, "a GE b", "Greater than or equal: 1 (true) or 0 (false)."),
    e(ALL, "LT", Op, "a LT b", "Less than: 1 (true) or 0 (false)."),
    e(ALL, "LE", Op, "a LE b", "Less than or equal: 1 (true) or 0 (false)."),
    // Logical operators: bitwise in Macro B, truth values in RS274/NGC.
    e(MACRO_B, "AND", Op, "a AND b", "Bitwise AND of two integers (binds like `*`). Conditions combine with it too: `[#1 GT 0] AND [#2 GT 0]`."),
    e(MACRO_B, "OR", Op, "a OR b", "Bitwise OR of two integers (binds like `+`)."),
    e(MACRO_B, "XOR", Op, "a XOR b", "Bitwise exclusive OR of two integers (binds like `+`)."),
    e(NGC, "AND", Op, "a AND b", "Logical AND: 1 when both sides are non-zero, else 0. Lowest precedence, with OR and XOR."),
    e(NGC, "OR", Op, "a OR b", "Logical OR: 1 when either side is non-zero, else 0."),
    e(NGC, "XOR", Op, "a XOR b", "Logical exclusive OR: 1 when exactly one side is non-zero, else 0."),
    e(ALL, "MOD", Op, "a MOD b", "Remainder of a / b. In RS274/NGC a negative result gets |b| added (`[-7 MOD 3]` = 2); on FANUC only later controls have it."),
    // Functions (angles in degrees everywhere).
    e(ALL, "SIN", F, "SIN[x]", "Sine of x degrees."),
    e(ALL, "COS", F, "COS[x]", "Cosine of x degrees."),
    e(ALL, "TAN", F, "TAN[x]", "Tangent of x degrees."),
    e(ALL, "ASIN", F, "ASIN[x]", "Arc sine in degrees; x must lie in −1…1."),
    e(ALL, "ACOS", F, "ACOS[x]", "Arc cosine in degrees (180…0); x must lie in −1…1."),
    e(MACRO_B, "ATAN", F, "ATAN[a]/[b]", "Arc tangent of a/b in degrees, by quadrant; the result lies in 0…360 unless a parameter selects −180…180. Later controls also accept `ATAN[a,b]`."),
    e(NGC, "ATAN", F, "ATAN[y]/[x]", "Four-quadrant arc tangent of y/x in degrees (atan2). The slash and the second bracket are required."),
    e(ALL, "SQRT", F, "SQRT[x]", "Square root; x must not be negative."),
    e(ALL, "ABS", F, "ABS[x]", "Absolute value."),
    e(MACRO_B, "ROUND", F, "ROUND[x]", "Rounds to the nearest integer inside an expression; written directly as an address value it rounds to that address's least input increment."),
    e(NGC, "ROUND", F, "ROUND[x]", "Nearest integer, halves away from zero: ROUND[2.5] = 3, ROUND[-2.5] = −3."),
    e(MACRO_B, "FIX", F, "FIX[x]", "Drops the fraction (toward zero): FIX[2.8] = 2, FIX[-2.8] = −2."),
    e(NGC, "FIX", F, "FIX[x]", "Rounds down (floor): FIX[2.8] = 2, FIX[-2.8] = −3."),
    e(MACRO_B, "FUP", F, "FUP[x]", "Raises the fraction to the next integer away from zero: FUP[2.2] = 3, FUP[-2.2] = −3."),
    e(NGC, "FUP", F, "FUP[x]", "Rounds up (ceiling): FUP[2.2] = 3, FUP[-2.2] = −2."),
    e(ALL, "LN", F, "LN[x]", "Natural logarithm; x must be positive."),
    e(ALL, "EXP", F, "EXP[x]", "e to the power x."),
    e(MACRO_B, "BIN", F, "BIN[x]", "Converts a BCD-coded value to binary (for PMC signals)."),
    e(MACRO_B, "BCD", F, "BCD[x]", "Converts a binary value to BCD (for PMC signals)."),
    e(MACRO_B, "POW", F, "POW[a,b]", "a to the power b (later controls)."),
    e(MACRO_B, "ADP", F, "ADP[#n]", "Adds the decimal point to a value read without one (later controls)."),
    e(NGC, "EXISTS", F, "EXISTS[#<name>]", "1 when the named parameter exists (is defined in the current scope or globally), else 0. The value is not read."),
    // RS274/NGC O-word keywords.
    e(NGC, "sub", O, "o<name> sub … o<name> endsub", "Starts a subroutine body; normal flow skips it and `call` runs it. Arguments arrive in #1…#30; bodies must not nest."),
    e(NGC, "endsub", O, "o<name> endsub [value]", "Ends a subroutine body and returns to the caller; #1–#30 get the caller's values back. An optional value goes to `#<_value>`."),
    e(NGC, "call", O, "o<name> call [a] [b] …", "Runs subroutine o<name> (from this file or from `name.ngc` on the subroutine path) with up to 30 bracketed arguments in #1…#n. Calls nest up to 10 levels."),
    e(NGC, "return", O, "o<name> return [value]", "Leaves the subroutine at once, as `endsub` would; an optional value goes to `#<_value>`."),
    e(NGC, "if", O, "oN if [cond] … oN endif", "Runs the blocks up to the matching `elseif`, `else` or `endif` when the condition is non-zero."),
    e(NGC, "elseif", O, "oN elseif [cond]", "Tested when the `if` (and earlier `elseif`s) of the same label were false."),
    e(NGC, "else", O, "oN else", "Runs when no `if`/`elseif` of the same label was true."),
    e(NGC, "endif", O, "oN endif", "Ends the conditional with the same label."),
    e(NGC, "while", O, "oN while [cond] … oN endwhile  /  oN do … oN while [cond]", "Loop while the condition is non-zero: tested before the body with `endwhile`, after it when it closes a `do`."),
    e(NGC, "endwhile", O, "oN endwhile", "Ends a `while` loop: control goes back to its test."),
    e(NGC, "do", O, "oN do … oN while [cond]", "Starts a loop whose `while` test comes after the body, so the body runs at least once."),
    e(NGC, "repeat", O, "oN repeat [count] … oN endrepeat", "Runs the body count times."),
    e(NGC, "endrepeat", O, "oN endrepeat", "Ends a `repeat` loop."),
    e(NGC, "break", O, "oN break", "Leaves the loop with the same label at once."),
    e(NGC, "continue", O, "oN continue", "Skips the rest of the body: the loop's test comes next."),
];

/// The keyword `word` (any case) in `dialect`.
pub fn lookup(dialect: Dialect, word: &str) -> Option<&'static Keyword> {
    TABLE
        .iter()
        .find(|e| e.dialects.contains(&dialect) && e.kw.name.eq_ignore_ascii_case(word))
        .map(|e| &e.kw)
}

/// Every keyword of `dialect`.
pub fn all(dialect: Dialect) -> impl Iterator<Item = &'static Keyword> {
    TABLE
        .iter()
        .filter(move |e| e.dialects.contains(&dialect))
        .map(|e| &e.kw)
}

/// Hover and completion documentation of a keyword.
pub fn markdown(k: &Keyword) -> String {
    let what = match k.kind {
        KwKind::Statement => "macro statement",
        KwKind::Operator => "operator",
        KwKind::Function => "function",
        KwKind::OWord => "O-word keyword",
    };
    format!("**{}** — {what}\n\n`{}`\n\n{}", k.name, k.syntax, k.doc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_dialect_has_only_its_words() {
        assert!(lookup(Dialect::Fanuc, "while").is_some());
        assert!(lookup(Dialect::Servoworks, "GOTO").is_some());
        assert!(lookup(Dialect::Rs274ngc, "GOTO").is_none());
        assert!(lookup(Dialect::Fanuc, "endwhile").is_none());
        assert!(lookup(Dialect::Fanuc, "EXISTS").is_none());
        assert!(lookup(Dialect::Rs274ngc, "BCD").is_none());
        assert_eq!(
            lookup(Dialect::Rs274ngc, "ATAN").unwrap().syntax,
            "ATAN[y]/[x]"
        );
        // FIX differs: toward zero in Macro B, floor in RS274/NGC.
        assert!(lookup(Dialect::Fanuc, "FIX").unwrap().doc.contains("−2."));
        assert!(lookup(Dialect::Rs274ngc, "FIX")
            .unwrap()
            .doc
            .contains("−3."));
        // No name twice in one dialect.
        for d in [Dialect::Fanuc, Dialect::Servoworks, Dialect::Rs274ngc] {
            let mut names: Vec<String> = all(d).map(|k| k.name.to_ascii_uppercase()).collect();
            let n = names.len();
            names.sort();
            names.dedup();
            assert_eq!(names.len(), n, "{d:?}");
        }
    }
}
