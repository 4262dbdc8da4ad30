/* SPDX-License-Identifier: MIT */
/* mon_host.c - OS services for the engine inside fbrlmon (the app may use the OS). */
#include "mon_host.h"
#include "fbrl/fileio.h"
#include "mon_files.h"

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <stdlib.h>

/* Refill the read-ahead; 0 at end of input or error. */
static int in_fill(mon_host *h)
{
    ssize_t n;
    if (h->in_eof)
        return 0;
    do {
        n = read(h->in_fd, h->inbuf, sizeof h->inbuf);
    } while (n < 0 && errno == EINTR && !h->interrupted);
    if (n < 0 && errno == EINTR)
        return 0; /* Ctrl-C while a word reads a line: not the end of input */
    if (n <= 0) {
        h->in_eof = 1;
        return 0;
    }
    h->inpos = 0;
    h->inlen = (size_t)n;
    return 1;
}

const char *mon_host_read_line(mon_host *h, size_t *len)
{
    size_t n = 0;
    int got = 0;
    if (h->line_too_long)
        return NULL; /* input was stopped */
    for (;;) {
        unsigned char c;
        if (h->inpos == h->inlen && !in_fill(h))
            break;
        c = h->inbuf[h->inpos++];
        got = 1;
        if (c == '\n')
            break;
        if (n >= (size_t)MON_HOST_LINE_MAX) {
            h->line_too_long = 1;
            h->in_eof = 1;
            break;
        }
        if (n + 1 >= h->line_cap) {
            size_t cap = h->line_cap ? h->line_cap * 2 : 256;
            char *p = realloc(h->line, cap);
            if (p == NULL)
                break; /* out of memory: hand over what fits */
            h->line = p;
            h->line_cap = cap;
        }
        h->line[n++] = (char)c;
    }
    if (!got)
        return NULL;
    if (n > 0 && h->line[n - 1] == '\r')
        n--;
    if (h->line == NULL) { /* an empty first line */
        h->line = malloc(1);
        if (h->line == NULL)
            return NULL;
        h->line_cap = 1;
    }
    h->line[n] = '\0';
    *len = n;
    return h->line;
}

void mon_host_free(mon_host *h)
{
    free(h->line);
    h->line = NULL;
    h->line_cap = 0;
}

static int only_blanks(const char *s, size_t n)
{
    while (n > 0 && (*s == ' ' || *s == '\t'))
        s++, n--;
    return n == 0;
}

/* On a terminal, a piece of output that would run past the right margin starts
 * a new line, so WORDS and long runs of numbers wrap between words, not inside
 * them. Piped output is written unchanged. */
static void host_write(void *user, const char *s, size_t n)
{
    mon_host *h = user;
    const char *nl;
    if (n == 0)
        return;
    if (h->width > 0 && h->column > 0 && h->column + (long)n >= h->width && memchr(s, '\n', n) == NULL &&
        !only_blanks(s, n)) {
        fputc('\n', h->out);
        h->column = 0;
    }
    fwrite(s, 1, n, h->out);
    for (nl = s + n; nl > s && nl[-1] != '\n'; nl--)
        ;
    n = nl > s ? (size_t)(s + n - nl) : (size_t)h->column + n;
    h->column = n > 65535 ? 65535 : (int)n; /* only compared with the width */
    if (h->out_is_tty)
        fflush(h->out);
}

static void update_width(mon_host *h)
{
    struct winsize ws;
    h->width = 0;
    if (h->out_is_tty && ioctl(fileno(h->out), TIOCGWINSZ, &ws) == 0)
        h->width = ws.ws_col > 0 ? ws.ws_col : 80;
}

/* One byte from the keyboard. On a terminal KEY must not wait for Enter, so the
 * line discipline is switched to single-byte, no-echo reads for this one key. */
static int host_key(void *user)
{
    mon_host *h = user;
    unsigned char c;
    ssize_t n;
    struct termios saved, raw;
    int restore = 0;

    if (h->inpos < h->inlen)
        return h->inbuf[h->inpos++];
    if (!h->in_is_tty)
        return in_fill(h) ? h->inbuf[h->inpos++] : -1;
    fflush(h->out);
    if (tcgetattr(h->in_fd, &saved) == 0) {
        raw = saved;
        raw.c_lflag &= ~(tcflag_t)(ICANON | ECHO);
        raw.c_cc[VMIN] = 1;
        raw.c_cc[VTIME] = 0;
        restore = tcsetattr(h->in_fd, TCSANOW, &raw) == 0;
    }
    n = -1;
    while (!h->interrupted && (n = read(h->in_fd, &c, 1)) < 0 && errno == EINTR)
        ;
    if (restore)
        tcsetattr(h->in_fd, TCSANOW, &saved);
    return n == 1 ? c : -1;
}

