/* SPDX-License-Identifier: MIT */
/* mon_session.h - shared by the e2e tests that drive fbrlmon through a real
 * pseudo-terminal (mon_pty.c, mon_teach.c): start it on a pty, type keys, wait for
 * output or a terminal mode, collect its exit status, print the transcript on failure.
 * The including file defines _XOPEN_SOURCE 600 (posix_openpt, grantpt, unlockpt,
 * ptsname) before any include. */
#ifndef MON_SESSION_H
#define MON_SESSION_H

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

typedef struct session {
    int master;
    pid_t pid;
    long timeout_ms;   /* for each wait */
    char buf[1 << 18]; /* everything fbrlmon wrote */
    size_t len;
    size_t mark; /* expect() searches from here */
} session;

static int g_failed; /* the first failure; later waits return at once */

static inline long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static inline void transcript(const session *s)
{
    size_t i;
    fprintf(stderr, "---- transcript (%zu bytes) ----\n", s->len);
    for (i = 0; i < s->len; i++) {
        unsigned char c = (unsigned char)s->buf[i];
        if (c == '\n' || (c >= 0x20 && c < 0x7f))
            fputc(c, stderr);
        else if (c != '\r')
            fprintf(stderr, "<%02x>", c);
    }
    fprintf(stderr, "\n---- end ----\n");
}

/* Read what is available within ms milliseconds; 0 at EOF/error. */
static inline int pump(session *s, int ms)
{
    struct pollfd p;
    ssize_t n;
    p.fd = s->master;
    p.events = POLLIN;
    if (poll(&p, 1, ms) <= 0)
        return 1;
    if (s->len + 1 >= sizeof s->buf)
        return 0;
    n = read(s->master, s->buf + s->len, sizeof s->buf - s->len - 1);
    if (n <= 0)
        return 0; /* EIO once the child closed the terminal */
    {
        /* Drop NUL padding (vt100 delays), so the text can be searched as a string. */
        size_t i, k = s->len;
        for (i = s->len; i < s->len + (size_t)n; i++)
            if (s->buf[i] != '\0')
                s->buf[k++] = s->buf[i];
        s->len = k;
    }
    s->buf[s->len] = '\0';
    return 1;
}

/* Wait until `text` appears after the mark; move the mark past it. */
static inline int expect(session *s, const char *text, const char *what)
{
    long deadline = now_ms() + s->timeout_ms;
    if (g_failed)
        return 0; /* after the first failure the rest would only wait and repeat it */
    for (;;) {
        char *hit;
        s->buf[s->len] = '\0';
        hit = strstr(s->buf + s->mark, text);
        if (hit != NULL) {
            s->mark = (size_t)(hit - s->buf) + strlen(text);
            return 1;
        }
        if (now_ms() > deadline || !pump(s, 200)) {
            /* one last look after EOF */
            hit = strstr(s->buf + s->mark, text);
            if (hit != NULL) {
                s->mark = (size_t)(hit - s->buf) + strlen(text);
                return 1;
            }
            fprintf(stderr, "FAIL: %s: did not see \"%s\"\n", what, text);
            transcript(s);
            g_failed = 1;
            return 0;
        }
    }
}

/* Wait until the terminal is in single-key mode (ICANON off): libedit's prompt or
 * TEACH's pendant reads keys. libedit draws the prompt a moment before it leaves line
 * mode, and keys typed in between would be taken by the kernel's line discipline (^D as
 * end-of-line, ^C as a signal before libedit listens). The master sees the slave's
 * termios. */
static inline void wait_keys(session *s)
{
    long deadline = now_ms() + s->timeout_ms;
    struct termios t;
    while (now_ms() < deadline && tcgetattr(s->master, &t) == 0 && (t.c_lflag & ICANON))
        if (!pump(s, 5))
            return;
}

/* Wait until the terminal is back in line mode (ICANON on): fbrlmon has left
 * the line editor and is evaluating the line. */
static inline void wait_running(session *s)
{
    long deadline = now_ms() + s->timeout_ms;
    struct termios t;
    while (now_ms() < deadline && tcgetattr(s->master, &t) == 0 && !(t.c_lflag & ICANON))
        if (!pump(s, 5))
            return;
}

/* Read output for ms milliseconds (pump() returns as soon as anything came). */
static inline void settle(session *s, long ms)
{
    long end = now_ms() + ms;
    while (now_ms() < end)
        if (!pump(s, (int)(end - now_ms())))
            return;
}

/* Occurrences of text in the string p. */
static inline int occurrences(const char *p, const char *text)
{
    int n = 0;
    while ((p = strstr(p, text)) != NULL) {
        n++;
        p += strlen(text);
    }
    return n;
}

/* Occurrences of text in a file (its first MiB), or -1 if it cannot be read. */
static inline int file_count(const char *path, const char *text)
{
    static char buf[1 << 20];
    size_t n;
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return -1;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return occurrences(buf, text);
}

/* Start fbrlsim with args (after the program's name, NULL-terminated) on a pty; its first
 * output line is the pty's path, read within timeout_ms. Returns the emulator's pid, or -1. */
