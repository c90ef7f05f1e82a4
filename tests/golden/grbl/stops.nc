(stops)
G40 G49 G17 G90 G94 G21
(tap drill M8, first row)
(Insert tool 1: 6.8 mm drill - tap drill M8)
M0
S1200 M3
G0 Z20
X10 Y10
Z5
Z2
G1 Z-15 F120
G0 Z5
X30
Z2
G1 Z-15
G0 Z5
Z20
(optional stop)
M5
M0 (Check the depth of the first row)
(let the chips settle)
(chips settle)
G4 P1
(tap drill M8, second row)
S1200 M3
G4 P2
G0 Z20
X10 Y30
Z5
Z2
G1 Z-15 F120
G0 Z5
X30
Z2
G1 Z-15
G0 Z5
Z20
M5
(tap M8 x 1.25)
(Insert tool 7: 8 mm tap - M8 right-hand tap)
M0
S300 M3
G0 Z20
X10 Y10
Z5
(tap M8 x 1.25: machine grbl cannot tap; made by hand at the stop after this operation)
(Tap with tool 7, 8 mm tap - M8 right-hand tap, pitch 1.25 mm, from Z0 to Z-12)
(hole 1: X10 Y10)
(hole 2: X30 Y10)
(hole 3: X10 Y30)
(hole 4: X30 Y30)
Z20
X30 Y30
M5
M0 (Tap by hand with tool 7 at X10 Y10, X30 Y10, X10 Y30, X30 Y30, 4 holes)
(stop)
M0 (Turn the plate over and clamp it on the drilled face)
(centre hole from the other side)
(Insert tool 1: 6.8 mm drill - tap drill M8)
M0
S1200 M3
G0 Z20
X20 Y20
Z5
Z2
G1 Z-15
G0 Z5
Z20
M5
M2
