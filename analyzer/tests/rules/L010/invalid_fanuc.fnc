%
O1000;
IF [#1 EQ 1] X10.;
WHILE [#1 LT 3];
M30;
%
