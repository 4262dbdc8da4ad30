/* SPDX-License-Identifier: MIT */
/* sim_e2e_test.c - fbrlsim driven over real pseudo-terminals (and TCP) by a
 * small raw client: line discipline, every command with its effects, readout
 * formats, persistence, baud pacing, faults and the command log.
 * Usage: sim_e2e_test GROUP (line motion io persist baud faults log tcp embed). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "fbrlsim.h"

#define TIMEOUT 15.0 /* seconds: generous, the machine may be loaded */
#define SILENCE_S 0.5 /* seconds of nothing that prove no unasked-for byte comes */

typedef struct simp {
    pid_t pid;
    int fd;
    char path[256];
} simp;

static char g_dir[64];   /* per-run scratch directory */
static pid_t g_pids[64]; /* emulators started, killed by the group teardown if a test failed */
static int g_npids;
static char g_buf[1 << 16];
static int g_real; /* spawn as a user would: no --status-extra (2: --aci, no prompt at all) */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static const char *tmp(const char *name)
{
    static char p[8][256];
    static int k;
    k = (k + 1) % 8;
    snprintf(p[k], sizeof p[k], "%s/%s", g_dir, name);
    return p[k];
}

static void raw_fd(int fd)
{
    struct termios t;
    if (tcgetattr(fd, &t) == 0) {
        cfmakeraw(&t);
        tcsetattr(fd, TCSANOW, &t);
    }
}

static void expect_greeting(simp *p);

/* Starts fbrlsim with the given options (NULL-terminated) and opens its line. */
static void spawn(simp *p, const char *const *extra)
{
    const char *argv[32];
    int pipefd[2], n = 0, i;
    size_t len = 0;
    double end = now_s() + TIMEOUT;

    argv[n++] = FBRLSIM_PATH;
    if (!g_real)
        argv[n++] = "--status-extra"; /* these tests read fbrlsim's own STATUS lines */
    for (i = 0; extra && extra[i]; i++)
        argv[n++] = extra[i];
    argv[n] = NULL;
    assert_int_equal(pipe(pipefd), 0);
    p->pid = fork();
    assert_true(p->pid >= 0);
    if (p->pid == 0) {
        dup2(pipefd[1], 1);
        close(pipefd[0]);
        execv(FBRLSIM_PATH, (char *const *)argv);
        _exit(127);
    }
    close(pipefd[1]);
    if (g_npids < 64)
        g_pids[g_npids++] = p->pid;
    while (now_s() < end) {
        struct pollfd pf = {pipefd[0], POLLIN, 0};
        char c;
        if (poll(&pf, 1, 100) > 0) {
            if (read(pipefd[0], &c, 1) != 1)
                break;
            if (c == '\n')
                break;
            if (len < sizeof p->path - 1)
                p->path[len++] = c;
        }
    }
    p->path[len] = 0;
    close(pipefd[0]);
    if (!len)
        fail_msg("fbrlsim printed no path");
    if (!strncmp(p->path, "tcp:", 4)) {
        struct sockaddr_in a;
        memset(&a, 0, sizeof a);
        a.sin_family = AF_INET;
        a.sin_port = htons((unsigned short)atoi(strrchr(p->path, ':') + 1));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        p->fd = socket(AF_INET, SOCK_STREAM, 0);
        assert_int_equal(connect(p->fd, (struct sockaddr *)&a, sizeof a), 0);
        {
            int one = 1; /* as fbrlsim's end: no small write held back */
            setsockopt(p->fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        }
        expect_greeting(p);
    } else {
        /* a pty is greeted only when asked (--greet-pty): a serial line's controller cannot
         * see a program open its port; the first reply of each test is its proof of silence */
        p->fd = open(p->path, O_RDWR | O_NOCTTY);
        assert_true(p->fd >= 0);
        raw_fd(p->fd);
        for (i = 0; extra && extra[i]; i++)
            if (strcmp(extra[i], "--greet-pty") == 0)
                expect_greeting(p);
    }
}

static void forget(pid_t pid)
{
    int i;
    for (i = 0; i < g_npids; i++)
        if (g_pids[i] == pid)
            g_pids[i] = g_pids[--g_npids];
}

static int kill_all(void **st)
{
    (void)st;
    g_real = 0;
    while (g_npids > 0) {
        pid_t pid = g_pids[--g_npids];
        kill(pid, SIGKILL);
        waitpid(pid, NULL, 0);
    }
    return 0;
}

static void stop(simp *p)
{
    int st = 0;
    close(p->fd);
    kill(p->pid, SIGTERM);
    forget(p->pid);
    assert_int_equal(waitpid(p->pid, &st, 0), p->pid);
    assert_true(WIFEXITED(st));
    assert_int_equal(WEXITSTATUS(st), 0);
}

static void put(simp *p, const char *b, size_t n)
{
    while (n) {
        ssize_t w = write(p->fd, b, n);
        if (w < 0 && errno == EINTR)
            continue;
        assert_true(w > 0);
        b += w;
        n -= (size_t)w;
    }
}

static void puts_(simp *p, const char *s) { put(p, s, strlen(s)); }

static int ends_with(const char *b, size_t n, const char *suf)
{
    size_t k = strlen(suf);
    return n >= k && !memcmp(b + n - k, suf, k);
}

/* Reads until the data ends with suf (or the timeout); returns the length. */
static size_t read_until(simp *p, char *buf, size_t cap, const char *suf, double timeout)
{
    size_t n = 0;
    double end = now_s() + timeout;
    while (n < cap - 1 && !(suf && ends_with(buf, n, suf)) && now_s() < end) {
        struct pollfd pf = {p->fd, POLLIN, 0};
        if (poll(&pf, 1, 20) > 0) {
            ssize_t r = read(p->fd, buf + n, cap - 1 - n);
            if (r <= 0)
                break;
            n += (size_t)r;
        }
    }
    buf[n] = 0;
    return n;
}

/* A client is greeted with the prompt as soon as it connects (TCP) or, with --greet-pty,
 * opens the pty. */
static void expect_greeting(simp *p)
{
    size_t n = read_until(p, g_buf, sizeof g_buf, ">>", TIMEOUT);
    if (n != 2 || strcmp(g_buf, ">>") != 0)
        fail_msg("no prompt on connect: got '%s'", g_buf);
}

/* Nothing arrives for a while (SILENCE_S): no byte that nobody typed for. */
static void expect_silence(simp *p)
{
    size_t n = read_until(p, g_buf, sizeof g_buf, NULL, SILENCE_S);
    if (n != 0)
        fail_msg("%zu bytes nobody typed for: '%s'", n, g_buf);
}

/* Sends a line with CR; returns everything up to and including the prompt. */
static const char *raw(simp *p, const char *line)
{
    size_t n;
    puts_(p, line);
    puts_(p, "\r");
    n = read_until(p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    if (!ends_with(g_buf, n, "\r\n>>"))
        fail_msg("no prompt after '%s': got '%s'", line, g_buf);
    return g_buf;
}

/* Sends a command (NOHELP already given): checks the echo and returns the reply
 * body between the echoed line's CR LF and the prompt. */
static const char *cmd(simp *p, const char *line)
{
    const char *r = raw(p, line);
    size_t k = strlen(line), n = strlen(r);
    char up[256];
    size_t i;
    for (i = 0; i <= k; i++)
        up[i] = (char)(line[i] >= 'a' && line[i] <= 'z' ? line[i] - 32 : line[i]);
    if (strncmp(r, up, k) != 0 || strncmp(r + k, "\r\n", 2) != 0)
        fail_msg("echo of '%s' wrong: '%s'", line, r);
    g_buf[n - 2] = 0; /* drop ">>" */
    return r + k + 2;
}

static void ok(simp *p, const char *line)
{
    const char *r = cmd(p, line);
    if (*r)
        fail_msg("'%s' gave '%s'", line, r);
}

static void err(simp *p, const char *line, int code)
{
    const char *r = cmd(p, line);
    char want[8];
    snprintf(want, sizeof want, "%03d-", code);
    if (strncmp(r, want, 4) != 0 || !strstr(r, ".\r\n"))
        fail_msg("'%s': want error %03d, got '%s'", line, code, r);
}

static void start(simp *p, const char *const *extra)
{
    spawn(p, extra);
    ok(p, "NOHELP");
}

static const char *const FAST[] = {"--time-scale", "200", NULL};

/* Position from W2: six WORLD numbers and five JOINTS. */
static void where(simp *p, double w[6], double j[5], long pulses[5])
{
    const char *r = cmd(p, "W2"), *x;
    x = strstr(r, "WORLD     ");
    assert_non_null(x);
    assert_int_equal(sscanf(x + 5, "%lf %lf %lf %lf %lf %lf", &w[0], &w[1], &w[2], &w[3], &w[4], &w[5]), 6);
    x = strstr(r, "JOINTS   ");
    assert_non_null(x);
    if (j)
        assert_int_equal(sscanf(x + 6, "%lf %lf %lf %lf %lf", &j[0], &j[1], &j[2], &j[3], &j[4]), 5);
    x = strstr(r, "PULSES   ");
    assert_non_null(x);
    if (pulses)
        assert_int_equal(
            sscanf(x + 6, "%ld %ld %ld %ld %ld", &pulses[0], &pulses[1], &pulses[2], &pulses[3], &pulses[4]),
            5);
}

static void at(simp *p, double x, double y, double z, double pitch, double roll)
{
    double w[6];
    ok(p, "FINISH");
    where(p, w, NULL, NULL);
    if (fabs(w[0] - x) > 0.001 || fabs(w[1] - y) > 0.001 || fabs(w[2] - z) > 0.001 ||
        fabs(w[4] - pitch) > 0.001 || fabs(w[5] - roll) > 0.001)
        fail_msg("at %f %f %f %f %f, want %f %f %f %f %f", w[0], w[1], w[2], w[4], w[5], x, y, z, pitch,
                 roll);
}

static const char *status_line(simp *p, const char *prefix)
{
    static char line[256];
    const char *r = cmd(p, "STATUS"), *x = strstr(r, prefix), *e;
    if (!x)
        fail_msg("STATUS has no '%s': %s", prefix, r);
    e = strstr(x, "\r\n");
    snprintf(line, sizeof line, "%.*s", (int)(e - x), x);
    return line;
}

/* ---- line discipline ------------------------------------------------- */

static void t_echo_prompt(void **st)
{
    simp p;
    size_t n;
    (void)st;
    spawn(&p, FAST);
    /* HELP mode is on at power-up: the hint is written and erased again */
    assert_string_equal(raw(&p, "SPEED 40"),
                        "SPEED <PERCENT>\b \b\b \b\b \b\b \b\b \b\b \b\b \b\b \b\b \b40\r\n>>");
    assert_string_equal(raw(&p, "NOHELP"), "NOHELP\r\n>>");
    assert_string_equal(raw(&p, "SPEED 40"), "SPEED 40\r\n>>");
    assert_string_equal(raw(&p, "speed 41"), "SPEED 41\r\n>>");
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +41");
    assert_string_equal(raw(&p, ""), "\r\n>>");
    /* LF and CRLF end lines too, without an extra prompt */
    puts_(&p, "SPEED 42\n");
    n = read_until(&p, g_buf, sizeof g_buf, ">>", TIMEOUT);
    assert_string_equal(g_buf, "SPEED 42\r\n>>");
    puts_(&p, "SPEED 43\r\n");
    n = read_until(&p, g_buf, sizeof g_buf, ">>", TIMEOUT);
    assert_string_equal(g_buf, "SPEED 43\r\n>>");
    n = read_until(&p, g_buf, sizeof g_buf, NULL, 0.2);
    assert_int_equal(n, 0);
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +43");
    ok(&p, "HELP");
    {
        /* the hint follows a comma as well; the echo of the line itself is unchanged */
        char want[256];
        const char *hint = "<JOINT#>,<DEGREES>";
        size_t i;
        snprintf(want, sizeof want, "JOINT,%s", hint);
        for (i = 0; i < strlen(hint); i++)
            strcat(want, "\b \b");
        strcat(want, "1,5\r\n041-ROBOT HAS NOT BEEN HOMED.\r\n>>");
        assert_string_equal(raw(&p, "JOINT,1,5"), want);
    }
    /* a terminal program that opens the pty again hears nothing until it types: a
     * controller on a serial line cannot see a program open its port */
    close(p.fd);
    p.fd = open(p.path, O_RDWR | O_NOCTTY);
    assert_true(p.fd >= 0);
    raw_fd(p.fd);
    expect_silence(&p);
    assert_string_equal(raw(&p, "NOHELP"), "NOHELP\r\n>>");
    stop(&p);
}

/* --greet-pty: each program that opens the pty is greeted, as a TCP client is. */
static void t_greet_pty(void **st)
{
    static const char *const opts[] = {"--greet-pty", "--time-scale", "200", NULL};
    simp p;
    (void)st;
    spawn(&p, opts); /* the first open's greeting is read there */
    assert_string_equal(raw(&p, "NOHELP"), "NOHELP\r\n>>");
    close(p.fd);
    p.fd = open(p.path, O_RDWR | O_NOCTTY);
    assert_true(p.fd >= 0);
    raw_fd(p.fd);
    expect_greeting(&p);
    assert_string_equal(raw(&p, "SPEED 30"), "SPEED 30\r\n>>");
    stop(&p);
}

static void t_editing(void **st)
{
    simp p;
    (void)st;
    start(&p, FAST);
    assert_string_equal(raw(&p, "SPEEX\bD 3\x7f"
                                "44"),
                        "SPEEX\b \bD 3\b \b44\r\n>>");
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +44");
    /* BS on an empty line echoes nothing; Ctrl-X erases the whole line */
    assert_string_equal(raw(&p, "\b\bFOO\x18SPEED 45"), "FOO\b \b\b \b\b \bSPEED 45\r\n>>");
    /* control characters are ignored */
    assert_string_equal(raw(&p, "SPE\x01\x02"
                                "ED 46"),
                        "SPEED 46\r\n>>");
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +46");
    /* XOFF from the host holds all output, XON releases it */
    {
        size_t n;
        puts_(&p, "\x13SPEED 47\r");
        n = read_until(&p, g_buf, sizeof g_buf, NULL, 0.3);
        assert_int_equal(n, 0);
        puts_(&p, "\x11");
        n = read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
        assert_string_equal(g_buf, "SPEED 47\r\n>>");
    }
    /* an over-long line emptied with Ctrl-X is a fresh line */
    {
        char l[100];
        memset(l, 'B', 90);
        l[90] = 0;
        puts_(&p, l);
        puts_(&p, "\x18");
        read_until(&p, g_buf, sizeof g_buf, NULL, 0.3);
        assert_string_equal(raw(&p, "SPEED 48"), "SPEED 48\r\n>>");
    }
    stop(&p);
}

static void t_errors(void **st)
{
    simp p;
    char longline[120];
    (void)st;
    start(&p, FAST);
    assert_string_equal(status_line(&p, "LAST ERROR"), "LAST ERROR CODE: NONE");
    err(&p, "FOO", 12);
    assert_string_equal(status_line(&p, "LAST ERROR"), "LAST ERROR CODE: 012-COMMAND ERROR.");
    err(&p, "S 1", 50); /* SPEED, SET, SERIAL, ... */
    ok(&p, "SP 30");    /* unique prefix */
    ok(&p, "/016 20");  /* token form */
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +20");
    err(&p, "/999", 12);
    {
        char a[4096];
        snprintf(a, sizeof a, "%s", cmd(&p, "STATUS"));
        assert_string_equal(cmd(&p, "/025"), a);
        snprintf(a, sizeof a, "%s", cmd(&p, "W2"));
        assert_string_equal(cmd(&p, "/031"), a);
        snprintf(a, sizeof a, "%s", cmd(&p, "SERIAL"));
        assert_string_equal(cmd(&p, "/111"), a);
        ok(&p, "/089 5");                                      /* OUTPUT */
        assert_string_equal(cmd(&p, "/059 OSIG(5)"), "1\r\n"); /* TYPEI */
        ok(&p, "/020");                                        /* HOME */
        ok(&p, "/015");                                        /* READY */
        ok(&p, "/010");                                        /* FINISH */
        ok(&p, "/050 TP,12,0,20,0,0,0");                       /* POINT */
        ok(&p, "/006 1,10");                                   /* JOINT */
        ok(&p, "/002 TP,0");                                   /* APPRO */
        ok(&p, "/010");
        assert_non_null(strstr(cmd(&p, "W2"), "WORLD     +012.0000 +000.0000 +020.0000"));
    }
    err(&p, "/16 20", 12);
    err(&p, "SPEED", 13);
    err(&p, "SPEED 1,2", 14);
    err(&p, "SPEED 1,,2", 14);
    err(&p, "SPEED 0", 18);
    err(&p, "SPEED 101", 20);
    err(&p, "SPEED Q", 10);
    err(&p, "SPEED 1X", 14);
    memset(longline, 'A', 100);
    longline[100] = 0;
    /* beyond 80 characters nothing is stored or echoed, and the line fails */
    {
        const char *r;
        puts_(&p, longline);
        puts_(&p, "\r");
        read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
        r = g_buf;
        assert_int_equal(strspn(r, "A"), 80);
        assert_string_equal(r + 80, "\r\n025-LINE TOO LONG.\r\n>>");
    }
    assert_string_equal(status_line(&p, "LAST ERROR"), "LAST ERROR CODE: 025-LINE TOO LONG.");
    ok(&p, "SPEED 10"); /* success keeps the last error */
    assert_string_equal(status_line(&p, "LAST ERROR"), "LAST ERROR CODE: 025-LINE TOO LONG.");
    stop(&p);
}

/* ---- motion ---------------------------------------------------------- */

static void t_home_ready(void **st)
{
    simp p;
    long pul[5];
    double w[6], j[5];
    const char *r;
    (void)st;
    start(&p, FAST);
    err(&p, "READY", 41);
    err(&p, "JOINT 1,10", 41);
    assert_string_equal(status_line(&p, "CONTROLLER"), "CONTROLLER IS NOT HOMED");
    ok(&p, "HOME");
    assert_string_equal(status_line(&p, "CONTROLLER"), "CONTROLLER IS HOMED");
    assert_string_equal(status_line(&p, "HOMED "), "HOMED        Y Y Y Y Y");
    ok(&p, "JOINT 1,30");
    ok(&p, "READY");
    ok(&p, "FINISH");
    where(&p, w, j, pul);
    assert_int_equal(pul[1], 18000);
    assert_int_equal(pul[2], -18000);
    r = cmd(&p, "W2");
    assert_string_equal(r, "\r\nCURRENT ACTUAL POSITION :\r\n"
                           "NAME       AX#1        AX#2        AX#3        AX#4        AX#5\r\n"
                           "PULSES   +0000000000 +0000018000 -0000018000 +0000000000 +0000000000\r\n"
                           "NAME       JT#1      JT#2      JT#3      JT#4      JT#5\r\n"
                           "JOINTS   +000.0000 +090.0000 -090.0000 +000.0000 +000.0000\r\n"
                           "WORLD     +012.0000 +000.0000 +020.0000 +000.0000 +000.0000 +000.0000\r\n");
    assert_non_null(strstr(cmd(&p, "W0"), "CURRENT COMMAND POSITION :\r\n"));
    assert_non_null(strstr(cmd(&p, "W4"), "END OF PATH POSITION :\r\n"));
    stop(&p);
}

static void t_moves(void **st)
{
    simp p;
    long pul[5];
    double w[6];
    (void)st;
    start(&p, FAST);
    ok(&p, "HOME");
    ok(&p, "POINT P1,10,5,4,0,-90,30");
    ok(&p, "MOVE P1");
    at(&p, 10, 5, 4, -90, 30);
    ok(&p, "POINT P2,14,-3,8.5,0,-45,-20");
    ok(&p, "MOVE P2,S");
    at(&p, 14, -3, 8.5, -45, -20);
    ok(&p, "JOG 1,2,-3");
    at(&p, 15, -1, 5.5, -45, -20);
    ok(&p, "APPRO P1,2");
    at(&p, 10, 5, 6, -90, 30);
    ok(&p, "APPRO P1,1,S");
    at(&p, 10, 5, 5, -90, 30);
    ok(&p, "MOVE P1,S");
    at(&p, 10, 5, 4, -90, 30);
    ok(&p, "DEPART 3");
    at(&p, 10, 5, 7, -90, 30);
    ok(&p, "DEPART -2,S");
    at(&p, 10, 5, 5, -90, 30);
    /* yaw is reported, not obeyed */
    ok(&p, "POINT P3,0,12,10,77,0,0");
    ok(&p, "MOVE P3");
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[3] - 90.0) < 0.001);
    /* precision points: exact pulses */
    ok(&p, "POINT #Q1,1000,16000,-20000,444,-222");
    ok(&p, "MOVE #Q1");
    ok(&p, "FINISH");
    where(&p, w, NULL, pul);
    assert_int_equal(pul[0], 1000);
    assert_int_equal(pul[1], 16000);
    assert_int_equal(pul[2], -20000);
    assert_int_equal(pul[3], 444);
    assert_int_equal(pul[4], -222);
    ok(&p, "HERE #H1");
    ok(&p, "HERE H2");
    ok(&p, "ACTUAL H3");
    {
        char a[256];
        snprintf(a, sizeof a, "%s", cmd(&p, "LISTL H2"));
        a[1] = '3';
        assert_string_equal(cmd(&p, "LISTL H3"), a);
    }
    assert_string_equal(cmd(&p, "LISTL #H1"),
                        "#H1       +0000001000 +0000016000 -0000020000 +0000000444 -0000000222\r\n");
    ok(&p, "READY");
    ok(&p, "MOVE H2,S");
    ok(&p, "FINISH");
    where(&p, w, NULL, pul);
    assert_int_equal(pul[1], 16000);
    /* joint moves, MI/MA in radians, MOTOR in pulses */
    ok(&p, "READY");
    ok(&p, "JOINT 1,-45");
    ok(&p, "JOINT 5,90");
    ok(&p, "FINISH");
    where(&p, w, NULL, pul);
    assert_int_equal(pul[0], -9000);
    assert_int_equal(pul[4], 2000); /* 90 * 22.22 = 1999.8, rounded */
    ok(&p, "MA 0,1.5707963267948966,-1.5707963267948966,0,0");
    ok(&p, "MI 0.1,0,0,0,0");
    ok(&p, "MOTOR 3,-200");
    ok(&p, "FINISH");
    where(&p, w, NULL, pul);
    assert_int_equal(pul[0], 1146); /* 0.1 rad = 5.7296 deg * 200 */
    assert_int_equal(pul[1], 18000);
    assert_int_equal(pul[2], -18200);
    ok(&p, "MA 0,1.5707963267948966,-1.5707963267948966,0,0,S");
    at(&p, 12, 0, 20, 0, 0);
    /* ALIGN: pitch to the nearest of -90, 0, 90 */
    ok(&p, "POINT A1,12,0,8,0,-70,0");
    ok(&p, "MOVE A1");
    ok(&p, "ALIGN");
    at(&p, 12, 0, 8, -90, 0);
    stop(&p);
}

