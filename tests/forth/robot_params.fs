\ robot_params.fs - the two ways to give a robot word its parameters (docs/robot.md):
\ on the stacks before the word (Forth style) or after the word on the line (the
\ thesis's style). The rule: when the stacks hold enough values for every parameter
\ they are used; otherwise all parameters are read from the input after the word.

: COMP ( loc n -- ) ( F: -- r ) FLOATS + F@ ;
: ~= ( F: a b -- ) ( -- flag ) F- FABS 2E-3 F< ;
: AT? ( loc -- flag ) ( F: x y z -- )
   >R  R@ 2 COMP ~=  R@ 1 COMP ~= AND  R> 0 COMP ~= AND ;

LOG-SKIP
HOME READY LOG-SKIP
CREATE-LOC P1  12E0 3E0 8E0 0E0 -90E0 0E0 P1 DEFINE-LOC
CREATE-LOC P2  12E0 -3E0 8E0 0E0 -90E0 0E0 P2 DEFINE-LOC
CREATE-LOC H

\ the same command both ways
T{ SPEED 30 -> }T  LOG: SPEED 30
T{ 40 SPEED -> }T  LOG: SPEED 40
T{ MOV P1 -> }T  LOG: POINT FBRLT?,12,3,8,0,-90,0
                 LOG: MOVE FBRLT?
T{ P2 MOV -> }T  LOG: POINT FBRLT?,12,-3,8,0,-90,0
                 LOG: MOVE FBRLT?
T{ ARM-HERE H  12E0 -3E0 8E0 H AT? -> TRUE }T  LOG-SKIP
\ several on a line, either way, run in order
T{ MOV P1 MOV P2 -> }T  LOG: POINT FBRLT?,12,3,*
                        LOG: MOVE FBRLT?
                        LOG: POINT FBRLT?,12,-3,*
                        LOG: MOVE FBRLT?
T{ P2 MOV P1 MOV -> }T  LOG: POINT FBRLT?,12,-3,*
                        LOG: MOVE FBRLT?
                        LOG: POINT FBRLT?,12,3,*
                        LOG: MOVE FBRLT?
\ numbers after the word may be written without E (they are reals where reals are meant)
T{ APPROACH P1 2.5 -> }T  LOG: POINT FBRLT?,12,3,*
                          LOG: APPRO FBRLT?,2.5
T{ P1 2.5E0 APPROACH -> }T  LOG-SKIP
T{ JOG 1 0 -0.5 -> }T  LOG: JOG 1,0,-0.5
T{ 1E0 0E0 -0.5E0 JOG -> }T  LOG: JOG 1,0,-0.5
T{ GRIP 50 1.5 -> }T  LOG: GRIP 1.5,50
T{ JOINT 1 -5 -> }T  LOG: JOINT 1,-5
\ constants and values stand for their numbers
30 CONSTANT SLOW   2.25E0 FCONSTANT GAP   7 VALUE AX
T{ SPEED SLOW -> }T  LOG: SPEED 30
T{ APPROACH P2 GAP -> }T  LOG: POINT FBRLT?,*
                          LOG: APPRO FBRLT?,2.25
T{ DEPART GAP -> }T  LOG: DEPART 2.25
T{ SET-RAPL-INT VAX AX -> }T  LOG: VAX=7
\ strings (controller names) either way
T{ OUT-CLEAR TYPEINT VAX S" VAX" TYPEINT OUT" 7 7" -> TRUE }T  LOG: TYPEI VAX
                                                               LOG: TYPEI VAX
\ inside a definition the stack is the natural way; parsing still works at run time
: GO-P1 P1 MOV ;
: GO ( "loc" -- ) MOV ;
T{ GO-P1 -> }T  LOG: POINT FBRLT?,12,3,*
                LOG: MOVE FBRLT?
T{ GO P2 -> }T  LOG: POINT FBRLT?,12,-3,*
                LOG: MOVE FBRLT?
\ mistakes are reported, never guessed; nothing is sent
T{ S" MOV" ' EVALUATE CATCH NIP NIP -> -16 }T
T{ S" MOV 5" ' EVALUATE CATCH NIP NIP -> -24 }T
T{ S" MOV HOME" ' EVALUATE CATCH NIP NIP -> -24 }T
T{ S" 50 GRIP 1.5" ' EVALUATE CATCH NIP NIP -> -24 }T
T{ S" SPEED FAST" ' EVALUATE CATCH NIP NIP -> -24 }T
T{ LOG-COUNT" HOME" LOG-COUNT" GRIP 1.5,50" -> 0 0 }T
\ a location must be one: a number on the stack is refused
T{ 12345 ' MOV CATCH NIP -> -9 }T
FINISH LOG-SKIP
