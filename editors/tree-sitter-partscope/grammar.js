/**
 * Tree-sitter grammar for CNC part programs in Partscope's three dialects:
 * ServoWorks S-100M/S-120M/S-140M, RS274/NGC (LinuxCNC, EMC2) and FANUC 30i
 * (Custom Macro B). One grammar serves all three, because an editor picks a
 * grammar by file type while the dialect is often known only from the text.
 *
 * The dialects differ on a few characters; the choices made here:
 * - `;` is an end of block (FANUC, ServoWorks) when nothing but blanks follows
 *   it, or when the rest of the line is again G-code ending in `;` (several
 *   FANUC blocks on one line); otherwise it starts a comment to the end of the
 *   line (RS274/NGC comment, ServoWorks prose after the block). The external
 *   scanner (src/scanner.c) decides.
 * - `%` at the start of a line: alone it is the tape mark; with text after it
 *   the whole line is not executed (ServoWorks block delete, FANUC leader).
 * - Multi-letter words (`IF`, `GOTO`, `WHILE`, `DO`, `END`, `THEN`, `DPRNT`, …)
 *   are Macro B statements; single letters are addresses. RS274/NGC spells
 *   none of its words that way, so no program of it changes meaning.
 * - Operators nest by the RS274/NGC precedence levels; FANUC's differ (`AND`
 *   binds like `*`), which changes only the shape of the tree, not its tokens.
 *
 * Like Partscope's own parser the grammar is case-insensitive and allows
 * blanks inside numbers (`X1 5` is `X15` in RS274/NGC and FANUC).
 */

/** A case-insensitive pattern for `word`; blanks may stand where `word` has one. */
function ci(word) {
  const parts = word.split(' ').map((part) =>
    part
      .split('')
      .map((c) => (/[a-z]/i.test(c) ? `[${c.toLowerCase()}${c.toUpperCase()}]` : c))
      .join(''),
  );
  return new RegExp(parts.join('[ \\t]*'));
}

/** A keyword node named after its upper-case spelling. */
function kw(word) {
  return alias(ci(word), word.replace(/ /g, '').toUpperCase());
}

const PREC = {
  logical: 1,
  relational: 2,
  additive: 3,
  multiplicative: 4,
  power: 5,
  unary: 6,
};

const FUNCTIONS = [
  'ABS', 'ACOS', 'ADP', 'ASIN', 'ATAN', 'BCD', 'BIN', 'COS', 'EXISTS', 'EXP', 'FIX',
  'FUP', 'LN', 'POW', 'ROUND', 'SIN', 'SQRT', 'TAN',
];

// Digit runs may be split by blanks (RS274/NGC and FANUC drop them).
const DIGITS = /[0-9]+([ \t]+[0-9]+)*/.source;
const BLANKS = /[ \t]*/.source;