static void t_motion_errors(void **st)
{
    simp p;
    double w[6];
    (void)st;
    start(&p, FAST);
    ok(&p, "POINT FAR,30,0,10,0,0,0");
    err(&p, "MOVE FAR", 41);
    ok(&p, "HOME");
    err(&p, "MOVE FAR", 29);
    err(&p, "MOVE FAR,S", 29);
    err(&p, "MOVE NOPE", 11);
    err(&p, "MOVE #NOPE", 11);
    err(&p, "APPRO NOPE,1", 11);
    err(&p, "MOVE TOOLONGNAME", 18);
    err(&p, "JOINT 1,200", 42);
    err(&p, "JOINT 2,30", 43);
    err(&p, "JOINT 3,100", 44);
    err(&p, "JOINT 4,150", 45);
    err(&p, "JOINT 5,-200", 46);
    err(&p, "JOINT 6,1", 65);
    err(&p, "JOINT 1", 13);
    /* reachable but elbow past its range: pointing up, close to the base */
    ok(&p, "POINT UP,2,0,10,0,90,0");
    {
        const char *r = cmd(&p, "MOVE UP");
        assert_true(!strncmp(r, "04", 2));
    }
    /* straight line through the base axis */
    ok(&p, "POINT L1,14,0,10,0,-90,0");
    ok(&p, "POINT L2,-14,-2,10,0,-90,0");
    ok(&p, "MOVE L1");
    err(&p, "MOVE L2,S", 68);
    ok(&p, "MOVE L2");
    at(&p, -14, -2, 10, -90, 0);
    /* a failed move leaves the arm where it was */
    err(&p, "JOG 0,0,30", 29);
    at(&p, -14, -2, 10, -90, 0);
    /* LIMP forbids motion, NOLIMP allows it again */
    ok(&p, "LIMP 2");
    assert_string_equal(status_line(&p, "LIMP "), "LIMP         N Y N N N");
    err(&p, "JOINT 1,1", 18);
    ok(&p, "NOLIMP");
    ok(&p, "JOINT 1,1");
    /* LOCK holds a joint in joint moves; an S move needing it fails */
    ok(&p, "READY");
    ok(&p, "LOCK 1");
    assert_string_equal(status_line(&p, "LOCK "), "LOCK         Y N N N N");
    ok(&p, "POINT SIDE,0,12,20,0,0,0");
    ok(&p, "MOVE SIDE");
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[3]) < 0.001);
    err(&p, "MOVE SIDE,S", 68);
    ok(&p, "UNLOCK");
    ok(&p, "MOVE SIDE");
    at(&p, 0, 12, 20, 0, 0);
    ok(&p, "LOCK 5");
    ok(&p, "READY"); /* READY clears LOCK */
    assert_string_equal(status_line(&p, "LOCK "), "LOCK         N N N N N");
    assert_string_equal(status_line(&p, "CURRENT ROBOT"),
                        "CURRENT ROBOT CONFIG : UPRIGHT/REACH FORWARD/ELBOW UP/WRIST FREE");
    /* a target whose forward reach passes the waist limit is reached backward, over the shoulder */
    ok(&p, "POINT BACK,-2.5,-0.1,30.5,0,30,0");
    ok(&p, "MOVE BACK");
    at(&p, -2.5, -0.1, 30.5, 30, 0);
    assert_string_equal(status_line(&p, "CURRENT ROBOT"),
                        "CURRENT ROBOT CONFIG : UPRIGHT/REACH BACKWARD/ELBOW UP/WRIST FREE");
    ok(&p, "READY");
    ok(&p, "ARM OFF");
    err(&p, "READY", 40);
    assert_string_equal(status_line(&p, "ARM POWER IS"), "ARM POWER IS OFF");
    ok(&p, "ARM ON");
    ok(&p, "READY");
    stop(&p);
}

/* The DONE flag of axis 1 in STATUS. */
static char done1(simp *p) { return status_line(p, "DONE ")[13]; }

/* A motion command returns at the start; the next waits until it is done. */
static void t_motion_timing(void **st)
{
    static const char *const rt[] = {"--time-scale", "1", NULL};
    simp p;
    double t0, t1, w[6];
    (void)st;
    start(&p, rt);
    ok(&p, "HOME");
    ok(&p, "SPEED 100");
    t0 = now_s();
    ok(&p, "JOINT 1,90"); /* 1.5 s at 60 deg/s */
    t1 = now_s();
    if (t1 - t0 < 1.0) {
        char d = done1(&p);
        assert_true(d == 'N' || now_s() - t0 >= 1.5);
    }
    cmd(&p, "W2"); /* readouts do not wait */
    if (now_s() - t0 < 1.2) {
        /* W4: the end of the path, while W0 still shows the way there */
        assert_non_null(strstr(cmd(&p, "W4"), "JOINTS   +090.0000 +090.0000"));
        assert_null(strstr(cmd(&p, "W0"), "JOINTS   +090.0000 +090.0000"));
    }
    ok(&p, "JOINT 1,-90"); /* waits for the first */
    assert_true(now_s() - t0 >= 1.4);
    ok(&p, "HALT");
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(w[3] > 0.0 && w[3] < 90.0); /* stopped on the way back */
    assert_int_equal(done1(&p), 'Y');
    stop(&p);
}

static void t_locations(void **st)
{
    simp p;
    (void)st;
    start(&p, FAST);
    ok(&p, "HOME");
    ok(&p, "POINT B,1,2,3,4,5,6");
    ok(&p, "POINT A,10,0,5,0,-90,0");
    err(&p, "POINT C,1,2,3", 13);
    err(&p, "POINT C,1,2,3,4,5,6,7", 14);
    err(&p, "POINT #C,1,2", 13);
    err(&p, "POINT 9X,1,2,3,4,5,6", 18);
    ok(&p, "SET C=A");
    ok(&p, "SET #D=A");
    ok(&p, "SET E = #D");
    assert_string_equal(cmd(&p, "LISTL"),
                        "A         +010.0000 +000.0000 +005.0000 +000.0000 -090.0000 +000.0000\r\n"
                        "B         +001.0000 +002.0000 +003.0000 +004.0000 +005.0000 +006.0000\r\n"
                        "C         +010.0000 +000.0000 +005.0000 +000.0000 -090.0000 +000.0000\r\n"
                        "#D        +0000000000 +0000008367 -0000023413 -0000000656 +0000000000\r\n"
                        "E         +010.0004 +000.0000 +005.0003 +000.0000 -089.9915 +000.0000\r\n");
    /* E went through whole pulses: within a pulse of A (0.0225 deg on the wrist) */
    err(&p, "SET F=NOPE", 11);
    ok(&p, "POINT FAR,30,0,0,0,0,0");
    err(&p, "SET #F=FAR", 29);
    ok(&p, "SHIFT C,1,-1,0.5");
    assert_string_equal(cmd(&p, "LISTL C"),
                        "C         +011.0000 -001.0000 +005.5000 +000.0000 -090.0000 +000.0000\r\n");
    ok(&p, "SHIFTA C,B");
    assert_string_equal(cmd(&p, "LISTL C"),
                        "C         +012.0000 +001.0000 +008.5000 +004.0000 -085.0000 +006.0000\r\n");
    err(&p, "SHIFTA C,#D", 15);
    err(&p, "SHIFT #D,1,1,1", 15);
    ok(&p, "DLOCN B");
    err(&p, "LISTL B", 11);
    err(&p, "DLOCN B", 11);
    /* TOOL: a tool length moves the tool point along the tool axis */
    ok(&p, "POINT T,0,0,3,0,0,0");
    ok(&p, "POINT BADT,1,0,3,0,0,0");
    err(&p, "TOOL BADT", 18);
    ok(&p, "READY");
    ok(&p, "TOOL T");
    at(&p, 15, 0, 20, 0, 0);
    assert_string_equal(status_line(&p, "TOOL  "),
                        "TOOL      +000.0000 +000.0000 +003.0000 +000.0000 +000.0000 +000.0000");
    ok(&p, "MOVE A");
    at(&p, 10, 0, 5, -90, 0);
    ok(&p, "TOOL");
    at(&p, 10, 0, 8, -90, 0);
    /* 100 locations fit, the 101st does not */
    {
        int i, n = 0;
        char line[64];
        for (i = 0; i < 200 && n == 0; i++) {
            const char *r;
            snprintf(line, sizeof line, "POINT L%d,1,2,3,4,5,6", i);
            r = cmd(&p, line);
            if (*r) {
                assert_string_equal(r, "022-TABLE FULL.\r\n");
                n = i;
            }
        }
        assert_int_equal(n, 100 - 7); /* A C #D E FAR T BADT were there */
    }
    stop(&p);
}

static void t_teach(void **st)
{
    simp p;
    const char *ctl = tmp("ctl-teach");
    const char *const opts[] = {"--time-scale", "200", "--control", ctl, NULL};
    int fd;
    (void)st;
    start(&p, opts);
    ok(&p, "HOME");
    ok(&p, "TEACH PT");
    assert_string_equal(status_line(&p, "TEACH"), "TEACH MODE IS ON: PT, NEXT 001");
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "TEACH\n", 6), 6);
    usleep(100000);
    ok(&p, "JOINT 1,90");
    ok(&p, "FINISH");
    assert_int_equal(write(fd, "TEACH\n", 6), 6);
    usleep(100000);
    assert_string_equal(cmd(&p, "LISTL"),
                        "PT001     +012.0000 +000.0000 +020.0000 +000.0000 +000.0000 +000.0000\r\n"
                        "PT002     +000.0000 +012.0000 +020.0000 +090.0000 +000.0000 +000.0000\r\n");
    ok(&p, "NOTEACH");
    err(&p, "TEACH TOOLONG", 18);
    close(fd);
    stop(&p);
}

/* ---- I/O, gripper, settings, programs -------------------------------- */

