/* SPDX-License-Identifier: MIT */
/* mon_pty.c - fbrlmon's interactive session through a real pseudo-terminal:
 * prompts ("ok>" / "compiling>"), echo and output, one error line, TAB
 * completion of a word name, KEY in raw mode, and history kept between sessions.
 *
 *   mon_pty FBRLMON TMPDIR      exit 0 on success; the transcript is printed on failure */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */
#include <sys/stat.h>

#include "mon_session.h"

#define TIMEOUT_MS 30000 /* generous: the machine may be loaded, or ASan slow */

static const char *g_mon, *g_dir;

static int start(session *s) { return start_mon(s, TIMEOUT_MS, g_dir, g_mon, "--offline", NULL); }

/* Longest line (printable bytes between newlines; escape sequences skipped)
 * in buf[from, to). */
static size_t longest_line(const char *buf, size_t from, size_t to)
{
    size_t i, col = 0, max = 0;
    for (i = from; i < to; i++) {
        unsigned char c = (unsigned char)buf[i];
        if (c == '\n' || c == '\r') {
            col = 0;
        } else if (c == 0x1b) { /* ESC [ ... final byte */
            if (i + 1 < to && buf[i + 1] == '[') {
                i += 2;
                while (i < to && !((unsigned char)buf[i] >= 0x40 && (unsigned char)buf[i] <= 0x7e))
                    i++;
            }
        } else if (c >= 0x20) {
            if (++col > max)
                max = col;
        }
    }
    return max;
}

static int file_contains(const char *path, const char *text)
{
    char buf[65536];
    size_t n;
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strstr(buf, text) != NULL;
}

/* A pty nobody answers on: fbrlmon --port must say so and exit with status 3
 * (it must not pretend to be connected). */
static void silent_controller(void)
{
    char errpath[1024], *slave;
    int master = posix_openpt(O_RDWR | O_NOCTTY), st;
    long deadline = now_ms() + TIMEOUT_MS;
    pid_t pid;
    int reaped = 0;
    if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0 || (slave = ptsname(master)) == NULL) {
        perror("mon_pty: posix_openpt");
        g_failed = 1;
        return;
    }
    snprintf(errpath, sizeof errpath, "%s/silent.err", g_dir);
    pid = fork();
    if (pid == 0) {
        int fd = open(errpath, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        int null = open("/dev/null", O_RDWR);
        dup2(null, 0);
        dup2(null, 1);
        dup2(fd, 2);
        execl(g_mon, g_mon, "--port", slave, "-e", "1 .", (char *)NULL);
        _exit(127);
    }
    /* Drain what fbrlmon types (it waits for an echo that never comes). */
    for (;;) {
        char junk[256];
        struct pollfd p;
        if (waitpid(pid, &st, WNOHANG) == pid) {
            reaped = 1;
            break;
        }
        if (now_ms() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            fprintf(stderr, "FAIL: fbrlmon --port on a silent pty did not give up\n");
            g_failed = 1;
            close(master);
            return;
        }
        p.fd = master;
        p.events = POLLIN;
        if (poll(&p, 1, 50) > 0 && read(master, junk, sizeof junk) < 0)
            break;
    }
    if (!reaped)
        waitpid(pid, &st, 0);
    close(master);
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 3 || !file_contains(errpath, "no controller answers")) {
        fprintf(stderr,
                "FAIL: fbrlmon --port on a silent pty: status %d, want 3 and 'no controller answers'\n",
                WIFEXITED(st) ? WEXITSTATUS(st) : -1);
        g_failed = 1;
    }
}

