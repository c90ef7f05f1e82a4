%
O1000 (shaft-stops)
N10 G18 G40 G80 G98 G21
(centre drill)
(T1 4 mm centre drill - A4 centre drill)
N15 T0101
N20 G50 S3000
N25 G97 S1500 M3
N30 M8
N35 G0 Z20.000
N40 X0.000
N45 Z5.000
N50 Z2.000
N55 G1 Z-4.000 F60
N60 G0 Z5.000
N65 Z20.000
(optional stop)
N70 M9
N75 M5
N80 M1 (Check the centre hole)
(centre drill again, a little deeper)
N85 G97 S1500 M3
N90 G4 P1000
N95 M8
N100 G0 Z20.000
N105 X0.000
N110 Z5.000
N115 Z2.000
N120 G1 Z-4.500
N125 G0 Z5.000
N130 Z20.000
N135 M9
N140 M5
(tap drill 6.8, 20 deep)
N145 G99
(T2 6.8 mm drill - tap drill M8)
N150 T0202
N155 G97 S900 M3
N160 M8
N165 G0 Z20.000
N170 X0.000
N175 Z5.000
N180 Z2.000
N185 G74 R1.000
N190 G74 Z-20.000 Q5000 F0.1000
N195 G0 Z5.000
N200 G80
N205 G0 Z20.000
(let the chips settle)
N210 G4 P1000
N215 M9
N220 M5
(tap M8 x 1.25)
N225 G98
(T4 8 mm tap - M8 right-hand tap)
N230 T0404
N235 G97 S200 M3
N240 G0 Z20.000
N245 X0.000
N250 Z5.000
(tap M8 x 1.25: machine fanuc-lathe cannot tap; made by hand at the stop after this operation)
(Tap with tool 4, 8 mm tap - M8 right-hand tap, pitch 1.25 mm, from Z0 to Z-15)
(hole 1: X0)
N255 Z20.000
N260 M5
N265 M0 (Tap by hand with tool 4 at X0, 1 hole)
N270 M30
%
