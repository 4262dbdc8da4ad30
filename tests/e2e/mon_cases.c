/* mon_cases.c - the bad-input test: every case of a data file is fed to a fresh
 * fbrlmon, followed by a line that must work. Each case must give exactly one
 * error line (naming a place: "(FILE:LINE)"; an error inside a colon definition
 * may be followed by indented lines: its backtrace), leave both stacks empty, let the
 * next line run, exit with status 1, and not crash.
 *
 *   mon_cases FBRLMON CASES TMPDIR
 *
 * Case file: one case per line; blank lines and lines starting with '#' are
 * skipped. A case is its input text, optionally prefixed by a mode:
 *   (none)    the text is piped to standard input, then the check line
 *   file:     the text is written to a file given on the command line (it must
 *             fail there), the check line is piped
 *   -e:       the text is passed with -e, the check line is piped
 * Escapes in the text: \n newline, \t tab, \\ backslash, \xHH a byte,
 * \R<count>{<text>} <text> repeated <count> times. Any other backslash is kept
 * (Forth's \ comment). */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define TIMEOUT_MS 60000
#define CHECK_LINE "depth . fdepth . 7 6 * . cr\n"
#define CHECK_OUT  "0 0 42 \n"

typedef struct buf {
    char *p;
    size_t len, cap;
} buf;

static void put(buf *b, const char *s, size_t n)
{
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->len + n + 1)
            cap *= 2;
        b->p = realloc(b->p, cap);
        if (b->p == NULL) {
            perror("mon_cases");
            exit(2);
        }
        b->cap = cap;
    }
    memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = '\0';
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* Expand the escapes of one case text into b. */
static void unescape(const char *s, buf *b)
{
    while (*s) {
        if (s[0] == '\\' && s[1] == 'n') {
            put(b, "\n", 1), s += 2;
        } else if (s[0] == '\\' && s[1] == 't') {
            put(b, "\t", 1), s += 2;
        } else if (s[0] == '\\' && s[1] == '\\') {
            put(b, "\\", 1), s += 2;
        } else if (s[0] == '\\' && s[1] == 'x' && hexval(s[2]) >= 0 && hexval(s[3]) >= 0) {
            char c = (char)(hexval(s[2]) * 16 + hexval(s[3]));
            put(b, &c, 1), s += 4;
        } else if (s[0] == '\\' && s[1] == 'R') {
            char *end;
            unsigned long n = strtoul(s + 2, &end, 10), i;
            const char *close = end[0] == '{' ? strchr(end, '}') : NULL;
            if (close == NULL) {
                fprintf(stderr, "mon_cases: bad \\R in case\n");
                exit(2);
            }
            for (i = 0; i < n; i++)
                put(b, end + 1, (size_t)(close - end - 1));
            s = close + 1;
        } else {
            put(b, s, 1), s++;
        }
    }
}

static long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Run argv with `in` on stdin; collect stdout and stderr. Returns the wait
 * status, or -1 on timeout (the child is killed). */
static int run(char *const argv[], const buf *in, buf *out, buf *err)
{
    int pin[2], pout[2], perr[2], st;
    size_t off = 0;
    pid_t pid;
    long deadline = now_ms() + TIMEOUT_MS;

    if (pipe(pin) != 0 || pipe(pout) != 0 || pipe(perr) != 0) {
        perror("mon_cases: pipe");
        exit(2);
    }
    pid = fork();
    if (pid == 0) {
        dup2(pin[0], 0);
        dup2(pout[1], 1);
        dup2(perr[1], 2);
        close(pin[0]), close(pin[1]), close(pout[0]), close(pout[1]), close(perr[0]), close(perr[1]);
        execv(argv[0], argv);
        _exit(127);
    }
    close(pin[0]), close(pout[1]), close(perr[1]);
    fcntl(pin[1], F_SETFL, O_NONBLOCK);
    if (in->len == 0)
        close(pin[1]), pin[1] = -1;
    while (pout[0] >= 0 || perr[0] >= 0) {
        struct pollfd p[3];
        int i, n;
        long left = deadline - now_ms();
        if (left <= 0) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
            if (pin[1] >= 0)
                close(pin[1]);
            if (pout[0] >= 0)
                close(pout[0]);
            if (perr[0] >= 0)
                close(perr[0]);
            return -1;
        }
        p[0].fd = pout[0], p[1].fd = perr[0], p[2].fd = pin[1];
        p[0].events = p[1].events = POLLIN;
        p[2].events = POLLOUT;
        n = poll(p, 3, (int)(left > 1000 ? 1000 : left));
        if (n < 0 && errno != EINTR)
            break;
        for (i = 0; i < 2; i++) {
            if (p[i].fd >= 0 && (p[i].revents & (POLLIN | POLLHUP | POLLERR))) {
                char tmp[4096];
                ssize_t r = read(p[i].fd, tmp, sizeof tmp);
                if (r > 0) {
                    put(i == 0 ? out : err, tmp, (size_t)r);
                } else {
                    close(p[i].fd);
                    if (i == 0)
                        pout[0] = -1;
                    else
                        perr[0] = -1;
                }
            }
        }
        if (pin[1] >= 0 && (p[2].revents & (POLLOUT | POLLERR | POLLHUP))) {
            ssize_t w = write(pin[1], in->p + off, in->len - off);
            if (w > 0)
                off += (size_t)w;
            if (w < 0 && errno != EAGAIN && errno != EINTR)
                off = in->len; /* the child stopped reading (EPIPE): fine */
            if (off == in->len)
                close(pin[1]), pin[1] = -1;
        }
    }
    if (pin[1] >= 0)
        close(pin[1]);
    waitpid(pid, &st, 0);
    return st;
}

