/* SPDX-License-Identifier: MIT */
/* mon_conn.c - opening the controller connection for fbrlmon, through fbrl_port. */
#include "mon_conn.h"

#include <locale.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#ifdef FBRL_HAVE_SERIALPORT
#include "fbrl/uart_serialport.h"
#endif

const char *mon_conn_hint(fbrl_status st)
{
    return st == FBRL_EPERM ? " (serial ports usually belong to the group dialout: "
                              "sudo usermod -aG dialout $USER, then log in again)"
                            : "";
}

#ifdef FBRLMON_HAVE_SIM
/* The built-in emulator reads and writes its state file as "C" text; fbrlmon runs in the
 * user's locale (setlocale in main), so its create and destroy (load and save) run with
 * the "C" locale on this thread. Its own thread sets "C" itself. */
static locale_t sim_c_locale(void)
{
    static locale_t c;
    if (!c)
        c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    return c;
}

static fbrl_status sim_create_c(fbrl_sim **sim, const fbrl_sim_options *so, char *err, size_t errlen)
{
    locale_t prev = sim_c_locale() ? uselocale(sim_c_locale()) : (locale_t)0;
    fbrl_status st = fbrl_sim_create(sim, so, err, errlen);
    if (prev)
        uselocale(prev);
    return st;
}

static void sim_destroy_c(fbrl_sim *sim)
{
    locale_t prev = sim_c_locale() ? uselocale(sim_c_locale()) : (locale_t)0;
    fbrl_sim_destroy(sim);
    if (prev)
        uselocale(prev);
}

/* fbrl_port's "sim:" hook: fbrlsim's core on a pty in a thread of this process (the
 * library itself never starts an emulator). arg (after "sim:") names a state file. */
static fbrl_status sim_start(void *ctx, const char *arg, char *path, size_t cap)
{
    mon_conn *c = ctx;
    fbrl_sim_options so;
    fbrl_status st;
    fbrl_sim_options_init(&so);
    so.state_path = arg[0] ? arg : c->sim_state;
    so.inputs_path = c->sim_inputs;
    so.model = c->arm ? c->arm->name : NULL;
    so.clock = c->sim_clock;
    so.skip = c->sim_skip;
    so.clock_ctx = c->sim_clock_ctx;
    so.status_extra = 1; /* the robot words read outputs from fbrlsim's own STATUS lines */
    st = sim_create_c(&c->sim, &so, c->sim_err, sizeof c->sim_err);
    if (st != FBRL_OK) {
        c->sim = NULL;
        return st;
    }
    {
        /* The emulator's thread must not take the terminal's signals: the
         * line editor (Ctrl-C, window size) handles them in the main thread. */
        static const int sigs[] = {SIGINT, SIGQUIT, SIGTSTP, SIGCONT, SIGWINCH, SIGHUP, SIGTERM};
        sigset_t block, old;
        size_t i;
        sigemptyset(&block);
        for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
            sigaddset(&block, sigs[i]);
        pthread_sigmask(SIG_BLOCK, &block, &old);
        st = fbrl_sim_start(c->sim);
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    }
    if (st != FBRL_OK)
        return st;
    snprintf(path, cap, "%s", fbrl_sim_path(c->sim));
    return FBRL_OK;
}

static void sim_stop(void *ctx)
{
    mon_conn *c = ctx;
    if (c->sim != NULL)
        sim_destroy_c(c->sim);
    c->sim = NULL;
}
#endif

/* The connect read the controller's units and refused millimetres (FBRL_EUNITS): the
 * link stays connected, so that the user can switch it; the robot words refuse their
 * commands until then (rb_units). */
static fbrl_status units_note(mon_conn *c, fbrl_status st)
{
    c->note[0] = '\0';
    if (st != FBRL_EUNITS)
        return st;
    snprintf(c->note, sizeof c->note,
             "the controller on %s works in millimetres (STATUS: METRIC UNITS.) and fbrlmon's robot "
             "words send inches: they are refused until you switch it to inches (RAPL NOMETRIC)",
             c->port.name);
    return FBRL_OK;
}