static int host_key_ready(void *user)
{
    mon_host *h = user;
    struct pollfd p;
    if (h->inpos < h->inlen)
        return 1;
    if (h->in_eof)
        return 0;
    p.fd = h->in_fd;
    p.events = POLLIN;
    p.revents = 0;
    return poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP));
}

/* An open source file; the line count lets a "#!" first line be skipped. */
typedef struct mon_file {
    FILE *f;
    unsigned long lines;
    unsigned long skip; /* RESUME: lines read as empty */
} mon_file;

static fbrl_status host_file_open(void *user, const char *path, void **handle)
{
    mon_host *h = user;
    mon_file *mf;
    if (path == NULL || handle == NULL)
        return FBRL_EINVAL;
    mf = malloc(sizeof *mf);
    if (mf == NULL)
        return FBRL_ENOSPC;
    mf->lines = 0;
    mf->skip = 0;
    /* Only regular files: a device (/dev/zero) never ends, a FIFO with no writer would
     * block the open itself. O_NONBLOCK keeps that open from blocking; fstat on the open
     * descriptor then decides (no window between a check and the open). */
    {
        struct stat sb;
        int fd = open(path, O_RDONLY | O_NONBLOCK);
        if (fd < 0) {
            fbrl_status st = fbrl_file_status_of_errno(errno); /* permission, a link loop ... */
            free(mf);
            return st;
        }
        if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
            close(fd);
            free(mf);
            return FBRL_ENOTFILE;
        }
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
        mf->f = fdopen(fd, "r");
        if (mf->f == NULL) {
            close(fd);
            free(mf);
            return FBRL_EIO;
        }
    }
    if (h->skip_lines > 0 && h->skip_path != NULL && strcmp(h->skip_path, path) == 0) {
        mf->skip = h->skip_lines;
        h->skip_lines = 0;
    }
    h->file_depth++;
    *handle = mf;
    return FBRL_OK;
}

/* One line without its end (LF or CRLF). A line longer than cap is reported as
 * FBRL_ENOSPC as soon as cap is passed (the engine stops the file there and names
 * file:line); nothing more of it is read, so a file with no line end cannot keep
 * fbrlmon reading.
 * A first line starting with "#!" reads as empty, so a plan file can be an
 * executable script (#!/usr/bin/env fbrlmon) and line numbers stay right. (The
 * engine's #! word needs a blank after it, which a shebang line rarely has.) */
static fbrl_status host_file_read_line(void *user, void *handle, char *buf, size_t cap, size_t *len)
{
    mon_file *mf = handle;
    size_t n = 0;
    int c, too_long = 0;
    (void)user;
    if (mf == NULL || buf == NULL || len == NULL)
        return FBRL_EINVAL;
    *len = 0;
    while ((c = getc(mf->f)) != EOF && c != '\n') {
        if (n < cap)
            buf[n++] = (char)c;
        else if (!(c == '\r' && n == cap)) { /* a CR just before LF is not content */
            too_long = 1;
            break;
        }
    }
    if (ferror(mf->f))
        return FBRL_EIO;
    if (c == EOF && n == 0 && !too_long)
        return FBRL_EEOF;
    if (++mf->lines <= mf->skip) { /* RESUME: before the line to go on from */
        while (too_long && (c = getc(mf->f)) != EOF && c != '\n')
            ;
        return FBRL_OK;
    }
    if (mf->lines == 1 && n >= 2 && buf[0] == '#' && buf[1] == '!') {
        while (too_long && (c = getc(mf->f)) != EOF && c != '\n')
            ; /* the rest of a long "#!" line (a regular file ends) */
        return FBRL_OK;
    }
    if (too_long)
        return FBRL_ENOSPC;
    if (n > 0 && buf[n - 1] == '\r')
        n--;
    *len = n;
    return FBRL_OK;
}

static void host_file_close(void *user, void *handle)
{
    mon_host *h = user;
    mon_file *mf = handle;
    if (mf != NULL) {
        fclose(mf->f);
        free(mf);
        h->file_depth--;
    }
}

