%
O2005
#1 = -3.
#2 = 2.
IF[ABS[#1]GEABS[#2]]GOTO10
#3 = 1.
N10 M30
%
