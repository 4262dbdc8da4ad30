\ robot_motion.fs - motion and position words against fbrlsim (run by robot_e2e).
\ Every robot word's effect is checked twice: the exact command fbrlsim executed (LOG:)
\ and where the arm went (read back with ARM-HERE, or raw with the test word WORLD@).

: COMP ( loc n -- ) ( F: -- r ) FLOATS + F@ ;
: ~= ( F: a b -- ) ( -- flag ) F- FABS 2E-3 F< ;
: AT? ( loc -- flag ) ( F: x y z -- ) \ loc's x y z within 0.002 in
   >R  R@ 2 COMP ~=  R@ 1 COMP ~= AND  R> 0 COMP ~= AND ;
FVARIABLE WX  FVARIABLE WY  FVARIABLE WZ  FVARIABLE WP
: WORLD ( -- ) WORLD@ FDROP WP F! FDROP WZ F! WY F! WX F! ;

LOG-SKIP
T{ HOME -> }T                LOG: HOME
T{ READY -> }T               LOG: READY
T{ WORLD WX F@ 12E0 ~= WZ F@ 20E0 ~= WP F@ 0E0 ~= -> TRUE TRUE TRUE }T
T{ 50 SPEED -> }T            LOG: SPEED 50

CREATE-LOC P1  12E0 3E0 8E0 0E0 -90E0 0E0 P1 DEFINE-LOC
CREATE-LOC P2
CREATE-LOC HERE1

\ MOV: a scratch point, then MOVE; ARM-HERE waits for the motion and reads it back
T{ P1 MOV -> }T  LOG: POINT FBRLT1,12,3,8,0,-90,0
                 LOG: MOVE FBRLT1
T{ HERE1 ARM-HERE -> }T      LOG: FINISH
                             LOG: W2
T{ 12E0 3E0 8E0 HERE1 AT? -> TRUE }T
T{ HERE1 4 COMP -90E0 ~= -> TRUE }T

\ MOV-STRT: straight line
12E0 -3E0 8E0 0E0 -90E0 0E0 P2 DEFINE-LOC
T{ P2 MOV-STRT -> }T  LOG: POINT FBRLT2,12,-3,8,0,-90,0
                      LOG: MOVE FBRLT2,S
T{ HERE1 ARM-HERE  12E0 -3E0 8E0 HERE1 AT? -> TRUE }T  LOG-SKIP

\ APPROACH / APPROACH-STRT: distance back along the tool axis (tool down: above)
T{ P1 2E0 APPROACH -> }T  LOG: POINT FBRLT1,12,3,8,0,-90,0
                          LOG: APPRO FBRLT1,2
T{ HERE1 ARM-HERE  12E0 3E0 10E0 HERE1 AT? -> TRUE }T  LOG-SKIP
T{ P2 1.5E0 APPROACH-STRT -> }T  LOG: POINT FBRLT2,12,-3,8,0,-90,0
                                 LOG: APPRO FBRLT2,1.5,S
T{ HERE1 ARM-HERE  12E0 -3E0 9.5E0 HERE1 AT? -> TRUE }T  LOG-SKIP

\ DEPART / DEPART-STRT
T{ 1E0 DEPART -> }T        LOG: DEPART 1
T{ HERE1 ARM-HERE  12E0 -3E0 10.5E0 HERE1 AT? -> TRUE }T  LOG-SKIP
T{ 0.5E0 DEPART-STRT -> }T  LOG: DEPART 0.5,S
T{ HERE1 ARM-HERE  12E0 -3E0 11E0 HERE1 AT? -> TRUE }T  LOG-SKIP

\ JOG: straight-line offset
T{ 1E0 0.5E0 -2E0 JOG -> }T  LOG: JOG 1,0.5,-2
T{ HERE1 ARM-HERE  13E0 -2.5E0 9E0 HERE1 AT? -> TRUE }T  LOG-SKIP

\ FINISH, ACTUAL into a host location (the actual position, no FINISH sent)
T{ FINISH -> }T  LOG: FINISH
CREATE-LOC ACT1
T{ ACT1 ACTUAL -> }T  LOG: W2
T{ 13E0 -2.5E0 9E0 ACT1 AT? -> TRUE }T
\ ACTUAL with a name that is no FBRL word: the controller's own location
T{ ACTUAL CTLOC1 -> }T  LOG: ACTUAL CTLOC1

\ joints: READY, then JOINT (degrees), MOTOR (pulses: 200 per degree on axes 1-3)
: DEG>RAD ( F: d -- r ) PI F* 180E0 F/ ;
T{ READY -> }T  LOG: READY
T{ 1 30 JOINT -> }T  LOG: JOINT 1,30
T{ WORLD WX F@ 30E0 DEG>RAD FCOS 12E0 F* ~= WY F@ 30E0 DEG>RAD FSIN 12E0 F* ~= -> TRUE TRUE }T  LOG-SKIP
T{ 1 -2000 MOTOR -> }T  LOG: MOTOR 1,-2000
T{ WORLD WX F@ 20E0 DEG>RAD FCOS 12E0 F* ~= WY F@ 20E0 DEG>RAD FSIN 12E0 F* ~= -> TRUE TRUE }T  LOG-SKIP

\ MA / MI: joint angles in radians
T{ 0E0 90E0 DEG>RAD -90E0 DEG>RAD 0E0 0E0 MA -> }T
LOG: MA 0,1.5708,-1.5708,0,0
T{ WORLD WX F@ 12E0 ~= WY F@ 0E0 ~= WZ F@ 20E0 ~= -> TRUE TRUE TRUE }T  LOG-SKIP
T{ 10E0 DEG>RAD 0E0 0E0 0E0 0E0 MI -> }T  LOG: MI 0.1745,0,0,0,0
T{ WORLD WY F@ 10E0 DEG>RAD FSIN 12E0 F* ~= -> TRUE }T  LOG-SKIP

\ ALIGNTOOL: pitch to the nearest of -90 0 90 (tool 30 deg down -> 0)
T{ READY -> }T  LOG: READY
T{ 4 -30 JOINT -> }T  LOG: JOINT 4,-30
T{ ALIGNTOOL -> }T  LOG: ALIGN
T{ WORLD WP F@ 0E0 ~= -> TRUE }T  LOG-SKIP

\ HALT stops a motion where it is (a long slow move, halted at once)
T{ 5 SPEED -> }T  LOG: SPEED 5
T{ 1 -150 JOINT -> }T  LOG: JOINT 1,-150
T{ HALT -> }T  LOG: HALT
\ stopped on the way: moved (y < 0) but far from the end (x = 12 cos 150 = -10.39)
T{ WORLD WY F@ F0< WX F@ -10E0 F> -> TRUE TRUE }T
T{ 100 SPEED READY -> }T  LOG: SPEED 100
                          LOG: READY

\ errors from the controller become exceptions with its code (RAPL-ERROR keeps it)
CREATE-LOC FAR  40E0 0E0 0E0 0E0 -90E0 0E0 FAR DEFINE-LOC
T{ FAR ' MOV CATCH NIP -> -321 }T  LOG-SKIP
T{ RAPL-ERROR -> 29 }T
T{ 6 10 ' JOINT CATCH NIP NIP -> -24 }T
T{ 0 ' SPEED CATCH NIP -> -24 }T
