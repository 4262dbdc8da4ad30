/* mon_conn.c - opening the controller connection for fbrlmon. */
#include "mon_conn.h"

#include <locale.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#ifdef FBRL_HAVE_SERIALPORT
#include "fbrl/uart_serialport.h"
#endif

static fbrl_status fail(char *err, size_t errlen, fbrl_status st, const char *what, const char *path)
{
    snprintf(err, errlen, "%s %s: %s", what, path, fbrl_status_str(st));
    return st;
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
#endif

fbrl_status mon_conn_open(mon_conn *c, const mon_conn_options *o, char *err, size_t errlen)
{
    fbrl_status st;
    const char *path = o->port;

    memset(c, 0, sizeof *c);
    c->kind = o->kind;
    if (o->kind == MON_CONN_OFFLINE)
        return FBRL_OK;
    if (o->kind == MON_CONN_SIM) {
#ifdef FBRLMON_HAVE_SIM
        fbrl_sim_options so;
        char serr[256] = "";
        fbrl_sim_options_init(&so);
        so.state_path = o->sim_state;
        so.inputs_path = o->sim_inputs;
        st = sim_create_c(&c->sim, &so, serr, sizeof serr);
        if (st != FBRL_OK) {
            snprintf(err, errlen, "cannot start the emulator: %s", serr[0] ? serr : fbrl_status_str(st));
            return st;
        }
        {
            /* The emulator's thread must not take the terminal's signals: the
             * line editor (Ctrl-C, window size) handles them in the main thread. */
            static const int sigs[] = { SIGINT, SIGQUIT, SIGTSTP, SIGCONT, SIGWINCH, SIGHUP, SIGTERM };
            sigset_t block, old;
            size_t i;
            sigemptyset(&block);
            for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
                sigaddset(&block, sigs[i]);
            pthread_sigmask(SIG_BLOCK, &block, &old);
            st = fbrl_sim_start(c->sim);
            pthread_sigmask(SIG_SETMASK, &old, NULL);
        }
        if (st != FBRL_OK) {
            sim_destroy_c(c->sim);
            c->sim = NULL;
            snprintf(err, errlen, "cannot start the emulator: %s", fbrl_status_str(st));
            return st;
        }
        path = fbrl_sim_path(c->sim);
#else
        snprintf(err, errlen, "this fbrlmon was built without the emulator");
        return FBRL_EUNSUPPORTED;
#endif
    }
    snprintf(c->path, sizeof c->path, "%s", path);
    st = fbrl_uart_posix_open(&c->port, &c->uart, path, &o->line, c->rx, sizeof c->rx, c->tx,
                              sizeof c->tx, NULL);
    if (st != FBRL_OK) {
        mon_conn_close(c);
        return fail(err, errlen, st, "cannot open", path);
    }
    c->open = 1;
    st = fbrl_link_init(&c->link, &c->uart, NULL);
    if (st == FBRL_OK)
        st = fbrl_link_connect(&c->link);  /* NOHELP: a controller must answer */
    if (st != FBRL_OK) {
        mon_conn_close(c);
        return fail(err, errlen, st, "no controller answers on", path);
    }
    return FBRL_OK;
}

void mon_conn_describe(const mon_conn *c, char *buf, size_t cap)
{
    fbrl_uart_config l;
    if (c->kind == MON_CONN_OFFLINE || !c->open || fbrl_uart_get_config(&c->uart, &l) != FBRL_OK) {
        snprintf(buf, cap, "offline (no controller)");
        return;
    }
    snprintf(buf, cap, "%s %s (%lu %u%c%u, %s)", c->kind == MON_CONN_SIM ? "emulator on" : "controller on",
             c->path, (unsigned long)l.baud, (unsigned)l.data_bits, (char)l.parity, (unsigned)l.stop_bits,
             l.flow == FBRL_FLOW_XONXOFF ? "XON/XOFF" : "no flow control");
}

void mon_conn_close(mon_conn *c)
{
    if (c->open)
        fbrl_uart_close(&c->uart);
    c->open = 0;
#ifdef FBRLMON_HAVE_SIM
    if (c->sim != NULL)
        sim_destroy_c(c->sim);
    c->sim = NULL;
#endif
}

fbrl_status mon_conn_list_ports(FILE *out)
{
#ifdef FBRL_HAVE_SERIALPORT
    fbrl_serial_port_info ports[64];
    size_t i, n = 0;
    fbrl_status st = fbrl_uart_serialport_list(ports, sizeof ports / sizeof ports[0], &n);
    if (st != FBRL_OK)
        return st;
    if (n > sizeof ports / sizeof ports[0])
        n = sizeof ports / sizeof ports[0];
    for (i = 0; i < n; i++) {
        fprintf(out, "%s", ports[i].name);
        if (ports[i].description[0])
            fprintf(out, "  %s", ports[i].description);
        if (ports[i].usb)
            fprintf(out, "  [USB %04x:%04x]", ports[i].vid, ports[i].pid);
        fputc('\n', out);
    }
    return FBRL_OK;
#else
    (void)out;
    return FBRL_EUNSUPPORTED;
#endif
}
