\ robot_tasks.fs - several procedures at once (docs/tasks.md) against fbrlsim (run by
\ robot_e2e, simulated time 20 times real time): timed steps in two tasks, a task that
\ pulses an output while another waits for a motion, an input handler (ONSIG), the arm
\ claimed for a manoeuvre, and a task that fails holding the arm. Times are host times.

LOG-SKIP
HOME READY
5 OUTPUT-DEVICE VALVE-A   6 OUTPUT-DEVICE VALVE-B   3 INPUT-DEVICE SENSOR
TASK TA   TASK TB   TASK TH
LOG-SKIP

\ 1. two tasks, each with timed steps 1 s apart (B half a second behind A), hold them:
\    each step runs within 20 ms of its time, and both tasks run beside each other
: STEPS-A ( -- ) 4 1 DO I 1000 * AT VALVE-A ON LOOP ;
: STEPS-B ( -- ) 4 1 DO I 1000 * 500 + AT VALVE-B ON LOOP ;
T{ ' STEPS-A TA START  ' STEPS-B TB START  TA AWAIT TB AWAIT -> }T
T{ TA TASK-STATE TB TASK-STATE -> 5 5 }T
T{ TA LATE-MAX 20000 < TB LATE-MAX 20000 < -> TRUE TRUE }T
LOG: OUTPUT 5
LOG: OUTPUT 6
LOG: OUTPUT 5
LOG: OUTPUT 6
LOG: OUTPUT 5
LOG: OUTPUT 6
VALVE-A OFF VALVE-B OFF LOG-SKIP

\ 2. a task waiting for a motion lets another pulse an output meanwhile: the pulses are
\    in fbrlsim's log after the motion started and before FINISH (sent once it ended)
CREATE-LOC FAR   -12E0 8E0 6E0 0E0 -90E0 0E0 FAR DEFINE-LOC
: GO-FAR ( -- ) FAR MOV FINISH ;
: PULSES ( -- ) 100 MS  3 0 DO 30 VALVE-A PULSE LOOP ;
T{ 10 SPEED -> }T  LOG: SPEED 10
T{ ' GO-FAR TA START  ' PULSES TB START  TA AWAIT TB AWAIT -> }T
LOG: POINT FBRLT?,-12,8,6,0,-90,0
LOG: MOVE FBRLT?
LOG: OUTPUT 5
LOG: OUTPUT -5
LOG: OUTPUT 5
LOG: OUTPUT -5
LOG: OUTPUT 5
LOG: OUTPUT -5
LOG: FINISH
T{ TA TASK-STATE TB TASK-STATE -> 5 5 }T
T{ 50 SPEED -> }T LOG-SKIP

\ 3. an input handler: ONSIG runs the word as a task within 20 ms of the input change
\    (the change made over fbrlsim's control channel)
VARIABLE SEEN   VARIABLE T-CHANGE
: NOTE ( -- ) UTIME DROP SEEN ! ;
T{ 0 SEEN !  ' NOTE SENSOR TRUE TH ONSIG -> }T
T{ 200 MS  SEEN @ -> 0 }T
SIM: IN 3 1
UTIME DROP T-CHANGE !
T{ 300 MS  SEEN @ 0<> -> TRUE }T
T{ SEEN @ T-CHANGE @ - 20000 < -> TRUE }T
T{ TH TASK-STATE -> 3 }T  \ still watching for the next change
T{ TH STOP  TH TASK-STATE -> 7 }T
SIM: IN 3 0
\ WHEN: once the input is in the state (at once if it is); INPUT-EDGE waits for a change
T{ 0 SEEN !  ' NOTE SENSOR FALSE TH WHEN  100 MS  SEEN @ 0<>  TH TASK-STATE -> TRUE 5 }T
T{ 0 SEEN !  ' NOTE SENSOR TRUE TH WHEN  100 MS  SEEN @ -> 0 }T
SIM: IN 3 1
T{ 200 MS SEEN @ 0<>  TH TASK-STATE -> TRUE 5 }T
T{ SENSOR FALSE 2 ' INPUT-EDGE TH START-WITH  100 MS TH TASK-STATE -> 3 }T
SIM: IN 3 0
T{ 200 MS TH TASK-STATE -> 5 }T
LOG-SKIP

\ 4. two tasks both moving the arm: a claimed manoeuvre (approach, down, grip, up) is
\    never cut into by the other task's moves
CREATE-LOC SPOT-A   10E0 6E0 4E0 0E0 -90E0 0E0 SPOT-A DEFINE-LOC
CREATE-LOC SPOT-B   10E0 -6E0 4E0 0E0 -90E0 0E0 SPOT-B DEFINE-LOC
: MANOEUVRE ( loc -- ) CLAIM-ARM  DUP 1E0 APPROACH  DUP MOV  CLOSE-GRIP  1E0 APPROACH  RELEASE-ARM ;
: SERVE-A ( -- ) 2 0 DO SPOT-A MANOEUVRE 10 MS LOOP ;
: SERVE-B ( -- ) 5 MS  2 0 DO SPOT-B MANOEUVRE 10 MS LOOP ;
T{ ' SERVE-A TA START  ' SERVE-B TB START  TA AWAIT TB AWAIT -> }T
T{ TA TASK-STATE TB TASK-STATE -> 5 5 }T
\ the log: A's manoeuvre whole, then B's, A's, B's (claims wait in turn)
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: MOVE FBRLT?
LOG: CLOSE
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: MOVE FBRLT?
LOG: CLOSE
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: MOVE FBRLT?
LOG: CLOSE
LOG: POINT FBRLT?,10,6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: MOVE FBRLT?
LOG: CLOSE
LOG: POINT FBRLT?,10,-6,4,0,-90,0
LOG: APPRO FBRLT?,1
LOG-SKIP

\ 5. a task that throws while it holds the arm releases it; the others are told, and the
\    next claim gets the arm
: FAIL-HOLDING ( -- ) CLAIM-ARM  SPOT-A MOV  1 0 / ;
: AFTER ( -- ) 20 MS  CLAIM-ARM  SPOT-B MOV  RELEASE-ARM ;
T{ OUT-CLEAR ' FAIL-HOLDING TA START  ' AFTER TB START  TA AWAIT TB AWAIT -> }T
T{ TA TASK-STATE TB TASK-STATE -> 6 5 }T
T{ OUT" task TA: division by zero" -> TRUE }T
T{ OUT" task TA: released the arm" -> TRUE }T
T{ THE-ARM CLAIM  THE-ARM RELEASE -> }T
