\ glossary_loc.fs - location templates, matrices and metric conversion
\ (thesis appendix III and I-7). Run by tests/unit/test_glossary.c with the glossary installed.
DECIMAL
FVARIABLE INF-BITS  HEX 7FF0000000000000 DECIMAL INF-BITS !
: +INF ( F: -- inf ) INF-BITS F@ ;  \ F/ refuses to divide by zero, so build it from its bits
: ~0 ( F: r -- r' ) \ snap rounding noise to zero, so exact expectations can be written
   FDUP FABS 1E-9 F< IF FDROP 0E0 THEN ;
: GETALL ( loc -- ) ( F: -- x y z o a t )
   DUP GETX DUP GETY DUP GETZ DUP GETO DUP GETA GETT ;

\ III-1 location templates
T{ CREATE-LOC P1 CREATE-LOC P2 CREATE-LOC P3 -> }T
T{ P1 GETALL -> 0E0 0E0 0E0 0E0 0E0 0E0 }T                \ a new location is zeroed
T{ P2 P1 - ABS 48 < -> FALSE }T                             \ 48 bytes each
T{ P1 8 MOD -> 0 }T                                         \ aligned for floats
T{ 1.5E0 P1 SETX -2.25E0 P1 SETY 3E0 P1 SETZ -> }T
T{ 90E0 P1 SETO -45E0 P1 SETA 10E0 P1 SETT -> }T
T{ P1 GETALL -> 1.5E0 -2.25E0 3E0 90E0 -45E0 10E0 }T
T{ P1 F@ P1 FLOAT+ F@ P1 5 FLOATS + F@ -> 1.5E0 -2.25E0 10E0 }T   \ stored X Y Z O A T
T{ P2 P1 SET-LOC P2 GETALL -> 1.5E0 -2.25E0 3E0 90E0 -45E0 10E0 }T
T{ 7E0 P2 SETX P1 GETX -> 1.5E0 }T                          \ a copy, not an alias
T{ 1E0 2E0 3E0 4E0 5E0 6E0 P3 DEFINE-LOC P3 GETALL -> 1E0 2E0 3E0 4E0 5E0 6E0 }T
T{ P1 P3 SHIFTA P1 GETALL -> 2.5E0 -0.25E0 6E0 94E0 -40E0 16E0 }T
T{ P3 P3 SHIFTA P3 GETALL -> 2E0 4E0 6E0 8E0 10E0 12E0 }T
: SETINDEF ( loc -- ) 11E0 DUP SETX 22E0 DUP SETY 33E0 SETZ ;   \ compiled use
T{ P3 SETINDEF P3 GETX P3 GETY P3 GETZ -> 11E0 22E0 33E0 }T
2 LOCATION ARRAY OV                                         \ overlapping copies are exact
T{ 1E0 2E0 3E0 4E0 5E0 6E0 0 OV DEFINE-LOC 0 OV 8 + 0 OV SET-LOC 0 OV GETX 0 OV GETY 0 OV GETZ 1 OV GETX -> 1E0 1E0 2E0 6E0 }T
T{ 4 LOCATION ARRAY LOCS -> }T                              \ locations in an ARRAY
T{ 1E0 2E0 3E0 0E0 -90E0 0E0 2 LOCS DEFINE-LOC 2 LOCS GETZ 2 LOCS GETA -> 3E0 -90E0 }T

\ bad input: clear errors, nothing changed
T{ 0 ' GETX CATCH NIP -> -9 }T                              \ not in data space
T{ P1 1+ ' GETX CATCH NIP -> -23 }T                         \ misaligned
CREATE JUNK 64 ALLOT   JUNK 64 ERASE   -1 JUNK 8 + !       \ y = a NaN bit pattern
T{ JUNK ' GETX CATCH NIP -> -12 }T                          \ not a location
T{ P1 JUNK ' SET-LOC CATCH NIP NIP -> -12 }T
T{ P1 GETX -> 2.5E0 }T
T{ +INF P1 ' SETX CATCH NIP FDROP -> -303 }T          \ infinity refused
T{ P1 GETX -> 2.5E0 }T
T{ ' GETX CATCH -> -4 }T
T{ S" CREATE-LOC" ' EVALUATE CATCH NIP NIP -> -16 }T       \ name missing                                    \ empty stack
T{ P1 ' SETX CATCH NIP -> -45 }T                            \ empty float stack
T{ 1E308 1E308 1E308 0E0 0E0 0E0 P2 DEFINE-LOC P2 P2 ' SHIFTA CATCH NIP NIP -> -327 }T  \ overflow
T{ P2 GETX -> 1E308 }T

\ III-2 rectangular matrix: base + (i*dx, j*dy, k*dz), orientation of the base
T{ 1E0 2E0 3E0 30E0 -90E0 5E0 P1 DEFINE-LOC -> }T
T{ P1 0.75E0 -1.25E0 0.5E0 RECTMAT MAT -> }T
T{ 2 1 3 P2 MAT P2 GETALL -> 2.5E0 0.75E0 4.5E0 30E0 -90E0 5E0 }T
T{ 0 0 0 P2 MAT P2 GETALL -> P1 GETALL }T
T{ -1 -2 0 P2 MAT P2 GETX P2 GETY -> 0.25E0 4.5E0 }T         \ negative indices reach back
: MAT11 ( loc -- ) >R 1 1 1 R> MAT ;
T{ P2 MAT11 P2 GETX P2 GETY P2 GETZ -> 1.75E0 0.75E0 3.5E0 }T
T{ 9E0 P1 SETX 0 0 0 P2 MAT P2 GETX -> 1E0 }T               \ the base was copied at RECTMAT
T{ P1 1E0 1E0 1E0 AUTOMAT AM -> }T
T{ 1 2 3 P2 AM P2 GETX P2 GETY P2 GETZ -> 10E0 4E0 6E0 }T
T{ 1 2 3 0 ' MAT CATCH NIP NIP NIP NIP -> -9 }T
T{ 1 2 3 P2 1+ ' MAT CATCH NIP NIP NIP NIP -> -23 }T
T{ JUNK 1E0 1E0 1E0 ' RECTMAT CATCH NIP FDROP FDROP FDROP -> -12 }T   \ base not a location
T{ 1 2 3 P2 ' MAT CATCH -> 0 }T                              \ MAT still works

\ III-2 radial matrix: base (10, 0, 2): radius 10, angle 0
T{ 10E0 0E0 2E0 0E0 -90E0 0E0 P1 DEFINE-LOC -> }T
T{ P1 PI 2E0 F/ 1E0 0.5E0 RADMAT RM -> }T
T{ 0 0 0 P2 RM P2 GETALL -> 10E0 0E0 2E0 0E0 -90E0 0E0 }T     \ (0,0,0) is the base
T{ 1 1 2 P2 RM P2 GETX ~0 P2 GETY P2 GETZ P2 GETO -> 0E0 11E0 3E0 90E0 }T
T{ 0 2 0 P2 RM P2 GETX P2 GETY ~0 P2 GETO -> -10E0 0E0 180E0 }T
T{ -2 -1 -1 P2 RM P2 GETX ~0 P2 GETY P2 GETZ P2 GETO -> 0E0 -8E0 1.5E0 -90E0 }T
T{ -11 0 0 P2 ' RM CATCH NIP NIP NIP NIP -> -302 }T         \ radius through the centre
T{ 3E0 4E0 0E0 0E0 0E0 0E0 P3 DEFINE-LOC P3 0.1E0 1E0 0E0 RADMAT RM2 -> }T
T{ 5 0 0 P2 RM2 P2 GETX P2 GETY -> 6E0 8E0 }T                \ radius 5 -> 10 along (3,4)
T{ 0E0 0E0 1E0 0E0 0E0 0E0 P3 DEFINE-LOC P3 1E0 1E0 1E0 ' RADMAT CATCH NIP FDROP FDROP FDROP -> -302 }T

\ SHOW-AUTOMAT / SHOW-RADMAT take the execution token; anything else is refused
T{ ' MAT SHOW-AUTOMAT ' RM SHOW-RADMAT -> }T
T{ ' RM ' SHOW-AUTOMAT CATCH NIP -> -12 }T
T{ ' MAT ' SHOW-RADMAT CATCH NIP -> -12 }T
T{ P1 ' SHOW-AUTOMAT CATCH NIP -> -12 }T
T{ ' DUP ' SHOW-RADMAT CATCH NIP -> -12 }T

\ I-7 metric conversion: lengths in cm at the user side, inches stored; angles never convert
T{ METRIC? -> FALSE }T
T{ 2.54E0 CM->IN 1E0 IN->CM 3E0 METRIC-IN 3E0 METRIC-OUT -> 1E0 2.54E0 3E0 3E0 }T
T{ METRIC-ON METRIC? -> TRUE }T
T{ 2.54E0 METRIC-IN 1E0 METRIC-OUT -> 1E0 2.54E0 }T
T{ 25.4E0 P1 SETX 90E0 P1 SETO P1 GETX P1 GETO -> 25.4E0 90E0 }T
T{ 2.54E0 5.08E0 7.62E0 45E0 -90E0 0E0 P2 DEFINE-LOC -> }T
T{ P2 1.27E0 2.54E0 0E0 RECTMAT MMAT -> }T                  \ steps in cm: 0.5 1 0 in
T{ METRIC-OFF METRIC? -> FALSE }T
T{ P1 GETX P1 GETO -> 10E0 90E0 }T                           \ stored in inches
T{ P2 GETALL -> 1E0 2E0 3E0 45E0 -90E0 0E0 }T
T{ 2 2 0 P3 MMAT P3 GETX P3 GETY -> 2E0 4E0 }T
T{ METRIC-ON 2 2 0 P3 MMAT P3 GETX P3 GETY METRIC-OFF -> 5.08E0 10.16E0 }T
T{ +INF ' CM->IN CATCH FDROP -> -303 }T
T{ 1E308 ' IN->CM CATCH FDROP -> -327 }T