fbrl_status mon_conn_open(mon_conn *c, const mon_conn_options *o, char *err, size_t errlen)
{
    fbrl_status st;
    fbrl_port_options po = o->line;
    const char *name = o->port;

    c->kind = o->kind;
    c->sim_state = o->sim_state;
    c->sim_inputs = o->sim_inputs;
    c->arm = o->arm;
    c->sim_clock = o->sim_clock;
    c->sim_skip = o->sim_skip;
    c->sim_clock_ctx = o->sim_clock_ctx;
    if (o->kind == MON_CONN_OFFLINE)
        return FBRL_OK;
    if (o->kind == MON_CONN_SIM) {
#ifdef FBRLMON_HAVE_SIM
        po.sim_start = sim_start;
        po.sim_stop = sim_stop;
        po.sim_ctx = c;
        name = "sim:";
#else
        snprintf(err, errlen, "this fbrlmon was built without the emulator");
        return FBRL_EUNSUPPORTED;
#endif
    }
    st = fbrl_port_open(&c->port, name, &po);
    if (st != FBRL_OK) {
        if (o->kind == MON_CONN_SIM)
            snprintf(err, errlen, "cannot start the emulator: %s",
                     c->sim_err[0] ? c->sim_err : fbrl_status_str(st));
        else
            snprintf(err, errlen, "cannot open %s: %s%s", name, fbrl_status_str(st), mon_conn_hint(st));
        return st;
    }
    c->open = 1;
    c->url = name;
    c->opts = po;
    {
        /* The link reads W2 and STATUS rows for as many axes as the arm has. */
        fbrl_link_config lc;
        fbrl_link_config_init(&lc);
#ifdef FBRLMON_HAVE_SIM
        if (c->sim != NULL)
            c->arm = fbrl_sim_arm(c->sim); /* --arm's, or the one its memory holds */
#endif
        if (c->arm == NULL)
            c->arm = fbrl_arm_model(0);
        lc.arm = c->arm;
        lc.naxes = o->axes ? o->axes : c->arm->naxes;
        lc.on_exec = o->on_exec; /* the run log (mon_runlog.c), or the dry run's report */
        lc.exec_ctx = o->exec_ctx;
        fbrl_link_modes_init(&c->modes);
        lc.modes = &c->modes; /* sent again after a reconnect (mon_relink.c) */
        c->lcfg = lc;         /* mon_conn_reopen uses it again */
        st = fbrl_link_init(&c->link, fbrl_port_uart(&c->port), &lc);
    }
    if (st == FBRL_OK)
        st = fbrl_link_connect(&c->link); /* NOHELP: a controller must answer */
    if (st == FBRL_ETIMEOUT && c->kind == MON_CONN_PORT) {
        /* Not one character echoed: a controller that powered up in ACI mode ignores typed
         * text until a host switches it to terminal mode (docs/link.md). The switch is
         * harmless to a line that is dead, and the link erases it on a controller that
         * was in terminal mode after all; it is kept for reconnecting after a power cycle. */
        c->lcfg.aci = 1;
        st = fbrl_link_init(&c->link, fbrl_port_uart(&c->port), &c->lcfg);
        if (st == FBRL_OK)
            st = fbrl_link_connect(&c->link);
        if (st != FBRL_OK)
            c->lcfg.aci = 0;
    }
    st = units_note(c, st);
    if (st != FBRL_OK) {
        snprintf(err, errlen, "no controller answers on %s: %s%s", c->port.name, fbrl_status_str(st),
                 c->kind == MON_CONN_PORT ? " (neither in terminal mode nor to the switch from ACI mode)" : "");
        mon_conn_close(c);
        return st;
    }
    return FBRL_OK;
}

void mon_conn_describe(const mon_conn *c, char *buf, size_t cap)
{
    char port[400];
    if (c->kind == MON_CONN_OFFLINE || !c->open ||
        fbrl_port_describe(&c->port, port, sizeof port) != FBRL_OK) {
        snprintf(buf, cap, "offline (no controller)");
        return;
    }
    snprintf(buf, cap, "%s %s%s", c->kind == MON_CONN_SIM ? "emulator on" : "controller on", port,
             c->lcfg.aci ? ", switched from ACI to terminal mode" : "");
}

void mon_conn_close(mon_conn *c)
{
    /* the port stops an emulator it started (sim_stop), also after a failed open */
    if (c->open || c->port.sim_running)
        fbrl_port_close(&c->port);
    c->open = 0;
}

