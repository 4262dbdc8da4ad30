/* SPDX-License-Identifier: MIT */
/* mon_safe.c - Ctrl-C in fbrlmon. One handler serves the whole run: while the engine
 * evaluates it asks it to stop (the engine throws "user interrupt" at its next call,
 * loop step or robot wait); at the prompt it discards the line. Either way the main
 * thread then makes the safe stop (fbrl_robot_safe_stop: HALT, the session's outputs
 * off) and reports where it stopped and what the arm was doing. A second Ctrl-C within
 * MON_QUIT_WINDOW_MS ends fbrlmon after that stop; a third, while the stop still runs,
 * ends it at once (the controller does not answer: check the cell by hand). */
#include "mon_safe.h"
#include "fbrl/num.h"
#include "fbrl/vm_throw.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { MODE_IDLE, MODE_EVAL, MODE_STOP };

static mon *g_m;
static volatile sig_atomic_t g_mode, g_pending, g_quit;
/* g_armed: a Ctrl-C came and no line was started since; g_last_ms: its time (only the
 * handler reads and writes it) */
static volatile sig_atomic_t g_armed;
static long g_last_ms;

static long mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts); /* async-signal-safe */
    return (long)ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

static void on_sigint(int sig)
{
    long now = mono_ms();
    if (g_quit && g_mode != MODE_IDLE) {
        static const char msg[] = "\nfbrlmon: ended by a third Ctrl-C before the safe stop finished:"
                                  " check the arm and the outputs\n";
        ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
        (void)w;
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    if (g_armed && now - g_last_ms <= MON_QUIT_WINDOW_MS)
        g_quit = 1;
    g_last_ms = now;
    g_armed = 1;
    g_pending = 1;
    if (g_mode == MODE_EVAL && g_m != NULL) {
        g_m->host.interrupted++; /* waits in MS and KEY end at once */
        fbrl_vm_interrupt(g_m->vm);
    }
}

void mon_safe_install(mon *m)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint; /* no SA_RESTART: waits return */
    sigemptyset(&sa.sa_mask);
    g_m = m;
    sigaction(SIGINT, &sa, NULL);
}

int mon_safe_pending(void) { return g_pending != 0; }
int mon_safe_quit(void) { return g_quit != 0; }

void mon_safe_begin(mon *m)
{
    m->host.interrupted = 0;
    if (!g_pending)
        g_armed = 0; /* a new line: the next Ctrl-C is a first one again */
    g_mode = MODE_EVAL;
}

/* " 1-4 6 9-16", or " none". */
static void put_outputs(const char *label, uint32_t bits)
{
    int n, any = 0;
    fputs(label, stderr);
    for (n = 1; n <= FBRL_ROBOT_IO_MAX; n++) {
        int last = n;
        if (!(bits & (1u << (n - 1))))
            continue;
        while (last < FBRL_ROBOT_IO_MAX && (bits & (1u << last)))
            last++;
        fprintf(stderr, last > n ? " %d-%d" : " %d", n, last);
        n = last;
        any = 1;
    }
    if (!any)
        fputs(" none", stderr);
}

/* What is known of the outputs after the stop, and for those that are not known, why. */
static void tell_outputs(const fbrl_link_stop *so)
{
    uint32_t others = so->unknown & ~so->off_failed;
    fputs("stopped:", stderr);
    put_outputs(" outputs switched off:", so->switched_off);
    if (so->have_outputs)
        put_outputs("; outputs still on:", so->left_on);
    if (so->off_failed) {
        put_outputs("; switching off failed for", so->off_failed);
        fputs(so->have_outputs ? " (may still be on)" : " (may still be on: not known)", stderr);
    }
    if (others) {
        put_outputs("; not known:", others);
        if (so->have_status)
            fputs(" (this controller's STATUS does not show its outputs, and this session did not"
                  " switch them on: check them at the controller)",
                  stderr);
        else
            fprintf(stderr, " (STATUS could not be read after HALT: %s; check them at the controller)",
                    fbrl_status_str(so->status_result));
    }
    fputc('\n', stderr);
}

