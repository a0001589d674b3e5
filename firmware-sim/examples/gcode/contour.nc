(A milled contour: a plate outline of lines, arcs in both forms and a Bezier, corners)
(blended within G64 P; a helical entry into a circular pocket; a slot cut with exact)
(stops under G61 and a dwell at its end; an incremental G91 pass. Units mm.)
(Play it with: strak-sim gcode contour.nc)
G21 G90 G17 G94
T1 M6 (6 mm end mill)
M3 S12000
G0 Z5
G0 X0 Y0
G64 P0.02
G1 Z-1 F300
G1 X40 F1200
G3 X50 Y10 R10
G1 Y30
G2 X40 Y40 I-10 J0
G1 X20
G5 I-5 J0 P5 Q10 X0 Y20
G1 Y0
G1 Z2 F600
(a helical entry into a 10 mm circle about X25 Y20)
G0 X30 Y20
G1 Z0 F600
G2 X30 Y20 Z-1.5 I-5 J0 F800
G2 X30 Y20 I-5 J0
G1 Z2 F600
(a slot with exact stops and a dwell at its end)
G61
G0 X10 Y50
G1 Z-0.5 F300
G1 X40 F900
G4 P0.5
G1 Y52
G1 X10
G64
(an incremental pass along the top edge)
G91
G1 Y3 F1200
G1 X30
G1 Y-3
G90
G0 Z5
M5
G0 X0 Y0
M30