int main(int argc, char **argv)
{
    session s;
    char hist[1024];
    int st;

    if (argc != 3) {
        fprintf(stderr, "usage: mon_pty FBRLMON TMPDIR\n");
        return 2;
    }
    g_mon = argv[1];
    g_dir = argv[2];
    mkdir(g_dir, 0700);
    snprintf(hist, sizeof hist, "%s/history", g_dir);
    unlink(hist);

    silent_controller();

    /* Session 1. */
    if (start(&s) != 0)
        return 1;
    if (expect(&s, "offline", "banner names the connection") && expect(&s, "ok> ", "first prompt")) {
        type(&s, "1 2 + .\r");
        expect(&s, "1 2 + .", "echo of the typed line");
        expect(&s, "3 ", "output of 1 2 + .");
        expect(&s, "ok> ", "prompt after a line");
        /* A definition spanning lines changes the prompt. */
        type(&s, ": zebra-count\r");
        expect(&s, "compiling> ", "prompt inside a definition");
        type(&s, "42 ;\r");
        expect(&s, "ok> ", "prompt after the definition");
        /* One clear error line; the session goes on. */
        type(&s, "nosuchword\r");
        expect(&s, "error: ", "error line");
        expect(&s, "nosuchword", "error names the word");
        expect(&s, "ok> ", "prompt after an error");
        /* TAB completes a unique prefix (without completion "zeb" is undefined). */
        type(&s, "zeb\t");
        expect(&s, "ra-count", "TAB completion echo");
        type(&s, ".\r");
        expect(&s, "42 ", "completed word runs");
        expect(&s, "ok> ", "prompt after completed line");
        /* TAB with several candidates lists them; more letters then complete. */
        type(&s, ": zz-one 1 ; : zz-two 2 ;\r");
        expect(&s, "ok> ", "prompt after two definitions");
        type(&s, "zz-\t");
        expect(&s, "zz-one", "candidate list (1)");
        expect(&s, "zz-two", "candidate list (2)");
        type(&s, "t\t.\r");
        expect(&s, "2 ", "completed second candidate runs");
        expect(&s, "ok> ", "prompt after completed candidate");
        /* Ctrl-C at the prompt drops the half-typed line; the session goes on. */
        type(&s, "11 22 33");
        expect(&s, "33", "echo before Ctrl-C");
        type(&s, "\003");
        expect(&s, "ok> ", "prompt after Ctrl-C");
        type(&s, "depth .\r");
        expect(&s, "depth .", "echo after Ctrl-C");
        expect(&s, "0 ", "the dropped line was not evaluated");
        expect(&s, "ok> ", "prompt after depth");
        /* Ctrl-C while a line runs interrupts it (an endless loop, a long MS);
         * one error line, and the session goes on with the dictionary intact. */
        type(&s, ": spin begin again ;\r");
        expect(&s, "ok> ", "prompt after spin");
        type(&s, "spin\r");
        expect(&s, "spin", "echo of spin");
        wait_running(&s);
        settle(&s, 200);
        type_now(&s, "\003");
        expect(&s, "interrupt", "Ctrl-C stops an endless loop");
        expect(&s, "ok> ", "prompt after the interrupted loop");
        type(&s, "600000 ms\r");
        expect(&s, "600000 ms", "echo of ms");
        wait_running(&s);
        settle(&s, 200);
        type_now(&s, "\003");
        expect(&s, "interrupt", "Ctrl-C stops a long MS");
        expect(&s, "ok> ", "prompt after the interrupted MS");
        type(&s, ": naps begin 600000 ms again ; naps\r");
        expect(&s, "naps\r", "echo of naps");
        wait_running(&s);
        settle(&s, 200);
        type_now(&s, "\003");
        expect(&s, "interrupt in naps", "Ctrl-C stops a plan waiting in MS");
        expect(&s, "ok> ", "prompt after the interrupted plan");
        type(&s, "zebra-count .\r");
        expect(&s, "42 ", "dictionary intact after interrupts");
        expect(&s, "ok> ", "prompt after zebra-count");
        /* KEY reads one key without waiting for Enter. */
        type(&s, "key .\r");
        expect(&s, "key .", "echo of key line");
        type(&s, "A");
        expect(&s, "65 ", "KEY got the key");
        expect(&s, "ok> ", "prompt after KEY");
        /* WORDS fits the 80-column terminal: names wrap between words. */
        {
            size_t from;
            type(&s, "words\r");
            expect(&s, "words", "echo of words");
            from = s.mark;
            if (expect(&s, "ok> ", "prompt after WORDS")) {
                size_t longest = longest_line(s.buf, from, s.mark);
                if (longest > 80 || s.mark - from < 400) {
                    fprintf(stderr, "FAIL: WORDS output: %zu bytes, longest line %zu columns (want <= 80)\n",
                            s.mark - from, longest);
                    transcript(&s);
                    g_failed = 1;
                }
            }
        }
        type(&s, "1000 7 + .\r");
        expect(&s, "1007 ", "last line of session 1");
        expect(&s, "ok> ", "prompt before end");
        type(&s, "\004"); /* Ctrl-D: end of input */
        st = finish(&s);
        if (st != 0 && st != -1) {
            fprintf(stderr, "FAIL: session 1 exit status %d (errors typed at the terminal must not count)\n",
                    st);
            transcript(&s);
            g_failed = 1;
        }
    } else {
        kill(s.pid, SIGKILL);
        finish(&s);
    }

    if (!file_contains(hist, "zebra-count")) {
        fprintf(stderr, "FAIL: history file %s lacks the typed lines\n", hist);
        g_failed = 1;
    }

    /* Session 2: the previous session's last line is one Ctrl-P away. */
    if (!g_failed && start(&s) == 0) {
        if (expect(&s, "ok> ", "session 2 prompt")) {
            type(&s, "\020\r");
            expect(&s, "1007 ", "history recalled from session 1");
            expect(&s, "ok> ", "session 2 prompt after recall");
            type(&s, "bye\r");
            st = finish(&s);
            if (st != 0 && st != -1) {
                fprintf(stderr, "FAIL: session 2 exit status %d\n", st);
                transcript(&s);
                g_failed = 1;
            }
        } else {
            kill(s.pid, SIGKILL);
            finish(&s);
        }
    }
    if (!g_failed)
        printf("mon_pty: all interactive checks passed\n");
    return g_failed;
}
