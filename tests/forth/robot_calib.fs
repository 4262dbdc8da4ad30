\ robot_calib.fs - the end-to-end calibration check (run by robot_e2e against fbrlsim).
\ A work block with a 4 x 4 rack of tubes is taught where it first stood; then it is moved
\ by a known rigid motion (turned 25 degrees about z, tilted 2 degrees about x, shifted).
\ Its three calibration points are taught again by moving the emulated arm to where they
\ now physically are and reading its position back (GET-CAL-POINTS). After CALIBRATE and
\ MAP-ON every rack position, defined on the original block, is sent to the arm; where
\ the arm went (W2 WORLD line) must lie within 0.002 in of where that position now
\ physically is, and ARM-HERE must give back the original-frame location.

: COMP ( loc n -- ) ( F: -- r ) FLOATS + F@ ;
: DEG>RAD ( F: d -- r ) PI F* 180E0 F/ ;
: NEAR? ( loc -- flag ) ( F: x y z -- ) \ x y z within 0.002 in of loc's
   >R  R@ 2 COMP F- FABS 2E-3 F<  R@ 1 COMP F- FABS 2E-3 F< AND  R> 0 COMP F- FABS 2E-3 F< AND ;

\ ---- the known rigid motion: p' = Rz(25) Rx(2) p + (1.2, 2.0, 0.4) ----
FVARIABLE CT  FVARIABLE ST  FVARIABLE CA  FVARIABLE SA
25E0 DEG>RAD FDUP FCOS CT F!  FSIN ST F!
2E0 DEG>RAD FDUP FCOS CA F!  FSIN SA F!
FVARIABLE X0  FVARIABLE Y0  FVARIABLE Z0
: PHYS ( src dst -- ) \ dst := where src's point is on the moved block (tool straight down)
   SWAP DUP 0 COMP X0 F!  DUP 1 COMP Y0 F!  2 COMP Z0 F!
   CA F@ Y0 F@ F*  SA F@ Z0 F@ F* F-   SA F@ Y0 F@ F*  CA F@ Z0 F@ F* F+   Z0 F!  Y0 F!
   CT F@ X0 F@ F*  ST F@ Y0 F@ F* F-   ST F@ X0 F@ F*  CT F@ Y0 F@ F* F+   Y0 F!  X0 F!
   X0 F@ 1.2E0 F+  Y0 F@ 2.0E0 F+  Z0 F@ 0.4E0 F+  0E0 -90E0 0E0  DEFINE-LOC ;

LOG-SKIP
HOME READY 100 SPEED

\ ---- the block where it first stood: calibration points and the rack ----
CREATE-LOC PO1  10E0 -2E0 6E0 0E0 -90E0 0E0 PO1 DEFINE-LOC   \ origin
CREATE-LOC PO2  14E0 -2E0 6E0 0E0 -90E0 0E0 PO2 DEFINE-LOC   \ on the block's x axis
CREATE-LOC PO3  10E0  2E0 6E0 0E0 -90E0 0E0 PO3 DEFINE-LOC   \ in its plane
CREATE-LOC RB   10.5E0 -1.5E0 6E0 0E0 -90E0 0E0 RB DEFINE-LOC
RB 0.75E0 0.75E0 0E0 RECTMAT RACK

CREATE-CAL CAL-O   CREATE-CAL CAL-R   CREATE-CAL-STRU BLOCK
CREATE-LOC C1  CREATE-LOC C2  CREATE-LOC C3

\ teach the original block's points with the arm (mapping off): the lines after
\ GET-CAL-POINTS move the arm; each empty line takes the point
CAL-O GET-CAL-POINTS
PO1 MOV

PO2 MOV

PO3 MOV

T{ CAL-O 1 C1 GET-CAL  10E0 -2E0 6E0 C1 NEAR? -> TRUE }T
T{ CAL-O 2 C2 GET-CAL  14E0 -2E0 6E0 C2 NEAR? -> TRUE }T
T{ CAL-O 3 C3 GET-CAL  10E0  2E0 6E0 C3 NEAR? -> TRUE }T

\ ---- the block is moved; its points are now here ----
CREATE-LOC PR1  PO1 PR1 PHYS
CREATE-LOC PR2  PO2 PR2 PHYS
CREATE-LOC PR3  PO3 PR3 PHYS

\ teach them again: the arm goes to each (several moves, as a technician would jog it)
CAL-R GET-CAL-POINTS
READY
PR1 MOV

JOG 0 0 1
PR2 MOV

PR3 MOV

T{ CAL-R 1 C1 GET-CAL  PR1 0 COMP PR1 1 COMP PR1 2 COMP C1 NEAR? -> TRUE }T
T{ CAL-R 2 C2 GET-CAL  PR2 0 COMP PR2 1 COMP PR2 2 COMP C2 NEAR? -> TRUE }T
T{ CAL-R 3 C3 GET-CAL  PR3 0 COMP PR3 1 COMP PR3 2 COMP C3 NEAR? -> TRUE }T

\ ---- calibrate and map ----
CAL-R CAL-O BLOCK CALIBRATE
BLOCK WITH-CAL MAP-ON

