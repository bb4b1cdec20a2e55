%
O8100 (SET WORK OFFSET FROM A PROBED EDGE)
// the probe settings live in a shared macro
G65 "PROBESET"
#1 = @120 // probe feed
IF [#1 != #0]
  G31 X10. F#1
END_IF
M99
%
