/* sim_core.c - fbrlsim's event loop: pty/TCP, line pacing, flow control, faults,
 * the line editor, the control FIFO and scripted inputs. Commands: sim_cmd.c. */
#include "sim_internal.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <locale.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#define TX_BUSY 512 /* pending output bytes at which the controller stops reading input */

static double mono(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

double sim_now(fbrl_sim *s)
{
    return (mono() - s->t0) * s->opt.time_scale;
}

static double real_now(fbrl_sim *s)
{
    return mono() - s->t0;
}

static char *dupstr(const char *p)
{
    char *d;
    if (!p)
        return NULL;
    d = malloc(strlen(p) + 1);
    if (d)
        strcpy(d, p);
    return d;
}

void sim_seterr(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    if (!err || !errlen)
        return;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* xorshift64*: reproducible faults from a seed. */
static double rnd(fbrl_sim *s)
{
    unsigned long long x = s->rng;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    s->rng = x;
    return (double)((x * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static unsigned char rnd_byte(fbrl_sim *s)
{
    return (unsigned char)(rnd(s) * 256.0);
}

static int parse_faults(fbrl_sim *s, const char *spec, char *err, size_t errlen)
{
    char buf[256], *tok, *save = NULL;
    unsigned long long seed = 1;
    if (strlen(spec) >= sizeof buf) {
        sim_seterr(err, errlen, "fault spec too long");
        return -1;
    }
    strcpy(buf, spec);
    for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '='), *end;
        double v;
        if (!eq) {
            sim_seterr(err, errlen, "fault '%s': expected name=value", tok);
            return -1;
        }
        *eq = 0;
        v = strtod(eq + 1, &end);
        if (*end || end == eq + 1 || !isfinite(v) || v < 0) {
            sim_seterr(err, errlen, "fault '%s': bad value", tok);
            return -1;
        }
        if (!strcmp(tok, "drop") && v <= 1)
            s->f_drop = v;
        else if (!strcmp(tok, "corrupt") && v <= 1)
            s->f_corrupt = v;
        else if (!strcmp(tok, "noise") && v <= 1)
            s->f_noise = v;
        else if (!strcmp(tok, "stall") && v <= 600000)
            s->f_stall = (int)v;
        else if (!strcmp(tok, "seed"))
            seed = (unsigned long long)v;
        else {
            sim_seterr(err, errlen, "fault '%s': unknown name or value out of range", tok);
            return -1;
        }
    }
    s->rng = seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    if (!s->rng)
        s->rng = 1;
    return 0;
}

/* The host channel checks parity (CONFIG 0 / --parity E or O). */
static int parity_on(fbrl_sim *s)
{
    return s->chan[0].parity == 'E' || s->chan[0].parity == 'O';
}

/* Applies the line faults to one byte; returns how many bytes went to out (0..2).
 * bad[k] = the receiving UART sees a parity error on out[k] (only with parity on): a
 * corrupted byte always (one bit flipped: an odd number), a noise byte half the time
 * (its parity bit is as random as its data). */
static int fault_byte(fbrl_sim *s, unsigned char b, unsigned char out[2], int bad[2])
{
    int n = 0;
    bad[0] = bad[1] = 0;
    if (s->f_drop > 0 && rnd(s) < s->f_drop)
        return 0;
    if (s->f_corrupt > 0 && rnd(s) < s->f_corrupt) {
        b ^= (unsigned char)(1u << (int)(rnd(s) * 8.0)); /* one bit flipped: always a different byte */
        bad[0] = parity_on(s);
    }
    out[n++] = b;
    if (s->f_noise > 0 && rnd(s) < s->f_noise) {
        bad[n] = parity_on(s) && rnd(s) < 0.5;
        out[n++] = rnd_byte(s);
    }
    return n;
}

/* A parity error, noted in the log (not a command: the line starts with '#'). */
static void log_parity(fbrl_sim *s, const char *dir)
{
    if (s->log) {
        fprintf(s->log, "# PARITY ERROR %s\n", dir);
        fflush(s->log);
    }
}

static void tx_push(fbrl_sim *s, unsigned char b)
{
    if (s->txlen == s->txcap) {
        size_t cap;
        unsigned char *t;
        if (s->txoff > 0) { /* compact first */
            memmove(s->tx, s->tx + s->txoff, s->txlen - s->txoff);
            s->txlen -= s->txoff;
            s->txoff = 0;
        }
        if (s->txlen == s->txcap) {
            cap = s->txcap ? s->txcap * 2 : 4096;
            t = realloc(s->tx, cap);
            if (!t)
                return; /* out of memory: the byte is lost, as on an overrun */
            s->tx = t;
            s->txcap = cap;
        }
    }
    s->tx[s->txlen++] = b;
}

/* What the host reads is what its UART delivers. With parity on, that is the format of
 * a Linux serial port opened with INPCK|PARMRK: a byte with a parity error comes as
 * 0xFF 0x00 byte, a data byte 0xFF as 0xFF 0xFF. */
void sim_emit(fbrl_sim *s, const char *bytes, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        unsigned char o[2];
        int bad[2];
        int k = fault_byte(s, (unsigned char)bytes[i], o, bad), j;
        for (j = 0; j < k; j++) {
            if (bad[j]) {
                s->parity_out++;
                log_parity(s, "OUT");
                tx_push(s, 0xFF);
                tx_push(s, 0x00);
            } else if (parity_on(s) && o[j] == 0xFF) {
                tx_push(s, 0xFF);
            }
            tx_push(s, o[j]);
        }
    }
}

static void emit_str(fbrl_sim *s, const char *str)
{
    sim_emit(s, str, strlen(str));
}

static int flow_on(fbrl_sim *s)
{
    return s->chan[0].handshake == 'X';
}

/* ---- receive side ---------------------------------------------------- */

static void rx_byte(fbrl_sim *s, unsigned char b)
{
    if (flow_on(s) && b == 0x11) {
        s->peer_xoff = 0;
        return;
    }
    if (flow_on(s) && b == 0x13) {
        s->peer_xoff = 1;
        return;
    }
    if (s->rxcount == s->rxcap) {
        s->overruns++;
        return;
    }
    s->rx[(s->rxhead + s->rxcount) % s->rxcap] = b;
    s->rxcount++;
    if (s->opt.baud > 0 && flow_on(s) && !s->xoff_sent && s->rxcount >= s->rxcap * 3 / 4) {
        s->urgent = 0x13;
        s->xoff_sent = 1;
    }
}

static int rx_pop(fbrl_sim *s)
{
    int b;
    if (!s->rxcount)
        return -1;
    b = s->rx[s->rxhead];
    s->rxhead = (s->rxhead + 1) % s->rxcap;
    s->rxcount--;
    if (s->xoff_sent && s->rxcount <= s->rxcap / 4) {
        s->urgent = 0x11;
        s->xoff_sent = 0;
    }
    return b;
}

static void close_conn(fbrl_sim *s)
{
    if (s->conn >= 0)
        close(s->conn);
    s->conn = -1;
    s->io = -1;
    if (s->ps == PS_STREAM)
        s->ps = PS_IDLE; /* nobody left to stop the readout */
    s->len = 0;
    s->overlong = 0;
    s->rxcount = 0;
    s->txoff = s->txlen = 0;
    s->peer_xoff = s->xoff_sent = 0;
    s->urgent = -1;
}

/* How many bytes may be read from the line now. */
static int rx_allow(fbrl_sim *s)
{
    if (s->io < 0)
        return 0;
    if (s->opt.baud > 0)
        return (int)s->rx_credit; /* bytes arrive at line rate; a full buffer overruns */
    return s->rxcap - s->rxcount; /* no line model: the kernel buffer holds the rest */
}

static void read_line(fbrl_sim *s)
{
    unsigned char buf[512];
    int allow = rx_allow(s), i;
    ssize_t n;
    if (allow <= 0)
        return;
    if (allow > (int)sizeof buf)
        allow = (int)sizeof buf;
    n = read(s->io, buf, (size_t)allow);
    if (n == 0 && s->conn >= 0) {
        close_conn(s);
        return;
    }
    if (n < 0) {
        if (errno != EAGAIN && errno != EINTR && s->conn >= 0)
            close_conn(s);
        return;
    }
    if (s->opt.baud > 0)
        s->rx_credit -= (double)n;
    for (i = 0; i < n; i++) {
        unsigned char o[2];
        int bad[2];
        int k = fault_byte(s, buf[i], o, bad), j;
        for (j = 0; j < k; j++) {
            if (bad[j]) {
                /* the controller's UART flags it; its firmware drops the character */
                s->parity_in++;
                log_parity(s, "IN");
                continue;
            }
            rx_byte(s, o[j]);
        }
    }
}

/* ---- transmit side --------------------------------------------------- */

static int tx_pending(fbrl_sim *s)
{
    return (int)(s->txlen - s->txoff);
}

static void write_line(fbrl_sim *s)
{
    double now = real_now(s);
    size_t n;
    ssize_t w;
    if (s->io < 0) {
        s->txoff = s->txlen = 0; /* nobody listening: the bytes fall off the line */
        s->urgent = -1;
        return;
    }
    if (s->urgent >= 0 && (s->opt.baud <= 0 || s->tx_credit >= 1.0)) {
        unsigned char b = (unsigned char)s->urgent;
        if (write(s->io, &b, 1) == 1) {
            s->urgent = -1;
            if (s->opt.baud > 0)
                s->tx_credit -= 1.0;
        }
    }
    if (s->peer_xoff || now < s->tx_hold_until || !tx_pending(s))
        return;
    n = (size_t)tx_pending(s);
    if (s->opt.baud > 0) {
        if (s->tx_credit < 1.0)
            return;
        if (n > (size_t)s->tx_credit)
            n = (size_t)s->tx_credit;
    }
    w = write(s->io, s->tx + s->txoff, n);
    if (w > 0) {
        s->txoff += (size_t)w;
        if (s->opt.baud > 0)
            s->tx_credit -= (double)w;
        if (s->txoff == s->txlen)
            s->txoff = s->txlen = 0;
    } else if (w < 0 && errno != EAGAIN && errno != EINTR && s->conn >= 0) {
        close_conn(s);
    }
}

/* ---- the line editor and the reply framing --------------------------- */

static void finish(fbrl_sim *s, int err)
{
    if (s->out.len)
        sim_emit(s, s->out.buf, s->out.len);
    s->out.len = 0;
    if (err >= 0) {
        char e[96];
        snprintf(e, sizeof e, "%03d-%s.\r\n", err, sim_error_text(err));
        emit_str(s, e);
        s->last_error = err;
    }
    if (s->ps == PS_STREAM) {
        s->stream_next = real_now(s);
    } else {
        s->ps = PS_IDLE;
        emit_str(s, ">>");
    }
    if (s->dirty && s->state_path) {
        if (sim_state_save(s) != 0 && !s->save_warned) {
            fprintf(stderr, "fbrlsim: cannot write %s: %s\n", s->state_path, strerror(errno));
            s->save_warned = 1;
        }
        s->dirty = 0;
    }
}

static void submit(fbrl_sim *s)
{
    char text[SIM_LINE_MAX + 1];
    int overlong = s->overlong, err = -1, i, blank = 1;
    memcpy(text, s->line, (size_t)s->len);
    text[s->len] = 0;
    s->len = 0;
    s->overlong = 0;
    if (s->f_stall > 0)
        s->tx_hold_until = real_now(s) + s->f_stall / 1000.0;
    emit_str(s, "\r\n");
    for (i = 0; text[i]; i++)
        if (text[i] != ' ')
            blank = 0;
    if (blank && !overlong) {
        emit_str(s, ">>");
        return;
    }
    if (s->log) {
        fprintf(s->log, "%s\n", text);
        fflush(s->log);
    }
    if (overlong) {
        finish(s, 25);
        return;
    }
    if (sim_exec(s, text, &err) == EXEC_BLOCK) {
        s->ps = PS_BUSY;
        return;
    }
    finish(s, err);
}

static void echo(fbrl_sim *s, const char *b, size_t n)
{
    if (s->chan[0].echo)
        sim_emit(s, b, n);
}

static void erase_one(fbrl_sim *s)
{
    if (s->len > 0) {
        s->len--;
        echo(s, "\b \b", 3);
    }
    if (s->len == 0)
        s->overlong = 0; /* an emptied line starts afresh */
}

static void line_byte(fbrl_sim *s, unsigned char b)
{
    char c;
    if (b == '\n' && s->last_cr) {
        s->last_cr = 0;
        return;
    }
    s->last_cr = b == '\r';
    if (b == '\r' || b == '\n') {
        submit(s);
        return;
    }
    if (b == 0x08 || b == 0x7f) {
        erase_one(s);
        return;
    }
    if (b == 0x18) {
        while (s->len > 0)
            erase_one(s);
        return;
    }
    if (b < 0x20 || b > 0x7e)
        return;
    c = (char)toupper(b);
    if (s->len >= SIM_LINE_MAX) {
        s->overlong = 1;
        return;
    }
    s->line[s->len++] = c;
    echo(s, &c, 1);
    if (s->help && (c == ' ' || c == ',')) {
        /* HELP mode: after the first word, show its syntax and erase it again. */
        char word[SIM_LINE_MAX + 1];
        const char *hint;
        int i;
        memcpy(word, s->line, (size_t)s->len - 1);
        word[s->len - 1] = 0;
        for (i = 0; word[i]; i++)
            if (word[i] == ' ' || word[i] == ',')
                return;
        hint = sim_help_hint(word);
        if (hint && *hint) {
            size_t k, n = strlen(hint);
            echo(s, hint, n);
            for (k = 0; k < n; k++)
                echo(s, "\b \b", 3);
        }
    }
}

static void process_input(fbrl_sim *s)
{
    int err;
    if (s->ps == PS_BUSY && sim_exec_step(s, &err) == EXEC_DONE)
        finish(s, err);
    if (s->ps == PS_STREAM) {
        int b = rx_pop(s);
        if (b >= 0) {
            s->ps = PS_IDLE;
            emit_str(s, "\r\n>>");
        } else if (real_now(s) >= s->stream_next) {
            sim_stream_line(s, &s->out);
            sim_emit(s, s->out.buf, s->out.len);
            s->out.len = 0;
            s->stream_next += 0.1;
            if (s->stream_next < real_now(s))
                s->stream_next = real_now(s) + 0.1;
        }
    }
    while (s->ps == PS_IDLE && s->rxcount > 0 && tx_pending(s) < TX_BUSY) {
        int b = rx_pop(s);
        line_byte(s, (unsigned char)b);
    }
}

/* ---- control FIFO and scripted inputs -------------------------------- */

static void read_control(fbrl_sim *s)
{
    char buf[256];
    ssize_t n = read(s->ctl, buf, sizeof buf), i;
    for (i = 0; i < n; i++) {
        if (buf[i] == '\n' || buf[i] == '\r') {
            s->ctlbuf[s->ctllen] = 0;
            if (s->ctllen)
                sim_control(s, s->ctlbuf);
            s->ctllen = 0;
        } else if (s->ctllen < sizeof s->ctlbuf - 1) {
            s->ctlbuf[s->ctllen++] = buf[i];
        }
    }
}

static int load_inputs(fbrl_sim *s, const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    char line[256];
    int lineno = 0;
    if (!f) {
        sim_seterr(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        char *end, *p = line;
        double t;
        struct sim_event *ev;
        int i;
        lineno++;
        line[strcspn(line, "\r\n")] = 0;
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p || *p == '#')
            continue;
        t = strtod(p, &end);
        if (end == p || !isfinite(t) || t < 0) {
            sim_seterr(err, errlen, "%s:%d: expected a time in seconds", path, lineno);
            fclose(f);
            return -1;
        }
        while (*end == ' ' || *end == '\t')
            end++;
        ev = realloc(s->events, (size_t)(s->nevents + 1) * sizeof *ev);
        if (!ev) {
            fclose(f);
            return -1;
        }
        s->events = ev;
        /* insertion keeps equal times in file order */
        for (i = s->nevents; i > 0 && s->events[i - 1].t > t; i--)
            s->events[i] = s->events[i - 1];
        s->events[i].t = t;
        s->events[i].cmd = dupstr(end);
        s->nevents++;
        if (sim_control(NULL, end) != 0) {
            sim_seterr(err, errlen, "%s:%d: unknown control line '%s'", path, lineno, end);
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    return 0;
}

static void run_events(fbrl_sim *s)
{
    double now = sim_now(s);
    while (s->next_event < s->nevents && s->events[s->next_event].t <= now) {
        sim_control(s, s->events[s->next_event].cmd);
        s->next_event++;
    }
}

/* ---- opening the line ------------------------------------------------ */

static int open_pty(fbrl_sim *s, char *err, size_t errlen)
{
    struct termios tio;
    s->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (s->master < 0 || grantpt(s->master) != 0 || unlockpt(s->master) != 0
        || ptsname_r(s->master, s->path, sizeof s->path) != 0) {
        sim_seterr(err, errlen, "pseudo-terminal: %s", strerror(errno));
        return -1;
    }
    /* Holding the slave open keeps the master from hanging up between clients. */
    s->slave = open(s->path, O_RDWR | O_NOCTTY);
    if (s->slave < 0 || tcgetattr(s->slave, &tio) != 0) {
        sim_seterr(err, errlen, "%s: %s", s->path, strerror(errno));
        return -1;
    }
    cfmakeraw(&tio);
    tcsetattr(s->slave, TCSANOW, &tio);
    fcntl(s->master, F_SETFL, fcntl(s->master, F_GETFL) | O_NONBLOCK);
    s->io = s->master;
    if (s->link_path) {
        struct stat st;
        if (lstat(s->link_path, &st) == 0 && !S_ISLNK(st.st_mode)) {
            sim_seterr(err, errlen, "link %s: exists and is not a symlink", s->link_path);
            free(s->link_path);
            s->link_path = NULL;
            return -1;
        }
        unlink(s->link_path); /* a stale link from an earlier run */
        if (symlink(s->path, s->link_path) != 0) {
            sim_seterr(err, errlen, "link %s: %s", s->link_path, strerror(errno));
            free(s->link_path);
            s->link_path = NULL;
            return -1;
        }
    }
    return 0;
}

static int open_tcp(fbrl_sim *s, char *err, size_t errlen)
{
    struct sockaddr_in a;
    socklen_t alen = sizeof a;
    int one = 1;
    s->lfd = socket(AF_INET, SOCK_STREAM, 0);
    if (s->lfd < 0) {
        sim_seterr(err, errlen, "socket: %s", strerror(errno));
        return -1;
    }
    setsockopt(s->lfd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((unsigned short)s->opt.tcp_port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(s->lfd, (struct sockaddr *)&a, sizeof a) != 0 || listen(s->lfd, 1) != 0
        || getsockname(s->lfd, (struct sockaddr *)&a, &alen) != 0) {
        sim_seterr(err, errlen, "tcp port %d: %s", s->opt.tcp_port, strerror(errno));
        return -1;
    }
    fcntl(s->lfd, F_SETFL, fcntl(s->lfd, F_GETFL) | O_NONBLOCK);
    snprintf(s->path, sizeof s->path, "tcp:127.0.0.1:%d", ntohs(a.sin_port));
    return 0;
}

static void accept_conn(fbrl_sim *s)
{
    int fd = accept(s->lfd, NULL, NULL);
    if (fd < 0)
        return;
    if (s->conn >= 0) { /* one client at a time, like one serial line */
        close(fd);
        return;
    }
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    s->conn = s->io = fd;
    s->credit_time = real_now(s);
}

static int open_control(fbrl_sim *s, char *err, size_t errlen)
{
    struct stat st;
    if (stat(s->control_path, &st) == 0 && !S_ISFIFO(st.st_mode)) {
        sim_seterr(err, errlen, "%s exists and is not a FIFO", s->control_path);
        return -1;
    }
    if (stat(s->control_path, &st) != 0 && mkfifo(s->control_path, 0600) != 0) {
        sim_seterr(err, errlen, "mkfifo %s: %s", s->control_path, strerror(errno));
        return -1;
    }
    /* Read-write so the FIFO never reports end-of-file between writers. */
    s->ctl = open(s->control_path, O_RDWR | O_NONBLOCK);
    if (s->ctl < 0) {
        sim_seterr(err, errlen, "%s: %s", s->control_path, strerror(errno));
        return -1;
    }
    return 0;
}

void fbrl_sim_options_init(fbrl_sim_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->tcp_port = -1;
    o->time_scale = 1.0;
    o->rx_buffer = 128;
}

fbrl_status fbrl_sim_create(fbrl_sim **out, const fbrl_sim_options *o, char *err, size_t errlen)
{
    fbrl_sim *s;
    if (!out || !o) {
        sim_seterr(err, errlen, "null argument");
        return FBRL_EINVAL;
    }
    *out = NULL;
    if (!(o->time_scale > 0) || !isfinite(o->time_scale) || o->baud < 0 || o->rx_buffer < 0
        || o->tcp_port > 65535) {
        sim_seterr(err, errlen, "bad option value");
        return FBRL_EINVAL;
    }
    s = calloc(1, sizeof *s);
    if (!s)
        return FBRL_ENOMEM;
    s->opt = *o;
    s->master = s->slave = s->lfd = s->conn = s->io = s->ctl = -1;
    s->wake[0] = s->wake[1] = -1;
    s->urgent = -1;
    /* Without a line model the buffer stands in for the kernel's: large, so that XON
     * from the host is still read while the controller waits for output to drain. */
    s->rxcap = o->baud > 0 ? (o->rx_buffer > 0 ? o->rx_buffer : 128) : 65536;
    s->rx = malloc((size_t)s->rxcap);
    s->state_path = dupstr(o->state_path);
    s->log_path = dupstr(o->log_path);
    s->control_path = dupstr(o->control_path);
    s->link_path = o->tcp_port < 0 ? dupstr(o->link_path) : NULL;
    s->opt.state_path = s->opt.log_path = s->opt.control_path = s->opt.link_path = NULL;
    s->opt.inputs_path = s->opt.faults = NULL;
    s->rng = 1;
    sim_state_defaults(s);
    if (!s->rx)
        goto fail_mem;
    if (o->faults && parse_faults(s, o->faults, err, errlen) != 0)
        goto fail;
    if (s->state_path && sim_state_load(s, err, errlen) != 0)
        goto fail;
    if (o->baud > 0)
        s->chan[0].baud = o->baud;
    if (o->parity) {
        if (o->parity != 'N' && o->parity != 'E' && o->parity != 'O') {
            sim_seterr(err, errlen, "parity must be N, E or O");
            goto fail;
        }
        s->chan[0].parity = o->parity;
    }
    if (o->inputs_path && load_inputs(s, o->inputs_path, err, errlen) != 0)
        goto fail;
    if (s->log_path && !(s->log = fopen(s->log_path, "a"))) {
        sim_seterr(err, errlen, "%s: %s", s->log_path, strerror(errno));
        goto fail;
    }
    if (pipe(s->wake) != 0) {
        sim_seterr(err, errlen, "pipe: %s", strerror(errno));
        goto fail;
    }
    fcntl(s->wake[0], F_SETFL, O_NONBLOCK);
    fcntl(s->wake[1], F_SETFL, O_NONBLOCK);
    if ((o->tcp_port >= 0 ? open_tcp(s, err, errlen) : open_pty(s, err, errlen)) != 0)
        goto fail;
    if (s->control_path && open_control(s, err, errlen) != 0)
        goto fail;
    s->t0 = mono();
    *out = s;
    return FBRL_OK;
fail_mem:
    sim_seterr(err, errlen, "out of memory");
fail:
    free(s->state_path); /* nothing was loaded into a file: do not write it back */
    s->state_path = NULL;
    fbrl_sim_destroy(s);
    return FBRL_EIO;
}

const char *fbrl_sim_path(const fbrl_sim *s)
{
    return s ? s->path : "";
}

/* Real seconds until something is due, capped by limit. */
static double due_in(fbrl_sim *s, double limit)
{
    double r = limit, now = real_now(s), scale = s->opt.time_scale, t;
    if (s->moving || s->xmoving) {
        double end = s->moving ? s->mt1 : s->xt1;
        if (s->moving && s->xmoving && s->xt1 < end)
            end = s->xt1;
        t = (end - sim_now(s)) / scale;
        if (t < r)
            r = t;
    }
    if (s->ps == PS_BUSY && r > 0.005)
        r = 0.005; /* WAIT and RUN poll their conditions */
    if (s->ps == PS_STREAM && s->stream_next - now < r)
        r = s->stream_next - now;
    if (s->next_event < s->nevents) {
        t = (s->events[s->next_event].t - sim_now(s)) / scale;
        if (t < r)
            r = t;
    }
    if (tx_pending(s) && s->tx_hold_until > now && s->tx_hold_until - now < r)
        r = s->tx_hold_until - now;
    if (s->opt.baud > 0 && (tx_pending(s) || s->urgent >= 0 || s->io >= 0)) {
        t = 1.0 / (s->opt.baud / 10.0); /* the next character time */
        if ((tx_pending(s) || s->urgent >= 0 || s->rx_credit < 1.0) && t < r)
            r = t;
    }
    if (s->ps == PS_IDLE && s->rxcount > 0 && r > 0.001)
        r = 0.001;
    return r < 0 ? 0 : r;
}

fbrl_status fbrl_sim_step(fbrl_sim *s, int timeout_ms)
{
    struct pollfd p[4];
    int np = 0, iw = -1, ictl = -1, iio = -1, ilfd = -1, ms;
    double now, wait;

    if (!s)
        return FBRL_EINVAL;
    now = real_now(s);
    if (s->opt.baud > 0) {
        double rate = s->opt.baud / 10.0, cap = rate * 0.02;
        if (cap < 2.0)
            cap = 2.0;
        s->rx_credit += (now - s->credit_time) * rate;
        s->tx_credit += (now - s->credit_time) * rate;
        if (s->rx_credit > cap)
            s->rx_credit = cap;
        if (s->tx_credit > cap)
            s->tx_credit = cap;
    }
    s->credit_time = now;
    sim_arm_update(s);
    run_events(s);
    process_input(s);
    write_line(s);

    wait = due_in(s, timeout_ms < 0 ? 1.0 : timeout_ms / 1000.0);
    ms = (int)ceil(wait * 1000.0);
    iw = np;
    p[np].fd = s->wake[0];
    p[np++].events = POLLIN;
    if (s->ctl >= 0) {
        ictl = np;
        p[np].fd = s->ctl;
        p[np++].events = POLLIN;
    }
    if (s->lfd >= 0 && s->conn < 0) {
        ilfd = np;
        p[np].fd = s->lfd;
        p[np++].events = POLLIN;
    }
    if (s->io >= 0) {
        short ev = 0;
        if (rx_allow(s) > 0)
            ev |= POLLIN;
        if ((tx_pending(s) && !s->peer_xoff && now >= s->tx_hold_until) || s->urgent >= 0)
            if (s->opt.baud <= 0 || s->tx_credit >= 1.0)
                ev |= POLLOUT;
        iio = np;
        p[np].fd = s->io;
        p[np++].events = ev;
    }
    if (poll(p, (nfds_t)np, ms) < 0) {
        if (errno == EINTR)
            return FBRL_OK;
        return FBRL_EIO;
    }
    if (p[iw].revents & POLLIN) {
        char b[64];
        while (read(s->wake[0], b, sizeof b) > 0)
            ;
    }
    if (ictl >= 0 && (p[ictl].revents & POLLIN))
        read_control(s);
    if (ilfd >= 0 && (p[ilfd].revents & POLLIN))
        accept_conn(s);
    if (iio >= 0 && s->io >= 0) {
        if (p[iio].revents & (POLLIN | POLLHUP | POLLERR))
            read_line(s);
        if (s->io >= 0 && (p[iio].revents & POLLOUT))
            write_line(s);
    }
    process_input(s);
    write_line(s);
    return FBRL_OK;
}

static int stopping(fbrl_sim *s)
{
    return __atomic_load_n(&s->stop, __ATOMIC_ACQUIRE);
}

fbrl_status fbrl_sim_run(fbrl_sim *s)
{
    if (!s)
        return FBRL_EINVAL;
    while (!stopping(s)) {
        fbrl_status st = fbrl_sim_step(s, 200);
        if (st != FBRL_OK)
            return st;
    }
    return FBRL_OK;
}

static void *thread_main(void *arg)
{
    /* RAPL replies and the state file are "C" text whatever locale the host process set
     * (a program embedding the emulator may call setlocale(LC_ALL, "")). */
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c)
        uselocale(c);
    fbrl_sim_run(arg);
    if (c) {
        uselocale(LC_GLOBAL_LOCALE);
        freelocale(c);
    }
    return NULL;
}

fbrl_status fbrl_sim_start(fbrl_sim *s)
{
    if (!s || s->thread_started)
        return FBRL_EINVAL;
    if (pthread_create(&s->thread, NULL, thread_main, s) != 0)
        return FBRL_EIO;
    s->thread_started = 1;
    return FBRL_OK;
}

void fbrl_sim_stop(fbrl_sim *s)
{
    char b = 1;
    ssize_t r;
    if (!s)
        return;
    __atomic_store_n(&s->stop, 1, __ATOMIC_RELEASE);
    r = write(s->wake[1], &b, 1);
    (void)r;
}

void fbrl_sim_destroy(fbrl_sim *s)
{
    int i;
    if (!s)
        return;
    if (s->thread_started) {
        fbrl_sim_stop(s);
        pthread_join(s->thread, NULL);
        s->thread_started = 0;
    }
    if (s->state_path) {
        sim_arm_update(s);
        sim_state_save(s);
    }
    if (s->conn >= 0)
        close(s->conn);
    if (s->lfd >= 0)
        close(s->lfd);
    if (s->master >= 0)
        close(s->master);
    if (s->slave >= 0)
        close(s->slave);
    if (s->ctl >= 0)
        close(s->ctl);
    if (s->wake[0] >= 0)
        close(s->wake[0]);
    if (s->wake[1] >= 0)
        close(s->wake[1]);
    if (s->link_path) {
        char target[sizeof s->path];
        ssize_t n = readlink(s->link_path, target, sizeof target - 1);
        if (n > 0) {
            target[n] = 0;
            if (!strcmp(target, s->path)) /* still ours, not a newer emulator's */
                unlink(s->link_path);
        }
    }
    if (s->log)
        fclose(s->log);
    for (i = 0; i < s->nevents; i++)
        free(s->events[i].cmd);
    free(s->events);
    sim_free_memory(s);
    free(s->out.buf);
    free(s->tx);
    free(s->rx);
    free(s->state_path);
    free(s->log_path);
    free(s->control_path);
    free(s->link_path);
    free(s);
}