static void t_io(void **st)
{
    simp p;
    const char *ctl = tmp("ctl-io");
    const char *const opts[] = {"--time-scale", "200", "--control", ctl, NULL};
    int fd;
    double t0;
    (void)st;
    start(&p, opts);
    ok(&p, "OUTPUT 1,3,-1,16");
    assert_string_equal(status_line(&p, "OUTPUTS"), "OUTPUTS 1-16: 0010000000000001");
    err(&p, "OUTPUT 17", 16);
    err(&p, "OUTPUT 0", 16);
    err(&p, "OUTPUT", 13);
    assert_string_equal(cmd(&p, "TYPEI OSIG(3)+OSIG(16)*10"), "11\r\n");
    assert_string_equal(cmd(&p, "TYPEI SIG(3)"), "0\r\n");
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "IN 3 1\n", 7), 7);
    usleep(100000);
    assert_string_equal(cmd(&p, "TYPEI SIG(3)"), "1\r\n");
    assert_string_equal(status_line(&p, "INPUTS"), "INPUTS  1-16: 0010000000000000");
    ok(&p, "WAIT 3,-4");
    /* WAIT blocks until the inputs match */
    puts_(&p, "WAIT -3\r");
    read_until(&p, g_buf, sizeof g_buf, ">>", 0.5);
    assert_string_equal(g_buf, "WAIT -3\r\n");
    t0 = now_s();
    assert_int_equal(write(fd, "IN 3 0\n", 7), 7);
    read_until(&p, g_buf, sizeof g_buf, ">>", TIMEOUT);
    assert_string_equal(g_buf, ">>");
    assert_true(now_s() - t0 < TIMEOUT);
    err(&p, "WAIT 20", 16);
    close(fd);
    stop(&p);
}

static void t_inputs_script(void **st)
{
    simp p;
    const char *script = tmp("inputs.txt");
    const char *const opts[] = {"--time-scale", "10", "--inputs", script, NULL};
    FILE *f = fopen(script, "w");
    (void)st;
    assert_non_null(f);
    fprintf(f, "# t IN n v\n0 IN 1 1\n5 IN 2 1\n5 IN 1 0\n");
    fclose(f);
    start(&p, opts);
    ok(&p, "WAIT 2,-1"); /* 5 simulated seconds = 0.5 s */
    assert_string_equal(status_line(&p, "INPUTS"), "INPUTS  1-16: 0100000000000000");
    stop(&p);
    /* a line fbrlsim does not understand stops it at start */
    f = fopen(script, "w");
    fprintf(f, "1 IN 17 1\n");
    fclose(f);
    {
        int pid = fork(), stt;
        if (pid == 0) {
            int dn = open("/dev/null", O_WRONLY);
            dup2(dn, 1);
            dup2(dn, 2);
            execl(FBRLSIM_PATH, FBRLSIM_PATH, "--inputs", script, (char *)NULL);
            _exit(127);
        }
        waitpid(pid, &stt, 0);
        assert_true(WIFEXITED(stt) && WEXITSTATUS(stt) == 1);
    }
}

static void t_gripper(void **st)
{
    simp p;
    const char *ctl = tmp("ctl-grip");
    const char *const opts[] = {"--time-scale", "200", "--control", ctl, NULL};
    int fd;
    (void)st;
    start(&p, opts);
    assert_string_equal(status_line(&p, "GRIPPER OPENING"),
                        "GRIPPER OPENING: +002.0000 FORCE (% OF FULL):    +50");
    ok(&p, "CLOSE 80");
    assert_string_equal(status_line(&p, "GRIPPER OPENING"),
                        "GRIPPER OPENING: +000.0000 FORCE (% OF FULL):    +80");
    ok(&p, "GRIP 1.25");
    assert_string_equal(cmd(&p, "TYPEV GRIPPER"), "+1.250000\r\n");
    ok(&p, "OPEN");
    err(&p, "GRIP 2.5", 20);
    err(&p, "GRIP -1", 18);
    err(&p, "CLOSE 101", 20);
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "OBJECT 0.75\n", 12), 12);
    usleep(100000);
    ok(&p, "CLOSE");
    assert_string_equal(cmd(&p, "TYPEV GRIPPER"), "+0.750000\r\n");
    ok(&p, "GRIP 0.5,30");
    assert_string_equal(status_line(&p, "GRIPPER OPENING"),
                        "GRIPPER OPENING: +000.7500 FORCE (% OF FULL):    +30");
    close(fd);
    stop(&p);
}

static void t_variables(void **st)
{
    simp p;
    (void)st;
    start(&p, FAST);
    ok(&p, "X=3*4+1");
    ok(&p, "Y = (X - 1) / 4");
    ok(&p, "GRIP=-2.5");
    assert_string_equal(cmd(&p, "TYPEI X"), "13\r\n");
    assert_string_equal(cmd(&p, "TYPEV Y"), "+3.000000\r\n");
    assert_string_equal(cmd(&p, "TYPEV SIN(30)+COS(60)+ABS(GRIP)+SQRT(16)+INT(-2.7)"), "+5.500000\r\n");
    assert_string_equal(cmd(&p, "TYPEI ATAN(1)"), "45\r\n");
    assert_string_equal(cmd(&p, "TYPE \"HELLO, WORLD\""), "HELLO, WORLD\r\n");
    assert_string_equal(cmd(&p, "LISTV"),
                        "GRIP     = -2.500000\r\nX        = +13.000000\r\nY        = +3.000000\r\n");
    assert_string_equal(cmd(&p, "LISTV X"), "X        = +13.000000\r\n");
    err(&p, "TYPEV Z", 10);
    err(&p, "TYPEV 1/0", 18);
    err(&p, "TYPEV (1", 14);
    err(&p, "TYPEV ASIN(2)", 18);
    err(&p, "TYPEV SIG(17)", 16);
    err(&p, "Z=", 14);
    err(&p, "TOOLONGNAME=1", 18);
    ok(&p, "SPEED Y*10");
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +30");
    ok(&p, "DVAR X");
    err(&p, "DVAR X", 10);
    err(&p, "TYPEI X", 10);
    stop(&p);
}

static void t_settings(void **st)
{
    simp p;
    (void)st;
    start(&p, FAST);
    assert_string_equal(cmd(&p, "SERIAL"),
                        "CHANNEL 0: BAUD 9600 PARITY N DATA 8 STOP 1 HANDSHAKE X ECHO 1\r\n"
                        "CHANNEL 1: BAUD 9600 PARITY N DATA 8 STOP 1 HANDSHAKE N ECHO 1\r\n");
    ok(&p, "CONFIG 1,2400,E,7,2,N,1");
    err(&p, "CONFIG 2,2400,E,7,2,N,1", 61);
    err(&p, "CONFIG 1,2401,E,7,2,N,1", 18);
    err(&p, "CONFIG 1,2400,Q,7,2,N,1", 18);
    err(&p, "CONFIG 1,2400,E,7,2,N", 13);
    assert_string_equal(cmd(&p, "SERIAL"),
                        "CHANNEL 0: BAUD 9600 PARITY N DATA 8 STOP 1 HANDSHAKE X ECHO 1\r\n"
                        "CHANNEL 1: BAUD 2400 PARITY E DATA 7 STOP 2 HANDSHAKE N ECHO 1\r\n");
    /* echo off on channel 0: only the reply comes back */
    assert_string_equal(raw(&p, "CONFIG 0,9600,N,8,1,X,OFF"), "CONFIG 0,9600,N,8,1,X,OFF\r\n>>");
    assert_string_equal(raw(&p, "SPEED 20"), "\r\n>>");
    assert_string_equal(raw(&p, "CONFIG 0,9600,N,8,1,X,ON"), "\r\n>>");
    assert_string_equal(raw(&p, "SPEED 21"), "SPEED 21\r\n>>");
    ok(&p, "GAIN 0,2.5");
    ok(&p, "GAIN 3,4");
    assert_string_equal(cmd(&p, "GAIN 3"), "GAIN MOTOR 3: +4.0000,+0.2500,+100.0000\r\n");
    assert_string_equal(cmd(&p, "GAIN 1"), "GAIN MOTOR 1: +2.5000,+0.2500,+100.0000\r\n");
    err(&p, "GAIN 7,1", 65);
    ok(&p, "FLASH 0.5");
    assert_string_equal(status_line(&p, "PENDANT"), "PENDANT LAMP IS FLASHING");
    ok(&p, "NOFLASH");
    assert_string_equal(status_line(&p, "PENDANT"), "PENDANT LAMP IS OFF");
    ok(&p, "MANUAL JOI");
    assert_string_equal(status_line(&p, "MANUAL"), "MANUAL MODE STATUS IS ON");
    ok(&p, "NOMANUAL");
    assert_string_equal(status_line(&p, "MANUAL"), "MANUAL MODE STATUS IS OFF");
    err(&p, "MANUAL XYZ", 18);
    err(&p, "HALT ON 3", 66);
    ok(&p, "HOME");
    err(&p, "MOTOR 1,10,ONHOME", 66);
    stop(&p);
}

/* Starts a continuous readout, takes its first value, stops it with CR. */
static long stream_value(simp *p, const char *command, const char *title)
{
    char *x;
    long v = -1;
    size_t n;
    puts_(p, command);
    puts_(p, "\r");
    n = read_until(p, g_buf, sizeof g_buf, NULL, 0.35);
    x = strstr(g_buf, title);
    if (!x || sscanf(x + strlen(title), "\r\n%ld", &v) != 1)
        fail_msg("%s: '%s'", command, g_buf);
    puts_(p, "\r");
    n = read_until(p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "\r\n>>"));
    return v;
}

static void t_streams_extra(void **st)
{
    simp p;
    size_t n;
    (void)st;
    start(&p, FAST);
    ok(&p, "HOME");
    /* W1: title, then lines ended by CR until any byte */
    puts_(&p, "W1\r");
    n = read_until(&p, g_buf, sizeof g_buf, NULL, 0.35);
    assert_true(n > 0);
    assert_int_equal(strncmp(g_buf,
                             "W1\r\nACTUAL POSITION (MOTOR PULSES):\r\n+0000000000 +0000018000 -0000018000 "
                             "+0000000000 +0000000000\r",
                             4 + 33 + 60),
                     0);
    puts_(&p, "\r");
    n = read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "\r\n>>"));
    /* the extra axis */
    err(&p, "XHOME 5", 65);
    ok(&p, "MOTOR 6,500");
    ok(&p, "FINISH");
    assert_int_equal(stream_value(&p, "WE1", "EXTRA AXIS ACTUAL (MOTOR PULSES):"), 500);
    ok(&p, "XCAL 6");
    ok(&p, "XZERO 6");
    assert_int_equal(stream_value(&p, "WE3", "EXTRA AXIS COMMAND (MOTOR PULSES):"), 0);
    ok(&p, "XHOME 6");
    ok(&p, "FINISH");
    assert_int_equal(stream_value(&p, "WE1", "EXTRA AXIS ACTUAL (MOTOR PULSES):"), 500);
    assert_int_equal(stream_value(&p, "WE5", "EXTRA AXIS VELOCITY (PULSES/SEC):"), 0);
    assert_int_equal(stream_value(&p, "W5", "VELOCITY (PULSES/SEC):"), 0);
    ok(&p, "JOINT 1,-10");
    ok(&p, "FINISH");
    assert_int_equal(stream_value(&p, "W3", "COMMAND POSITION (MOTOR PULSES):"), -2000);
    assert_int_equal(stream_value(&p, "W1", "ACTUAL POSITION (MOTOR PULSES):"), -2000);
    ok(&p, "SPEED 50");
    stop(&p);
}

static void t_run(void **st)
{
    simp p;
    const char *state = tmp("prog.state");
    const char *const opts[] = {"--time-scale", "200", "--state", state, NULL};
    FILE *f = fopen(state, "w");
    (void)st;
    assert_non_null(f);
    fprintf(f, "FBRLSIM-STATE 1\nVAR N 0\nPROGRAM COUNT\n  N=N+1\n  JOINT 1,1\nEND\n"
               "PROGRAM BAD\n  TYPE BEFORE\n  MOVE NOWHERE\n  TYPE AFTER\nEND\n");
    fclose(f);
    start(&p, opts);
    ok(&p, "HOME");
    ok(&p, "RUN COUNT,5");
    ok(&p, "FINISH");
    assert_string_equal(cmd(&p, "TYPEI N"), "5\r\n");
    assert_string_equal(cmd(&p, "TYPEI INT(0.5+1000*0)"), "0\r\n");
    {
        double w[6], j[5];
        where(&p, w, j, NULL);
        assert_true(fabs(j[0] - 5.0) < 1e-6);
    }
    assert_string_equal(cmd(&p, "RUN BAD"), "BEFORE\r\n011-LOCATION UNDEFINED.\r\n");
    err(&p, "RUN NONE", 17);
    err(&p, "RUN COUNT,0", 18);
    stop(&p);
    /* the programs are written back with the rest of the memory */
    {
        char text[4096];
        size_t n;
        f = fopen(state, "r");
        assert_non_null(f);
        n = fread(text, 1, sizeof text - 1, f);
        text[n] = 0;
        fclose(f);
        assert_non_null(strstr(text, "\nVAR N 5\n"));
        assert_non_null(strstr(text, "\nPROGRAM COUNT\n  N=N+1\n  JOINT 1,1\nEND\n"));
        assert_non_null(strstr(text, "\nPROGRAM BAD\n  TYPE BEFORE\n  MOVE NOWHERE\n  TYPE AFTER\nEND\n"));
    }
}

/* A person managing programs at the controller's terminal (S11's lab steps): FREE, EDIT
 * and lines typed in edit mode (kept, never run: the command log is the proof), DIR,
 * LISTP, RUN, the program table's 16, and all of it kept in the state file. */
static void t_programs(void **st)
{
    simp p;
    const char *state = tmp("progs.state"), *log = tmp("progs.log");
    const char *const opts[] = {"--time-scale", "200", "--state", state, "--log", log, NULL};
    char name[16];
    int i;
    (void)st;
    start(&p, opts);
    assert_string_equal(cmd(&p, "FREE"), "PROGRAMS  : 00000 OF 00016\r\n"
                                         "VARIABLES : 00000 OF 00100\r\n"
                                         "LOCATIONS : 00000 OF 00100\r\n");
    err(&p, "EDIT", 13); /* no program named yet */
    ok(&p, "POINT P1,14,2,8,0,-90,0");
    ok(&p, "EDIT PICK");
    /* not homed: each of these would answer 041 if it ran */
    assert_string_equal(raw(&p, "APPRO P1,2"), "APPRO P1,2\r\n>>");
    assert_string_equal(raw(&p, "MOVE P1"), "MOVE P1\r\n>>");
    assert_string_equal(raw(&p, ""), "\r\n>>"); /* an empty line ends edit mode */
    err(&p, "MOVE P1", 41);                     /* typed again: runs */
    ok(&p, "EDIT");                             /* the same program, lines go on */
    assert_string_equal(raw(&p, "V1=V1+1"), "V1=V1+1\r\n>>");
    assert_string_equal(raw(&p, ""), "\r\n>>");
    assert_string_equal(cmd(&p, "LISTP PICK"), "#00001 APPRO P1,2\r\n#00002 MOVE P1\r\n#00003 V1=V1+1\r\n");
    assert_string_equal(cmd(&p, "DIR"), "PICK     00003 LINES 00027 BYTES\r\n");
    assert_string_equal(cmd(&p, "FREE"), "PROGRAMS  : 00001 OF 00016\r\n"
                                         "VARIABLES : 00000 OF 00100\r\n"
                                         "LOCATIONS : 00001 OF 00100\r\n");
    err(&p, "LISTP NOPE", 17);
    err(&p, "LISTP PICK,1", 18); /* the printer channel: not there */
    err(&p, "FREE 1", 18);
    err(&p, "DIR 1", 18);
    ok(&p, "V1=0");
    ok(&p, "HOME");
    ok(&p, "RUN PICK");
    ok(&p, "FINISH");
    assert_string_equal(cmd(&p, "TYPEI V1"), "1\r\n");
    for (i = 2; i <= 16; i++) { /* the table holds 16 programs */
        snprintf(name, sizeof name, "EDIT Q%d", i);
        ok(&p, name);
        assert_string_equal(raw(&p, ""), "\r\n>>");
    }
    err(&p, "EDIT Q17", 22);
    assert_string_equal(cmd(&p, "DIR"), "PICK     00003 LINES 00027 BYTES\r\n"
                                        "Q10      00000 LINES 00000 BYTES\r\n"
                                        "Q11      00000 LINES 00000 BYTES\r\n"
                                        "Q12      00000 LINES 00000 BYTES\r\n"
                                        "Q13      00000 LINES 00000 BYTES\r\n"
                                        "Q14      00000 LINES 00000 BYTES\r\n"
                                        "Q15      00000 LINES 00000 BYTES\r\n"
                                        "Q16      00000 LINES 00000 BYTES\r\n"
                                        "Q2       00000 LINES 00000 BYTES\r\n"
                                        "Q3       00000 LINES 00000 BYTES\r\n"
                                        "Q4       00000 LINES 00000 BYTES\r\n"
                                        "Q5       00000 LINES 00000 BYTES\r\n"
                                        "Q6       00000 LINES 00000 BYTES\r\n"
                                        "Q7       00000 LINES 00000 BYTES\r\n"
                                        "Q8       00000 LINES 00000 BYTES\r\n"
                                        "Q9       00000 LINES 00000 BYTES\r\n");
    stop(&p);
    start(&p, opts); /* kept in the state file */
    assert_string_equal(cmd(&p, "LISTP PICK"), "#00001 APPRO P1,2\r\n#00002 MOVE P1\r\n#00003 V1=V1+1\r\n");
    stop(&p);
    {
        /* the log: the lines kept in edit mode are marked, not logged as commands run */
        char text[8192];
        size_t n;
        FILE *f = fopen(log, "r");
        assert_non_null(f);
        n = fread(text, 1, sizeof text - 1, f);
        text[n] = 0;
        fclose(f);
        assert_non_null(strstr(text, "\n# EDIT PICK: APPRO P1,2\n# EDIT PICK: MOVE P1\nMOVE P1\nEDIT\n"));
        assert_null(strstr(text, "\nAPPRO P1,2\n"));
    }
}

