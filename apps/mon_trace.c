/* SPDX-License-Identifier: MIT */
/* mon_trace.c - fbrlmon's command trace (docs/debugging.md): TRACE-ON prints each line
 * the controller ran, as the link reports it (so the trace's commands are the controller's
 * command log), with what became of it and the plan's word, file and line that sent it.
 * TRACE-TO sends the trace to a file; TRACE-WORDS and TRACE-OFF (mon_step.c, the step
 * hook's owner) add each word entered and stop it all. */
#include <errno.h>
#include <string.h>

#include "fbrl/status.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"
#include "mon.h"
#include "mon_trace.h"

FILE *mon_trace_out(struct mon *m) { return m->trace.file ? m->trace.file : m->host.out; }

static const char *fate(fbrl_status result)
{
    switch (result) {
    case FBRL_OK: return "ran";
    case FBRL_ECONTROLLER: return "ran: controller error";
    case FBRL_EMAYBE: return "may have run";
    default: return fbrl_status_str(result);
    }
}

static void on_exec(void *ctx, const char *line, size_t len, fbrl_status result)
{
    mon *m = ctx;
    if (m->trace.commands) {
        const char *word = "", *file = "";
        unsigned long ln = 0;
        FILE *out = mon_trace_out(m);
        if (out == m->host.out)
            mon_host_newline(&m->host);
        fbrl_vm_where(m->vm, &word, &file, &ln);
        fprintf(out, "trace: %.*s  (%s", (int)len, line, fate(result));
        if (file[0] || ln)
            fprintf(out, "; %s:%lu", file[0] ? file : "typed", ln);
        if (word[0])
            fprintf(out, " in %s", word);
        fputs(")\n", out);
        fflush(out);
    }
    if (m->trace.prev)
        m->trace.prev(m->trace.prev_ctx, line, len, result);
}

static void hook(mon *m)
{
    if (!m->trace.hooked && m->link &&
        fbrl_link_set_exec_handler(m->link, on_exec, m, &m->trace.prev, &m->trace.prev_ctx) == FBRL_OK)
        m->trace.hooked = 1;
}

/* TRACE-ON ( -- ) */
static fbrl_status w_trace_on(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    if (!m->link)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "TRACE-ON: no controller (offline): nothing to trace");
    hook(m);
    m->trace.commands = 1;
    return FBRL_OK;
}

/* TRACE-TO ( "file" -- ): the trace goes to the end of file */
static fbrl_status w_trace_to(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    const char *p;
    size_t n;
    char path[256], msg[320];
    fbrl_vm_parse_name(vm, &p, &n);
    if (n == 0 || n >= sizeof path)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "TRACE-TO: name the file, e.g. TRACE-TO run.trace");
    memcpy(path, p, n);
    path[n] = 0;
    FILE *f = fopen(path, "a");
    if (!f) {
        snprintf(msg, sizeof msg, "TRACE-TO: cannot open %s: %s", path, strerror(errno));
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, msg);
    }
    mon_trace_close(m);
    m->trace.file = f;
    return FBRL_OK;
}

void mon_trace_stop(struct mon *m)
{
    m->trace.commands = 0;
    mon_trace_close(m);
}

void mon_trace_close(struct mon *m)
{
    if (m->trace.file)
        fclose(m->trace.file);
    m->trace.file = NULL;
}

fbrl_status mon_trace_install(struct mon *m)
{
    static const fbrl_vmx_reg words[] = {
        {"TRACE-ON", w_trace_on, "", 0, 0, 0,
         FBRL_DOC("( -- )", "trace each command the controller runs, with the plan line that sent it")},
        {"TRACE-TO", w_trace_to, "", 0, 0, 0,
         FBRL_DOC("( \"file\" -- )", "send the trace to the end of file instead of the terminal")},
    };
    return fbrl_vmx_define_table(m->vm, words, sizeof words / sizeof words[0], m);
}
