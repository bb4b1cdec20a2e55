" Basic G-code highlighting for Neovim versions without LSP semantic tokens (before 0.9).
" The Partscope server's semantic tokens take over where the client supports them.
if exists('b:current_syntax')
  finish
endif
syntax case ignore

syntax match gcodeNumber      /[-+]\?\(\d\+\.\?\d*\|\.\d\+\)/
syntax match gcodeAddress     /[A-Z]\ze\s*[-+.0-9#\[]/
syntax match gcodeAxis        /[XYZABCUVW]\ze\s*[-+.0-9#\[]/
syntax match gcodeSequence    /N\s*\d\+/
syntax match gcodeGCode       /G\s*\d\+\(\.\d\+\)\?/
syntax match gcodeMCode       /M\s*\d\+/
syntax match gcodeTool        /T\s*\d\+/
syntax match gcodeVariable    /#\(<[^>]*>\|\s*\d\+\|_[A-Za-z0-9_]\+\)/
syntax match gcodeOWord       /\<O\s*\(<[^>]*>\|\d\+\)\(\s*\(sub\|endsub\|call\|return\|if\|elseif\|else\|endif\|while\|endwhile\|do\|repeat\|endrepeat\|break\|continue\)\>\)\?/
syntax match gcodeKeyword     /\<\(IF\|THEN\|WHILE\)\>\|GOTO\|\(DO\|END\)\ze\d/
syntax match gcodeFunction    /\(ATAN\|ASIN\|ACOS\|SQRT\|ROUND\|EXISTS\|SIN\|COS\|TAN\|ABS\|BIN\|BCD\|FIX\|FUP\|LN\|EXP\|POW\|ADP\)\ze\s*\[/
syntax match gcodeOperator    /\(EQ\|NE\|GT\|GE\|LT\|LE\|AND\|OR\|XOR\|MOD\)\ze\s*[-+.0-9#\[]/
syntax match gcodeBlockDelete /^\s*\/\d\?/
syntax region gcodeComment    start=/(/ end=/)\|$/ oneline
syntax match gcodeComment     /;.\+$/
syntax match gcodeComment     /^%.\+$/

highlight default link gcodeNumber      Number
highlight default link gcodeAddress     Identifier
highlight default link gcodeAxis        Identifier
highlight default link gcodeSequence    LineNr
highlight default link gcodeGCode       Statement
highlight default link gcodeMCode       PreProc
highlight default link gcodeTool        Type
highlight default link gcodeVariable    Special
highlight default link gcodeOWord       Function
highlight default link gcodeKeyword     Conditional
highlight default link gcodeFunction    Function
highlight default link gcodeOperator    Operator
highlight default link gcodeBlockDelete Special
highlight default link gcodeComment     Comment

let b:current_syntax = 'gcode'