/* ---- persistence ----------------------------------------------------- */

static void t_persist(void **st)
{
    simp p;
    const char *state = tmp("persist.state");
    const char *const opts[] = {"--time-scale", "200", "--state", state, NULL};
    struct stat sb;
    double w[6];
    (void)st;
    start(&p, opts);
    ok(&p, "HOME");
    ok(&p, "POINT P1,10,5,4,0,-90,30");
    ok(&p, "POINT #Q,1,2,3,4,5");
    ok(&p, "V1=42.5");
    ok(&p, "OUTPUT 2,15");
    ok(&p, "SPEED 33");
    ok(&p, "GRIP 1.5");
    ok(&p, "CONFIG 1,4800,O,7,1,N,0");
    ok(&p, "GAIN 2,5,.5,90");
    ok(&p, "MOVE P1");
    ok(&p, "FINISH");
    stop(&p);
    assert_int_equal(stat(tmp("persist.state.tmp"), &sb), -1); /* no temporary left behind */
    start(&p, opts);
    assert_string_equal(status_line(&p, "CONTROLLER"), "CONTROLLER IS NOT HOMED");
    assert_string_equal(cmd(&p, "LISTL"),
                        "P1        +010.0000 +005.0000 +004.0000 +000.0000 -090.0000 +030.0000\r\n"
                        "#Q        +0000000001 +0000000002 +0000000003 +0000000004 +0000000005\r\n");
    assert_string_equal(cmd(&p, "TYPEV V1"), "+42.500000\r\n");
    assert_string_equal(status_line(&p, "OUTPUTS"), "OUTPUTS 1-16: 0100000000000010");
    assert_string_equal(status_line(&p, "SPEED"), "SPEED (% OF FULL) :    +33");
    assert_string_equal(cmd(&p, "TYPEV GRIPPER"), "+1.500000\r\n");
    assert_string_equal(cmd(&p, "SERIAL"),
                        "CHANNEL 0: BAUD 9600 PARITY N DATA 8 STOP 1 HANDSHAKE X ECHO 1\r\n"
                        "CHANNEL 1: BAUD 4800 PARITY O DATA 7 STOP 1 HANDSHAKE N ECHO 0\r\n");
    assert_string_equal(cmd(&p, "GAIN 2"), "GAIN MOTOR 2: +5.0000,+0.5000,+90.0000\r\n");
    /* the arm is where it stopped */
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[0] - 10) < 0.001 && fabs(w[1] - 5) < 0.001 && fabs(w[2] - 4) < 0.001);
    stop(&p);
    /* a damaged state file is refused, not silently replaced */
    {
        FILE *f = fopen(state, "a");
        int pid, stt;
        fputs("GARBAGE LINE\n", f);
        fclose(f);
        pid = fork();
        if (pid == 0) {
            int dn = open("/dev/null", O_WRONLY);
            dup2(dn, 1);
            dup2(dn, 2);
            execl(FBRLSIM_PATH, FBRLSIM_PATH, "--state", state, (char *)NULL);
            _exit(127);
        }
        waitpid(pid, &stt, 0);
        assert_true(WIFEXITED(stt) && WEXITSTATUS(stt) == 1);
    }
}

/* Runs fbrlsim with a state file that must be refused: exit status 1 and a message
 * naming file:line on stderr. */
static void refused_state(const char *state, const char *where)
{
    int pfd[2], stt;
    pid_t pid;
    size_t n = 0;
    ssize_t r;
    char msg[1024];
    assert_int_equal(pipe(pfd), 0);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        int dn = open("/dev/null", O_WRONLY);
        dup2(dn, 1);
        dup2(pfd[1], 2);
        close(pfd[0]);
        alarm(5); /* an accepted file would let it run forever */
        execl(FBRLSIM_PATH, FBRLSIM_PATH, "--state", state, (char *)NULL);
        _exit(127);
    }
    close(pfd[1]);
    while (n < sizeof msg - 1 && (r = read(pfd[0], msg + n, sizeof msg - 1 - n)) > 0)
        n += (size_t)r;
    msg[n] = 0;
    close(pfd[0]);
    assert_int_equal(waitpid(pid, &stt, 0), pid);
    if (!WIFEXITED(stt) || WEXITSTATUS(stt) != 1)
        fail_msg("state line '%s' was accepted (status %d)", where, stt);
    {
        char want[512];
        snprintf(want, sizeof want, "%s:2: ", state);
        if (!strstr(msg, want))
            fail_msg("state line '%s': message without %s: %s", where, want, msg);
    }
}

/* Each junk value is refused with file:line, and the file is left as it was. */
static void t_state_junk(void **st)
{
    static const char *const junk[] = {
        "SPEED nan",
        "SPEED inf",
        "SPEED -inf",
        "SPEED 101",
        "SPEED 0",
        "SPEED 50x",
        "SPEED 50 7",
        "SPEED 1e999",
        "SPEED",
        "JOINTS 0 90 -90 0 nan",
        "JOINTS 0 90 -90 0",
        "JOINTS 0 90 -90 0 0 0",
        "JOINTS 0 200 -90 0 0",
        "CONFIG 0 -9223372036854775808 N 8 1 X 1",
        "CONFIG 0 99999999999999999999 N 8 1 X 1",
        "CONFIG 0 9600 N 8 1 X 1 junk",
        "CONFIG 2 9600 N 8 1 X 1",
        "CONFIG 0 9600.5 N 8 1 X 1",
        "CONFIG 0 9600 Q 8 1 X 1",
        "CONFIG 0 9600 N 9 1 X 1",
        "CONFIG 0 9600 N 8 1 X 7",
        "GAIN 1 1e999",
        "GAIN 9 1",
        "GAIN 1 -1",
        "GAIN 1 0x10",
        "GAIN 1 8 0.25",
        "GAIN 1 8 0.25 100 7",
        "GAIN 1 8 -0.25 100",
        "VAR V1 -inf",
        "VAR V1 nan",
        "VAR 1X 3",
        "VAR TOOLONGNAME 1",
        "VAR V1 1 2",
        "PLOC P 1 2 3 4 99999999999",
        "PLOC P 1 2 3 4 5.5",
        "PLOC P 1 2 3 4",
        "LOC P 1 2 3 4 5 nan",
        "LOC P 1 2 3 4 5",
        "LOC P 1 2 3 4 5 6 7",
        "EXTRA 1e300 0",
        "EXTRA 0 inf",
        "GRIPPER 3 50",
        "GRIPPER 1 0",
        "GRIPPER 1 50 x",
        "OUTPUTS 01",
        "OUTPUTS 000000000000000x",
        "FLASH 2",
        "FLASH -1",
        "FLASH 1 1",
        "TOOL T 0 0 1 0 0 0 x",
        "TOOL T 0 0 nan 0 0 0",
        "PROGRAM P junk",
        "PROGRAM",
        "FOO 1",
        "SPEED\t50\tjunk",
    };
    const char *state = tmp("junk.state");
    size_t i;
    (void)st;
    for (i = 0; i < sizeof junk / sizeof junk[0]; i++) {
        FILE *f = fopen(state, "w");
        char text[256], back[256];
        size_t n;
        snprintf(text, sizeof text, "FBRLSIM-STATE 1\n%s\nSPEED 50\n", junk[i]);
        assert_non_null(f);
        fputs(text, f);
        fclose(f);
        refused_state(state, junk[i]);
        f = fopen(state, "r");
        n = fread(back, 1, sizeof back - 1, f);
        back[n] = 0;
        fclose(f);
        assert_string_equal(back, text); /* not overwritten */
    }
    {
        /* a duplicate name, a program without END and a program line too long, too */
        static const char *const late[] = {"VAR A 1\nVAR A 2\n", "LOC P 1 2 3 4 5 6\nLOC P 1 2 3 4 5 6\n",
                                           "PROGRAM P\n  HOME\n"};
        for (i = 0; i < sizeof late / sizeof late[0]; i++) {
            FILE *f = fopen(state, "w");
            int pid, stt;
            fprintf(f, "FBRLSIM-STATE 1\n%s", late[i]);
            fclose(f);
            pid = fork();
            if (pid == 0) {
                int dn = open("/dev/null", O_WRONLY);
                dup2(dn, 1);
                dup2(dn, 2);
                execl(FBRLSIM_PATH, FBRLSIM_PATH, "--state", state, (char *)NULL);
                _exit(127);
            }
            waitpid(pid, &stt, 0);
            assert_true(WIFEXITED(stt) && WEXITSTATUS(stt) == 1);
        }
    }
}

/* A symlink planted where the old fixed temporary name was (and the directory's
 * other files) is never written through; no temporary is left behind. */
static void t_state_symlink(void **st)
{
    const char *state = tmp("sym.state"), *victim = tmp("victim"), *planted = tmp("sym.state.tmp");
    const char *const opts[] = {"--time-scale", "200", "--state", state, NULL};
    simp p;
    FILE *f = fopen(victim, "w");
    char back[64];
    size_t n;
    struct stat sb;
    int i;
    (void)st;
    fputs("precious\n", f);
    fclose(f);
    assert_int_equal(symlink(victim, planted), 0);
    start(&p, opts);
    for (i = 0; i < 20; i++) {
        char c[64];
        snprintf(c, sizeof c, "POINT P%d,%d,1,2,0,-90,0", i, i);
        ok(&p, c);
    }
    stop(&p);
    f = fopen(victim, "r");
    n = fread(back, 1, sizeof back - 1, f);
    back[n] = 0;
    fclose(f);
    assert_string_equal(back, "precious\n");
    assert_int_equal(lstat(planted, &sb), 0);
    assert_true(S_ISLNK(sb.st_mode)); /* left alone */
    assert_int_equal(lstat(state, &sb), 0);
    assert_true(S_ISREG(sb.st_mode));
    {
        /* only the state, the victim and the planted link: no temporary left */
        char c[512];
        snprintf(c, sizeof c, "test $(ls -A '%s' | grep -c '^sym.state') -eq 2", g_dir);
        assert_int_equal(system(c), 0);
    }
    start(&p, opts);
    assert_non_null(strstr(cmd(&p, "LISTL P19"), "+019.0000"));
    stop(&p);
}

/* Names are upper-cased wherever they enter memory: a program written in lower case
 * defines upper-case names, the state it saves loads again, and RUN still works. */
static void t_state_lowercase(void **st)
{
    const char *state = tmp("lower.state");
    const char *const opts[] = {"--time-scale", "200", "--state", state, NULL};
    simp p;
    FILE *f = fopen(state, "w");
    int i;
    (void)st;
    fputs("FBRLSIM-STATE 1\nvar count 0\nPROGRAM teach\n  here p1\n  point #q2,1,2,3,4,5\n"
          "  set p3=p1\n  count=count+1\n  type done\nEND\n",
          f);
    fclose(f);
    for (i = 0; i < 2; i++) {
        start(&p, opts);
        ok(&p, "HOME");
        assert_string_equal(cmd(&p, "RUN TEACH"), "DONE\r\n");
        assert_string_equal(cmd(&p, "LISTL #Q2"),
                            "#Q2       +0000000001 +0000000002 +0000000003 +0000000004 +0000000005\r\n");
        assert_non_null(strstr(cmd(&p, "LISTL"), "P1 "));
        assert_non_null(strstr(cmd(&p, "LISTL P3"), "P3 "));
        assert_string_equal(cmd(&p, "TYPEI COUNT"), i ? "2\r\n" : "1\r\n");
        stop(&p); /* saves; the second round loads what was saved */
    }
    {
        char text[4096];
        size_t n;
        f = fopen(state, "r");
        n = fread(text, 1, sizeof text - 1, f);
        text[n] = 0;
        fclose(f);
        assert_non_null(strstr(text, "\nPLOC Q2 1 2 3 4 5\n"));
        assert_non_null(strstr(text, "\nPROGRAM TEACH\n  HERE P1\n"));
        assert_null(strstr(text, " p1"));
    }
}

/* ---- baud pacing and overrun ----------------------------------------- */

static char *slurp(const char *path);

static void t_baud(void **st)
{
    const char *ctl = tmp("ctl-baud"), *out = tmp("ctl-baud.out");
    const char *const opts[] = {"--time-scale",  "1", "--baud", "9600", "--control", ctl,
                                "--control-out", out, NULL};
    simp p;
    double t0, dt;
    size_t n, i, k, bytes;
    int xoff = 0, xon = 0;
    char big[301];
    (void)st;
    start(&p, opts);
    /* STATUS is about 900 characters: at 960 characters per second, about 0.9 s */
    puts_(&p, "STATUS\r");
    t0 = now_s();
    n = read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    dt = now_s() - t0;
    bytes = n;
    assert_true(ends_with(g_buf, n, "\r\n>>"));
    assert_true(dt >= 0.7 * (double)bytes / 960.0);
    /* overrun: while a motion command waits, input piles up in the 128-byte buffer */
    ok(&p, "HOME");
    ok(&p, "SPEED 10");
    ok(&p, "JOINT 1,10"); /* 10 deg at 6 deg/s: 1.7 s */
    puts_(&p, "JOINT 1,-10\r");
    memset(big, 'A', 300);
    big[300] = 0;
    memcpy(big, "TYPE ", 5);
    usleep(50000);
    puts_(&p, big);
    puts_(&p, "\r");
    /* the motion ends after about 1.7 s; then the buffered bytes are processed */
    n = read_until(&p, g_buf, sizeof g_buf, NULL, 4.0);
    /* the CR may have been lost in the overrun: end the line again */
    puts_(&p, "\r");
    n += read_until(&p, g_buf + n, sizeof g_buf - n, "\r\n>>", TIMEOUT);
    for (i = 0, k = 0; i < n; i++) {
        if (g_buf[i] == 0x13)
            xoff++;
        if (g_buf[i] == 0x11)
            xon++;
        if (g_buf[i] == 'A')
            k++;
    }
    assert_true(xoff >= 1);
    assert_true(xon >= 1);
    assert_true(k > 0);
    {
        /* this host's tty has no IXON: its port ignores XOFF, characters overrun */
        char *text;
        long over = -1;
        int fd = open(ctl, O_WRONLY);
        assert_true(fd >= 0);
        assert_int_equal(write(fd, "GET LINE\n", 9), 9);
        close(fd);
        usleep(200000);
        text = slurp(out);
        assert_int_equal(sscanf(text, "LINE OVERRUNS %ld", &over), 1);
        assert_true(over > 100); /* of 300, at most the buffer's 128 fit */
        free(text);
    }
    stop(&p);
}

/* ---- the strict line ------------------------------------------------- */

/* How late this test or the emulator may be woken by the OS (the machine is shared).
 * Bytes handed over late bunch up at the receiver; that is the only slack the window
 * check allows. The cumulative checks allow nothing: lateness can only make them
 * hold more easily, earliness breaks them. */
#define LATENESS 0.010 /* s: the least allowance, also on an idle machine */
#define WINDOW   0.100

/* How late the OS wakes a thread of this process while the flood runs: a thread sleeps
 * 1 ms at a time and records its worst oversleep. The emulator competes for the same
 * CPUs, so twice this bounds how late either side handled bytes. */
static volatile int g_probe_run;
static double g_probe_late;

static void *late_probe(void *arg)
{
    (void)arg;
    g_probe_late = 0;
    while (g_probe_run) {
        double t0 = now_s(), late;
        usleep(1000);
        late = now_s() - t0 - 0.001;
        if (late > g_probe_late)
            g_probe_late = late;
    }
    return NULL;
}

