\ glossary_cal.fs - calibration and mapping words (thesis appendix II).
\ Run by tests/unit/test_glossary.c with the glossary installed.
DECIMAL
FVARIABLE INF-BITS  HEX 7FF0000000000000 DECIMAL INF-BITS !
: +INF ( F: -- inf ) INF-BITS F@ ;  \ F/ refuses to divide by zero, so build it from its bits
: ~0 ( F: r -- r' ) FDUP FABS 1E-9 F< IF FDROP 0E0 THEN ;
: GETXYZ ( loc -- ) ( F: -- x y z ) DUP GETX ~0 DUP GETY ~0 GETZ ~0 ;
: GETALL ( loc -- ) ( F: -- x y z o a t ) DUP GETXYZ DUP GETO ~0 DUP GETA ~0 GETT ~0 ;
: XYZ ( loc -- ) ( F: x y z -- ) >R 0E0 -90E0 0E0 R> DEFINE-LOC ;   \ tool down

\ II-1 calibration structures
T{ CREATE-CAL C1 CREATE-CAL R1 CREATE-CAL-STRU S1 CREATE-CAL-STRU S2 -> }T
T{ C1 2 CAL-ADDR C1 1 CAL-ADDR - C1 3 CAL-ADDR C1 2 CAL-ADDR - -> 48 48 }T
T{ C1 1 CAL-ADDR GETX C1 3 CAL-ADDR GETT -> 0E0 0E0 }T       \ slots start zeroed
CREATE-LOC L1  CREATE-LOC L2  CREATE-LOC L3
T{ 1E0 2E0 3E0 4E0 5E0 6E0 L1 DEFINE-LOC C1 2 L1 SET-CAL C1 2 CAL-ADDR GETALL -> 1E0 2E0 3E0 4E0 5E0 6E0 }T
T{ C1 2 L2 GET-CAL L2 GETALL -> 1E0 2E0 3E0 4E0 5E0 6E0 }T
T{ 9E0 C1 2 CAL-ADDR SETZ C1 2 L2 GET-CAL L2 GETZ -> 9E0 }T
T{ C1 1 C1 2 CAL-ADDR 16 - SET-CAL C1 1 CAL-ADDR GETT C1 2 CAL-ADDR GETY -> 4E0 2E0 }T   \ overlap
T{ C1 2 C1 2 CAL-ADDR 8 + GET-CAL C1 2 CAL-ADDR GETY -> 1E0 }T
T{ C1 0 ' CAL-ADDR CATCH NIP NIP -> -302 }T                 \ slots are 1 2 3
T{ C1 4 L1 ' SET-CAL CATCH NIP NIP NIP -> -302 }T
T{ L1 1 ' CAL-ADDR CATCH NIP NIP -> -12 }T                  \ a location is not a calibration
T{ S1 1 L1 ' GET-CAL CATCH NIP NIP NIP -> -12 }T            \ nor is a structure
T{ 0 1 ' CAL-ADDR CATCH NIP NIP -> -12 }T
T{ C1 1 0 ' SET-CAL CATCH NIP NIP NIP -> -9 }T

\ a new structure is the identity (block not moved), entries row by row of [r | t]
: STRU ( s -- ) ( F: -- r11 r12 r13 tx r21 r22 r23 ty r31 r32 r33 tz ) 13 1 DO DUP I CAL-STRU@ ~0 LOOP DROP ;
T{ S1 STRU -> 1E0 0E0 0E0 0E0 0E0 1E0 0E0 0E0 0E0 0E0 1E0 0E0 }T
T{ NUM-CAL-CELLS -> 12 }T
T{ S1 0 ' CAL-STRU@ CATCH NIP NIP -> -302 }T
T{ S1 13 ' CAL-STRU@ CATCH NIP NIP -> -302 }T
T{ C1 1 ' CAL-STRU@ CATCH NIP NIP -> -12 }T
T{ 7.5E0 S2 4 CAL-STRU! S2 4 CAL-STRU@ -> 7.5E0 }T           \ t x
T{ 0E0 S2 4 CAL-STRU! -> }T

\ II-2 planar helpers
T{ 0E0 0E0 -1E0 -1E0 ANG-FROM-ORIGIN PI -0.75E0 F* F- ~0 -> 0E0 }T   \ third quadrant, not atan's
T{ 1E0 1E0 1E0 3E0 ANG-FROM-ORIGIN -> PI 2E0 F/ }T
T{ 2E0 0E0 5E0 0E0 ANG-FROM-ORIGIN -> 0E0 }T
T{ 1E0 1E0 1E0 1E0 ' ANG-FROM-ORIGIN CATCH FDROP FDROP FDROP FDROP -> -307 }T
T{ 1E0 0E0 PI 2E0 F/ ROTATE FSWAP ~0 FSWAP -> 0E0 1E0 }T
T{ 3E0 4E0 PI ROTATE ~0 FSWAP ~0 FSWAP -> -3E0 -4E0 }T

\ CALIBRATE: block turned 90 degrees about z and moved by (10, 5, 0).
\ Original points P1 (0,0,0) P2 (1,0,0) P3 (0,1,0) -> moved (10,5,0) (10,6,0) (9,5,0).
: TEACH ( cal slot -- ) ( F: x y z -- ) L3 XYZ L3 SET-CAL ;
T{ 0E0 0E0 0E0 C1 1 TEACH 1E0 0E0 0E0 C1 2 TEACH 0E0 1E0 0E0 C1 3 TEACH -> }T
T{ 10E0 5E0 0E0 R1 1 TEACH 10E0 6E0 0E0 R1 2 TEACH 9E0 5E0 0E0 R1 3 TEACH -> }T
T{ R1 C1 S1 CALIBRATE -> }T
\ p_moved = Rz(90) p + (10, 5, 0):  [ 0 -1 0 10 ; 1 0 0 5 ; 0 0 1 0 ]
T{ S1 STRU -> 0E0 -1E0 0E0 10E0 1E0 0E0 0E0 5E0 0E0 0E0 1E0 0E0 }T
\ (MAP) maps for a 5-axis arm (docs/calibration.md): yaw becomes the waist direction at the
\ mapped place; the grip's heading (waist - roll + 90, tool down) turns with the block.
\ At (2, 3) the waist is 56.3099, the grip heads 56.3099 - 10 + 90; turned 90, at (7, 7)
\ the waist is 45, so roll = 45 + 90 - (56.3099... - 10 + 180).
: W0 ( F: -- deg ) 3E0 2E0 FATAN2 180E0 F* PI F/ ;
T{ 2E0 3E0 1E0 30E0 -90E0 10E0 L1 DEFINE-LOC S1 L1 (MAP) L1 GETALL
   -> 7E0 7E0 1E0 45E0 -90E0 45E0 90E0 F+ W0 10E0 F- 180E0 F+ F- }T
T{ S1 L1 UNMAP L1 GETALL -> 2E0 3E0 1E0 W0 -90E0 10E0 }T      \ round trip (yaw: the waist)
\ tilted 45 degrees, the turned tool axis would lie 43.9 degrees across the arm: refused
T{ 2E0 3E0 1E0 30E0 -45E0 10E0 L1 DEFINE-LOC S1 L1 ' (MAP) CATCH NIP NIP L1 GETA -> -302 -45E0 }T
T{ 0E0 0E0 0E0 0E0 -90E0 0E0 L1 DEFINE-LOC S1 L1 (MAP) L1 GETXYZ -> 10E0 5E0 0E0 }T  \ P1 -> R1

\ A block tilted up 90 degrees about x: y goes to z. Same original points, taught on S2.
T{ 0E0 0E0 0E0 R1 1 TEACH 1E0 0E0 0E0 R1 2 TEACH 0E0 0E0 1E0 R1 3 TEACH R1 C1 S2 CALIBRATE -> }T
T{ S2 STRU -> 1E0 0E0 0E0 0E0 0E0 0E0 -1E0 0E0 0E0 1E0 0E0 0E0 }T
T{ 0E0 2E0 0E0 L1 XYZ S2 L1 (MAP) L1 GETXYZ -> 0E0 0E0 2E0 }T
T{ S2 L1 UNMAP L1 GETXYZ -> 0E0 2E0 0E0 }T

\ A general motion: map then unmap returns every component
\ (turned and shifted, not tilted: a 5-axis arm follows it exactly; tool down)
T{ 1E0 1E0 1E0 R1 1 TEACH 1.6E0 1.8E0 1E0 R1 2 TEACH 0.2E0 1.6E0 1E0 R1 3 TEACH R1 C1 S2 CALIBRATE -> }T
T{ 3.5E0 -2E0 4E0 -2E0 3.5E0 FATAN2 180E0 F* PI F/ -90E0 33E0 L2 DEFINE-LOC L1 L2 SET-LOC
   S2 L1 (MAP) S2 L1 UNMAP L1 GETALL -> L2 GETALL }T
T{ S2 L1 (MAP) L1 GETX L2 GETX F- FABS 0.1E0 F> -> TRUE }T         \ mapping moved it

\ degenerate calibrations are refused and leave the structure unchanged
T{ S1 4 CAL-STRU@ -> 10E0 }T
T{ 5E0 0E0 0E0 C1 3 TEACH R1 C1 S1 ' CALIBRATE CATCH NIP NIP NIP -> -307 }T   \ collinear
T{ 0E0 1E0 0E0 C1 3 TEACH 1E0 1E0 1E0 R1 2 TEACH R1 C1 S1 ' CALIBRATE CATCH NIP NIP NIP -> -307 }T \ coincident
T{ S1 4 CAL-STRU@ -> 10E0 }T
T{ C1 C1 C1 ' CALIBRATE CATCH NIP NIP NIP -> -12 }T        \ cal-stru must be a structure
T{ S1 S1 S1 ' CALIBRATE CATCH NIP NIP NIP -> -12 }T

\ (MAP) / UNMAP input checks
T{ C1 L1 ' (MAP) CATCH NIP NIP -> -12 }T                    \ not a structure
T{ S1 0 ' UNMAP CATCH NIP NIP -> -9 }T                      \ not a location
T{ S1 L1 1+ ' (MAP) CATCH NIP NIP -> -23 }T

\ mapping switch
T{ MAPPING? -> FALSE }T
T{ ' MAP-ON CATCH -> -325 }T                                \ nothing selected yet
T{ MAPPING? -> FALSE }T
T{ L1 ' WITH-CAL CATCH NIP -> -12 }T
T{ S1 WITH-CAL MAP-ON MAPPING? -> TRUE }T
T{ MAP-OFF MAPPING? -> FALSE }T

\ CAL-STRU! can make a structure that is no rigid motion: mapping then refuses it
CREATE-CAL-STRU S3
T{ 2E0 S3 1 CAL-STRU! S3 L1 ' (MAP) CATCH NIP NIP -> -325 }T
T{ S3 WITH-CAL ' MAP-ON CATCH -> -325 }T
T{ +INF S3 1 ' CAL-STRU! CATCH NIP NIP FDROP -> -303 }T
T{ 1E0 S3 1 CAL-STRU! S3 L1 ' (MAP) CATCH -> 0 }T    \ rigid again
T{ S1 WITH-CAL -> }T

\ CALIBRATE-N: 5 point pairs related by the S1 motion, in ARRAYs of LOCATION cells
5 LOCATION ARRAY CPTS   5 LOCATION ARRAY RPTS
: PT ( i -- ) ( F: x y z -- ) CPTS XYZ ;
T{ 0E0 0E0 0E0 0 PT 4E0 0E0 0E0 1 PT 0E0 3E0 0E0 2 PT 4E0 3E0 1E0 3 PT 2E0 1E0 2E0 4 PT -> }T
: MOVED ( -- ) 5 0 DO I RPTS I CPTS SET-LOC S1 I RPTS (MAP) LOOP ;
T{ MOVED 5 0 CPTS 0 RPTS S2 CALIBRATE-N FDROP DROP S2 STRU -> S1 STRU }T
T{ 0.1E0 3 RPTS GETZ F+ 3 RPTS SETZ -> }T                  \ mistaught point 3
T{ 5 0 CPTS 0 RPTS S2 CALIBRATE-N 0.001E0 F> -> 3 TRUE }T
T{ 2 0 CPTS 0 RPTS S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -302 }T     \ n >= 3
T{ 5 0 CPTS 0 RPTS C1 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -12 }T
T{ 5 0 CPTS 1+ 0 RPTS S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -23 }T
T{ 5 0 0 RPTS S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -9 }T
5 LOCATION ARRAY LINE
: ONLINE ( -- ) 5 0 DO I S>F 0E0 0E0 I LINE XYZ LOOP ;
T{ S2 4 CAL-STRU@ ONLINE 5 0 LINE 0 RPTS S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP S2 4 CAL-STRU@ F= -> -307 TRUE }T
T{ 5 0 RPTS 0 LINE S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -307 }T
T{ -1 2 CPTS 8 + ! 5 0 CPTS 0 RPTS S2 ' CALIBRATE-N CATCH NIP NIP NIP NIP -> -12 }T
