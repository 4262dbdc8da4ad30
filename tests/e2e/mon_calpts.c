/* SPDX-License-Identifier: MIT */
/* mon_calpts.c - GET-CAL-POINTS at the terminal, on a real pseudo-terminal against a real
 * fbrlsim process (its command log is the witness of what ran):
 *  1. the point's lines are edited as at the prompt: the typed text echoes, Backspace
 *     erases (the log shows the corrected JOG, never the typo);
 *  2. a line with a typo is reported and the same point asked again (the calibration goes
 *     on); BACK asks the point before again;
 *  3. TEACH at the point's prompt runs the keyboard pendant: Enter there takes the point;
 *  4. the three points are the arm's positions (GET-CAL);
 *  5. Ctrl-C at a point's prompt cancels: reported as a cancel, the calibration unchanged.
 *
 *   mon_calpts FBRLMON FBRLSIM TMPDIR      exit 0 on success; the transcript on failure */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <sys/stat.h>

#include "mon_session.h"

#define TIMEOUT_MS 60000 /* generous: the machine may be loaded, or ASan slow */

static void check(int ok, const char *what, const session *s)
{
    if (!ok && !g_failed) {
        fprintf(stderr, "FAIL: %s\n", what);
        transcript(s);
        g_failed = 1;
    }
}

