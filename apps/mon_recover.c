/* mon_recover.c - corrective actions in fbrlmon (docs/debugging.md): ASK puts the failure
 * in plain words and the choices Retry / Skip / Abort to the operator at the terminal (or
 * reads the answer from piped input, echoing it); every action taken is printed as a
 * "recovery:" line. */
#include <ctype.h>
#include <stdio.h>

#include "mon.h"
#include "mon_recover.h"

#define ASK_TRIES 5 /* unclear answers before the question counts as Abort */

static int ask(void *ctx, const char *question)
{
    mon *m = ctx;
    FILE *out = m->host.out;
    mon_host_newline(&m->host);
    fprintf(out, "%s\n", question);
    for (int i = 0; i < ASK_TRIES; i++) {
        fputs("[R]etry, [S]kip this sample or [A]bort? ", out);
        fflush(out);
        size_t len;
        const char *line = mon_host_read_line(&m->host, &len);
        m->host.column = 0;
        if (!line) {
            fputs("(no answer: abort)\n", out);
            return 'A';
        }
        if (!m->host.in_is_tty)
            fprintf(out, "%.*s\n", (int)len, line);
        while (len > 0 && isspace((unsigned char)*line))
            line++, len--;
        int c = len > 0 ? toupper((unsigned char)*line) : 0;
        if (c == 'R' || c == 'S' || c == 'A')
            return c;
    }
    return 'A';
}

static void note(void *ctx, const char *step, const char *kind, const char *what, const char *action,
                 long sample)
{
    mon *m = ctx;
    FILE *out = m->host.out;
    mon_host_newline(&m->host);
    fprintf(out, "recovery: %s", step);
    if (sample > 0)
        fprintf(out, " (sample %ld)", sample);
    fprintf(out, ": %s (%s): %s\n", kind, what, action);
    fflush(out);
}

fbrl_status mon_recover_install(struct mon *m)
{
    fbrl_status st = fbrl_recover_install(m->vm, &m->recover, &m->robot);
    if (st == FBRL_OK)
        st = fbrl_recover_set_ask(&m->recover, ask, m);
    if (st == FBRL_OK)
        st = fbrl_recover_set_note(&m->recover, note, m);
    return st;
}
