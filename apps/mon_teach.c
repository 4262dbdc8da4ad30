/* SPDX-License-Identifier: MIT */
/* mon_teach.c - TEACH: fbrlmon's keyboard teach pendant.
 *
 *   TEACH P      (or P TEACH)
 *
 * The arrow keys jog the tool point in X and Y, Page Up / Page Down in Z (RAPL JOG,
 * a straight-line offset that keeps the orientation); [ ] turn the pitch and , .
 * the roll (a straight MOVE to a scratch point, so the tool point stays put); o / c
 * open and close the gripper; 1..4, + and - choose the step. Every motion passes the
 * robot words' gate (fbrl_robot_motion): the work cell's guard refuses one that would hit
 * before a byte is sent. After every motion the arm is waited for (FINISH) and read back
 * (W2), so the status line always shows where the arm really is; a refusal or a
 * controller error (029 out of reach ...) is shown there too and TEACH goes on. Enter stores the position into the location through
 * ARM-HERE (so BASE-OFFSET and MAP-ON apply exactly as to every read-back), Esc
 * leaves it untouched. docs/fbrlmon.md "TEACH" lists the keys. */
#include "mon_teach.h"
#include "fbrl/num.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

/* After ESC, the rest of an escape sequence arrives at once (the terminal sends it in
 * one write); a lone ESC is the user's cancel once this much silence follows it. */
#define ESC_WAIT_MS 100
/* The longest single wait for a key: a Ctrl-C whose handler ran between the check of
 * the flag and poll() would not wake poll, so the flag is looked at again this often. */
#define KEY_SLICE_MS 100

enum { NSTEP = 4 };
static const double step_in[NSTEP] = {0.01, 0.1, 0.5, 1.0};   /* inches */
static const double step_cm[NSTEP] = {0.025, 0.25, 1.0, 2.5}; /* METRIC-ON */
static const double step_deg[NSTEP] = {0.5, 1.0, 5.0, 10.0};  /* pitch, roll */

typedef enum key {
    K_NONE,
    K_CHAR,
    K_ENTER,
    K_ESC,
    K_UP,
    K_DOWN,
    K_RIGHT,
    K_LEFT,
    K_PGUP,
    K_PGDN,
    K_EOF,
    K_INTR
} key;

typedef struct teach {
    mon *m;
    fbrl_link *link;
    int metric;    /* METRIC-ON when TEACH started: lengths shown and stepped in cm */
    int level;     /* index into the step tables */
    double pos[6]; /* the arm's WORLD position (W2): x y z (in), yaw pitch roll (deg) */
    int have_pos;
    double grip; /* gripper opening (in) */
    int have_grip;
    char msg[256];   /* the last error or note, shown on the status line */
    char above[256]; /* the message already printed on its own line above it */
} teach;

/* ---- keys ---- */

/* One byte from the keyboard: the monitor's read-ahead first (keys typed ahead),
 * then the terminal. timeout_ms < 0 waits. -1 timeout, -2 end of input, -3 Ctrl-C. */
static int read_byte(teach *t, int timeout_ms)
{
    mon_host *h = &t->m->host;
    if (h->inpos < h->inlen)
        return h->inbuf[h->inpos++];
    for (;;) {
        struct pollfd p;
        unsigned char c;
        ssize_t n;
        int r;
        int slice = timeout_ms < 0 || timeout_ms > KEY_SLICE_MS ? KEY_SLICE_MS : timeout_ms;
        if (h->interrupted)
            return -3;
        p.fd = h->in_fd;
        p.events = POLLIN;
        p.revents = 0;
        r = poll(&p, 1, slice);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return -2;
        if (r == 0) {
            if (timeout_ms < 0)
                continue;
            timeout_ms -= slice;
            if (timeout_ms <= 0)
                return -1;
            continue;
        }
        n = read(h->in_fd, &c, 1);
        if (n == 1)
            return c;
        if (n < 0 && errno == EINTR)
            continue;
        return -2;
    }
}

/* The next key. Escape sequences: CSI (ESC [) and SS3 (ESC O) with parameters,
 * e.g. ESC [ A (Up), ESC O A (Up in application mode), ESC [ 1 ; 5 A (Ctrl-Up),
 * ESC [ 5 ~ / ESC [ 6 ~ (Page Up / Down). Sequences TEACH does not use are
 * consumed whole and ignored. */