static inline pid_t start_sim_pty_args(const char *sim, const char *const *args, char *port, size_t cap,
                                       long timeout_ms)
{
    const char *argv[32];
    int pfd[2], na = 0;
    pid_t pid;
    size_t n = 0;
    long deadline = now_ms() + timeout_ms;
    argv[na++] = sim;
    for (; args && *args && na < 31; args++)
        argv[na++] = *args;
    argv[na] = NULL;
    if (pipe(pfd) != 0)
        return -1;
    pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        dup2(pfd[1], 1);
        close(pfd[0]);
        close(pfd[1]);
        execv(sim, (char *const *)argv);
        _exit(127);
    }
    close(pfd[1]);
    while (n + 1 < cap && now_ms() < deadline) {
        char c;
        ssize_t r = read(pfd[0], &c, 1);
        if (r <= 0 || c == '\n')
            break;
        port[n++] = c;
    }
    port[n] = '\0';
    close(pfd[0]); /* fbrlsim prints nothing more on stdout */
    if (strncmp(port, "/dev/", 5) != 0) {
        fprintf(stderr, "FAIL: fbrlsim printed no device path (\"%s\")\n", port);
        kill(pid, SIGTERM);
        waitpid(pid, NULL, 0);
        return -1;
    }
    return pid;
}

/* Start fbrlsim on a pty with a command log (removed first) and its own STATUS lines. */
static inline pid_t start_sim_pty(const char *sim, const char *log, char *port, size_t cap, long timeout_ms)
{
    const char *args[] = {"--status-extra", "--log", log, NULL};
    remove(log);
    return start_sim_pty_args(sim, args, port, cap, timeout_ms);
}

/* Write keys at once (for Ctrl-C while a line runs and the terminal is in line mode). */
static inline void type_now(session *s, const char *text)
{
    size_t n = strlen(text), off = 0;
    while (off < n) {
        ssize_t w = write(s->master, text + off, n - off);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return;
        off += (size_t)w;
    }
}

static inline void type(session *s, const char *text)
{
    wait_keys(s);
    type_now(s, text);
}

/* Start `mon argv[1] ...` (argv NULL-terminated, argv[0] = mon) with a new 80x24 pty as
 * its controlling terminal (TEACH cuts its status line to that width), HOME and the
 * history file in dir (no ~/.editrc of the person running the tests) and TERM=vt100. */
static inline int start_mon_argv(session *s, long timeout_ms, const char *dir, char *const argv[])
{
    char hist[1024], *slave;
    struct winsize ws;
    memset(s, 0, sizeof *s);
    s->timeout_ms = timeout_ms;
    s->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (s->master < 0 || grantpt(s->master) != 0 || unlockpt(s->master) != 0 ||
        (slave = ptsname(s->master)) == NULL) {
        perror("posix_openpt");
        return -1;
    }
    memset(&ws, 0, sizeof ws);
    ws.ws_row = 24;
    ws.ws_col = 80;
    ioctl(s->master, TIOCSWINSZ, &ws);
    snprintf(hist, sizeof hist, "%s/history", dir);
    s->pid = fork();
    if (s->pid < 0)
        return -1;
    if (s->pid == 0) {
        int fd;
        setsid();
        fd = open(slave, O_RDWR); /* becomes the controlling terminal */
        if (fd < 0)
            _exit(127);
        dup2(fd, 0);
        dup2(fd, 1);
        dup2(fd, 2);
        if (fd > 2)
            close(fd);
        close(s->master);
        setenv("HOME", dir, 1);
        setenv("FBRLMON_HISTORY", hist, 1);
        setenv("TERM", "vt100", 1);
        execv(argv[0], argv);
        _exit(127);
    }
    return 0;
}

/* start_mon_argv() with `mon arg1 arg2` (arg2 may be NULL). */
static inline int start_mon(session *s, long timeout_ms, const char *dir, const char *mon, const char *arg1,
                            const char *arg2)
{
    char *argv[4];
    argv[0] = (char *)mon;
    argv[1] = (char *)arg1;
    argv[2] = (char *)arg2;
    argv[3] = NULL;
    return start_mon_argv(s, timeout_ms, dir, argv);
}

/* Wait for the child to end; its exit status, or -1. */
static inline int finish(session *s)
{
    long deadline = now_ms() + s->timeout_ms;
    int st;
    for (;;) {
        pid_t r = waitpid(s->pid, &st, WNOHANG);
        if (r == s->pid)
            break;
        if (now_ms() > deadline) {
            kill(s->pid, SIGKILL);
            waitpid(s->pid, &st, 0);
            fprintf(stderr, "FAIL: fbrlmon did not exit\n");
            transcript(s);
            g_failed = 1;
            close(s->master);
            return -1;
        }
        pump(s, 50);
    }
    while (pump(s, 0) && s->len < sizeof s->buf - 1) {
        struct pollfd p;
        p.fd = s->master;
        p.events = POLLIN;
        if (poll(&p, 1, 0) <= 0)
            break;
    }
    close(s->master);
    if (!WIFEXITED(st)) {
        fprintf(stderr, "FAIL: fbrlmon died (signal %d)\n", WIFSIGNALED(st) ? WTERMSIG(st) : 0);
        transcript(s);
        g_failed = 1;
        return -1;
    }
    return WEXITSTATUS(st);
}

#endif