/* fbrlsim hands over at most about 1 ms of characters at once (at least 2) when the OS
 * woke it late (docs/fbrlsim.md): a fixed allowance, not one that grows with lateness. */
static size_t burst(double rate)
{
    double c = ceil(0.001 * rate);
    return c > 2 ? (size_t)c : 2;
}

static double lateness(void) { return 2.0 * g_probe_late > LATENESS ? 2.0 * g_probe_late : LATENESS; }

typedef struct arrivals {
    double *t; /* when each read returned */
    size_t *n; /* how many bytes (or prompts) it brought */
    size_t k, cap;
} arrivals;

static void arr_add(arrivals *a, double t, size_t n)
{
    if (a->k == a->cap) {
        a->cap = a->cap ? 2 * a->cap : 1024;
        a->t = realloc(a->t, a->cap * sizeof *a->t);
        a->n = realloc(a->n, a->cap * sizeof *a->n);
        assert_non_null(a->t);
        assert_non_null(a->n);
    }
    a->t[a->k] = t;
    a->n[a->k++] = n;
}

/* The most units that arrived in any window of length w that starts at a read, not
 * counting that read's own units: a read takes everything waiting, so what it brought
 * may have piled up while this test or the OS was late, but what the later reads
 * bring cannot have arrived before it. */
static size_t max_window(const arrivals *a, double w)
{
    size_t i, j = 0, sum = 0, best = 0;
    for (i = 1; i < a->k; i++) {
        sum += a->n[i];
        while (j + 1 <= i && a->t[i] - a->t[j] > w) {
            j++;
            sum -= a->n[j];
        }
        if (sum > best)
            best = sum;
    }
    return best;
}

/* Sends `count` copies of line (with CR) as fast as the pty takes them, never waiting
 * for an echo, and records when the output bytes and the prompts arrive. */
static double g_flood_t0; /* just before flood()'s first write: no byte left earlier */

static void flood(simp *p, const char *line, int count, arrivals *bytes, arrivals *prompts)
{
    char out[8192];
    size_t len = strlen(line), sent = 0, total = (size_t)count * (len + 1), got_prompts = 0;
    char *all = malloc(total);
    double end = now_s() + 60.0;
    int prev_gt = 0, i;
    assert_non_null(all);
    for (i = 0; i < count; i++) {
        memcpy(all + (size_t)i * (len + 1), line, len);
        all[(size_t)i * (len + 1) + len] = '\r';
    }
    pthread_t probe;
    fcntl(p->fd, F_SETFL, fcntl(p->fd, F_GETFL) | O_NONBLOCK);
    g_probe_run = 1;
    assert_int_equal(pthread_create(&probe, NULL, late_probe, NULL), 0);
    g_flood_t0 = now_s();
    while (got_prompts < (size_t)count && now_s() < end) {
        struct pollfd pf = {p->fd, (short)(POLLIN | (sent < total ? POLLOUT : 0)), 0};
        if (poll(&pf, 1, 100) <= 0)
            continue;
        if ((pf.revents & POLLOUT) && sent < total) {
            ssize_t w = write(p->fd, all + sent, total - sent);
            if (w > 0)
                sent += (size_t)w;
        }
        if (pf.revents & POLLIN) {
            ssize_t r = read(p->fd, out, sizeof out);
            double t = now_s();
            size_t np = 0;
            if (r <= 0)
                continue;
            for (i = 0; i < r; i++) {
                if (out[i] == '>' && prev_gt)
                    np++;
                prev_gt = out[i] == '>' && !prev_gt;
            }
            arr_add(bytes, t, (size_t)r);
            if (np)
                arr_add(prompts, t, np);
            got_prompts += np;
        }
    }
    g_probe_run = 0;
    pthread_join(probe, NULL);
    fcntl(p->fd, F_SETFL, fcntl(p->fd, F_GETFL) & ~O_NONBLOCK);
    free(all);
    assert_int_equal(got_prompts, count);
}

/* With --baud N: no direction carries more than N/10 bytes per second over any window
 * (measured here, on the receiving side, with real clocks), and no byte arrives before
 * its start plus ten bit times, not even after the line was idle. */
static void t_strict(void **st)
{
    static const long bauds[] = {9600, 38400, 115200};
    size_t b;
    (void)st;
    for (b = 0; b < sizeof bauds / sizeof bauds[0]; b++) {
        char baud[16];
        /* over TCP (the same line model, sim_line.c): on loopback the emulator's write()
         * delivers to this socket itself, while a pty's data waits for a kernel worker
         * thread, seen holding back 10 ms of a loaded line (40 bytes at once at 38400)
         * with no CPU pressure to show for it */
        const char *const opts[] = {"--tcp", "0",           "--time-scale", "200", "--baud",
                                    baud,    "--rx-buffer", "65536",        NULL};
        double rate = (double)bauds[b] / 10.0, bit10 = 1.0 / rate, fastest = 1e9;
        arrivals out = {0}, prompts = {0}, in = {0}, inprompts = {0};
        size_t most, allowed, k;
        int i, cmds = (int)(rate * 0.6 / 14.0); /* 0.6 s of output: "TYPEI 1" -> 14 bytes back */
        simp p;
        snprintf(baud, sizeof baud, "%ld", bauds[b]);
        start(&p, opts);
        /* one character after an idle line: its echo needs two character times */
        for (i = 0; i < 20; i++) {
            double t0;
            usleep(20000);
            t0 = now_s();
            puts_(&p, "A");
            assert_int_equal(read_until(&p, g_buf, sizeof g_buf, "A", TIMEOUT), 1);
            if (now_s() - t0 < fastest)
                fastest = now_s() - t0;
            puts_(&p, "\b");
            read_until(&p, g_buf, sizeof g_buf, "\b \b", TIMEOUT);
        }
        if (fastest < 2.0 * bit10)
            fail_msg("%ld baud: an echo came back after %.3f ms, before two character times (%.3f ms)",
                     bauds[b], fastest * 1e3, 2e3 * bit10);
        /* controller -> host, saturated: the host sends without waiting for echoes */
        flood(&p, "TYPEI 1", cmds, &out, &prompts);
        most = max_window(&out, WINDOW);
        allowed = (size_t)floor((WINDOW + lateness()) * rate) + 1 + burst(rate);
        print_message("%6ld baud, output: at most %zu bytes in a 100 ms window (N/10 per 100 ms = %.0f, "
                      "ratio %.3f; allowed with %.0f ms lateness %zu); fastest echo %.3f ms >= %.3f ms\n",
                      bauds[b], most, rate * WINDOW, most / (rate * WINDOW), lateness() * 1e3, allowed,
                      fastest * 1e3, 2e3 * bit10);
        if (most > allowed)
            fail_msg("%ld baud: %zu bytes in 100 ms, the line carries %.0f", bauds[b], most, rate * WINDOW);
        /* strict: the first byte back is the echo of the first byte sent (two character
         * times), and each later one at least one character time after it */
        for (k = 0, i = 0; i < (int)out.k; i++) {
            k += out.n[i];
            if ((double)k > (out.t[i] - g_flood_t0) / bit10 - 1.0)
                fail_msg("%ld baud: %zu bytes back %.3f ms after the first was sent: faster than the line",
                         bauds[b], k, (out.t[i] - g_flood_t0) * 1e3);
        }
        /* host -> controller, saturated: echo off, so each 9-byte command gives only
         * CR LF >> back and the input side limits; commands done per window tell how
         * many bytes the controller took in */
        ok(&p, "CONFIG 0,9600,N,8,1,X,0");
        cmds = (int)(rate * 0.6 / 9.0);
        flood(&p, "SPEED 50", cmds, &in, &inprompts);
        most = max_window(&inprompts, WINDOW);
        allowed = (size_t)floor(((WINDOW + lateness()) * rate + (double)burst(rate)) / 9.0) + 1;
        print_message(
            "%6ld baud, input: at most %zu commands = %zu bytes taken in a 100 ms window (N/10 per 100 ms "
            "= %.0f, ratio %.3f; allowed with %.0f ms lateness %zu commands)\n",
            bauds[b], most, most * 9, rate * WINDOW, most * 9 / (rate * WINDOW), lateness() * 1e3, allowed);
        if (most > allowed)
            fail_msg("%ld baud: %zu commands of 9 bytes in 100 ms, the line carries %.0f bytes", bauds[b],
                     most, rate * WINDOW);
        /* strict: command m's CR is byte 9(m+1) sent; its CR LF >> takes four more */
        for (k = 0, i = 0; i < (int)inprompts.k; i++) {
            k += inprompts.n[i];
            if (inprompts.t[i] - g_flood_t0 < (9.0 * (double)k + 4.0) * bit10)
                fail_msg(
                    "%ld baud: %zu commands done %.3f ms after the first byte was sent: faster than the line",
                    bauds[b], k, (inprompts.t[i] - g_flood_t0) * 1e3);
        }
        free(out.t);
        free(out.n);
        free(prompts.t);
        free(prompts.n);
        free(in.t);
        free(in.n);
        free(inprompts.t);
        free(inprompts.n);
        stop(&p);
    }
}

/* --cmd-time: the controller reads a line for that long (simulated ms) before the
 * reply starts. */
static void t_cmd_time(void **st)
{
    static const char *const opts[] = {"--time-scale", "2", "--cmd-time", "200", NULL};
    simp p;
    double t0, dt;
    (void)st;
    start(&p, opts); /* NOHELP too waited */
    t0 = now_s();
    ok(&p, "SPEED 30");
    dt = now_s() - t0;
    assert_true(dt >= 0.1); /* 200 simulated ms at time scale 2 */
    assert_true(dt < 5.0);
    stop(&p);
}

/* ---- faults ---------------------------------------------------------- */

static size_t exchange(simp *p, const char *line, double wait)
{
    puts_(p, line);
    puts_(p, "\r");
    return read_until(p, g_buf, sizeof g_buf, "\r\n>>", wait);
}

static void t_faults(void **st)
{
    static const char *const clean[] = {"--time-scale", "200", "--faults", "drop=0,corrupt=0,noise=0,seed=3",
                                        NULL};
    static const char *const noisy[] = {"--time-scale", "200", "--faults", "corrupt=0.05,seed=7", NULL};
    static const char *const drops[] = {"--time-scale", "200", "--faults", "drop=0.05,noise=0.05,seed=9",
                                        NULL};
    static const char *const stall[] = {"--time-scale", "200", "--faults", "stall=400", NULL};
    simp p;
    int i, bad = 0;
    double t0;
    (void)st;
    /* disabled faults: every byte exact */
    spawn(&p, clean);
    assert_string_equal(raw(&p, "NOHELP"), "NOHELP\r\n>>");
    for (i = 0; i < 50; i++)
        assert_string_equal(
            raw(&p, "TYPE ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"),
            "TYPE ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789\r\nABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789\r\n>>");
    stop(&p);
    /* corrupted bytes: some exchanges differ from the clean text */
    for (i = 0; i < 2; i++) {
        int k;
        spawn(&p, i == 0 ? noisy : drops);
        bad = 0;
        for (k = 0; k < 30; k++) {
            exchange(&p, "TYPE ABCDEFGHIJKLMNOPQRSTUVWXYZ", 0.3);
            if (strcmp(g_buf, "TYPE ABCDEFGHIJKLMNOPQRSTUVWXYZ\r\nABCDEFGHIJKLMNOPQRSTUVWXYZ\r\n>>") != 0 &&
                strstr(g_buf, "HELP") == NULL)
                bad++;
        }
        assert_true(bad > 0);
        stop(&p);
    }
    /* stall: the reply is held back */
    spawn(&p, stall);
    t0 = now_s();
    exchange(&p, "NOHELP", TIMEOUT);
    assert_true(now_s() - t0 >= 0.35);
    assert_string_equal(g_buf, "NOHELP\r\n>>");
    stop(&p);
}

/* --parity E: a corrupted byte is never an altered byte. Inbound the controller drops
 * it (the log shows "# PARITY ERROR IN", and no executed line holds a character that
 * was not sent); outbound it comes as 0xFF 0x00 X (PARMRK), X one bit away from a
 * byte the controller meant, and every unmarked byte is one it meant. With parity N
 * the same faults alter bytes. */
static int one_bit_from(unsigned char x, const char *set)
{
    for (; *set; set++) {
        unsigned d = x ^ (unsigned char)*set;
        if (d && !(d & (d - 1)))
            return 1;
    }
    return 0;
}

