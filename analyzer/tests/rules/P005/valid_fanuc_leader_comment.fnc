(comment before the tape start is leader)
%
O1000 (TITLE)
G0 X0 Y0
M30
%
