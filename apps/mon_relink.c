/* SPDX-License-Identifier: MIT */
/* mon_relink.c - a controller that went away and came back (fbrlsim restarted, a USB
 * adapter unplugged and plugged in again on the same path), and going on with the plan.
 *
 *   RECONNECT   open the port again, the connect handshake (NOHELP, the units), send the
 *               session's modes again (speed, units, tool ...: a restarted controller
 *               lost them; docs/link.md 1), and say what state the controller reports
 *               (STATUS: homed? moving? outputs on?)
 *   RESUME      run the plan file that failed last again, from the line that failed
 *
 * The session (the dictionary, locations, calibrations) is kept: only the port and the
 * link are new. After the controller was lost, the next robot word typed at the prompt
 * reconnects by itself; inside a plan file (or piped input) it does not: the plan
 * stops with the error, and the user decides (RECONNECT, check the arm, RESUME).
 * docs/fbrlmon.md "When the controller goes away". */
#include "mon_relink.h"

#include <stdio.h>
#include <string.h>

#include "fbrl/runlog.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"
#include "mon_conn.h"

/* Send the session's modes again, before anything else can move the arm, and say which
 * (on the console, and in the run log while a run is logged). A restarted controller has
 * its defaults: the rest of a plan would run at another speed, with another tool. */
static void resend_modes(mon *m)
{
    char text[4 * FBRL_LINK_LINE_MAX + 200];
    size_t sent = 0, len = 0, i;
    const fbrl_link_modes *md = &m->conn->modes;
    const char *line;
    fbrl_status st = fbrl_link_modes_resend(m->link, &sent);
    if (fbrl_link_modes_line(md, 0) == NULL)
        return; /* the session set none */
    text[0] = '\0';
    for (i = 0; i < sent && (line = fbrl_link_modes_line(md, i)) != NULL && len + 3 < sizeof text; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "%s%s", i ? "; " : "", line);
    if (len >= sizeof text)
        len = sizeof text - 1;
    if (st != FBRL_OK && len + 3 < sizeof text) {
        int code = -1;
        const char *etext = "";
        if (st == FBRL_ECONTROLLER)
            fbrl_link_error(m->link, &code, &etext);
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "%snot sent: %s (%s%s%s) and the modes after it: send them before moving",
                                sent ? "; " : "", fbrl_link_modes_line(md, sent),
                                st == FBRL_EUNITS ? "typed in other units than the controller's now"
                                                  : fbrl_status_str(st),
                                code >= 0 ? ": " : "", code >= 0 ? etext : "");
    }
    mon_host_newline(&m->host);
    fprintf(m->host.out, "the session's modes sent again: %s\n", text);
    fflush(m->host.out);
    m->host.column = 0;
    if (m->runlog != NULL && fbrl_runlog_is_open(m->runlog))
        fbrl_runlog_note(m->runlog, "modes-resent", NULL, text);
}

/* What the controller says about itself now, in one line to the console. */
static void tell_state(mon *m)
{
    fbrl_rapl_status_info si;
    FILE *o = m->host.out;
    fbrl_status st = fbrl_link_status(m->link, &si);
    mon_host_newline(&m->host);
    fprintf(o, "reconnected to %s", m->conn->port.name);
    if (st != FBRL_OK) {
        fprintf(o, "; STATUS failed (%s): the arm's state is unknown\n", fbrl_status_str(st));
    } else {
        int moving = 0, n;
        for (n = 0; n < (int)si.naxes && n < FBRL_RAPL_MAX_AXES; n++)
            moving |= (si.have & FBRL_RAPL_ST_DONE) && !si.done[n];
        if (!moving)
            m->robot.moving = 0; /* seen standing: the next motion need not ask */
        fprintf(o, ": controller %s, arm %s", si.homed ? "homed" : "NOT HOMED (HOME before moving)",
                moving ? "MOVING (a motion from before the loss; HALT stops it)" : "standing");
        if (si.have & FBRL_RAPL_ST_OUTPUTS) {
            fputs(", outputs on:", o);
            if ((si.outputs & 0xFFFFu) == 0)
                fputs(" none", o);
            for (n = 1; n <= FBRL_ROBOT_IO_MAX; n++)
                if (si.outputs & (1u << (n - 1)))
                    fprintf(o, " %d", n);
        }
        fputs(".\n", o);
        fputs("The command that failed may or may not have run: check before going on (RESUME runs the"
              " failed plan line again).\n",
              o);
    }
    fflush(o);
    m->host.column = 0;
}