static void t_parity(void **st)
{
    const char *log = tmp("parity.log");
    const char *const opts[] = {"--time-scale",        "200", "--log", log, "--parity", "E", "--faults",
                                "corrupt=0.05,seed=5", NULL};
    const char *const opts_n[] = {"--time-scale",        "200", "--parity", "N", "--faults",
                                  "corrupt=0.05,seed=5", NULL};
    /* no space: no HELP-mode hint; a line cut by a lost byte may give an error line */
    static const char sent[] = "V1=1234567890";
    static const char meant[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789=-. \r\n>";
    char buf[4096], line[256];
    simp p;
    int k, marks = 0, in = 0, lines = 0, altered = 0;
    size_t n, i;
    FILE *f;
    (void)st;
    remove(log);
    spawn(&p, opts);
    for (k = 0; k < 40; k++) {
        puts_(&p, sent);
        puts_(&p, "\r");
        n = read_until(&p, buf, sizeof buf, "\r\n>>", 0.3);
        for (i = 0; i < n; i++) {
            unsigned char b = (unsigned char)buf[i];
            if (b == 0xFF) {
                assert_true(i + 2 < n + 1 && (unsigned char)buf[i + 1] == 0x00);
                assert_true(i + 2 < n);
                assert_true(one_bit_from((unsigned char)buf[i + 2], meant));
                marks++;
                i += 2;
            } else {
                assert_non_null(strchr(meant, b));
            }
        }
    }
    stop(&p);
    /* parity N: the same faults alter bytes */
    spawn(&p, opts_n);
    for (k = 0; k < 40; k++) {
        puts_(&p, "\x18");
        puts_(&p, sent);
        puts_(&p, "\r");
        n = read_until(&p, buf, sizeof buf, "\r\n>>", 0.3);
        for (i = 0; i < n; i++)
            altered += !strchr(meant, buf[i]) && buf[i] != '\b';
    }
    stop(&p);
    assert_true(marks > 0);
    assert_true(altered > 0);
    f = fopen(log, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        if (!strcmp(line, "# PARITY ERROR IN")) {
            in++;
            continue;
        }
        if (!strcmp(line, "# PARITY ERROR OUT"))
            continue;
        lines++;
        for (i = 0; line[i]; i++)
            if (!strchr(sent, line[i]))
                fail_msg("executed line '%s' holds a byte that was not sent", line);
    }
    fclose(f);
    assert_true(in > 0);
    assert_true(lines > 0);
}

/* Random keystrokes (no W: WAIT could wait for ever): the emulator survives
 * and still answers afterwards. Runs under the sanitizers in CI. */
static void t_garbage(void **st)
{
    static const char alphabet[] =
        "ABCDEFGHIJKLMNOPQSTUVXYZ0123456789 ,.-+*/()=#\"\r\r\r\b\x18\x7f\x01\x13\x11";
    simp p;
    unsigned long x = 99;
    char chunk[256];
    int i, k;
    (void)st;
    start(&p, FAST);
    ok(&p, "HOME");
    for (i = 0; i < 200; i++) {
        for (k = 0; k < (int)sizeof chunk; k++) {
            x = x * 6364136223846793005UL + 1442695040888963407UL;
            chunk[k] = alphabet[(x >> 33) % (sizeof alphabet - 1)];
        }
        put(&p, chunk, sizeof chunk);
        read_until(&p, g_buf, sizeof g_buf, NULL, 0.005); /* keep the pty drained */
    }
    puts_(&p, "\x11\x18\r");
    read_until(&p, g_buf, sizeof g_buf, NULL, 1.0);
    puts_(&p, "\x11\x18");
    read_until(&p, g_buf, sizeof g_buf, NULL, 0.3);
    ok(&p, "NOHELP");
    ok(&p, "FINISH");
    ok(&p, "NOLIMP");
    ok(&p, "ARM ON");
    ok(&p, "READY");
    at(&p, 12, 0, 20, 0, 0);
    stop(&p);
}

/* ---- the command log ------------------------------------------------- */

static void t_log(void **st)
{
    simp p;
    const char *log = tmp("commands.log");
    const char *const opts[] = {"--time-scale", "200", "--log", log, NULL};
    char line[256];
    FILE *f;
    static const char *want[] = {"NOHELP", "SPEED 25", "FOO", "POINT P1,10,0,5,0,-90,0",
                                 "HOME",   "MOVE P1",  "W2"};
    int i = 0;
    (void)st;
    start(&p, opts);
    assert_string_equal(raw(&p, "SPEEX\bD 25"), "SPEEX\b \bD 25\r\n>>");
    err(&p, "FOO", 12);
    ok(&p, "POINT P1,10,0,5,0,-90,0");
    raw(&p, "");
    ok(&p, "HOME");
    ok(&p, "move p1");
    cmd(&p, "W2");
    stop(&p);
    f = fopen(log, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = 0;
        assert_true(i < 7);
        assert_string_equal(line, want[i]);
        i++;
    }
    assert_int_equal(i, 7);
    fclose(f);
}

/* ---- TCP and in-process ---------------------------------------------- */

static void t_tcp(void **st)
{
    static const char *const opts[] = {"--tcp", "0", "--time-scale", "200", NULL};
    simp p;
    (void)st;
    start(&p, opts);
    assert_int_equal(strncmp(p.path, "tcp:127.0.0.1:", 14), 0);
    ok(&p, "HOME");
    ok(&p, "READY");
    at(&p, 12, 0, 20, 0, 0);
    /* a second connection while one is open is refused; after closing, a new one works */
    close(p.fd);
    usleep(100000);
    {
        struct sockaddr_in a;
        memset(&a, 0, sizeof a);
        a.sin_family = AF_INET;
        a.sin_port = htons((unsigned short)atoi(strrchr(p.path, ':') + 1));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        p.fd = socket(AF_INET, SOCK_STREAM, 0);
        assert_int_equal(connect(p.fd, (struct sockaddr *)&a, sizeof a), 0);
        expect_greeting(&p);
    }
    assert_string_equal(status_line(&p, "CONTROLLER"), "CONTROLLER IS HOMED");
    stop(&p);
}

static int tcp_connect(const char *path)
{
    struct sockaddr_in a;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((unsigned short)atoi(strrchr(path, ':') + 1));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_true(fd >= 0);
    assert_int_equal(connect(fd, (struct sockaddr *)&a, sizeof a), 0);
    return fd;
}

/* A second client while one is connected is told the controller is busy and closed at
 * once; what it typed never runs, not even after the first client leaves (the log is
 * the truth for what ran). */
static void t_tcp_busy(void **st)
{
    const char *log = tmp("busy.log");
    const char *const opts[] = {"--tcp", "0", "--time-scale", "200", "--log", log, NULL};
    simp p, q;
    size_t n;
    double t0;
    char line[256];
    FILE *f;
    int i;
    (void)st;
    start(&p, opts);
    ok(&p, "V1=1");
    for (i = 0; i < 3; i++) {
        q.fd = tcp_connect(p.path);
        puts_(&q, "V7=99\rOUTPUT 3\r");
        t0 = now_s();
        n = read_until(&q, g_buf, sizeof g_buf, "\r\n", TIMEOUT);
        assert_true(n > 0);
        assert_non_null(strstr(g_buf, "busy"));
        assert_null(strstr(g_buf, ">>"));
        /* and then end of file: closed at once, not left waiting */
        n = read_until(&q, g_buf, sizeof g_buf, NULL, 2.0);
        assert_int_equal(n, 0);
        assert_true(now_s() - t0 < 2.0);
        close(q.fd);
    }
    ok(&p, "V2=2"); /* the first client was not disturbed */
    close(p.fd);
    usleep(200000);
    p.fd = tcp_connect(p.path);
    expect_greeting(&p);
    err(&p, "TYPEV V7", 10);
    assert_string_equal(status_line(&p, "OUTPUTS"), "OUTPUTS 1-16: 0000000000000000");
    p.fd = p.fd;
    stop(&p);
    f = fopen(log, "r");
    assert_non_null(f);
    n = 0;
    while (fgets(line, sizeof line, f)) {
        assert_null(strstr(line, "V7=99"));
        assert_null(strstr(line, "OUTPUT 3"));
        n++;
    }
    fclose(f);
    assert_int_equal(n, 5); /* NOHELP V1=1 V2=2 TYPEV V7 STATUS */
}

static void t_embed(void **st)
{
    fbrl_sim_options o;
    fbrl_sim *s = NULL;
    simp p;
    char e[256];
    const char *link = tmp("robot-link");
    struct stat sb;
    (void)st;
    fbrl_sim_options_init(&o);
    o.time_scale = 100;
    o.link_path = link;
    assert_int_equal(fbrl_sim_create(&s, &o, e, sizeof e), FBRL_OK);
    assert_int_equal(fbrl_sim_start(s), FBRL_OK);
    p.pid = 0;
    p.fd = open(link, O_RDWR | O_NOCTTY);
    assert_true(p.fd >= 0);
    raw_fd(p.fd);
    expect_silence(&p); /* opening the pty sends nothing: a serial line cannot see it */
    ok(&p, "NOHELP");
    ok(&p, "HOME");
    ok(&p, "JOINT 1,45");
    ok(&p, "FINISH");
    {
        double w[6];
        where(&p, w, NULL, NULL);
        assert_true(fabs(w[0] - 12 * cos(M_PI / 4)) < 0.001);
    }
    close(p.fd);
    fbrl_sim_stop(s);
    fbrl_sim_destroy(s);
    assert_int_equal(lstat(link, &sb), -1); /* the link is removed */
    /* bad options are refused with a message */
    o.time_scale = 0;
    assert_int_equal(fbrl_sim_create(&s, &o, e, sizeof e), FBRL_EINVAL);
    assert_null(s);
    {
        /* a --link that names an ordinary file is refused, and the file kept */
        const char *plain = tmp("plain-file");
        FILE *f = fopen(plain, "w");
        fputs("keep\n", f);
        fclose(f);
        fbrl_sim_options_init(&o);
        o.link_path = plain;
        assert_int_equal(fbrl_sim_create(&s, &o, e, sizeof e), FBRL_EIO);
        assert_non_null(strstr(e, "not a symlink"));
        assert_int_equal(stat(plain, &sb), 0);
        assert_true(S_ISREG(sb.st_mode));
    }
    fbrl_sim_options_init(&o);
    o.faults = "bogus=1";
    assert_int_equal(fbrl_sim_create(&s, &o, e, sizeof e), FBRL_EIO);
    assert_non_null(strstr(e, "bogus"));
}

/* ---- arm models ------------------------------------------------------ */

/* fbrlsim --model a465: six axes in every readout, the A465's limits, a yaw the arm
 * chooses, precision points of six pulses, and the model kept in the state file. */
static void t_model_a465(void **st)
{
    const char *state = tmp("a465.state");
    const char *const opts[] = {"--time-scale", "200", "--model", "a465", "--state", state, NULL};
    const char *const plain[] = {"--time-scale", "200", "--state", state, NULL};
    simp p;
    double w[6];
    const char *r, *x;
    long pl[6];
    (void)st;
    start(&p, opts);
    assert_non_null(strstr(cmd(&p, "STATUS"), "A465 Robot"));
    assert_string_equal(status_line(&p, "AXIS#"), "AXIS#        1 2 3 4 5 6");
    ok(&p, "HOME");
    ok(&p, "READY");
    r = cmd(&p, "W2");
    x = strstr(r, "PULSES   ");
    assert_non_null(x);
    assert_int_equal(sscanf(x + 6, "%ld %ld %ld %ld %ld %ld", &pl[0], &pl[1], &pl[2], &pl[3], &pl[4], &pl[5]),
                     6);
    assert_non_null(strstr(r, "AX#6"));
    assert_non_null(strstr(r, "JT#6"));
    /* READY: upper arm upright, forearm and tool level: 406 mm out, 635 mm up */
    at(&p, 406.0 / 25.4, 0, 635.0 / 25.4, 0, 0);
    /* its limits: wrist bend 105, tool roll 180 (048 for the sixth joint) */
    err(&p, "JOINT 5,106", 46);
    err(&p, "JOINT 6,181", 48);
    err(&p, "JOINT 7,1", 65);
    ok(&p, "JOINT 5,-30");
    ok(&p, "FINISH");
    /* six joints for MA (radians); five are not enough */
    err(&p, "MA 0,0,1.5,0,0", 13);
    ok(&p, "MA 0.2,0.3,1.2,0.1,-0.5,0.4");
    ok(&p, "FINISH");
    ok(&p, "HERE #Q");
    ok(&p, "HERE Q");
    /* a yaw of its own: the waist points one way, the tool another */
    ok(&p, "POINT T,16,4,14,10,-45,20");
    ok(&p, "MOVE T");
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[0] - 16) < 1e-3 && fabs(w[1] - 4) < 1e-3 && fabs(w[2] - 14) < 1e-3);
    assert_true(fabs(w[3] - 10) < 1e-3 && fabs(w[4] + 45) < 1e-3 && fabs(w[5] - 20) < 1e-3);
    ok(&p, "MOVE T,S");
    ok(&p, "MOVE #Q");
    ok(&p, "FINISH");
    r = cmd(&p, "LISTL #Q");
    assert_int_equal(sscanf(r + 9, "%ld %ld %ld %ld %ld %ld", &pl[0], &pl[1], &pl[2], &pl[3], &pl[4], &pl[5]),
                     6);
    assert_true(labs(pl[5] - lround(0.4 * 180.0 / M_PI * 138.89)) <= 1);
    stop(&p);
    {
        char text[4096];
        size_t n;
        FILE *f = fopen(state, "r");
        n = fread(text, 1, sizeof text - 1, f);
        text[n] = 0;
        fclose(f);
        assert_int_equal(
            strncmp(text, "FBRLSIM-STATE 1\nMODEL A465\n", strlen("FBRLSIM-STATE 1\nMODEL A465\n")), 0);
    }
    /* without --model the state file's arm comes back */
    start(&p, plain);
    assert_non_null(strstr(cmd(&p, "STATUS"), "A465 Robot"));
    ok(&p, "HOME");
    ok(&p, "MOVE Q");
    ok(&p, "FINISH");
    stop(&p);
    {
        /* another arm's memory is refused: --model a255 on an A465 file, and an old
         * file without MODEL (an A255's) under --model a465 */
        const char *old = tmp("old.state");
        FILE *f = fopen(old, "w");
        int i;
        fputs("FBRLSIM-STATE 1\nSPEED 40\nJOINTS 0 90 -90 0 0\n", f);
        fclose(f);
        for (i = 0; i < 2; i++) {
            int pid = fork(), stt;
            if (pid == 0) {
                int dn = open("/dev/null", O_WRONLY);
                dup2(dn, 1);
                dup2(dn, 2);
                execl(FBRLSIM_PATH, FBRLSIM_PATH, "--model", i ? "a465" : "a255", "--state", i ? old : state,
                      (char *)NULL);
                _exit(127);
            }
            waitpid(pid, &stt, 0);
            assert_true(WIFEXITED(stt) && WEXITSTATUS(stt) == 1);
        }
    }
}

/* ---- what real clients send (research notes 2.5 and 4) ---------------- */

/* Reads exactly n bytes (or what came by the timeout); returns how many. */
static size_t read_n(simp *p, char *buf, size_t n, double timeout)
{
    size_t got = 0;
    double end = now_s() + timeout;
    while (got < n && now_s() < end) {
        struct pollfd pf = {p->fd, POLLIN, 0};
        if (poll(&pf, 1, 20) > 0) {
            ssize_t r = read(p->fd, buf + got, n - got);
            if (r <= 0)
                break;
            got += (size_t)r;
        }
    }
    return got;
}

static void expect_bytes(simp *p, const char *want, size_t n)
{
    char got[64];
    size_t k = read_n(p, got, n, TIMEOUT);
    assert_int_equal(k, n);
    assert_memory_equal(got, want, n);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    char *b = calloc(1, 1 << 20);
    size_t n;
    assert_non_null(f);
    n = fread(b, 1, (1 << 20) - 1, f);
    b[n] = 0;
    fclose(f);
    return b;
}

/* S2 (G3000 driver, ACI_to_Term): each step waits for the controller's reply. */
static const char S2_PKT[] = "\x01\x21\x21\x00\x48\x00\x00\x00\x00\x00\x00\x03\x8a";
/* S5 (A255 C# class): another data byte, so another checksum; no reads at all. */
static const char S5_ALL[] = "\x52\x21\x05"
                             "\x01\x21\x21\x00\x48\x00\x01\x00\x00\x00\x00\x03\x8b"
                             "\x06\x04NOHELP\r";
/* S6 (TurnOffACI.m): source id 0xFF, ACK ACK ETX ETX, then NOHELP and DC2. */
static const char S6_ALL[] = "R!\x05"
                             "\x01!\xff\x00H\x00\x01\x00\x00\x00\x00\x03i"
                             "\x06\x06\x03\x03NOHELP\r\x12";

