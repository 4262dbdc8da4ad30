/* SPDX-License-Identifier: MIT */
/* mon_teach.c - TEACH, fbrlmon's keyboard teach pendant, on a real pseudo-terminal
 * against a real fbrlsim process (its command log is the independent witness):
 *  1. arrow, page and pitch keys jog the arm, Enter stores: P holds the position W2
 *     reports, the log shows the JOG / POINT / MOVE commands;
 *  2. a jog out of the workspace shows the controller's error on the status line
 *     and TEACH goes on; Esc leaves P unchanged;
 *  3. with MAP-ON (a calibration that shifts the block by +1 +2 in) the stored
 *     location is the arm's position unmapped; METRIC-ON shows cm; Ctrl-C cancels;
 *  4. W2 prints its position block once;
 *  5. Ctrl-C ends a robot word's wait for the arm (FINISH) at once and halts the arm
 *     on its way; Ctrl-C ends WAIT-INPUT.
 *
 *   mon_teach FBRLMON FBRLSIM TMPDIR      exit 0 on success; the transcript is printed on failure */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <sys/stat.h>

#include "mon_session.h"

#define TIMEOUT_MS 60000 /* generous: the machine may be loaded, or ASan slow */

/* expect() with its own time limit (ms). */
static int expect_within(session *s, const char *text, const char *what, long ms)
{
    long deadline = now_ms() + ms;
    if (g_failed)
        return 0;
    while (strstr(s->buf + s->mark, text) == NULL && now_ms() < deadline)
        if (!pump(s, 50))
            break;
    if (strstr(s->buf + s->mark, text) == NULL) {
        fprintf(stderr, "FAIL: %s: did not see \"%s\" within %ld ms\n", what, text, ms);
        transcript(s);
        g_failed = 1;
        return 0;
    }
    return expect(s, text, what);
}

/* Occurrences of text in the output since `from`. */
static int count(const session *s, size_t from, const char *text) { return occurrences(s->buf + from, text); }

/* A key inside TEACH, then its status line (the arm has moved and been read back). */
static void key(session *s, const char *seq, const char *status_text, const char *what)
{
    type(s, seq);
    expect(s, status_text, what);
}

