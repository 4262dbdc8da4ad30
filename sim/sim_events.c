/* SPDX-License-Identifier: MIT */
/* sim_events.c - the world outside the serial line: control lines from the
 * --control FIFO at any time and from the time-stamped --inputs script. What a
 * control line does is sim_control(). */
#include "sim_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char *dupstr(const char *p)
{
    char *d = malloc(strlen(p) + 1);
    if (d)
        strcpy(d, p);
    return d;
}

int sim_events_open_fifo(sim_events *ev, const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISFIFO(st.st_mode)) {
        sim_seterr(err, errlen, "%s exists and is not a FIFO", path);
        return -1;
    }
    if (stat(path, &st) != 0 && mkfifo(path, 0600) != 0) {
        sim_seterr(err, errlen, "mkfifo %s: %s", path, strerror(errno));
        return -1;
    }
    /* Read-write so the FIFO never reports end-of-file between writers. */
    ev->ctl = open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (ev->ctl < 0) {
        sim_seterr(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    return 0;
}

void sim_events_read_fifo(fbrl_sim *s)
{
    sim_events *ev = &s->events;
    char buf[256];
    ssize_t n = read(ev->ctl, buf, sizeof buf), i;
    for (i = 0; i < n; i++) {
        if (buf[i] == '\n' || buf[i] == '\r') {
            ev->ctlbuf[ev->ctllen] = 0;
            if (ev->ctllen && !ev->ctl_overlong) {
                char why[160];
                if (sim_control_why(s, ev->ctlbuf, why, sizeof why) != 0)
                    sim_control_say(s, "REFUSED %s: %s", ev->ctlbuf, why);
            } else if (ev->ctl_overlong) {
                sim_control_say(s, "REFUSED a line longer than %d characters", (int)sizeof ev->ctlbuf - 1);
            }
            ev->ctllen = 0;
            ev->ctl_overlong = 0;
        } else if (ev->ctllen < sizeof ev->ctlbuf - 1) {
            ev->ctlbuf[ev->ctllen++] = buf[i];
        } else {
            ev->ctl_overlong = 1; /* dropped whole: a cut line could mean something else */
        }
    }
}

int sim_events_load(sim_events *ev, const char *path, char *err, size_t errlen)
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
        struct sim_event *e;
        int i;
        lineno++;
        if (!strchr(line, '\n') && !feof(f)) {
            sim_seterr(err, errlen, "%s:%d: line too long (at most %d characters)", path, lineno,
                       (int)sizeof line - 2);
            fclose(f);
            return -1;
        }
        line[strcspn(line, "\r\n")] = 0;
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p || *p == '#')
            continue;
        /* a decimal time (strtod alone would take hex, nan, inf), then a space */
        t = strtod(p, &end);
        if (end == p || strspn(p, "0123456789+-.eE") != (size_t)(end - p) || !isfinite(t) || t < 0 ||
            (*end != ' ' && *end != '\t')) {
            sim_seterr(err, errlen, "%s:%d: expected a time in seconds", path, lineno);
            fclose(f);
            return -1;
        }
        while (*end == ' ' || *end == '\t')
            end++;
        char why[160];
        if (sim_control_why(NULL, end, why, sizeof why) != 0) {
            sim_seterr(err, errlen, "%s:%d: %s: '%s'", path, lineno, why, end);
            fclose(f);
            return -1;
        }
        e = realloc(ev->list, (size_t)(ev->n + 1) * sizeof *e);
        if (!e) {
            sim_seterr(err, errlen, "out of memory");
            fclose(f);
            return -1;
        }
        ev->list = e;
        /* insertion keeps equal times in file order */
        for (i = ev->n; i > 0 && ev->list[i - 1].t > t; i--)
            ev->list[i] = ev->list[i - 1];
        ev->list[i].t = t;
        ev->list[i].cmd = dupstr(end);
        if (!ev->list[i].cmd) {
            sim_seterr(err, errlen, "out of memory");
            fclose(f);
            return -1;
        }
        ev->n++;
    }
    fclose(f);
    return 0;
}

void sim_events_run(fbrl_sim *s)
{
    sim_events *ev = &s->events;
    double now = sim_now(s);
    while (ev->next < ev->n && ev->list[ev->next].t <= now) {
        sim_control(s, ev->list[ev->next].cmd);
        ev->next++;
    }
}

/* Real seconds until the next scripted line, capped by limit. */
double sim_events_due(const fbrl_sim *s, double limit)
{
    const sim_events *ev = &s->events;
    double t;
    if (ev->next >= ev->n)
        return limit;
    t = (ev->list[ev->next].t - sim_now(s)) / s->opt.time_scale;
    return t < limit ? t : limit;
}

void sim_events_free(sim_events *ev)
{
    int i;
    if (ev->ctl >= 0)
        close(ev->ctl);
    ev->ctl = -1;
    for (i = 0; i < ev->n; i++)
        free(ev->list[i].cmd);
    free(ev->list);
    ev->list = NULL;
    ev->n = ev->next = 0;
}