static key get_key(teach *t, int *ch)
{
    char par[16];
    size_t np = 0;
    int c = read_byte(t, -1), intro;
    if (c == -3)
        return K_INTR;
    if (c < 0)
        return K_EOF;
    if (c == '\r' || c == '\n')
        return K_ENTER;
    if (c != 0x1b) {
        *ch = c;
        return K_CHAR;
    }
    c = read_byte(t, ESC_WAIT_MS);
    if (c == -3)
        return K_INTR;
    if (c < 0 || c == 0x1b)
        return K_ESC; /* a lone Esc (or Esc pressed twice) */
    if (c != '[' && c != 'O')
        return K_NONE; /* Alt+key */
    intro = c;
    for (;;) {
        c = read_byte(t, ESC_WAIT_MS);
        if (c == -3)
            return K_INTR;
        if (c < 0)
            return K_NONE; /* a cut sequence */
        if (c >= 0x40 && c <= 0x7e)
            break;
        if (np + 1 < sizeof par)
            par[np++] = (char)c;
    }
    par[np] = '\0';
    switch (c) {
    case 'A': return K_UP;
    case 'B': return K_DOWN;
    case 'C': return K_RIGHT;
    case 'D': return K_LEFT;
    case '~':
        if (intro == '[' && strcmp(par, "5") == 0)
            return K_PGUP;
        if (intro == '[' && strcmp(par, "6") == 0)
            return K_PGDN;
        return K_NONE;
    default: return K_NONE;
    }
}

/* ---- screen ---- */

static void out(teach *t, const char *s) { fputs(s, t->m->host.out); }

static double len_shown(const teach *t, double inches) { return t->metric ? inches * 2.54 : inches; }
static const char *unit(const teach *t) { return t->metric ? "cm" : "in"; }

/* Append " text" to line when it still fits in cap columns. */
static void seg(char *line, size_t cap, const char *text)
{
    size_t n = strlen(line), k = strlen(text);
    if (n + 2 + k < cap) {
        memcpy(line + n, "  ", 2);
        memcpy(line + n + 2, text, k + 1);
    }
}

/* Numbers as printf's %+.Nf / %g in the C locale, whatever locale fbrlmon runs in
 * (fbrl_num), so the pendant shows what the language prints. */
#define NUM_CHARS 32
static const char *fix(char b[NUM_CHARS], double v, int decimals, int plus)
{
    fbrl_num_fixed(b, NUM_CHARS, v, 0, decimals, plus ? FBRL_NUM_PLUS : 0, NULL);
    return b;
}
static const char *gen(char b[NUM_CHARS], double v)
{
    fbrl_num_general(b, NUM_CHARS, v, 6, NULL);
    return b;
}

/* Redraw the status line in place: position, then the last message, the step and
 * the gripper as far as the terminal is wide (so it never wraps). A message that does
 * not fit after the position is printed once on its own line above the status line:
 * a refused jog is always seen. */
static void status(teach *t)
{
    char line[256], pos[256], msg[272], step[128], grip[64];
    size_t width = t->m->host.width > 0 ? (size_t)t->m->host.width : 80;
    const double *p = t->pos;
    if (width > sizeof line)
        width = sizeof line;
    char n[6][NUM_CHARS];
    if (t->have_pos)
        snprintf(pos, sizeof pos, "X%s Y%s Z%s %s  pitch%s roll%s", fix(n[0], len_shown(t, p[0]), 3, 1),
                 fix(n[1], len_shown(t, p[1]), 3, 1), fix(n[2], len_shown(t, p[2]), 3, 1), unit(t),
                 fix(n[3], p[4], 1, 1), fix(n[4], p[5], 1, 1));
    else
        snprintf(pos, sizeof pos, "position unknown");
    snprintf(msg, sizeof msg, "! %s", t->msg);
    snprintf(step, sizeof step, "step %s %s %s deg",
             gen(n[0], t->metric ? step_cm[t->level] : step_in[t->level]), unit(t),
             gen(n[1], step_deg[t->level]));
    snprintf(grip, sizeof grip, "grip %s", fix(n[5], len_shown(t, t->grip), 2, 0));
    snprintf(line, width, "%s", pos);
    if (!t->msg[0]) {
        t->above[0] = '\0';
    } else if (strlen(line) + 2 + strlen(msg) < width) {
        seg(line, width, msg);
    } else if (strcmp(t->above, t->msg) != 0) {
        out(t, "\r\033[K");
        out(t, msg);
        out(t, "\n");
        snprintf(t->above, sizeof t->above, "%s", t->msg);
    }
    seg(line, width, step);
    if (t->have_grip)
        seg(line, width, grip);
    out(t, "\r");
    out(t, line);
    out(t, "\033[K"); /* erase the rest of the old line */
    fflush(t->m->host.out);
    t->m->host.column = (int)strlen(line);
}