/* The report: where, what the arm was doing and where it stands, the outputs. */
static void report(mon *m, const char *where, unsigned long line, const char *word)
{
    fbrl_robot_stop so;
    char place[300];
    if (where != NULL && line > 0)
        snprintf(place, sizeof place, "%s:%lu", where, line);
    else
        snprintf(place, sizeof place, "%s", where != NULL ? where : "at the prompt");
    if (word != NULL && word[0])
        snprintf(place + strlen(place), sizeof place - strlen(place), " in %s", word);
    if (m->link == NULL)
        return; /* offline: nothing to stop, and the error line said where */
    fbrl_robot_safe_stop(&m->robot, &so);
    fprintf(stderr, "stopped (%s): ", place);
    if (so.result == FBRL_EDISCONNECTED || so.result == FBRL_EOFFLINE) {
        fprintf(stderr, "the controller is not connected: the arm could not be halted%s%s\n",
                so.was_moving ? "; it was moving: " : "", so.was_moving ? so.motion : "");
        fputs("stopped: RECONNECT when the controller is back, then check the arm and the outputs\n", stderr);
        return;
    }
    if (so.result == FBRL_EBUSY) {
        fputs("the controller is still running a command that waits (WAIT or RUN) and reads nothing"
              " else: HALT could not be sent; stop the arm at the controller\n",
              stderr);
        return;
    }
    if (so.stop.halted)
        fprintf(stderr, "arm halted%s%s%s", so.was_moving ? " while moving (" : " (no motion was running",
                so.was_moving ? so.motion : "", ")");
    else
        fprintf(stderr, "HALT failed (%s)", fbrl_status_str(so.result));
    if (so.stop.have_where) {
        /* fbrl_num: the same digits in every locale (fbrlmon runs in the user's) */
        static const char *const label[6] = {"X", "Y", "Z", NULL, "pitch", "roll"};
        char num[40];
        int k;
        fputs("; it stands at", stderr);
        for (k = 0; k < 6; k++)
            if (label[k] != NULL) {
                fbrl_num_fixed(num, sizeof num, so.stop.where[k], 0, 4, 0, NULL);
                fprintf(stderr, " %s %s", label[k], num);
            }
    }
    fputc('\n', stderr);
    tell_outputs(&so.stop);
}

static void tail(mon *m)
{
    m->host.interrupted = 0; /* handled: waits (KEY, the line editor) may wait again */
    if (g_quit)
        fputs("fbrlmon: ended by a second Ctrl-C\n", stderr);
    else if (m->link != NULL)
        fprintf(stderr, "(a second Ctrl-C within %d s ends fbrlmon)\n", MON_QUIT_WINDOW_MS / 1000);
    fflush(stderr);
    g_mode = MODE_IDLE;
}

void mon_safe_stop(mon *m, const char *where, unsigned long line)
{
    g_mode = MODE_STOP;
    g_pending = 0;
    mon_host_newline(&m->host);
    report(m, where, line, NULL);
    tail(m);
}

int mon_safe_end(mon *m, const char *where, unsigned long line)
{
    const fbrl_vm_error *e = fbrl_vm_last_error(m->vm);
    g_mode = MODE_IDLE;
    if (!g_pending)
        return 0;
    g_mode = MODE_STOP;
    g_pending = 0;
    mon_host_newline(&m->host);
    if (e != NULL && e->throw_code == FBRL_THROW_INTERRUPT && e->file[0])
        report(m, e->file, e->line, e->word);
    else if (e != NULL && e->throw_code == FBRL_THROW_INTERRUPT)
        report(m, where, where != NULL && line > 0 ? line + (e->line > 1 ? e->line - 1 : 0) : 0, e->word);
    else
        report(m, where, line, NULL);
    tail(m);
    return 1;
}
