%
O1000 (shaft-control)
N10 G18 G40 G80 G98 G21
(finish the outside with G42: chamfer, D30, R5 fillet, D40)
N15 G99
(T3 0.8 mm turning tool - finishing insert, R0.4 nose)
N20 T0303
N25 G50 S3000
N30 G97 S1200 M3
N35 M8
N40 G0 Z20.000
N45 X24.000
N50 Z1.000
(G42 nose comp: offset 03 R0.4 nose radius, Fanuc tip T3: tip at -X -Z of the nose centre)
N55 G42 G1 Z0.000 F0.1000
N60 X28.000
N65 X30.000 Z-1.000
N70 Z-20.000
N75 G2 X40.000 Z-25.000 I5.000 K0.000
N80 G1 Z-39.600
N85 G40 X40.707 Z-39.646
N90 G0 X44.000
N95 Z20.000
N100 M9
N105 M5
N110 M30
%
