(plate)
G17 G21 G90 G94
(spot six holes)
(Insert tool 1: 10 mm spot drill - spot drill 90 deg)
M0
S1500 M3
G0 Z10
X10 Y10
Z2
G1 Z-1.5 F80
G0 Z2
X50
G1 Z-1.5
G0 Z2
X90
G1 Z-1.5
G0 Z2
Y40
G1 Z-1.5
G0 Z2
X50
G1 Z-1.5
G0 Z2
X10
G1 Z-1.5
G0 Z2
Z10
M5
(drill through the 8 mm plate)
(Insert tool 2: 6 mm drill - HSS jobber)
M0
S1200 M3
G0 Z10
X10 Y10
Z5
Z1
G1 Z-9.803 F120
G0 Z5
X50
Z1
G1 Z-9.803
G0 Z5
X90
Z1
G1 Z-9.803
G0 Z5
Y40
Z1
G1 Z-9.803
G0 Z5
X50
Z1
G1 Z-9.803
G0 Z5
X10
Z1
G1 Z-9.803
G0 Z5
Z10
M5
M2