static void help(teach *t)
{
    char s[400];
    out(t, "\r\033[K");
    out(t, "TEACH keys (the arm moves at once and is read back after each motion):\n"
           "  Left Right  X -/+    Down Up  Y -/+    PgDn PgUp  Z -/+\n"
           "  [ ]  pitch -/+       , .  roll -/+     o c  gripper open / close\n");
    char n[8][NUM_CHARS];
    snprintf(s, sizeof s, "  1 2 3 4  step %s %s %s %s %s, %s %s %s %s deg    - +  smaller / larger\n",
             gen(n[0], t->metric ? step_cm[0] : step_in[0]), gen(n[1], t->metric ? step_cm[1] : step_in[1]),
             gen(n[2], t->metric ? step_cm[2] : step_in[2]), gen(n[3], t->metric ? step_cm[3] : step_in[3]),
             unit(t), gen(n[4], step_deg[0]), gen(n[5], step_deg[1]), gen(n[6], step_deg[2]),
             gen(n[7], step_deg[3]));
    out(t, s);
    out(t, "  r  read again    ?  these keys\n"
           "  Enter  store the position    Esc  cancel (the location is not changed)\n");
    t->m->host.column = 0;
}

/* ---- the arm ---- */

/* Note a failed link call on the status line ("JOG: 029-TRANSFORM ILLEGAL."). */
static int failed(teach *t, fbrl_status st, const char *what)
{
    if (st == FBRL_OK)
        return 0;
    if (st == FBRL_ECONTROLLER) {
        int code = -1;
        const char *text = "";
        fbrl_link_error(t->link, &code, &text);
        const char *help = fbrl_rapl_error_help(code);
        snprintf(t->msg, sizeof t->msg, "%s: %03d-%s.%s%s%s", what, code, text, help ? " (" : "",
                 help ? help : "", help ? ")" : "");
    } else {
        snprintf(t->msg, sizeof t->msg, "%s: %s", what, fbrl_status_str(st));
    }
    return 1;
}

/* A command left running by an interrupted robot word must end before TEACH talks
 * (its result is no longer anyone's). -1 if Ctrl-C came first. */
static int idle(teach *t)
{
    int done = 0;
    while (fbrl_link_busy(t->link) && !done) {
        if (t->m->host.interrupted)
            return -1;
        (void)fbrl_link_poll(t->link, 100, &done);
    }
    return 0;
}

/* Wait for the motion to end, then read where the arm is. */
static int read_pos(teach *t)
{
    fbrl_rapl_pos p;
    if (failed(t, fbrl_link_finish(t->link), "FINISH") ||
        failed(t, fbrl_link_where(t->link, FBRL_RAPL_W2, &p), "W2")) {
        t->have_pos = 0;
        return -1;
    }
    if (p.nworld < 6) {
        snprintf(t->msg, sizeof t->msg, "W2 had no WORLD line");
        t->have_pos = 0;
        return -1;
    }
    memcpy(t->pos, p.world, sizeof t->pos);
    t->have_pos = 1;
    return 0;
}

static void read_grip(teach *t) { t->have_grip = fbrl_link_typev(t->link, "GRIPPER", &t->grip) == FBRL_OK; }

/* A motion through the robot words' gate (fbrl_robot_motion): the work cell's guard checks
 * it from where the arm stands (it reads the arm itself) and refuses one that would hit,
 * with the obstacle in the message, before a byte is sent; a controller error is shown the
 * same way. Then the arm is read back, whether or not it moved. */
