\ robot_motion.fs - motion and position words against fbrlsim (run by robot_e2e)
LOG-SKIP
T{ HOME -> }T   LOG: HOME
T{ READY -> }T  LOG: READY
T{ 50 SPEED -> }T  LOG: SPEED 50
CREATE-LOC P1  12E0 3E0 8E0 0E0 -90E0 0E0 P1 DEFINE-LOC
T{ P1 MOV -> }T  LOG: POINT FBRLT1,12.0000,3.0000,8.0000,0.0000,-90.0000,0.0000
LOG: MOVE FBRLT1