static void t_aci(void **st)
{
    simp p;
    const char *log = tmp("aci.log");
    const char *const opts[] = {"--aci", "--log", log, "--time-scale", "200", NULL};
    char bad[sizeof S2_PKT];
    size_t n;
    char *text;
    (void)st;
    g_real = 2;
    spawn(&p, opts);
    /* ACI mode: nothing is echoed, a typed line never runs */
    puts_(&p, "NOHELP\r");
    assert_int_equal(read_n(&p, g_buf, 1, 0.3), 0);
    /* S2, step by step */
    put(&p, "R\x21\x05", 3);
    expect_bytes(&p, "R\x21\x06", 3);
    memcpy(bad, S2_PKT, sizeof S2_PKT);
    bad[12] = (char)0x8b; /* a wrong checksum: NAK, still in ACI mode */
    put(&p, bad, 13);
    expect_bytes(&p, "\x15", 1);
    put(&p, S2_PKT, 13);
    expect_bytes(&p, "\x06\x02\x03\x00", 4);
    put(&p, "\x06", 1);
    expect_bytes(&p, "\x04", 1);
    put(&p, "\x04", 1);
    assert_int_equal(read_n(&p, g_buf, 1, TIMEOUT), 1); /* S2 discards this byte */
    assert_string_equal(cmd(&p, "NOHELP"), "");
    assert_string_equal(cmd(&p, "SPEED 40"), ""); /* no HELP-mode artefacts in the echo */
    /* Ctrl-Z Ctrl-Z: back to ACI mode (S2 disconnect) */
    put(&p, "\x1a\x1a", 2);
    puts_(&p, "W2\r");
    assert_int_equal(read_n(&p, g_buf, 1, 0.3), 0);
    /* S5 sends everything without reading: it ends in terminal mode, NOHELP done */
    put(&p, S5_ALL, sizeof S5_ALL - 1);
    n = read_until(&p, g_buf, sizeof g_buf, "NOHELP\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "NOHELP\r\n>>"));
    assert_memory_equal(g_buf, "R\x21\x06\x06\x02\x03\x00\x04", 8);
    assert_null(strstr(g_buf, "012-"));
    put(&p, "\x1a\x1a", 2);
    /* S6: source 0xFF, two ACKs and ETXs; its DC2 is ignored (echo stays on) */
    put(&p, S6_ALL, sizeof S6_ALL - 1);
    n = read_until(&p, g_buf, sizeof g_buf, "NOHELP\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "NOHELP\r\n>>"));
    assert_null(strstr(g_buf, "012-"));
    ok(&p, "HOME");
    stop(&p);
    g_real = 0;
    /* the log holds what ran: never "R!!!HNOHELP", and W2 typed in ACI mode did not run */
    text = slurp(log);
    assert_string_equal(text,
                        "# ACI: PACKET REFUSED\n# ACI: TERMINAL MODE\nNOHELP\nSPEED 40\n# ACI MODE\n"
                        "# ACI: TERMINAL MODE\nNOHELP\n# ACI MODE\n# ACI: TERMINAL MODE\nNOHELP\nHOME\n");
    free(text);
    /* without --aci the bytes are typed text as on a terminal; Ctrl-Z does nothing */
    start(&p, FAST);
    put(&p, "\x1a\x1a", 2);
    err(&p, "R!", 12);
    stop(&p);
}

/* The clients' own start-up sequences after the switch (research notes section 4), each
 * checked the way that client checks it. */
static void t_client_startups(void **st)
{
    simp p;
    const char *state = tmp("startup.state");
    const char *const s2[] = {"--aci", "--model", "a465", "--state", state, "--time-scale", "200", NULL};
    const char *const s3[] = {"--nak", "--model", "a465", "--state", state, "--time-scale", "200", NULL};
    const char *const a255[] = {"--time-scale", "200", NULL};
    const char *r, *x;
    size_t n, lines;
    int i;
    FILE *f;
    (void)st;
    f = fopen(state, "w");
    fputs("FBRLSIM-STATE 1\nMODEL A465\nPROGRAM HOME\n  HOME\nEND\nPROGRAM QPOOL\n  MOVE #QPOOL\n  "
          "FINISH\nEND\n"
          "PROGRAM CAL\n  HOME\nEND\nPROGRAM INIT_SYS\n  READY\n  FINISH\nEND\n",
          f);
    fclose(f);
    /* S2 (G3000 driver): ACI switch, NOHELP, ENABLE ARM, RUN HOME, POINT #QPOOL, SPEED,
     * RUN QPOOL, JOINT 6 +90; every command done when the buffer ends "\r\n>>"; W2 read
     * after "JOINTS", STATUS after AXIS#, LIMP and HOMED */
    g_real = 2;
    spawn(&p, s2);
    put(&p, "R\x21\x05", 3);
    expect_bytes(&p, "R\x21\x06", 3);
    put(&p, S2_PKT, 13);
    expect_bytes(&p, "\x06\x02\x03\x00", 4);
    put(&p, "\x06", 1);
    expect_bytes(&p, "\x04", 1);
    put(&p, "\x04", 1);
    assert_int_equal(read_n(&p, g_buf, 1, TIMEOUT), 1);
    usleep(50000); /* S2 sleeps 500 ms here */
    static const char *const s2_cmds[] = {
        "NOHELP",   "ENABLE ARM", "RUN HOME",   "POINT #QPOOL 1000, 2000, 3000, 400, 500, 600",
        "SPEED 50", "RUN QPOOL",  "JOINT 6 +90"};
    for (i = 0; i < (int)(sizeof s2_cmds / sizeof s2_cmds[0]); i++) {
        r = raw(&p, s2_cmds[i]); /* expect(command), then "\r\n>>" */
        assert_int_equal(strncmp(r, s2_cmds[i], strlen(s2_cmds[i])), 0);
        assert_string_equal(r + strlen(s2_cmds[i]), "\r\n>>");
    }
    ok(&p, "FINISH");
    r = raw(&p, "W2");
    x = strstr(r, "JOINTS");
    assert_non_null(x);
    {
        double j[6];
        assert_int_equal(sscanf(x + 6, "%lf %lf %lf %lf %lf %lf", &j[0], &j[1], &j[2], &j[3], &j[4], &j[5]),
                         6);
        assert_true(fabs(j[0] - 1000 / 277.78) < 1e-3 && fabs(j[5] - (600 / 138.89 + 90)) < 1e-2);
    }
    r = raw(&p, "STATUS");
    assert_non_null(strstr(r, "\r\nAXIS#        1 2 3 4 5 6\r\n"));
    assert_non_null(strstr(r, "\r\nLIMP         N N N N N N\r\n"));
    assert_non_null(strstr(r, "\r\nHOMED        Y Y Y Y Y Y\r\n"));
    put(&p, "\x1a\x1a", 2); /* S2 disconnect */
    usleep(100000);
    stop(&p);
    /* S3 (gantry, Python): NOHELP, ONPOWER, STATUS read as 21 lines looking for NOT
     * HOMED, RUN CAL, @ZERO, RUN INIT_SYS, SPEED 40.00, MI ...,S; a line with NAK is
     * its error, lines with ACK are skipped */
    g_real = 1;
    spawn(&p, s3);
    assert_string_equal(raw(&p, "NOHELP"), "NOHELP\r\n>>");
    assert_string_equal(raw(&p, "ONPOWER"), "ONPOWER\r\n>>");
    puts_(&p, "STATUS\r");
    n = read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    for (lines = 0, x = g_buf; (x = strstr(x, "\r\n")); x += 2)
        lines++;
    assert_int_equal(lines, 21);
    assert_non_null(strstr(g_buf, "CONTROLLER IS NOT HOMED"));
    assert_null(strchr(g_buf, 0x15));
    assert_string_equal(raw(&p, "RUN CAL"), "RUN CAL\r\n>>");
    r = raw(&p, "@ZERO");
    assert_non_null(strstr(r, "\r\n\x15"
                              "012-COMMAND ERROR.\r\n")); /* S3: NAK, an error line */
    assert_string_equal(raw(&p, "RUN INIT_SYS"), "RUN INIT_SYS\r\n>>");
    assert_string_equal(raw(&p, "SPEED 40.00"), "SPEED 40.00\r\n>>");
    ok(&p, "JOINT 5,30"); /* off the straight wrist, where a straight line cannot start */
    ok(&p, "FINISH");
    assert_string_equal(raw(&p, "MI 0.1,0,0.05,0,0,0,S"), "MI 0.1,0,0.05,0,0,0,S\r\n>>");
    /* its W1 thread: the header, lines of six numbers ended by CR, a bare CR stops it */
    puts_(&p, "W1\r");
    n = read_until(&p, g_buf, sizeof g_buf, NULL, 0.5);
    assert_non_null(strstr(g_buf, "\r\nACTUAL POSITION (MOTOR PULSES):\r"));
    puts_(&p, "\r");
    n += read_until(&p, g_buf + n, sizeof g_buf - n, "\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "\r\n>>"));
    stop(&p);
    g_real = 0;
    /* S5 (A255, C#): after its blind ACI switch (t_aci) it sends commands with sleeps and
     * reads nothing; every one must run */
    start(&p, a255);
    static const char *const s5_cmds[] = {"HOME",       "HERE START", "SPEED 20",  "JOINT 1, 5", "FINISH",
                                          "OPEN 50",    "CLOSE 50",   "JOG 1,0,0", "FINISH",     "JOG 0,0,0",
                                          "MOVE START", "READY",      "FINISH",    "HALT"};
    for (i = 0; i < (int)(sizeof s5_cmds / sizeof s5_cmds[0]); i++)
        ok(&p, s5_cmds[i]);
    /* S4 (York, CRSPLUS 250): lines end in LF; the reply is good when the character after
     * the first LF is '>' (compare_resp) */
    static const char *const s4_cmds[] = {"NOHELP", "SPEED 30", "JOG 0.5,0,0", "FINISH", "DEPART 1"};
    for (i = 0; i < (int)(sizeof s4_cmds / sizeof s4_cmds[0]); i++) {
        puts_(&p, s4_cmds[i]);
        puts_(&p, "\n");
        n = read_until(&p, g_buf, sizeof g_buf, ">>", TIMEOUT);
        x = strchr(g_buf, '\n');
        assert_non_null(x);
        assert_int_equal(x[1], '>');
        assert_int_equal(strncmp(g_buf, s4_cmds[i], strlen(s4_cmds[i])), 0); /* its echo check */
    }
    puts_(&p, "FOO\n");
    read_until(&p, g_buf, sizeof g_buf, ">>", TIMEOUT);
    assert_int_not_equal(strchr(g_buf, '\n')[1], '>'); /* S4 sees the error */
    stop(&p);
}

/* A client working in millimetres (S2 STATUS "METRIC UNITS.", S3 MI in mm, S4). */
static void t_units(void **st)
{
    simp p;
    const char *state = tmp("units.state");
    const char *const opts[] = {"--time-scale", "200", "--state", state, NULL};
    double w[6];
    char *text;
    (void)st;
    g_real = 1;
    start(&p, opts);
    ok(&p, "HOME");
    err(&p, "JOG 0,0,-100", 29); /* 100 inches: out of reach */
    ok(&p, "METRIC");
    ok(&p, "JOG 0,0,-100"); /* 100 mm */
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[0] - 12 * 25.4) < 1e-3 && fabs(w[2] - (20 * 25.4 - 100)) < 1e-3);
    ok(&p, "POINT P1,304.8,25.4,406.4,0,-90,0");
    assert_string_equal(cmd(&p, "LISTL P1"),
                        "P1        +304.8000 +025.4000 +406.4000 +000.0000 -090.0000 +000.0000\r\n");
    ok(&p, "MOVE P1");
    ok(&p, "APPRO P1,50.8");
    ok(&p, "DEPART 25.4");
    ok(&p, "FINISH");
    where(&p, w, NULL, NULL);
    assert_true(fabs(w[2] - (406.4 + 50.8 + 25.4)) < 1e-3); /* the tool points down: back is up */
    err(&p, "GRIP 51", 20);                                 /* over 2 in = 50.8 mm */
    ok(&p, "GRIP 25.4");
    {
        const char *r = cmd(&p, "STATUS");
        assert_non_null(strstr(r, "MAX LINEAR SPEED: +499.9990\r\n")); /* 19.685 in/s */
        assert_true(ends_with(r, strlen(r), "METRIC UNITS.\r\n"));
    }
    stop(&p); /* kept in the state file */
    text = slurp(state);
    assert_non_null(strstr(text, "\nUNITS METRIC\n"));
    free(text);
    start(&p, opts);
    assert_non_null(strstr(cmd(&p, "STATUS"), "METRIC UNITS."));
    assert_string_equal(cmd(&p, "LISTL P1"),
                        "P1        +304.8000 +025.4000 +406.4000 +000.0000 -090.0000 +000.0000\r\n");
    ok(&p, "NOMETRIC");
    assert_string_equal(cmd(&p, "LISTL P1"),
                        "P1        +012.0000 +001.0000 +016.0000 +000.0000 -090.0000 +000.0000\r\n");
    assert_non_null(strstr(cmd(&p, "STATUS"), "INCH UNITS."));
    err(&p, "METRIC ON", 14);
    stop(&p);
    g_real = 0;
}

/* Every command of the RAPL-II table a client may send: implemented, or 012. */
static void t_client_commands(void **st)
{
    /* S1's table (research notes 1.1) minus what fbrlsim implements; PENDANT and @ZERO
     * are S3's (not in the table) */
    static const char *const unknown[] = {"XREADY",
                                          "ALLOC 1,1,1,1",
                                          "MAGGRIP 5",
                                          "PRINT X",
                                          "PRINTI 1",
                                          "PRINTV 1",
                                          "INPUT V",
                                          "ABORT",
                                          "IF A>B THEN 10",
                                          "IFSIG 1 THEN 10",
                                          "GOSUB 10",
                                          "GOTO 10",
                                          "PAUSE",
                                          "RETURN",
                                          "STOP",
                                          "TRACE",
                                          "DELAY 1",
                                          "TIME",
                                          "IORD 1",
                                          "IOWR 1,2",
                                          "IFSTART 10",
                                          "IGNORE 1",
                                          "AOUT 1,2",
                                          "DELETE P",
                                          "MEMRD 1",
                                          "PROCEED",
                                          "RENAME A,B",
                                          "RETRY",
                                          "DEVICE 0",
                                          "MEMWR 1,2",
                                          "PASSWORD X",
                                          "CUT A",
                                          "PASTE A",
                                          "DECODE A",
                                          "ENCODE A",
                                          "STRPOS A",
                                          "IFSTRING A",
                                          "HLIM 1",
                                          "IFPOWER 10",
                                          "CPATH A,B",
                                          "CTPATH A",
                                          "GOPATH A",
                                          "ELBOW UP",
                                          "INVERT ON",
                                          "REACH",
                                          "WRIST",
                                          "TRIGGER 1",
                                          "CIRCLE",
                                          "AXSTATUS",
                                          "EXECUTE 1",
                                          "HIMEM",
                                          "IFAUX 1",
                                          "RTCLOCK",
                                          "VIA A,B",
                                          "REMOTE",
                                          "PENDANT OFF",
                                          "@ZERO",
                                          "; A COMMENT",
                                          "++ I",
                                          "-- I",
                                          "/003",
                                          "/100",
                                          "/176X"};
    simp p;
    const char *ctl = tmp("ctl-cmds");
    const char *const opts[] = {"--time-scale", "200", "--control", ctl, NULL};
    size_t i, n;
    int fd;
    (void)st;
    g_real = 0;
    start(&p, opts);
    for (i = 0; i < sizeof unknown / sizeof unknown[0]; i++)
        err(&p, unknown[i], 12);
    /* what the lab's steps use (S11) is answered (t_programs has the rest) */
    assert_non_null(strstr(cmd(&p, "FREE"), "PROGRAMS  : 00000 OF 00016\r\n"));
    assert_string_equal(cmd(&p, "DIR"), "");
    err(&p, "LISTP P", 17);
    /* ENABLE/DISABLE ARM (S2), also by token */
    ok(&p, "HOME");
    ok(&p, "DISABLE ARM");
    assert_string_equal(status_line(&p, "ARM POWER IS"), "ARM POWER IS OFF");
    err(&p, "JOINT 1,5", 40);
    ok(&p, "/176 ARM");
    assert_string_equal(status_line(&p, "ARM POWER IS"), "ARM POWER IS ON");
    err(&p, "ENABLE", 13);
    err(&p, "ENABLE PENDANT", 66);
    ok(&p, "ONPOWER"); /* power on: returns at once */
    /* ONPOWER waits for the power (S3's start-up), here from the front panel */
    ok(&p, "ARM OFF");
    puts_(&p, "ONPOWER\r");
    n = read_until(&p, g_buf, sizeof g_buf, ">>", 0.5);
    assert_false(ends_with(g_buf, n, ">>"));
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "POWER 1\n", 8), 8);
    close(fd);
    n += read_until(&p, g_buf + n, sizeof g_buf - n, "\r\n>>", TIMEOUT);
    assert_string_equal(g_buf, "ONPOWER\r\n>>");
    /* GAIN: the lab's values at power-up (S11), its form GAIN 0,5,.25,100 for every motor,
     * one value for one motor, and GAIN 0 shows every motor (0 = all motors, S1) */
    assert_string_equal(cmd(&p, "GAIN 4"), "GAIN MOTOR 4: +8.0000,+0.2500,+100.0000\r\n");
    ok(&p, "GAIN 0,5,.25,100");
    ok(&p, "GAIN 2,1");
    ok(&p, "GAIN 3,6,0.5,90");
    assert_string_equal(cmd(&p, "GAIN 0"), "GAIN MOTOR 1: +5.0000,+0.2500,+100.0000\r\n"
                                          "GAIN MOTOR 2: +1.0000,+0.2500,+100.0000\r\n"
                                          "GAIN MOTOR 3: +6.0000,+0.5000,+90.0000\r\n"
                                          "GAIN MOTOR 4: +5.0000,+0.2500,+100.0000\r\n"
                                          "GAIN MOTOR 5: +5.0000,+0.2500,+100.0000\r\n");
    assert_string_equal(cmd(&p, "GAIN 2"), "GAIN MOTOR 2: +1.0000,+0.2500,+100.0000\r\n");
    err(&p, "GAIN 1,1,2", 13);
    err(&p, "GAIN 1,1,2,3,4", 14);
    err(&p, "GAIN 6,1", 65);
    err(&p, "GAIN 1,-1", 18);
    err(&p, "GAIN 1,1,-1,2", 18);
    assert_string_equal(cmd(&p, "GAIN 1"), "GAIN MOTOR 1: +5.0000,+0.2500,+100.0000\r\n");
    stop(&p);
}

/* Replies as the clients read them: STATUS as S3 reads it (21 lines after the command),
 * NAK before errors (S3), empty lines, lower case. */