static void move(teach *t, fbrl_robot_move *mv)
{
    t->msg[0] = '\0';
    (void)fbrl_robot_motion(&t->m->robot, mv, t->msg, sizeof t->msg);
    read_pos(t);
}

/* X Y Z: a straight-line JOG by the step (in inches on the wire). */
static void jog(teach *t, int axis, int sign)
{
    fbrl_robot_move mv;
    memset(&mv, 0, sizeof mv);
    mv.kind = FBRL_ROBOT_MOVE_JOG;
    mv.straight = 1;
    mv.word = "JOG";
    mv.v[axis] = sign * (t->metric ? step_cm[t->level] / 2.54 : step_in[t->level]);
    move(t, &mv);
}

/* Pitch or roll: a straight move to the present position with the angle changed (the tool
 * point stays where it is). */
static void turn(teach *t, int which, int sign)
{
    fbrl_robot_move mv;
    t->msg[0] = '\0';
    if (!t->have_pos && read_pos(t) != 0)
        return;
    memset(&mv, 0, sizeof mv);
    mv.kind = FBRL_ROBOT_MOVE_POSE;
    mv.straight = 1;
    mv.word = which == 4 ? "PITCH" : "ROLL";
    memcpy(mv.v, t->pos, sizeof mv.v);
    mv.v[which] += sign * step_deg[t->level];
    if (which == 5) { /* roll wraps; pitch past its limit is the controller's error to give */
        if (mv.v[5] > 180.0)
            mv.v[5] -= 360.0;
        if (mv.v[5] <= -180.0)
            mv.v[5] += 360.0;
    }
    move(t, &mv);
}

static void gripper(teach *t, fbrl_rapl_cmd cmd)
{
    t->msg[0] = '\0';
    failed(t, fbrl_link_cmd(t->link, cmd, NULL, 0, 0), cmd == FBRL_RAPL_OPEN ? "OPEN" : "CLOSE");
    read_grip(t);
}

/* ---- the word ---- */

/* The pendant loop: 1 = Enter, 0 = Esc, -1 = Ctrl-C, -2 = end of input. */
static int pendant(teach *t)
{
    for (;;) {
        int ch = 0;
        key k = get_key(t, &ch);
        switch (k) {
        case K_ENTER: return 1;
        case K_ESC: return 0;
        case K_INTR: return -1;
        case K_EOF: return -2;
        case K_RIGHT: jog(t, 0, +1); break;
        case K_LEFT: jog(t, 0, -1); break;
        case K_UP: jog(t, 1, +1); break;
        case K_DOWN: jog(t, 1, -1); break;
        case K_PGUP: jog(t, 2, +1); break;
        case K_PGDN: jog(t, 2, -1); break;
        case K_CHAR:
            switch (ch) {
            case '1':
            case '2':
            case '3':
            case '4': t->level = ch - '1'; break;
            case '+':
            case '=':
                if (t->level + 1 < NSTEP)
                    t->level++;
                break;
            case '-':
            case '_':
                if (t->level > 0)
                    t->level--;
                break;
            case '[': turn(t, 4, -1); break;
            case ']': turn(t, 4, +1); break;
            case ',': turn(t, 5, -1); break;
            case '.': turn(t, 5, +1); break;
            case 'o':
            case 'O': gripper(t, FBRL_RAPL_OPEN); break;
            case 'c':
            case 'C': gripper(t, FBRL_RAPL_CLOSE); break;
            case 'r':
            case 'R':
                t->msg[0] = '\0';
                read_pos(t);
                read_grip(t);
                break;
            case '?':
            case 'h':
            case 'H': help(t); break;
            case 0x03: return -1; /* Ctrl-C with ISIG off (it is on: belt and braces) */
            default: break;
            }
            break;
        default: break;
        }
        status(t);
    }
}

/* (TEACH) ( loc -- loc flag ): the pendant; flag true when Enter took the position
 * (TEACH then stores it with ARM-HERE). */