int main(int argc, char **argv)
{
    static session s;
    char port[256], log[1024];
    pid_t sim;
    size_t from;
    int st;

    if (argc != 4) {
        fprintf(stderr, "usage: mon_teach FBRLMON FBRLSIM TMPDIR\n");
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
    type(&s, "HOME READY CREATE-LOC P CREATE-LOC Q\r");
    expect(&s, "ok> ", "home");

    /* 1. jog X +0.5, Y +0.5, Z -0.5, pitch +1, then Enter */
    type(&s, "TEACH P\r");
    expect(&s, "TEACH keys", "TEACH shows its keys");
    expect(&s, "Enter  store the position", "the key list");
    expect(&s, "X+12.000 Y+0.000 Z+20.000 in  pitch+0.0 roll+0.0  step 0.1 in 1 deg  grip 2.00",
           "status line at READY");
    key(&s, "3", "step 0.5 in 5 deg", "3 chooses 0.5 in");
    key(&s, "\033[C", "X+12.500 Y+0.000 Z+20.000", "Right jogs X+");
    key(&s, "\033[A", "X+12.500 Y+0.500 Z+20.000", "Up jogs Y+");
    key(&s, "\033[6~", "X+12.500 Y+0.500 Z+19.500", "PgDn jogs Z-");
    key(&s, "2", "step 0.1 in 1 deg", "2 chooses 0.1 in");
    key(&s, "]", "Z+19.500 in  pitch+1.0", "] turns the pitch up");
    key(&s, "?", "TEACH keys", "? shows the keys again");
    type(&s, "\r");
    expect(&s, "stored", "Enter stores");
    expect(&s, "ok> ", "back at the prompt");
    type(&s, "P DISPLAY-LOC\r");
    /* (yaw O is the waist's direction, atan2(0.5, 12.5) = 2.291 deg: reported, not chosen) */
    expect(&s, "X   +12.5000 Y    +0.5000 Z   +19.5000 in  O   +2.291 A   +1.000 T   +0.000 deg",
           "P holds the taught position");
    expect(&s, "ok> ", "prompt");
    /* W2 read independently: the same position, printed once (not once per confirming read) */
    from = s.mark;
    type(&s, "W2\r");
    expect(&s, "WORLD     +012.5000 +000.5000 +019.5000 +002.2906 +001.0000 +000.0000", "W2 agrees with P");
    expect(&s, "ok> ", "prompt after W2");
    if (!g_failed && (count(&s, from, "CURRENT ACTUAL POSITION") != 1 || count(&s, from, "WORLD ") != 1)) {
        fprintf(stderr, "FAIL: W2 printed its block %d times\n", count(&s, from, "CURRENT ACTUAL POSITION"));
        transcript(&s);
        g_failed = 1;
    }

    /* 2. out of the workspace: the error shows on the status line, TEACH goes on; Esc */
    type(&s, "TEACH P\r");
    expect(&s, "X+12.500 Y+0.500 Z+19.500", "second TEACH starts at the arm's position");
    key(&s, "4", "step 1 in 10 deg", "4 chooses 1 in");
    key(&s, "\033[B", "X+12.500 Y-0.500 Z+19.500", "Down jogs Y-");
    {
        int k;
        for (k = 0; k < 12 && !g_failed; k++) {
            size_t before = s.mark;
            type(&s, "\033[5~"); /* PgUp until the arm cannot reach */
            expect(&s, "\033[K", "status line after PgUp");
            /* (with its meaning the message is longer than 80 columns leave: it is printed
             * on its own line above the status line) */
            if (strstr(s.buf + before,
                       "! JOG: controller error 029-TRANSFORM ILLEGAL (the position is out of the arm's reach") !=
                    NULL &&
                strstr(s.buf + before, "Z+26.500 in  pitch+1.0 roll+0.0") != NULL)
                break;
        }
        if (!g_failed && k == 12) {
            fprintf(stderr, "FAIL: 12 jogs up never left the workspace (no 029 on the status line)\n");
            transcript(&s);
            g_failed = 1;
        }
    }
    key(&s, "\033[D", "X+11.500", "TEACH goes on after the error: Left jogs X-");
    type(&s, "\033");
    expect(&s, "cancelled: the location is unchanged", "Esc cancels");
    expect(&s, "ok> ", "prompt after Esc");
    type(&s, "P DISPLAY-LOC\r");
    expect(&s, "X   +12.5000 Y    +0.5000 Z   +19.5000 in  O   +2.291 A   +1.000", "P unchanged after Esc");
    expect(&s, "ok> ", "prompt");

    /* 3. MAP-ON: a block moved by +1 +2 in; the taught location is stored unmapped */
    type(&s, "CREATE-CAL C0 CREATE-CAL C1 CREATE-CAL-STRU B CREATE-LOC T\r");
    expect(&s, "ok> ", "cal");
    type(&s, ": PT ( cal slot -- ) ( F: x y z -- ) T >R 0E0 -90E0 0E0 R@ DEFINE-LOC R> SET-CAL ;\r");
    expect(&s, "ok> ", "PT");
    type(&s, "10E0 -2E0 1E0 C0 1 PT 14E0 -2E0 1E0 C0 2 PT 10E0 2E0 1E0 C0 3 PT\r");
    expect(&s, "ok> ", "C0");
    type(&s, "11E0 0E0 1E0 C1 1 PT 15E0 0E0 1E0 C1 2 PT 11E0 4E0 1E0 C1 3 PT C1 C0 B CALIBRATE B WITH-CAL "
             "MAP-ON\r");
    expect(&s, "ok> ", "MAP-ON");
    type(&s, "TEACH Q\r");
    expect(&s, "X+11.500 Y-0.500 Z+", "TEACH under MAP-ON shows the arm's position");
    type(&s, "\r");
    expect(&s, "stored", "Enter under MAP-ON");
    expect(&s, "ok> ", "prompt");
    type(&s, "MAP-OFF Q DISPLAY-LOC\r");
    expect(&s, "X   +10.5000 Y    -2.5000 Z", "Q holds the unmapped position (arm - (1, 2))");
    expect(&s, "ok> ", "prompt");

    /* METRIC-ON: lengths and steps in cm; Ctrl-C cancels TEACH like Esc, with an error */
    type(&s, "MAP-OFF METRIC-ON TEACH Q\r");
    expect(&s, "X+29.210 Y-1.270 Z+67.310 cm  pitch+1.0 roll+0.0  step 0.25 cm 1 deg", "TEACH in cm");
    key(&s, "\033[D", "X+28.960 Y-1.270", "Left jogs 0.25 cm");
    type(&s, "\003");
    expect(&s, "cancelled: the location is unchanged", "Ctrl-C cancels TEACH");
    expect(&s, "TEACH cancelled by Ctrl-C", "the error line");
    expect(&s, "ok> ", "prompt");
    type(&s, "METRIC-OFF Q DISPLAY-LOC\r");
    expect(&s, "X   +10.5000 Y    -2.5000 Z", "Q unchanged after Ctrl-C");
    expect(&s, "ok> ", "prompt");

    /* 4. Ctrl-C while a robot word waits for the arm (FINISH of a 10 s motion at 1 %
     * speed): the word stops at once and the safe stop halts the arm on its way, so W2
     * sees joint 1 short of 6 degrees (tests/e2e/mon_safe.c has the full story) */
    type(&s, "MAP-OFF READY FINISH 1 SPEED\r");
    expect(&s, "ok> ", "READY");
    type(&s, "1 6 JOINT FINISH\r");
    wait_running(&s);
    settle(&s, 300); /* the line is running */
    {
        long t0 = now_ms();
        type_now(&s, "\003");
        if (expect_within(&s, "error: user interrupt", "Ctrl-C ends FINISH's wait", 6000) &&
            expect(&s, "in FINISH", "the interrupted word"))
            printf("mon_teach: FINISH interrupted after %ld ms\n", now_ms() - t0);
    }
    expect(&s, "arm halted while moving (JOINT 1,6", "the safe stop halts the arm");
    expect(&s, "ok> ", "prompt after Ctrl-C");
    type(&s, "W2 100 SPEED\r");
    expect(&s, "JOINTS   +00", "W2 after the halt");
    {
        double j1 = -1;
        if (!g_failed && (sscanf(s.buf + s.mark, "%lf", &j1) != 1 || !(j1 > 0.0 && j1 < 5.9))) {
            fprintf(stderr,
                    "FAIL: joint 1 after the halt is %.4f, want between 0 and 6 (stopped on the way)\n", j1);
            transcript(&s);
            g_failed = 1;
        }
    }
    expect(&s, "ok> ", "prompt");

    /* WAIT-INPUT polls the controller until its time is up: Ctrl-C ends it too */
    type(&s, "5 INPUT-DEVICE SENSOR  SENSOR TRUE 600000 WAIT-INPUT\r");
    wait_running(&s);
    settle(&s, 300); /* the line is running */
    type_now(&s, "\003");
    expect_within(&s, "error: user interrupt", "Ctrl-C ends WAIT-INPUT", 10000);
    expect(&s, "in WAIT-INPUT", "the interrupted word");
    expect(&s, "ok> ", "prompt after WAIT-INPUT");
    type(&s, "SENSOR INPUT? .\r");
    expect(&s, "0 ", "the link works after the interrupted WAIT-INPUT");
    expect(&s, "ok> ", "prompt");

    type(&s, "BYE\r");
    st = finish(&s);
    kill(sim, SIGTERM);
    waitpid(sim, NULL, 0);
    if (!g_failed && st != 0) {
        fprintf(stderr, "FAIL: fbrlmon exit status %d\n", st);
        g_failed = 1;
    }
    /* the emulator's log: the jogs and the pitch move TEACH sent */
    if (!g_failed && (file_count(log, "JOG ") < 4 || file_count(log, "POINT FBRLT") < 1 ||
                      file_count(log, "MOVE FBRLT1,S") + file_count(log, "MOVE FBRLT2,S") < 1)) {
        fprintf(stderr, "FAIL: the emulator's log lacks TEACH's commands (JOG %d, POINT %d, MOVE %d)\n",
                file_count(log, "JOG "), file_count(log, "POINT FBRLT"),
                file_count(log, "MOVE FBRLT1,S") + file_count(log, "MOVE FBRLT2,S"));
        g_failed = 1;
    }
    if (g_failed)
        return 1;
    printf("mon_teach: all checks passed\n");
    return 0;
}
