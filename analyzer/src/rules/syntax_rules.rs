//! Metadata of the diagnostics the parser emits (their checks live in
//! [`crate::syntax`], where the text is read).

use crate::declare_rule;

declare_rule! {
    /// ## What it does
    /// Flags a `(` comment that is not closed by `)` before the end of the block.
    ///
    /// ## Why is this bad?
    /// Comments never span blocks. RS274/NGC refuses the line (`Unclosed comment found`),
    /// FANUC raises a format alarm, and on ServoWorks the words you meant to follow the
    /// comment are swallowed by it.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X10 (rapid to start
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X10 (rapid to start)
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All. Error everywhere. A quick fix appends the missing `)`.
    ///
    /// Implements: SW010, NGC003, FAN006
    pub static UNCLOSED_COMMENT = {
        code: "L001",
        name: "unclosed-comment",
        summary: "Comment not closed before the end of the block",
        implements: &["SW010", "NGC003", "FAN006"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a `(` inside a comment.
    ///
    /// ## Why is this bad?
    /// Comments do not nest. LinuxCNC stops with `Nested comment found`; FANUC treats it
    /// as a format error. The comment ends at the first `)`, so the text after it would be
    /// read as program words.
    ///
    /// ## Example
    /// ```ngc
    /// G0 X1 (outer (inner) text)
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G0 X1 (outer - inner - text)
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and FANUC (error). ServoWorks does not define nesting.
    ///
    /// Implements: NGC004
    pub static NESTED_COMMENT = {
        code: "L002",
        name: "nested-comment",
        summary: "Comment inside a comment",
        implements: &["NGC004"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags an address letter with no value after it, such as `X` alone or `G` followed
    /// by another letter.
    ///
    /// ## Why is this bad?
    /// Every word is a letter followed by a number, a parameter or an expression. A bare
    /// letter is an alarm on FANUC (PS0005), an error in LinuxCNC, and an unparseable word
    /// on ServoWorks.
    ///
    /// ## Example
    /// ```ngc
    /// G1 X F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 X10 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error.
    ///
    /// Reported by this rule, not L010, when both see a `#` without a parameter on the same text (one diagnostic per fault).
    ///
    /// Reported by P008, not this rule, when both see an O-word label written with the digit 0 (its keyword read as words) on the same text (one diagnostic per fault).
    ///
    /// Implements: SW014, NGC006, NGC030, FAN002
    pub static MISSING_VALUE = {
        code: "L003",
        name: "missing-value",
        summary: "Address letter without a value",
        implements: &["SW014", "NGC006", "NGC030", "FAN002"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags numbers that cannot be read: a sign or point without digits (`X-`, `X.`),
    /// two decimal points (`X1.2.3`), or a value too large for a double.
    ///
    /// ## Why is this bad?
    /// The control stops with a number-format alarm (LinuxCNC `Bad number format`,
    /// FANUC PS0007 for two points, PS0003 for too many digits).
    ///
    /// ## Example
    /// ```ngc
    /// G1 X1.2.5 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 X1.25 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error.
    ///
    /// Implements: NGC005
    pub static MALFORMED_NUMBER = {
        code: "L004",
        name: "malformed-number",
        summary: "Number that cannot be read",
        implements: &["NGC005"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags characters that are not part of the language: stray numbers without an
    /// address, symbols, control or non-ASCII bytes outside comments.
    ///
    /// ## Why is this bad?
    /// LinuxCNC stops with `Bad character used`, FANUC with an address alarm. ServoWorks
    /// silently ignores data it does not recognise, so what you wrote is not executed.
    ///
    /// ## Example
    /// ```ngc
    /// G1 X10 ! F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 X10 F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// RS274/NGC and FANUC: error. ServoWorks: warning (the data is ignored). A UTF-8
    /// byte-order mark before the first line is one diagnostic: an error in RS274/NGC
    /// (rs274 stops with `Bad character '\357' used`), information in FANUC and
    /// ServoWorks, whose manuals say nothing of it; the line after it is read as if the
    /// mark were not there.
    ///
    /// Reported by P008, not this rule, when both see an O-word label written with the digit 0 on the same text (one diagnostic per fault).
    ///
    /// Implements: SW008, NGC002, NGC011, NGC111
    pub static UNKNOWN_CHARACTER = {
        code: "L005",
        name: "unknown-character",
        summary: "Character that is not part of the language",
        implements: &["SW008", "NGC002", "NGC011", "NGC111"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a `[` without its matching `]`.
    ///
    /// ## Why is this bad?
    /// The expression cannot be evaluated: LinuxCNC reports `Unclosed expression`, FANUC
    /// a macro format alarm (PS0114). The rest of the block is not read.
    ///
    /// ## Example
    /// ```ngc
    /// G1 X[1 + 2 F100
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 X[1 + 2] F100
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error.
    ///
    /// Implements: NGC010
    pub static UNBALANCED_BRACKET = {
        code: "L006",
        name: "unbalanced-bracket",
        summary: "Unclosed `[` expression",
        implements: &["NGC010"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a `/` that is not at the start of the block.
    ///
    /// ## Why is this bad?
    /// Block skip (optional skip) is only recognised as the first character of a block.
    /// ServoWorks reports a parse error for `/` anywhere else; LinuxCNC a bad character;
    /// on FANUC the effect depends on parameters (skip the rest of the block or alarm).
    ///
    /// ## Example
    /// ```servoworks
    /// N10 /G01 X1.0 F100
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// /N10 G01 X1.0 F100
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks and RS274/NGC: error. FANUC: warning.
    ///
    /// Implements: SW002, FAN014
    pub static MISPLACED_BLOCK_SKIP = {
        code: "L007",
        name: "misplaced-block-skip",
        summary: "`/` not at the start of the block",
        implements: &["SW002", "FAN014"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags lower-case address letters where the control does not accept them.
    ///
    /// ## Why is this bad?
    /// ServoWorks ignores lower-case letters outside comments and subprogram names, so a
    /// word like `x10.0` is silently dropped. FANUC programs are upper case by convention;
    /// most controls accept lower case only with a setting.
    ///
    /// ## Example
    /// ```servoworks
    /// G01 x10.0 F100.0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G01 X10.0 F100.0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks and FANUC: warning. RS274/NGC is case-insensitive.
    ///
    /// Implements: SW004, FAN015
    pub static LOWERCASE = {
        code: "L008",
        name: "lowercase-letter",
        summary: "Lower-case letter the control ignores",
        implements: &["SW004", "FAN015"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags malformed expressions and statements: an unknown function or operator name,
    /// a function without `[`, `ATAN` without its `/[x]`, a parameter reference that is not
    /// an assignment, O-word lines without a known keyword, `IF` without `GOTO`/`THEN`,
    /// `WHILE` without `DO`.
    ///
    /// ## Why is this bad?
    /// The control cannot evaluate the statement and stops (LinuxCNC: `Unknown operation
    /// name`, `Equal sign missing in parameter setting`; FANUC PS0114/PS0125).
    ///
    /// ## Example
    /// ```ngc
    /// #1 = ATAN[1]
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #1 = ATAN[1]/[1]
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error.
    ///
    /// Reported by L003, not this rule, when both see a `#` without a parameter on the same text (one diagnostic per fault).
    ///
    /// Implements: NGC012, NGC013, NGC020, NGC027, NGC600, NGC611, NGC612, FAN130, FAN131, FAN132
    pub static BAD_EXPRESSION = {
        code: "L010",
        name: "bad-expression",
        summary: "Malformed expression or statement",
        implements: &["NGC012", "NGC013", "NGC020", "NGC027", "NGC600", "NGC611", "NGC612", "FAN130", "FAN131", "FAN132"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a `%` where it has no meaning: not alone on its line (RS274/NGC, FANUC), not
    /// in the first column (ServoWorks), or a `%` line in an RS274/NGC file that did not
    /// open with `%`.
    ///
    /// ## Why is this bad?
    /// In ServoWorks a `%` deletes a block only in column 1; elsewhere it is ignored and the
    /// words after it run, which is rarely what was meant. LinuxCNC reports a bad character.
    ///
    /// ## Example
    /// ```servoworks
    /// G01 X1.0 % Y2.0 F100.0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// % G01 X1.0 Y2.0 F100.0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks: warning. RS274/NGC and FANUC: error.
    ///
    /// Reported by this rule, not X003, when both see a `%` that is not a program end on the same text (one diagnostic per fault).
    ///
    /// Reported by this rule, not P005, when both see a closing `%` without an opening one, read as the missing end on the same text (one diagnostic per fault).
    ///
    /// Implements: SW003
    pub static MISPLACED_PERCENT = {
        code: "L011",
        name: "misplaced-percent",
        summary: "`%` where it has no meaning",
        implements: &["SW003"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Notes text after a `;` end-of-block marker on a ServoWorks line.
    ///
    /// ## Why is this bad?
    /// The ServoWorks manual writes `;` at the end of blocks but never defines it. Partscope
    /// reads it as end of block, so what follows on the line is not executed; if you meant
    /// two blocks, put them on two lines.
    ///
    /// ## Example
    /// ```servoworks
    /// G80; G00 X0
    /// M30
    /// ```
    ///
    /// Use instead:
    /// ```servoworks
    /// G80
    /// G00 X0
    /// M30
    /// ```
    ///
    /// ## Dialects
    /// ServoWorks, info.
    ///
    /// Implements: SW013
    pub static TEXT_AFTER_EOB = {
        code: "L013",
        name: "text-after-end-of-block",
        summary: "Text after `;` is not executed",
        implements: &["SW013"],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags expressions nested more deeply than Partscope reads (64 levels).
    ///
    /// ## Why is this bad?
    /// No control accepts such nesting (FANUC allows 5 levels of brackets, PS0118). The
    /// rest of the block is not analysed.
    ///
    /// ## Example
    /// ```ngc
    /// #1 = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// #1 = [1]
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, error.
    ///
    /// Implements: (none; FANUC's five-level limit is checked by W014)
    pub static EXPRESSION_TOO_DEEP = {
        code: "L014",
        name: "expression-too-deep",
        summary: "Expression nested too deeply",
        implements: &[],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a block with more than 512 words and other items. The block rules check
    /// its first 512 only (some compare words pairwise, which a line of a million
    /// words would make take hours); the block-length rule checks the whole line.
    ///
    /// ## Why is this bad?
    /// No control reads such a block, and anything after the 512th word is not
    /// checked here.
    ///
    /// ## Example
    /// ```ngc
    /// G1 F100 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0 X0
    /// M2
    /// ```
    ///
    /// Use instead:
    /// ```ngc
    /// G1 F100 X0
    /// M2
    /// ```
    ///
    /// ## Dialects
    /// All, warning.
    ///
    /// Implements: (none)
    pub static BLOCK_TOO_MANY_ITEMS = {
        code: "L015",
        name: "block-too-many-items",
        summary: "Block with more items than the block rules check",
        implements: &[],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Reports a file that could not be read (missing, unreadable, a directory).
    ///
    /// ## Why is this bad?
    /// Nothing in it could be checked.
    ///
    /// ## Dialects
    /// All, error. `partscope check` exits with status 2 when a file could not be read.
    ///
    /// Implements:
    pub static IO_ERROR = {
        code: "L000",
        name: "io-error",
        summary: "File could not be read",
        implements: &[],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Reports a problem in a `partscope.toml` (or a machine profile given with
    /// `--machine`/`--config`): an unknown key (with the nearest valid one), a machine key
    /// written outside `[machine]`, a value of the wrong type or outside its range. It is
    /// reported once per file, at the key or value, in every output format.
    ///
    /// ## Why is this bad?
    /// The key keeps its default, so the check or cycle time is not for the machine the
    /// file describes: a misspelt `lookahed = 3` leaves the look-ahead at its default.
    ///
    /// ## Dialects
    /// All, warning. A file that is not TOML at all stops `check` and `run` with exit
    /// status 2 instead. The keys: `docs/configuration.md`.
    ///
    /// Implements:
    pub static CONFIG_ISSUE = {
        code: "L016",
        name: "config-issue",
        summary: "Unknown key or invalid value in a configuration file",
        implements: &[],
        origin: Syntax,
        default_enabled: true,
    }
}

declare_rule! {
    /// ## What it does
    /// Flags a file that is not text (it contains NUL bytes or mostly non-text bytes), and
    /// text that is not valid UTF-8.
    ///
    /// ## Why is this bad?
    /// A binary file is not a part program: it was probably picked up by mistake (an image,
    /// a compiled post-processor). Invalid UTF-8 usually means a file saved in a legacy code
    /// page; controls read only ASCII outside comments, and the comment text will show
    /// garbled in editors. A binary file is reported once and not analysed further.
    /// UTF-16 text (what Windows editors save as "Unicode", with or without a
    /// byte-order mark) is named as such, on the first bytes: re-saving it as ASCII
    /// or UTF-8 is the fix, and no control reads it as it is.
    ///
    /// ## Dialects
    /// All. Binary and UTF-16: error. Invalid UTF-8: warning.
    ///
    /// Implements:
    pub static NOT_TEXT = {
        code: "L009",
        name: "not-text",
        summary: "Binary file or invalid UTF-8",
        implements: &[],
        origin: Syntax,
        default_enabled: true,
    }
}