/* Lines that are not a backtrace's indented continuation lines. */
static size_t count_lines(const buf *b)
{
    size_t i, n = 0;
    for (i = 0; i < b->len; i++)
        n += b->p[i] == '\n' && !(i + 2 < b->len && b->p[i + 1] == ' ' && b->p[i + 2] == ' ');
    if (b->len > 0 && b->p[b->len - 1] != '\n')
        n++;
    return n;
}

/* "SOMEWHERE:NUMBER: error: ...\n" (the first line; a backtrace's lines follow it) */
static int good_error_line(const buf *e)
{
    const char *at, *d;
    const char *nl = memchr(e->p, '\n', e->len);
    if (e->len < 12 || e->p[e->len - 1] != '\n' || nl == NULL)
        return 0;
    at = strstr(e->p, ": error: ");
    if (at == NULL || at == e->p || at > nl)
        return 0;
    for (d = at - 1; d > e->p && d[0] >= '0' && d[0] <= '9'; d--)
        ;
    return d[0] == ':' && d != at - 1 && d > e->p;
}

static void show(const char *what, const buf *b)
{
    size_t i, n = b->len > 600 ? 600 : b->len;
    fprintf(stderr, "  %s (%zu bytes): ", what, b->len);
    for (i = 0; i < n; i++) {
        unsigned char c = (unsigned char)b->p[i];
        if (c >= 0x20 && c < 0x7f)
            fputc(c, stderr);
        else
            fprintf(stderr, "\\x%02x", c);
    }
    fprintf(stderr, "%s\n", n < b->len ? "..." : "");
}

int main(int argc, char **argv)
{
    FILE *cases;
    char *line = NULL, casefile[4096];
    size_t cap = 0;
    ssize_t n;
    unsigned long lineno = 0, total = 0, failed = 0;

    signal(SIGPIPE, SIG_IGN); /* a child that exits early must not kill the driver */
    if (argc != 4) {
        fprintf(stderr, "usage: mon_cases FBRLMON CASES TMPDIR\n");
        return 2;
    }
    cases = fopen(argv[2], "r");
    if (cases == NULL) {
        perror(argv[2]);
        return 2;
    }
    snprintf(casefile, sizeof casefile, "%s/case.fbrl", argv[3]);
    while ((n = getline(&line, &cap, cases)) >= 0) {
        buf text = {0}, in = {0}, out = {0}, err = {0};
        const char *src = line;
        char *args[6];
        int mode = 'p', st, ok;
        lineno++;
        while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r'))
            line[--n] = '\0';
        if (n == 0 || line[0] == '#')
            continue;
        if (strncmp(src, "file:", 5) == 0)
            mode = 'f', src += 5;
        else if (strncmp(src, "-e:", 3) == 0)
            mode = 'e', src += 3;
        while (*src == ' ')
            src++;
        unescape(src, &text);
        total++;

        args[0] = argv[1];
        args[1] = "--offline";
        args[2] = NULL;
        if (mode == 'p') {
            put(&in, text.p, text.len);
            put(&in, "\n", 1);
        } else if (mode == 'f') {
            FILE *f = fopen(casefile, "wb");
            if (f == NULL || fwrite(text.p, 1, text.len, f) != text.len || fclose(f) != 0) {
                perror(casefile);
                return 2;
            }
            args[2] = casefile;
            args[3] = NULL;
        } else {
            args[2] = "-e";
            args[3] = text.p;
            args[4] = NULL;
        }
        put(&in, CHECK_LINE, strlen(CHECK_LINE));
        st = run(args, &in, &out, &err);

        ok = st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 1 && count_lines(&err) == 1 &&
             good_error_line(&err) && out.len >= strlen(CHECK_OUT) &&
             strcmp(out.p + out.len - strlen(CHECK_OUT), CHECK_OUT) == 0;
        if (!ok) {
            failed++;
            fprintf(stderr, "FAIL case at %s:%lu: %.100s\n", argv[2], lineno, line);
            if (st == -1)
                fprintf(stderr, "  timed out\n");
            else if (WIFSIGNALED(st))
                fprintf(stderr, "  killed by signal %d\n", WTERMSIG(st));
            else
                fprintf(stderr, "  exit status %d (want 1)\n", WEXITSTATUS(st));
            show("stdout", &out);
            show("stderr", &err);
        }
        free(text.p), free(in.p), free(out.p), free(err.p);
    }
    free(line);
    fclose(cases);
    printf("mon_cases: %lu cases, %lu failed\n", total, failed);
    return failed != 0 || total == 0;
}