/* The latency timer's note: fbrlmon sets 1 ms when it opens the port. */
static void print_driver(FILE *out, const char *driver, int latency_timer_ms)
{
    if (!driver[0])
        return;
    fprintf(out, "  driver %s", driver);
    if (latency_timer_ms >= 0)
        fprintf(out, ", latency timer %d ms%s", latency_timer_ms,
                latency_timer_ms > 1 ? " (fbrlmon sets 1 ms when it opens the port)" : "");
}

/* Without sysfs (not Linux): what libserialport finds. */
static fbrl_status list_with_serialport(FILE *out)
{
#ifdef FBRL_HAVE_SERIALPORT
    fbrl_serial_port_info ports[MON_LIST_PORTS_MAX];
    size_t i, n = 0;
    fbrl_status st = fbrl_uart_serialport_list(ports, sizeof ports / sizeof ports[0], &n);
    if (st != FBRL_OK)
        return st;
    if (n > sizeof ports / sizeof ports[0])
        n = sizeof ports / sizeof ports[0];
    for (i = 0; i < n; i++) {
        fbrl_port_usb_info usb;
        fprintf(out, "%s", ports[i].name);
        if (ports[i].description[0])
            fprintf(out, "  %s", ports[i].description);
        if (ports[i].usb)
            fprintf(out, "  [USB %04x:%04x]", ports[i].vid, ports[i].pid);
        if (fbrl_port_usb_info_get(NULL, ports[i].name, &usb) == FBRL_OK)
            print_driver(out, usb.driver, usb.latency_timer_ms);
        fputc('\n', out);
    }
    return FBRL_OK;
#else
    (void)out;
    return FBRL_EUNSUPPORTED;
#endif
}

fbrl_status mon_conn_list_ports(FILE *out)
{
    static fbrl_port_entry ports[MON_LIST_PORTS_MAX];
    size_t i, n = 0;
    fbrl_status st =
        fbrl_port_list(getenv(MON_SYSFS_ENV), getenv(MON_DEV_ENV), ports, MON_LIST_PORTS_MAX, &n);
    if (st == FBRL_EUNSUPPORTED)
        return list_with_serialport(out);
    if (st != FBRL_OK)
        return st;
    if (n > MON_LIST_PORTS_MAX)
        n = MON_LIST_PORTS_MAX;
    /* one port a line: the stable name first when there is one (it survives re-plugging
     * and other adapters; fbrlmon --port takes it), then the device and what it is */
    for (i = 0; i < n; i++) {
        const fbrl_port_entry *p = &ports[i];
        fprintf(out, "%s", p->by_id[0] ? p->by_id : p->device);
        if (p->by_id[0])
            fprintf(out, "  (%s)", p->device);
        if (p->description[0])
            fprintf(out, "  %s", p->description);
        if (p->usb)
            fprintf(out, "  [USB %04x:%04x]", p->vid, p->pid);
        if (p->serial[0])
            fprintf(out, "  serial %s", p->serial);
        print_driver(out, p->driver, p->latency_timer_ms);
        fputc('\n', out);
    }
    return FBRL_OK;
}

fbrl_status mon_conn_reopen(mon_conn *c, char *err, size_t errlen)
{
    fbrl_status st;
    if (c->kind == MON_CONN_PORT) {
        /* the old descriptor leads to a pty or device that is gone: a new open finds
         * whatever the name stands for now */
        if (c->open)
            fbrl_port_close(&c->port);
        c->open = 0;
        st = fbrl_port_open(&c->port, c->url, &c->opts);
        if (st != FBRL_OK) {
            snprintf(err, errlen, "cannot open %s: %s%s", c->url, fbrl_status_str(st), mon_conn_hint(st));
            return st;
        }
        c->open = 1;
    }
    st = fbrl_link_init(&c->link, fbrl_port_uart(&c->port), &c->lcfg);
    if (st == FBRL_OK)
        st = units_note(c, fbrl_link_connect(&c->link)); /* NOHELP and the units, as at start */
    if (st != FBRL_OK)
        snprintf(err, errlen, "no controller answers on %s: %s", c->port.name, fbrl_status_str(st));
    return st;
}