static fbrl_status w_teach(fbrl_vm *vm, void *arg, const void *word)
{
    static const char offline[] = "no controller connected: start fbrlmon with --sim or --port";
    mon *m = arg;
    teach t;
    fbrl_vmx_val v[1];
    fbrl_loc *loc;
    struct termios saved, raw;
    int r, metric = 0;

    fbrl_status st = fbrl_vmx_check(vm, word, v); /* ( loc -- loc flag ): loc stays */
    if (st != FBRL_OK)
        return st;
    fbrl_cell addr = v[0].i;
    if ((st = fbrl_vmx_push(vm, addr)) != FBRL_OK)
        return st;
    if (fbrl_glossary_loc(vm, addr, &loc) != FBRL_OK)
        return fbrl_vm_throw(vm, FBRL_THROW_BAD_ADDRESS, "TEACH: not a location (use a CREATE-LOC name)");
    if (m->link == NULL)
        return fbrl_vm_throw(vm, FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE), offline);
    if (!m->host.in_is_tty || !isatty(m->host.in_fd))
        return fbrl_vm_throw(vm, FBRL_THROW_UNSUPPORTED,
                             "TEACH needs a terminal: it reads single keys (standard input is not one)");
    if (tcgetattr(m->host.in_fd, &saved) != 0)
        return fbrl_vm_throw(vm, FBRL_THROW_UNSUPPORTED, "TEACH: cannot read the terminal's settings");

    memset(&t, 0, sizeof t);
    t.m = m;
    t.link = m->link;
    t.level = 1;
    fbrl_units_is_metric(fbrl_glossary_units(&m->glossary), &metric);
    t.metric = metric;
    if (idle(&t) != 0)
        return fbrl_vm_throw(vm, FBRL_THROW_INTERRUPT,
                             "TEACH cancelled by Ctrl-C (the location is unchanged)");

    /* Single keys without echo; ISIG stays on, so Ctrl-C still reaches the monitor. */
    raw = saved;
    raw.c_lflag &= ~(tcflag_t)(ICANON | ECHO);
    raw.c_cc[VMIN] = 1;
    raw.c_cc[VTIME] = 0;
    tcsetattr(m->host.in_fd, TCSANOW, &raw);

    mon_host_newline(&m->host);
    help(&t);
    if (read_pos(&t) == 0)
        read_grip(&t);
    status(&t);
    r = pendant(&t);

    tcsetattr(m->host.in_fd, TCSANOW, &saved);
    out(&t, r == 1 ? "\nstored\n" : "\ncancelled: the location is unchanged\n");
    fflush(m->host.out);
    m->host.column = 0;
    if (r == -1)
        return fbrl_vm_throw(vm, FBRL_THROW_INTERRUPT,
                             "TEACH cancelled by Ctrl-C (the location is unchanged)");
    if (r == -2)
        return fbrl_vm_throw(vm, FBRL_THROW_CHAR_IO,
                             "TEACH: the terminal closed (the location is unchanged)");
    return fbrl_vm_push(vm, r == 1 ? -1 : 0) == FBRL_OK ? FBRL_OK
                                                        : fbrl_vm_throw(vm, FBRL_THROW_STACK_OVERFLOW, NULL);
}

fbrl_status mon_teach_install(mon *m)
{
    /* TEACH follows the robot words' rule for its location: from the stack when there
     * is one, else the name after it. Storing goes through ARM-HERE, the robot words'
     * own read-back (BASE-OFFSET, MAP-ON unmapping). */
    static const char def[] =
        ": TEACH ( loc -- ) \\ keyboard teach pendant: arrows X Y, PgUp PgDn Z, [ ] pitch, , . roll, "
        "o c gripper, 1-4 + - step, ? keys; Enter stores the arm's position in loc (as ARM-HERE), Esc "
        "cancels\n"
        "  DEPTH 0= IF ' >BODY THEN (TEACH) IF ARM-HERE ELSE DROP THEN ;\n";
    static const fbrl_vmx_reg words[] = {
        {"(TEACH)", w_teach, "A", 0, 0, 0,
         FBRL_DOC("( loc -- loc flag )", "TEACH's pendant; flag true when Enter took the position")},
    };
    fbrl_status st = fbrl_vmx_define_table(m->vm, words, 1, m);
    if (st == FBRL_OK)
        st = fbrl_vm_eval(m->vm, def, sizeof def - 1);
    return st;
}