fbrl_status mon_relink(mon *m, char *err, size_t errlen)
{
    fbrl_status st;
    if (m->conn == NULL || m->conn->kind == MON_CONN_OFFLINE || m->link == NULL) {
        snprintf(err, errlen, "no controller port to reconnect (fbrlmon runs offline)");
        return FBRL_EOFFLINE;
    }
    st = mon_conn_reopen(m->conn, err, errlen);
    if (st != FBRL_OK)
        return st;
    fbrl_robot_set_link(&m->robot, &m->conn->link); /* not lost; motion state unknown */
    resend_modes(m);
    if (fbrl_link_units(m->link) == FBRL_LINK_UNITS_INCH)
        m->conn->note[0] = '\0'; /* the session's NOMETRIC switched it back */
    tell_state(m);
    if (m->conn->note[0]) {
        fprintf(m->host.out, "%s\n", m->conn->note);
        fflush(m->host.out);
    }
    return FBRL_OK;
}

/* The robot words' hook: reconnect before the next robot word, but only for a line
 * typed at the prompt (a plan must not go on by itself with an arm in unknown state). */
static fbrl_status auto_relink(void *ctx, fbrl_robot *r)
{
    mon *m = ctx;
    char err[300];
    fbrl_status st;
    (void)r;
    if (!m->typed || m->host.file_depth > 0)
        return FBRL_EDISCONNECTED;
    mon_host_newline(&m->host);
    fputs("(the controller was lost: reconnecting first)\n", m->host.out);
    st = mon_relink(m, err, sizeof err);
    if (st != FBRL_OK) {
        fprintf(stderr, "reconnect: %s\n", err);
        fflush(stderr);
    }
    return st;
}

static fbrl_status w_reconnect(fbrl_vm *vm, void *arg, const void *word)
{
    (void)word;
    mon *m = arg;
    char err[300], msg[340];
    fbrl_status st = mon_relink(m, err, sizeof err);
    if (st == FBRL_OK)
        return FBRL_OK;
    snprintf(msg, sizeof msg, "RECONNECT: %s", err);
    return fbrl_vm_throw(vm, FBRL_VM_THROW_OF_STATUS(st), msg);
}

/* (RESUME) ( a -- a u ): the failed plan file's name into the buffer at a; its next
 * open skips to the failed line. */
static fbrl_status w_resume(fbrl_vm *vm, void *arg, const void *word)
{
    mon *m = arg;
    fbrl_vmx_val v[1];
    size_t n = strlen(m->resume_file);
    char *p;
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st != FBRL_OK)
        return st;
    fbrl_cell a = v[0].i;
    if (n == 0 || m->resume_line == 0)
        return fbrl_vm_throw(vm, FBRL_THROW_ABORTQ, "RESUME: no plan file has failed in this session");
    p = fbrl_vm_addr(vm, a, sizeof m->resume_file);
    if (p == NULL)
        return fbrl_vm_throw(vm, FBRL_THROW_BAD_ADDRESS, NULL);
    memcpy(p, m->resume_file, n);
    m->host.skip_path = m->resume_file;
    m->host.skip_lines = m->resume_line - 1;
    mon_host_newline(&m->host);
    fprintf(m->host.out, "resuming %s at line %lu\n", m->resume_file, m->resume_line);
    fflush(m->host.out);
    m->host.column = 0;
    if (fbrl_vm_push(vm, a) != FBRL_OK || fbrl_vm_push(vm, (fbrl_cell)n) != FBRL_OK)
        return fbrl_vm_throw(vm, FBRL_THROW_STACK_OVERFLOW, NULL);
    return FBRL_OK;
}

fbrl_status mon_relink_install(mon *m)
{
    static const char def[] =
        "CREATE (RESUME-FILE) 256 ALLOT\n"
        ": RESUME ( -- ) \\ run the plan file that failed last again, from the line that failed\n"
        "  (RESUME-FILE) (RESUME) INCLUDED ;\n";
    static const fbrl_vmx_reg words[] = {
        {"RECONNECT", w_reconnect, "", 0, 0, 0,
         FBRL_DOC("( -- )", "open the controller's port again, NOHELP, and report its state (STATUS)")},
        {"(RESUME)", w_resume, "A", 0, 0, 0,
         FBRL_DOC("( a -- a u )",
                  "RESUME's helper: the failed file's name at a; its next open starts at the failed line")},
    };
    fbrl_status st = fbrl_vmx_define_table(m->vm, words, sizeof words / sizeof words[0], m);
    if (st == FBRL_OK)
        st = fbrl_vm_eval(m->vm, def, sizeof def - 1);
    if (st == FBRL_OK)
        st = fbrl_robot_set_relink(&m->robot, auto_relink, m);
    return st;
}
