; Highlights for Helix, Neovim and Zed. Capture names are chosen so that each
; editor finds a colour for them: all three fall back from `a.b` to `a`
; (literals are `@constant.numeric`: Helix's name, `@constant` elsewhere).

; Comments and text the control does not execute.
(comment) @comment
(line_comment) @comment
(percent_line) @comment

(message) @string.special
(directive) @keyword.directive

; Block structure.
(tape_mark) @punctuation.special
(block_delete) @punctuation.special
(end_of_block) @punctuation.delimiter

; Every number is captured once, by what it is part of, so that no two
; patterns match one node (Helix lets the first pattern win, Neovim the last).
(line_number
  address: (address) @label
  value: (number) @label)

(g_code
  address: (address) @keyword)

(g_code
  value: (number) @keyword)

(m_code
  address: (address) @function.builtin)

(m_code
  value: (number) @function.builtin)

(word
  address: (address) @variable.parameter)

(word
  value: (number) @constant.numeric)

(word
  value: (name) @function)

(spindle_number) @constant.numeric

; Program heads and O-words.
(o_word
  address: (address) @keyword.function)

(o_word
  label: (number) @label)

(o_word
  label: (name) @function)

(program_head
  name: (name) @function)

[
  "SUB"
  "ENDSUB"
  "CALL"
] @keyword.function

"RETURN" @keyword.return

[
  "IF"
  "ELSEIF"
  "ELSE"
  "ENDIF"
  "THEN"
] @keyword.conditional

[
  "WHILE"
  "ENDWHILE"
  "DO"
  "END"
  "REPEAT"
  "ENDREPEAT"
  "BREAK"
  "CONTINUE"
] @keyword.repeat

"GOTO" @keyword.control

(goto_statement
  target: (number) @label)

(if_statement
  target: (number) @label)

(while_statement
  loop: (number) @constant.numeric)

(do_statement
  loop: (number) @constant.numeric)

(end_statement
  loop: (number) @constant.numeric)

[
  "POPEN"
  "PCLOS"
  "DPRNT"
  "BPRNT"
] @function.builtin

(print_format) @string

; Parameters and expressions.
(parameter) @variable

(parameter
  index: (number) @variable)

; `#<_x>`: LinuxCNC's predefined and global parameters. `[<]`, because Neovim
; reads these patterns as very magic Vim regexes, where a bare `<` is a word start.
((named_parameter) @variable
  (#not-match? @variable "^#[ \t]*[<]_"))

((named_parameter) @variable.builtin
  (#match? @variable.builtin "^#[ \t]*[<]_"))

(assignment
  right: (number) @constant.numeric)

(binary_expression
  left: (number) @constant.numeric)

(binary_expression
  right: (number) @constant.numeric)

(unary_expression
  argument: (number) @constant.numeric)

(bracketed_expression
  (number) @constant.numeric)

(argument_list
  (number) @constant.numeric)

(function_name) @function.builtin

[
  "MOD"
  "EQ"
  "NE"
  "GT"
  "GE"
  "LT"
  "LE"
  "AND"
  "OR"
  "XOR"
] @keyword.operator

[
  "="
  "+"
  "-"
  "*"
  "/"
  "**"
] @operator

[
  "["
  "]"
] @punctuation.bracket

"," @punctuation.delimiter