module.exports = grammar({
  name: 'partscope',

  // Blanks between items, and a UTF-8 byte-order mark some editors write.
  extras: (_) => [/[ \t\f\v\uFEFF]/],

  externals: ($) => [$.end_of_block, $.line_comment],

  rules: {
    source_file: ($) =>
      seq(repeat(seq(optional($._line_content), $._terminator)), optional($._line_content)),

    _terminator: ($) => choice($._newline, $.end_of_block),

    _newline: (_) => /\r\n|\r|\n/,

    _line_content: ($) => choice($.block, $.tape_mark, $.percent_line),

    // `%` alone on its line.
    tape_mark: (_) => '%',

    // `%` followed by text: a ServoWorks block-delete line or a FANUC leader.
    percent_line: (_) => token(/%[ \t]*[^ \t\r\n][^\r\n]*/),

    block: ($) =>
      choice(seq(optional($.block_delete), repeat1($._item)), $.block_delete),

    // `/` (RS274/NGC, ServoWorks) or `/1`…`/9` (FANUC) at the start of a block.
    block_delete: (_) => /\/[1-9]?/,

    _item: ($) =>
      choice(
        $.line_number,
        $.g_code,
        $.m_code,
        $.word,
        $.o_word,
        $.program_head,
        $.assignment,
        $.if_statement,
        $.goto_statement,
        $.while_statement,
        $.do_statement,
        $.end_statement,
        $.print_statement,
        $.comment,
        $.message,
        $.directive,
        $.line_comment,
      ),

    // ---- words ------------------------------------------------------------

    line_number: ($) => seq(field('address', alias(/[nN]/, $.address)), field('value', $.number)),

    g_code: ($) => seq(field('address', alias(/[gG]/, $.address)), field('value', $._value)),

    m_code: ($) => seq(field('address', alias(/[mM]/, $.address)), field('value', $._value)),

    word: ($) =>
      choice(
        seq(field('address', $.address), field('value', choice($._value, $.spindle_number))),
        // `P` takes a subprogram name in ServoWorks (`M98 PMoveXY`).
        seq(
          field('address', alias(/[pP]/, $.address)),
          field('value', choice($._value, alias($._identifier, $.name))),
        ),
      ),

    // Address letters other than G, M, N, O and P, which have rules of their
    // own; `$ @ ^` are RS274/NGC's, `,C` `,R` `,A` FANUC's chamfer, corner and angle.
    address: (_) => token(choice(/[a-fA-Fh-lH-Lq-zQ-Z]/, /[$@^]/, /,[ \t]*[cCrRaA]/)),

    // ServoWorks `S2_1500`: spindle 2 at 1500.
    spindle_number: (_) => token(/[0-9]+_[0-9]*\.?[0-9]*/),

    // Below the function names, so that `P SIN[…]` stays a call.
    _identifier: (_) => token(prec(-1, /[A-Za-z_][A-Za-z0-9_]*/)),

    // A literal: sign, digits, point, and blanks between digits.
    number: (_) =>
      token(
        new RegExp(
          `[+-]?${BLANKS}(${DIGITS}(${BLANKS}\\.(${BLANKS}${DIGITS})?)?|\\.${BLANKS}${DIGITS})`,
        ),
      ),

    _value: ($) =>
      choice(
        $.number,
        $.parameter,
        $.named_parameter,
        $.bracketed_expression,
        $.function_call,
        alias($._quotient_value, $.binary_expression),
        alias($._unary_value, $.unary_expression),
      ),

    // `X-#1`, `X-[…]`: a sign before what is not a literal.
    _unary_value: ($) =>
      seq(
        field('operator', choice('-', '+')),
        field('argument', choice($.parameter, $.named_parameter, $.bracketed_expression, $.function_call)),
      ),

    // ---- parameters and expressions ---------------------------------------

    // `#1`, `##1`, `#[#1+1]`, `##<name>` (the parameter whose number `#<name>` holds).
    parameter: ($) =>
      seq(
        '#',
        field(
          'index',
          choice(
            $.number,
            $.parameter,
            $.named_parameter,
            $.bracketed_expression,
            $.function_call,
            alias($._quotient_value, $.binary_expression),
          ),
        ),
      ),

    // `#<name>`, `#<_global>` (RS274/NGC).
    named_parameter: (_) => token(/#[ \t]*<[^>\r\n]*>/),

    assignment: ($) =>
      seq(
        field('left', choice($.parameter, $.named_parameter)),
        '=',
        field('right', $._expression),
      ),

    bracketed_expression: ($) => seq('[', $._expression, ']'),

    _expression: ($) =>
      choice(
        $.number,
        $.parameter,
        $.named_parameter,
        $.bracketed_expression,
        $.function_call,
        $.unary_expression,
        $.binary_expression,
      ),

    unary_expression: ($) =>
      prec(PREC.unary, seq(field('operator', choice('-', '+')), field('argument', $._expression))),

    binary_expression: ($) => {
      const table = [
        [PREC.power, '**'],
        [PREC.multiplicative, choice('*', '/', kw('MOD'))],
        [PREC.additive, choice('+', '-')],
        [PREC.relational, choice(kw('EQ'), kw('NE'), kw('GT'), kw('GE'), kw('LT'), kw('LE'))],
        [PREC.logical, choice(kw('AND'), kw('OR'), kw('XOR'))],
      ];
      return choice(
        ...table.map(([p, op]) =>
          prec.left(p, seq(field('left', $._expression), field('operator', op), field('right', $._expression))),
        ),
      );
    },

    function_call: ($) =>
      seq(field('name', $.function_name), field('arguments', $.argument_list)),

    // `X ATAN[y]/[x]`: a quotient, written without brackets around it, is a
    // word's value only in this form.
    // After `#` too: `#atan[1]/[2]` is one parameter, as LinuxCNC reads it.
    _quotient_value: ($) =>
      prec(1, seq(field('left', $.function_call), field('operator', '/'), field('right', $.bracketed_expression))),

    function_name: (_) => token(choice(...FUNCTIONS.map((f) => ci(f)))),

    // `[a]`, or `[a, b]` for FANUC `ATAN` and `POW`.
    argument_list: ($) => seq('[', $._expression, optional(seq(',', $._expression)), ']'),

    // ---- O-words and program heads ----------------------------------------

    // RS274/NGC `o100 sub`, `o<name> call [1] [2]`; FANUC `O1000`, `:1000`;
    // ServoWorks `OMoveXY`.
    o_word: ($) =>
      prec.right(
        seq(
          field('address', alias(choice(/[oO]/, ':'), $.address)),
          field(
            'label',
            choice(
              $.number,
              alias($._angle_name, $.name),
              alias($._identifier, $.name),
              $.parameter,
              $.named_parameter,
              $.bracketed_expression,
            ),
          ),
          optional(field('keyword', $._o_keyword)),
          // LinuxCNC reads comments between the arguments of a call.
          repeat(choice(field('argument', choice($.bracketed_expression, $.parameter, $.named_parameter)), $.comment)),
        ),
      ),

    _o_keyword: (_) =>
      choice(
        kw('sub'),
        kw('end sub'),
        kw('return'),
        kw('call'),
        kw('do'),
        kw('while'),
        kw('end while'),
        kw('break'),
        kw('continue'),
        kw('if'),
        kw('else if'),
        kw('else'),
        kw('end if'),
        kw('repeat'),
        kw('end repeat'),
      ),

    _angle_name: (_) => /<[^>\r\n]*>/,

    // FANUC 30i `<name>` program head.
    program_head: ($) => field('name', alias($._angle_name, $.name)),

    // ---- Custom Macro B statements ----------------------------------------

    if_statement: ($) =>
      prec.right(
        seq(
          kw('IF'),
          field('condition', $.bracketed_expression),
          optional(choice(seq(kw('GOTO'), field('target', $._value)), kw('THEN'))),
        ),
      ),

    goto_statement: ($) => seq(kw('GOTO'), field('target', $._value)),

    while_statement: ($) =>
      seq(kw('WHILE'), field('condition', $.bracketed_expression), kw('DO'), field('loop', $._value)),

    do_statement: ($) => seq(kw('DO'), field('loop', $._value)),

    end_statement: ($) => seq(kw('END'), field('loop', $._value)),

    // External output: `POPEN`, `PCLOS`, `DPRNT[…]`, `BPRNT[…]`.
    print_statement: ($) =>
      choice(
        kw('POPEN'),
        kw('PCLOS'),
        seq(choice(kw('DPRNT'), kw('BPRNT')), field('format', $.print_format)),
      ),

    // The text of a DPRNT/BPRNT: characters and `#n[ab]` formats, not an expression.
    print_format: (_) => token(/\[([^\[\]\r\n]|\[[^\[\]\r\n]*\])*\]/),

    // ---- comments ---------------------------------------------------------

    // `( … )`; a comment may hold one level of parentheses, and an unclosed one
    // runs to the end of the line, as Partscope's parser reads them.
    comment: (_) => token(/\(([^()\r\n]|\([^()\r\n]*\))*\)?/),

    // RS274/NGC messages and logs: `(MSG, …)`, `(DEBUG, …)`, `(PRINT, …)`,
    // `(LOG…)`, `(ABORT, …)`, `(PROBEOPEN …)`, `(PY, …)`.
    message: (_) =>
      token(
        prec(
          1,
          new RegExp(
            `\\(${BLANKS}(${['MSG', 'DEBUG', 'PRINT', 'ABORT', 'PY', 'PYRUN']
              .map((w) => ci(w).source + BLANKS + ',')
              .concat(['LOGOPEN', 'LOGAPPEND', 'LOGCLOSE', 'LOG', 'PROBEOPEN', 'PROBECLOSE', 'PYRELOAD'].map((w) => ci(w).source))
              .join('|')})([^()\\r\\n]|\\([^()\\r\\n]*\\))*\\)?`,
          ),
        ),
      ),

    // `(partscope: allow G001)`, `(partscope: dialect=fanuc)`.
    directive: (_) =>
      token(prec(2, new RegExp(`\\(${BLANKS}${ci('partscope').source}[ \\t:]([^()\\r\\n]|\\([^()\\r\\n]*\\))*\\)?`))),
  },
});
