0 BEGIN PGM bracket MM
1 ; outline with a round ear
2 ; T3 6 mm end mill - 3 flute carbide
3 TOOL CALL 3 Z S3000
4 M3
5 L Z+10 R0 FMAX
6 L X+0 Y+0 R0 FMAX
7 L Z-3 F100
8 L X+60 F400
9 CC X+60 Y+10
10 C X+70 Y+10 DR+
11 L Y+40
12 CC X+70 Y+50
13 C X+60 Y+50 DR+
14 L X+0
15 L Y+0
16 L Z+10 R0 FMAX
17 ; bore outline, full circle
18 L X+38 Y+25 R0 FMAX
19 L Z-3 F100
20 CC X+30 Y+25
21 C X+38 Y+25 DR- F400
22 L Z+10 R0 FMAX
23 M5
24 M30
25 END PGM bracket MM
