#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sample_prep.py PORT - the short sample-preparation run of examples/sample_prep.c, in
Python: the same steps, the same commands to the controller, the same output; the Python
link also reads W5 before a motion or FINISH while the arm may still move, so that Ctrl-C
can always halt it (docs/python.md, "Stopping the arm").

  1. link:  connect (NOHELP), HOME, READY, SPEED 50
  2. FBRL:  the heating block's tubes (RECTMAT) and locating pins; teach where the pins
            are today (ARM-HERE); CALIBRATE, WITH-CAL, MAP-ON; visit tubes A1..A3;
            dispense 2 ml; pulse the vacuum valve
  3. link:  the separation unit's tube sensor (TYPEI SIG(3)), READY, FINISH and where
            the arm ended (W2)

PORT is a serial device, a pty such as fbrlsim's, or tcp:HOST:PORT. Exit status 0 when
every step worked; 1 with one line on stderr saying what failed (docs/python.md)."""
import sys

import fbrl

# The plan's FBRL part: each string is evaluated as one line.
PLAN = [
    # the heating block: 4 x 6 tubes 0.75 in apart, and its three locating pins as taught
    "CREATE-LOC A1  10E0 -2E0 3E0 0E0 -90E0 0E0 A1 DEFINE-LOC",
    "A1 0.75E0 0.75E0 0E0 RECTMAT BLOCK-TUBE",
    "CREATE-LOC PIN-1   9.5E0 -2.5E0 2.5E0 0E0 -90E0 0E0 PIN-1 DEFINE-LOC",
    "CREATE-LOC PIN-2  13.5E0 -2.5E0 2.5E0 0E0 -90E0 0E0 PIN-2 DEFINE-LOC",
    "CREATE-LOC PIN-3   9.5E0  2.5E0 2.5E0 0E0 -90E0 0E0 PIN-3 DEFINE-LOC",
    "CREATE-CAL AS-TAUGHT  AS-TAUGHT 1 PIN-1 SET-CAL  AS-TAUGHT 2 PIN-2 SET-CAL  AS-TAUGHT 3 PIN-3 SET-CAL",
    # the block was cleaned and put back: bring the gripper onto each pin as it stands
    # today and take the arm's position (mapping is off: physical coordinates)
    "CREATE-CAL TODAY  CREATE-CAL-STRU HEATING-BLOCK  CREATE-LOC NOW",
    ": TEACH ( cal slot -- ) NOW ARM-HERE  NOW SET-CAL ;",
    "PIN-1 0.5E0 APPROACH  JOG 0.30 -0.40 -0.45  TODAY 1 TEACH",
    "PIN-2 0.5E0 APPROACH  JOG 0.30 -0.26 -0.45  TODAY 2 TEACH",
    "PIN-3 0.5E0 APPROACH  JOG 0.13 -0.40 -0.45  TODAY 3 TEACH",
    "TODAY AS-TAUGHT HEATING-BLOCK CALIBRATE  HEATING-BLOCK WITH-CAL  1E0 DEPART-STRT",
    ".( tube A1 stored: ) A1 DISPLAY-LOC",
    "MAP-ON .( tube A1 today:  ) A1 DISPLAY-LOC",
    # the first three tubes, through the calibration
    "CREATE-LOC SPOT",
    ": VISIT ( col -- ) 0 SWAP 0 SPOT BLOCK-TUBE  SPOT 1E0 APPROACH  SPOT MOV-STRT  1E0 DEPART-STRT ;",
    "0 VISIT  1 VISIT  2 VISIT  MAP-OFF",
    # peripherals by name
    "1 OUTPUT-DEVICE BUFFER-PUMP  50 BUFFER-PUMP PULSE-WIDTH  2E0 BUFFER-PUMP DISPENSE",
    "5 OUTPUT-DEVICE SEPARATOR-VACUUM  100 SEPARATOR-VACUUM PULSE",
    ".( dispensed 2 ml, vacuum pulsed) CR",
]

ECHO_TIMEOUT_MS = 500  # a loaded host may stall us; the controller is not slow


def main(argv):
    if len(argv) != 2:
        print("usage: %s PORT" % argv[0], file=sys.stderr)
        return 2
    try:
        with fbrl.Port(argv[1]) as port:
            link = fbrl.Link(port, echo_timeout_ms=ECHO_TIMEOUT_MS)
            # 1. straight through the link
            link.home()
            link.ready()
            link.speed(50)
            # 2. the FBRL part: an engine whose robot words use the same link
            with fbrl.Engine(link=link) as fb:
                for line in PLAN:
                    sys.stdout.write(fb.eval(line))
            # 3. back to the link: the sensor, home position, where the arm is
            print("tube on the separation unit: %s" % ("yes" if link.input(3) else "no"))
            link.ready()
            link.finish()  # the motion's end, not a point on the way
            w = link.where().world
            print("arm at X %.4f Y %.4f Z %.4f in" % (w.x, w.y, w.z))
    except fbrl.Error as e:
        sys.stdout.flush()
        sys.stdout.write(getattr(e, "output", ""))
        print("sample_prep: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