static uint64_t host_now_us(void *user)
{
    struct timespec ts;
    (void)user;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* Sleeps in slices so that a Ctrl-C (h->interrupted) ends the wait promptly even
 * if it came just before the sleep began. */
static void host_sleep_ms(void *user, uint32_t ms)
{
    mon_host *h = user;
    fflush(h->out);
    while (ms > 0 && !h->interrupted) {
        uint32_t slice = ms < 100u ? ms : 100u;
        struct timespec ts;
        ts.tv_sec = 0;
        ts.tv_nsec = (long)slice * 1000000L;
        while (nanosleep(&ts, &ts) != 0 && errno == EINTR && !h->interrupted)
            ;
        ms -= slice;
        if (h->tick != NULL && h->tick(h->tick_ctx))
            break;
    }
}

/* A console line for the engine (GET-CAL-POINTS): the line editor when the interactive
 * session runs, else a plain line (the prompt shown only on a terminal). */
static fbrl_status host_read_line(void *user, const char *prompt, char *buf, size_t cap, size_t *len)
{
    mon_host *h = user;
    const char *line;
    size_t n = 0;
    if (cap == 0)
        return FBRL_EINVAL;
    if (h->edit_line != NULL) {
        fflush(h->out);
        line = h->edit_line(h->edit_ctx, prompt, &n);
    } else {
        if (h->in_is_tty) {
            fputs(prompt, h->out);
            fflush(h->out);
        }
        line = h->interrupted ? NULL : mon_host_read_line(h, &n);
    }
    h->column = 0;
    if (line == NULL)
        return FBRL_EEOF;
    if (n >= cap)
        n = cap - 1;
    memcpy(buf, line, n);
    *len = n;
    return FBRL_OK;
}

static void host_time_date(void *user, int out[6])
{
    time_t t = time(NULL);
    struct tm tm;
    (void)user;
    memset(&tm, 0, sizeof tm);
    localtime_r(&t, &tm);
    out[0] = tm.tm_sec;
    out[1] = tm.tm_min;
    out[2] = tm.tm_hour;
    out[3] = tm.tm_mday;
    out[4] = tm.tm_mon + 1;
    out[5] = tm.tm_year + 1900;
}

/* The dry run's clock (mon_host_use_clock), or NULL. */
static uint64_t (*g_now_us)(void *user);
static void (*g_sleep_ms)(void *user, uint32_t ms);
static void (*g_time_date)(void *user, int out[6]);

void mon_host_use_clock(uint64_t (*now_us)(void *user), void (*sleep_ms)(void *user, uint32_t ms),
                        void (*time_date)(void *user, int out[6]))
{
    g_now_us = now_us;
    g_sleep_ms = sleep_ms;
    g_time_date = time_date;
}

void mon_host_init(mon_host *h, FILE *out, int in_fd, fbrl_vm_host *cb)
{
    memset(h, 0, sizeof *h);
    h->out = out;
    h->out_is_tty = isatty(fileno(out));
    update_width(h);
    h->in_fd = in_fd;
    h->in_is_tty = isatty(in_fd);

    memset(cb, 0, sizeof *cb);
    cb->user = h;
    cb->write = host_write;
    cb->key = host_key;
    cb->key_ready = host_key_ready;
    cb->file_open = host_file_open;
    cb->file_read_line = host_file_read_line;
    cb->file_close = host_file_close;
    cb->now_us = g_now_us ? g_now_us : host_now_us;
    cb->sleep_ms = g_sleep_ms ? g_sleep_ms : host_sleep_ms;
    cb->time_date = g_time_date ? g_time_date : host_time_date;
    cb->read_line = host_read_line;
    cb->files = mon_files();
}

void mon_host_progress(void *ctx, const char *text)
{
    mon_host *h = ctx;
    if (!h->out_is_tty || (h->column != 0 && !h->progress_shown))
        return;
    if (text == NULL) {
        if (h->progress_shown)
            fputs("\r\033[K", h->out); /* erase it: the column is 0 again */
        h->progress_shown = 0;
    } else {
        int room = h->width > 1 ? h->width - 1 : 79; /* never wrap */
        fprintf(h->out, "\r%.*s\033[K", room, text);
        h->progress_shown = 1;
    }
    fflush(h->out);
}

void mon_host_newline(mon_host *h)
{
    /* Only a terminal needs it; piped output stays exactly what the program wrote. */
    if (h->column && h->out_is_tty) {
        fputc('\n', h->out);
        h->column = 0;
    }
    fflush(h->out);
    update_width(h); /* the window may have been resized */
}
