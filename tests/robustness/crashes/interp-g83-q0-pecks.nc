(partscope: dialect=servoworks)
(fuzz: interpret target, out of memory: G83 with Q0. pecked 100000 times per hole)
G90 G17 G21 G40 G49 G80
T01 M6
S2000 M3
G0 X0. Y0. Z10.
G98 G83 X0. Y0. Z-10.55 R2. Q2. F200.
X7.5 Q0.
X15. Y7.5
X15. Y15.
X30. Y15.
G80
M30