static void t_replies(void **st)
{
    static const char *const labels[] = {
        "RAPL-II Version 2.60     A255 Robot",
        "LAST ERROR CODE: ",
        "SPEED (% OF FULL) :    +50",
        "MAX LINEAR SPEED: +019.6850",
        "CURRENT PROGRAM EXECUTING:",
        "[00]",
        "JOINT LIMIT CHECK IS ",
        "CONTROLLER IS NOT HOMED",
        "TOOL TRANSFORM",
        "NULL      +000.0000 +000.0000 +000.0000 +000.0000 +000.0000 +000.0000",
        "GRIPPER TYPE:  SERVO",
        "AXIS#        1 2 3 4 5",
        "LOCK         N N N N N",
        "DONE         Y Y Y Y Y",
        "LIMP         N N N N N",
        "HOMED        N N N N N",
        "REQUESTED ROBOT CONFIG : ",
        "CURRENT ROBOT CONFIG : ",
        "MANUAL MODE STATUS IS OFF",
        "INCH UNITS."};
    const char *log = tmp("replies.log");
    const char *const nak[] = {"--nak", "--time-scale", "200", NULL};
    const char *const typed[] = {"--echo-as-typed", "--log", log, "--time-scale", "200", NULL};
    const char *const extra[] = {"--status-extra", "--time-scale", "200", NULL};
    simp p;
    size_t n, lines = 0;
    const char *r, *x;
    char *text;
    (void)st;
    g_real = 1;
    start(&p, FAST);
    err(&p, "FOO", 12);
    assert_null(strchr(g_buf, 0x15)); /* no NAK by default */
    /* S3: send STATUS, read 21 lines (the echo and 20), then the prompt follows */
    puts_(&p, "STATUS\r");
    n = read_until(&p, g_buf, sizeof g_buf, "\r\n>>", TIMEOUT);
    assert_true(ends_with(g_buf, n, "UNITS.\r\n>>"));
    for (r = g_buf; (x = strstr(r, "\r\n")); r = x + 2) {
        if (lines > 0)
            assert_int_equal(strncmp(r, labels[lines - 1], strlen(labels[lines - 1])), 0);
        lines++;
    }
    assert_int_equal(lines, 21);
    assert_non_null(strstr(g_buf, "LAST ERROR CODE: 012-COMMAND ERROR.\r\n"));
    assert_non_null(strstr(g_buf, "[00]NONE\r\n"));
    /* an empty line: CR LF and the prompt, nothing runs */
    assert_string_equal(raw(&p, ""), "\r\n>>");
    assert_string_equal(raw(&p, "  "), "  \r\n>>");
    /* lower case runs upper-cased and echoes upper-cased */
    assert_string_equal(raw(&p, "speed 30"), "SPEED 30\r\n>>");
    stop(&p);
    /* the program line: where the last program stopped and why */
    {
        const char *state = tmp("replies.state");
        const char *const so[] = {"--state", state, "--time-scale", "200", NULL};
        FILE *f = fopen(state, "w");
        fputs("FBRLSIM-STATE 1\nPROGRAM PICK\n  SPEED 20\n  FOO\nEND\n", f);
        fclose(f);
        start(&p, so);
        err(&p, "RUN PICK", 12);
        assert_string_equal(status_line(&p, "[00]"), "[00]PICK#00002 :012-COMMAND ERROR.");
        stop(&p);
    }
    /* --nak: NAK, then the error line */
    start(&p, nak);
    r = cmd(&p, "FOO");
    assert_string_equal(r, "\x15"
                           "012-COMMAND ERROR.\r\n");
    stop(&p);
    /* --echo-as-typed: the echo keeps the case, the line runs upper-cased */
    spawn(&p, typed);
    assert_string_equal(raw(&p, "nohelp"), "nohelp\r\n>>");
    assert_string_equal(raw(&p, "Speed 30"), "Speed 30\r\n>>");
    stop(&p);
    text = slurp(log);
    assert_string_equal(text, "NOHELP\nSPEED 30\n");
    free(text);
    /* --status-extra: fbrlsim's own lines, the units line still last */
    start(&p, extra);
    r = cmd(&p, "STATUS");
    assert_non_null(strstr(r, "MANUAL MODE STATUS IS OFF\r\nARM POWER IS ON\r\n"));
    assert_int_equal(strncmp(r, "RAPL-II Version 2.60     A255 Robot (fbrlsim)\r\n", 47), 0);
    assert_null(strstr(r, "[00]"));
    assert_true(ends_with(r, strlen(r), "OUTPUTS 1-16: 0000000000000000\r\nINCH UNITS.\r\n"));
    stop(&p);
    g_real = 0;
}

/* One burst: 1,000 assignment lines as fast as the host can write them. honour: the
 * host's tty has IXON (its port stops on the controller's XOFF; the kernel holds its
 * writes), else its port ignores XOFF. Returns the lines the log shows, in order. */
static int burst_run(int honour, long *overruns, long *ignored)
{
    simp p;
    const char *log = tmp(honour ? "flow-h.log" : "flow-i.log");
    const char *out = tmp(honour ? "flow-h.out" : "flow-i.out");
    const char *ctl = tmp(honour ? "flow-h.ctl" : "flow-i.ctl");
    const char *const opts[] = {"--baud", "9600", "--log", log, "--control", ctl, "--control-out", out, NULL};
    enum { LINES = 1000 };
    char line[32], *text, *s;
    int sent = 0, good = 0, fd, fl;
    size_t off = 0, len = 0;
    double quiet;
    start(&p, opts);
    /* each line's echo and prompt are longer than the line: the controller's output is
     * the bottleneck, so its receive buffer fills and it sends XOFF */
    if (honour) {
        /* as S2 (c_iflag |= IXON|IXOFF) and S3 (xonxoff=True) set their port */
        struct termios t;
        assert_int_equal(tcgetattr(p.fd, &t), 0);
        t.c_iflag |= IXON | IXOFF;
        assert_int_equal(tcsetattr(p.fd, TCSANOW, &t), 0);
    }
    fl = fcntl(p.fd, F_GETFL);
    fcntl(p.fd, F_SETFL, fl | O_NONBLOCK);
    quiet = now_s();
    while (sent < LINES || off < len || now_s() - quiet < 1.0) {
        struct pollfd pf = {p.fd, POLLIN, 0};
        char b[4096];
        ssize_t r;
        if (!(off < len) && sent < LINES) {
            snprintf(line, sizeof line, "V=%d\r", sent);
            len = strlen(line);
            off = 0;
            sent++;
        }
        if (off < len)
            pf.events |= POLLOUT;
        if (poll(&pf, 1, 20) > 0) {
            if (pf.revents & POLLIN) {
                r = read(p.fd, b, sizeof b); /* echoes and prompts (and, without IXON, XON/XOFF) */
                if (r > 0)
                    quiet = now_s();
            }
            if ((pf.revents & POLLOUT) && off < len) {
                r = write(p.fd, line + off, len - off);
                if (r > 0)
                    off += (size_t)r;
            }
        }
        if (now_s() - quiet > TIMEOUT)
            break;
    }
    fcntl(p.fd, F_SETFL, fl);
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "GET LINE\n", 9), 9);
    close(fd);
    usleep(200000);
    stop(&p);
    text = slurp(out);
    assert_int_equal(sscanf(text, "LINE OVERRUNS %ld IGNORED-XOFF %ld", overruns, ignored), 2);
    free(text);
    text = slurp(log);
    /* the lines that ran exactly as sent, in order */
    for (s = strtok(text, "\n"); s; s = strtok(NULL, "\n")) {
        snprintf(line, sizeof line, "V=%d", good);
        if (!strcmp(s, line))
            good++;
    }
    free(text);
    return good;
}

/* Over TCP there is no tty to ask: a host that stops after the controller's XOFF (all it
 * sent before is held) loses nothing; one that sends on is seen ignoring it, and overruns. */
static void t_flow_tcp(void **st)
{
    const char *ctl = tmp("ctl-ftcp"), *out = tmp("ctl-ftcp.out");
    const char *const opts[] = {"--tcp", "0", "--baud", "9600", "--control", ctl, "--control-out", out, NULL};
    simp p;
    char big[301], *text;
    long over = -1, ign = -1;
    size_t n;
    int fd;
    (void)st;
    start(&p, opts);
    ok(&p, "HOME");
    ok(&p, "SPEED 10");
    ok(&p, "JOINT 1,10"); /* 1.7 s: the next motion waits, input piles up */
    puts_(&p, "JOINT 1,-10\r");
    usleep(50000);
    memset(big, 'A', 300);
    big[300] = 0;
    puts_(&p, big); /* all sent before the XOFF: it waits with the host */
    n = read_until(&p, g_buf, sizeof g_buf, "\x13", TIMEOUT);
    assert_true(ends_with(g_buf, n, "\x13"));
    usleep(300000);
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "GET LINE\n", 9), 9);
    usleep(200000);
    puts_(&p, big); /* sent after the XOFF: ignored it */
    usleep(500000);
    assert_int_equal(write(fd, "GET LINE\n", 9), 9);
    usleep(200000);
    close(fd);
    text = slurp(out);
    assert_int_equal(sscanf(text, "LINE OVERRUNS %ld IGNORED-XOFF %ld", &over, &ign), 2);
    assert_int_equal(over, 0);
    assert_int_equal(ign, 0);
    assert_int_equal(sscanf(strchr(text, '\n') + 1, "LINE OVERRUNS %ld IGNORED-XOFF %ld", &over, &ign), 2);
    assert_true(over > 0);
    assert_int_equal(ign, 1);
    free(text);
    stop(&p);
}

static void t_flow_burst(void **st)
{
    long over = -1, ign = -1;
    int got;
    (void)st;
    got = burst_run(1, &over, &ign);
    print_message("honours XOFF: %d of 1000 lines ran, %ld overruns, %ld XOFFs ignored\n", got, over, ign);
    assert_int_equal(got, 1000);
    assert_int_equal(over, 0);
    assert_int_equal(ign, 0);
    got = burst_run(0, &over, &ign);
    print_message("ignores XOFF: %d of 1000 lines ran, %ld overruns\n", got, over);
    assert_true(got < 1000);
    assert_true(over > 0);
}

/* The control channel's queries and refusals, the stamped log, --version. */
static void t_control_queries(void **st)
{
    simp p;
    const char *ctl = tmp("ctl-q"), *out = tmp("ctl-q.out"), *log = tmp("stamped.log");
    const char *const opts[] = {"--time-scale",  "200",     "--control", ctl,
                                "--control-out", out,       "--log",     log,
                                "--log-format",  "stamped", NULL};
    static const char *const lines =
        "GET POSITION\nGET OUTPUTS\nIN 3 1\nGET INPUTS\nGET ERROR\nGET MOTION\nGET LINE\nGET SPEED\n"
        "IN 17 1\nIN 3 2\nFOO 1\nGET\nAIN 1 nan\nPOWER 2\nOBJECT 9\nTEACH NOW\nIN 3 1 junk\n";
    char *text, *s;
    int fd, k = 0;
    (void)st;
    start(&p, opts);
    ok(&p, "OUTPUT 2,-5,16");
    err(&p, "FOO", 12);
    fd = open(ctl, O_WRONLY);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, lines, strlen(lines)), (ssize_t)strlen(lines));
    usleep(300000);
    ok(&p, "HOME");
    ok(&p, "SPEED 5");
    ok(&p, "JOINT 1,90"); /* 15 s simulated at 5 %: still moving */
    assert_int_equal(write(fd, "GET MOTION\n", 11), 11);
    usleep(200000);
    close(fd);
    stop(&p);
    text = slurp(out);
    {
        static const char *const want[] = {
            "POSITION JOINTS +0.0000 +90.0000 -90.0000 +0.0000 +0.0000 WORLD +12.0000 +0.0000 +20.0000 "
            "+0.0000 "
            "+0.0000 +0.0000",
            "OUTPUTS 0100000000000001",
            "INPUTS 0010000000000000",
            "ERROR 012-COMMAND ERROR.",
            "MOTION STOPPED EXTRA STOPPED POWER ON HOMED NO COMMAND IDLE",
            "LINE OVERRUNS 0 IGNORED-XOFF 0 PARITY-IN 0 PARITY-OUT 0",
            "REFUSED GET SPEED: GET: unknown item 'SPEED' (POSITION, OUTPUTS, INPUTS, ERROR, MOTION, LINE)",
            "REFUSED IN 17 1: IN: input '17' is not a whole number 1-16",
            "REFUSED IN 3 2: IN: value '2' is not 0 or 1",
            "REFUSED FOO 1: unknown control word 'FOO' (IN, AIN, POWER, OBJECT, TEACH, GET)",
            "REFUSED GET: GET takes one item",
            "REFUSED AIN 1 nan: AIN: 'nan' is not a decimal number of volts in -10..10",
            "REFUSED POWER 2: POWER takes 0 or 1",
            "REFUSED OBJECT 9: OBJECT takes a width in inches, 0..2",
            "REFUSED TEACH NOW: TEACH takes nothing after it",
            "REFUSED IN 3 1 junk: too many words or a word too long",
            "MOTION MOVING EXTRA STOPPED POWER ON HOMED YES COMMAND IDLE"};
        for (s = strtok(text, "\n"); s; s = strtok(NULL, "\n"), k++) {
            assert_true(k < (int)(sizeof want / sizeof want[0]));
            assert_string_equal(s, want[k]);
        }
        assert_int_equal(k, (int)(sizeof want / sizeof want[0]));
    }
    free(text);
    /* the stamped log: simulated time, OK or the error, the line */
    text = slurp(log);
    {
        static const char *const want[] = {"OK NOHELP", "OK OUTPUT 2,-5,16", "012 FOO",
                                           "OK HOME",   "OK SPEED 5",        "OK JOINT 1,90"};
        double t, last = -1;
        char rest[128];
        k = 0;
        for (s = strtok(text, "\n"); s; s = strtok(NULL, "\n"), k++) {
            assert_true(k < 6);
            assert_int_equal(sscanf(s, "%lf %127[^\n]", &t, rest), 2);
            assert_true(t >= last);
            last = t;
            assert_string_equal(rest, want[k]);
        }
        assert_int_equal(k, 6);
    }
    free(text);
    /* a bad --inputs line stops fbrlsim at start, saying why */
    {
        const char *in = tmp("bad.inputs"), *errf = tmp("bad.err");
        FILE *f = fopen(in, "w");
        int pid, stt;
        fputs("1.0 IN 3 1\n2.0 IN 3 7\n", f);
        fclose(f);
        pid = fork();
        if (pid == 0) {
            int e = open(errf, O_WRONLY | O_CREAT | O_TRUNC, 0600);
            dup2(e, 2);
            execl(FBRLSIM_PATH, FBRLSIM_PATH, "--inputs", in, (char *)NULL);
            _exit(127);
        }
        waitpid(pid, &stt, 0);
        assert_true(WIFEXITED(stt) && WEXITSTATUS(stt) == 1);
        text = slurp(errf);
        assert_non_null(strstr(text, "bad.inputs:2: IN: value '7' is not 0 or 1: 'IN 3 7'"));
        free(text);
    }
    /* --version: the project's version */
    {
        FILE *v = popen(FBRLSIM_PATH " --version", "r");
        char b[128] = "";
        assert_non_null(v);
        assert_non_null(fgets(b, sizeof b, v));
        assert_int_equal(pclose(v), 0);
        assert_int_equal(strncmp(b, "fbrlsim (libfbrl) ", 18), 0);
        assert_true(b[18] >= '0' && b[18] <= '9');
    }
}

static int cleanup(void)
{
    char c[128];
    snprintf(c, sizeof c, "rm -rf '%s'", g_dir);
    return system(c);
}

int main(int argc, char **argv)
{
    const char *g = argc > 1 ? argv[1] : "";
    int rc = 0;
    strcpy(g_dir, "/tmp/fbrlsim-test-XXXXXX");
    if (!mkdtemp(g_dir))
        return 1;
    signal(SIGPIPE, SIG_IGN);
#define GROUP(name, ...)                                                                \
    if (!strcmp(g, name) || !*g) {                                                      \
        const struct CMUnitTest t[] = {__VA_ARGS__};                                    \
        rc |= _cmocka_run_group_tests(name, t, sizeof t / sizeof t[0], NULL, kill_all); \
    }
    GROUP("line", cmocka_unit_test(t_echo_prompt), cmocka_unit_test(t_greet_pty), cmocka_unit_test(t_editing),
          cmocka_unit_test(t_errors))
    GROUP("motion", cmocka_unit_test(t_home_ready), cmocka_unit_test(t_moves),
          cmocka_unit_test(t_motion_errors), cmocka_unit_test(t_motion_timing), cmocka_unit_test(t_locations),
          cmocka_unit_test(t_teach))
    GROUP("io", cmocka_unit_test(t_io), cmocka_unit_test(t_inputs_script), cmocka_unit_test(t_gripper),
          cmocka_unit_test(t_variables), cmocka_unit_test(t_settings), cmocka_unit_test(t_streams_extra),
          cmocka_unit_test(t_run), cmocka_unit_test(t_programs))
    GROUP("persist", cmocka_unit_test(t_persist), cmocka_unit_test(t_state_junk),
          cmocka_unit_test(t_state_symlink), cmocka_unit_test(t_state_lowercase))
    GROUP("baud", cmocka_unit_test(t_baud), cmocka_unit_test(t_strict), cmocka_unit_test(t_cmd_time))
    GROUP("faults", cmocka_unit_test(t_faults), cmocka_unit_test(t_parity), cmocka_unit_test(t_garbage))
    GROUP("log", cmocka_unit_test(t_log))
    GROUP("tcp", cmocka_unit_test(t_tcp), cmocka_unit_test(t_tcp_busy))
    GROUP("embed", cmocka_unit_test(t_embed))
    GROUP("clients", cmocka_unit_test(t_aci), cmocka_unit_test(t_client_startups), cmocka_unit_test(t_units),
          cmocka_unit_test(t_client_commands), cmocka_unit_test(t_replies))
    GROUP("flow", cmocka_unit_test(t_flow_tcp), cmocka_unit_test(t_flow_burst))
    GROUP("ctlq", cmocka_unit_test(t_control_queries))
    GROUP("model", cmocka_unit_test(t_model_a465))
    cleanup();
    return rc;
}
