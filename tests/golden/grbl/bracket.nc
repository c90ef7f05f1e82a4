(bracket)
G40 G49 G17 G90 G94 G21
(outline with a round ear)
(Insert tool 3: 6 mm end mill - 3 flute carbide)
M0
S3000 M3
G0 Z10
X0 Y0
G1 Z-3 F100
X60 F400
G3 X70 Y10 I0 J10
G1 Y40
G3 X60 Y50 I0 J10
G1 X0
Y0
G0 Z10
(bore outline, full circle)
X38 Y25
G1 Z-3 F100
G2 X38 Y25 I-8 J0 F400
G0 Z10
M5
M2