CREATE-LOC TUBE  CREATE-LOC TRUEPOS  CREATE-LOC H
FVARIABLE WORST  0E0 WORST F!
: ERR ( loc -- ) ( F: x y z -- ) \ keep the largest distance seen
   >R  R@ 2 COMP F- Z0 F!  R@ 1 COMP F- Y0 F!  R> 0 COMP F- X0 F!
   X0 F@ FDUP F*  Y0 F@ FDUP F* F+  Z0 F@ FDUP F* F+  FSQRT  WORST F@ FMAX WORST F! ;
VARIABLE BAD  0 BAD !
FVARIABLE AX  FVARIABLE AY  FVARIABLE AZ
: ARM-XYZ ( F: -- x y z ) AX F@ AY F@ AZ F@ ;
: CHECK-TUBE ( i j -- )
   0 TUBE RACK  TUBE MOV  TUBE TRUEPOS PHYS
   WORLD@ FDROP FDROP FDROP  AZ F!  AY F!  AX F!
   ARM-XYZ TRUEPOS ERR  ARM-XYZ TRUEPOS NEAR? 0= IF 1 BAD +! THEN
   H ARM-HERE  TUBE 0 COMP TUBE 1 COMP TUBE 2 COMP H NEAR? 0= IF 1 BAD +! THEN ;
: ALL-TUBES 4 0 DO 4 0 DO J I CHECK-TUBE LOOP LOOP ;
T{ ALL-TUBES BAD @ -> 0 }T
WORST F@ F. .( in: worst distance between the arm and a moved rack position) CR
T{ WORST F@ 2E-3 F< -> TRUE }T

\ the controller saw mapped coordinates: the last tube (3,3) at 12.75 0.75 6 went elsewhere
LOG-SKIP
T{ 3 3 0 TUBE RACK TUBE MOV -> }T
LOG: POINT FBRLT?,*
LOG: MOVE FBRLT?
T{ LOG-COUNT" POINT FBRLT1,12.75,0.75,6,0,-90,0" -> 0 }T
T{ LOG-COUNT" POINT FBRLT2,12.75,0.75,6,0,-90,0" -> 0 }T

\ every outgoing location is mapped: RAPL-POINT and SEND-LOC too
T{ 1 2 0 TUBE RACK  TUBE TRUEPOS PHYS -> }T
T{ RAPL-POINT CLM TUBE -> }T  LOG-SKIP
RAPL MOVE CLM
T{ WORLD@ FDROP FDROP FDROP TRUEPOS NEAR? -> TRUE }T
T{ 2 1 0 TUBE RACK  TUBE TRUEPOS PHYS -> }T
T{ 50 SEND-COM S" CLN" SEND-TEXT SEND-COMMA TUBE SEND-LOC SEND-CR -> }T  LOG-SKIP
RAPL MOVE CLN
T{ WORLD@ FDROP FDROP FDROP TRUEPOS NEAR? -> TRUE }T
\ ACTUAL reads back in the original frame too
T{ FINISH H ACTUAL  TUBE 0 COMP TUBE 1 COMP TUBE 2 COMP H NEAR? -> TRUE }T

\ with MAP-OFF the same location goes where it says
MAP-OFF
T{ 3 3 0 TUBE RACK TUBE MOV WORLD@ FDROP FDROP FDROP TUBE NEAR? -> TRUE }T
T{ 12.75E0 0.75E0 6E0 TUBE NEAR? -> TRUE }T

\ a GET-CAL-POINTS session from the console (the text source has no more lines)
CREATE-CAL CAL-K
S" PO3 MOV||PO2 MOV||PO1 MOV||" KEYS!
T{ S" CAL-K GET-CAL-POINTS" EVALUATE -> }T
T{ CAL-K 1 C1 GET-CAL  10E0  2E0 6E0 C1 NEAR? -> TRUE }T
T{ CAL-K 3 C3 GET-CAL  10E0 -2E0 6E0 C3 NEAR? -> TRUE }T
\ input that ends too early: the calibration is left as it was
S" PO1 MOV||" KEYS!
T{ S" CAL-K GET-CAL-POINTS" ' EVALUATE CATCH NIP NIP -> -24 }T
T{ CAL-K 1 C1 GET-CAL  10E0  2E0 6E0 C1 NEAR? -> TRUE }T
T{ PO1 ' GET-CAL-POINTS CATCH NIP -> -12 }T
\ not inside its own lines; afterwards it works again
S" CAL-K GET-CAL-POINTS||" KEYS!
T{ S" CAL-K GET-CAL-POINTS" ' EVALUATE CATCH NIP NIP -> -24 }T
S" PO1 MOV||PO2 MOV||PO3 MOV||" KEYS!
T{ S" CAL-K GET-CAL-POINTS" EVALUATE CAL-K 1 C1 GET-CAL  10E0 -2E0 6E0 C1 NEAR? -> TRUE }T

\ METRIC-ON: lengths typed in cm, the wire in inches
METRIC-ON
T{ JOG 2.54 0 -5.08 -> }T  LOG-SKIP
T{ 2.54E0 DEPART -> }T  LOG: DEPART 1
METRIC-OFF
