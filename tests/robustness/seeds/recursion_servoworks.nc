%
(partscope: dialect=servoworks)
(unbounded recursion through G65)
G90 G21
G65 P9002 L5
M30
O9002
G01 X1.0 F100.0
G65 P9002 L5
M99
%
