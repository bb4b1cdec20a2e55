O1000 (BOLT CIRCLE)
( <- keyword.function)
(^ label)
(      ^ comment)
N10 G00 X0. M03
( <- label)
(^ label)
(   ^ keyword)
(    ^ keyword)
(       ^ variable.parameter)
(        ^ constant.numeric)
(           ^ function.builtin)
(            ^ function.builtin)
#1 = #2 + SIN[30.]
( <- variable)
(^ variable)
(  ^ operator)
(       ^ operator)
(         ^ function.builtin)
(            ^ punctuation.bracket)
(             ^ constant.numeric)
WHILE [#1 LT 6] DO1
( <- keyword.repeat)
(         ^ keyword.operator)
(            ^ constant.numeric)
(               ^ keyword.repeat)
(                 ^ constant.numeric)
IF [#1 EQ #0] GOTO 100
( <- keyword.conditional)
(      ^ keyword.operator)
(             ^ keyword.control)
(                  ^ label)
END1
( <- keyword.repeat)
(  ^ constant.numeric)
/2 G01 X#5 ,R1.5;
( <- punctuation.special)
(      ^ variable.parameter)
(       ^ variable)
(          ^ variable.parameter)
(               ^ punctuation.delimiter)
DPRNT[X#5041[44]]
( <- function.builtin)
(    ^ string)
%
( <- punctuation.special)
% PART 42
( <- comment)
:1001
( <- keyword.function)
(^ label)
<GAUGE_1>
( <- function)
#3000 = 1 (TOOL BROKEN)
(         ^ comment)