int main(int argc, char **argv)
{
    static session s;
    char port[256], log[1024];
    pid_t sim;
    size_t from;
    int st;

    if (argc != 4) {
        fprintf(stderr, "usage: mon_calpts FBRLMON FBRLSIM TMPDIR\n");
        return 2;
    }
    mkdir(argv[3], 0777);
    signal(SIGPIPE, SIG_IGN);
    snprintf(log, sizeof log, "%s/sim.log", argv[3]);
    sim = start_sim_pty(argv[2], log, port, sizeof port, TIMEOUT_MS);
    if (sim < 0)
        return 1;
    if (start_mon(&s, TIMEOUT_MS, argv[3], argv[1], "--port", port) != 0) {
        kill(sim, SIGTERM);
        return 1;
    }
    expect(&s, "ok> ", "first prompt");
    type(&s, "HOME READY CREATE-CAL C CREATE-LOC T\r");
    expect(&s, "ok> ", "home");

    /* 1. point 1: typed with a typo erased by Backspace (DEL, as terminals send it) */
    type(&s, "C GET-CAL-POINTS\r");
    expect(&s, "Calibration point 1 of 3 (P1, the block's origin)", "point 1 asked");
    expect(&s, "cal 1> ", "the point's prompt");
    type(&s, "0E0 0E0 -2E0 JOGX\177");
    expect(&s, "JOGX", "the typed text echoes");
    type(&s, "\r");
    expect(&s, "cal 1> ", "prompt again after the JOG");
    type(&s, "\r");
    expect(&s, "point 1 taken: X +12.0000 Y +0.0000 Z +18.0000 in", "point 1 is the arm's position");

    /* 2. point 2: a typo is reported and point 2 asked again; BACK goes to point 1 */
    expect(&s, "Calibration point 2 of 3", "point 2 asked");
    type(&s, "0E0 3E0 0E0 JGO\r");
    expect(&s, "error: undefined word JGO (point 2 again)", "the typo is reported");
    expect(&s, "cal 2> ", "point 2 asked again");
    type(&s, "0E0 3E0 0E0 JOG\r");
    expect(&s, "cal 2> ", "prompt after the JOG");
    type(&s, "BACK\r");
    expect(&s, "Calibration point 1 of 3", "BACK asks point 1 again");
    expect(&s, "cal 1> ", "point 1's prompt");
    type(&s, "\r");
    expect(&s, "point 1 taken: X +12.0000 Y +3.0000 Z +18.0000 in", "point 1 taught again");
    expect(&s, "cal 2> ", "point 2's prompt");

    /* 3. TEACH inside: Right jogs X +0.1, Enter takes point 2; point 3 likewise with Up */
    type(&s, "teach\r");
    expect(&s, "TEACH keys", "the pendant starts");
    expect(&s, "X+12.000 Y+3.000 Z+18.000 in", "the pendant's status line");
    type(&s, "\033[C");
    expect(&s, "X+12.100 Y+3.000 Z+18.000", "Right jogs X+");
    type(&s, "\r");
    expect(&s, "point 2 taken: X +12.1000 Y +3.0000 Z +18.0000 in", "Enter in TEACH takes point 2");
    expect(&s, "cal 3> ", "point 3's prompt");
    type(&s, "TEACH\r");
    expect(&s, "X+12.100 Y+3.000 Z+18.000 in", "the pendant at point 3");
    type(&s, "4");
    type(&s, "\033[A");
    expect(&s, "X+12.100 Y+4.000 Z+18.000", "Up jogs Y+ 1 in");
    type(&s, "\r");
    expect(&s, "point 3 taken: X +12.1000 Y +4.0000 Z +18.0000 in", "Enter in TEACH takes point 3");
    expect(&s, "ok> ", "GET-CAL-POINTS ends");

    /* 4. the slots hold the points */
    type(&s, "C 1 T GET-CAL T DISPLAY-LOC C 3 T GET-CAL T DISPLAY-LOC\r");
    expect(&s, "X   +12.0000 Y    +3.0000 Z   +18.0000 in", "slot 1");
    expect(&s, "X   +12.1000 Y    +4.0000 Z   +18.0000 in", "slot 3");
    expect(&s, "ok> ", "prompt");

    /* 5. Ctrl-C at point 2's prompt: a cancel, the slots unchanged */
    type(&s, "C GET-CAL-POINTS\r");
    expect(&s, "cal 1> ", "point 1 again");
    type(&s, "0E0 0E0 1E0 JOG\r");
    expect(&s, "cal 1> ", "prompt after the JOG");
    type(&s, "\r");
    expect(&s, "point 1 taken: X +12.1000 Y +4.0000 Z +19.0000 in", "point 1 taken");
    expect(&s, "cal 2> ", "point 2's prompt");
    from = s.mark;
    type(&s, "\003");
    expect(&s, "GET-CAL-POINTS cancelled by Ctrl-C: the calibration is unchanged", "Ctrl-C is a cancel");
    expect(&s, "ok> ", "prompt after the cancel");
    check(strstr(s.buf + from, "input ended") == NULL, "Ctrl-C reported as the end of input", &s);
    type(&s, "C 1 T GET-CAL T DISPLAY-LOC\r");
    expect(&s, "X   +12.0000 Y    +3.0000 Z   +18.0000 in", "slot 1 unchanged after the cancel");
    expect(&s, "ok> ", "prompt");
    check(strstr(s.buf + from, "unchanged in JOG") == NULL,
          "the cancel is GET-CAL-POINTS', not the last line's word", &s);
    /* leaving with unsaved changes to a saved workspace: fbrlmon offers to save them */
    {
        char cmd[1200];
        snprintf(cmd, sizeof cmd, "SAVE-WORKSPACE %s/cal.ws CREATE-LOC EXTRA\r", argv[3]);
        type(&s, cmd);
        expect(&s, "saved 1 location, 0 matrices, 1 calibration, 0 devices to", "SAVE-WORKSPACE");
        expect(&s, "ok> ", "prompt");
        type(&s, "BYE\r");
        expect(&s, "The workspace changed (2 locations, 0 matrices, 1 calibration, 0 devices). Saving it to ",
               "the offer to save at exit");
        expect(&s, "  add    EXTRA a location: X 0.000 Y 0.000 Z 0.000", "the offer names what a save adds");
        expect(&s, "cal.ws? [Y/n] ", "the offer names the file (adding only: yes by default)");
        type_now(&s, "y\r");
        expect(&s, "saved 2 locations, 0 matrices, 1 calibration, 0 devices to ", "saved at exit");
    }
    st = finish(&s);
    check(st == 0, "fbrlmon's exit status", &s);
    kill(sim, SIGTERM);
    waitpid(sim, NULL, 0);

    /* the controller ran the corrected line, never the typos */
    check(file_count(log, "JOGX") == 0 && file_count(log, "JGO") == 0, "a typo reached the controller", &s);
    check(file_count(log, "JOG 0,0,-2") + file_count(log, "JOG 0.0000,0.0000,-2.0000") == 1,
          "the corrected JOG ran once", &s);
    if (!g_failed)
        printf("mon_calpts: Backspace, typo, BACK, TEACH and Ctrl-C at GET-CAL-POINTS\n");
    return g_failed;
}
