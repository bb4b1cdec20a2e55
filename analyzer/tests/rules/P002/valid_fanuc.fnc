%
O1000;
#1 = 0;
WHILE [#1 LT 3] DO 1;
#2 = 0;
WHILE [#2 LT 3] DO 2;
#2 = #2 + 1;
END 2;
#1 = #1 + 1;
END 1;
WHILE [#1 GT 0] DO 1;
#1 = #1 - 1;
END 1;
M30;
%
