%
O1000;
DO 1;
IF [#1 GT 3] GOTO 10;
#1 = #1 + 1;
END 1;
N10 M30;
%
