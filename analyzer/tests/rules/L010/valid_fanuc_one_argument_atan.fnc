%
O1000 (THE 30I HAS A ONE-ARGUMENT ARC TANGENT)
#1 = 3.
#2 = ATAN[2 * [#1 - 1.] / [#1 + 1.]]
#3 = ATAN[#1]/[4.]
#4 = ATAN[#1, 4.]
M30
%
