/* SPDX-License-Identifier: MIT */
/* robot_rline.c - what a RAPL line typed by hand is (RAPL, SEND-CR, TYPE-COM, a line on
 * the link, Python's link): the command it starts with (fbrl_rapl_line_cmd's, the
 * library's one reading), what it does to the cell (fbrl_robot_line_effect), whether it can
 * move the arm, and the motion it makes, for the guard. */
#include <string.h>

#include "fbrl/rapl_reply.h"
#include "robot_internal.h"

static char upper(char c) { return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c; }

rb_line_kind rb_line_cmd(const char *line, size_t len, fbrl_rapl_cmd *cmd)
{
    char text[FBRL_LINK_LINE_MAX + 1]; /* the link's lines are no longer: a longer one is none */
    size_t i = 0;
    if (len >= sizeof text)
        return RB_LINE_UNKNOWN;
    memcpy(text, line, len);
    text[len] = '\0';
    if (fbrl_rapl_line_cmd(text, cmd, NULL) == FBRL_OK) /* the library's one reading of it */
        return *cmd == FBRL_RAPL_ASSIGN ? RB_LINE_ASSIGN : RB_LINE_CMD;
    while (i < len && line[i] == ' ')
        i++;
    return i == len ? RB_LINE_EMPTY : RB_LINE_UNKNOWN;
}

int rb_line_moves(rb_line_kind k, fbrl_rapl_cmd cmd)
{
    if (k == RB_LINE_UNKNOWN) /* a program's name, a word the host does not know: it might */
        return 1;
    if (k != RB_LINE_CMD)
        return 0;
    return (fbrl_rapl_cmd_info(cmd)->flags & FBRL_RAPL_F_MOTION) != 0 || cmd == FBRL_RAPL_RUN;
}

fbrl_status fbrl_robot_line_effect(const char *line, unsigned *effect, uint32_t *outputs_on)
{
    fbrl_rapl_cmd cmd = FBRL_RAPL_NCMDS;
    uint32_t on = 0;
    if (!line || !effect)
        return FBRL_EINVAL;
    size_t len = strlen(line);
    rb_line_kind k = rb_line_cmd(line, len, &cmd);
    *effect = rb_line_moves(k, cmd) ? FBRL_ROBOT_LINE_MOTION : 0;
    if (k == RB_LINE_CMD && cmd == FBRL_RAPL_FINISH)
        *effect = FBRL_ROBOT_LINE_FINISH;
    if (k == RB_LINE_CMD && cmd == FBRL_RAPL_HALT)
        *effect = FBRL_ROBOT_LINE_HALT;
    if (k == RB_LINE_CMD && cmd == FBRL_RAPL_OUTPUT) { /* OUTPUT n,-m,...: the n switched on */
        const char *p = line;
        while (*p == ' ')
            p++;
        while (*p && *p != ' ' && *p != ',')
            p++;
        for (; *p; p++)
            if (*p >= '1' && *p <= '9' && (p[-1] == ' ' || p[-1] == ',' || p[-1] == '+')) {
                long v = 0;
                while (*p >= '0' && *p <= '9' && v <= FBRL_ROBOT_IO_MAX)
                    v = v * 10 + (*p++ - '0');
                if (v >= 1 && v <= FBRL_ROBOT_IO_MAX)
                    on |= 1u << (v - 1);
                if (!*p)
                    break;
            }
    }
    if (outputs_on)
        *outputs_on = on;
    return FBRL_OK;
}

int rb_line_loses(rb_line_kind k, fbrl_rapl_cmd cmd)
{
    /* HALT stops the arm somewhere on its way; LIMP lets it be moved by hand; MANUAL and TEACH
     * give it to the pendant */
    return k == RB_LINE_CMD && (cmd == FBRL_RAPL_HALT || cmd == FBRL_RAPL_LIMP || cmd == FBRL_RAPL_MANUAL ||
                                cmd == FBRL_RAPL_TEACH);
}

/* The raw motions the guard can follow: the command, the move it makes, how many numbers
 * it takes (MA MI: one per axis, 5 or 6). */
static const struct rline_follow {
    uint8_t cmd, kind, nmin, nmax;
} follow[] = {
    {FBRL_RAPL_READY, FBRL_ROBOT_MOVE_READY, 0, 0},   {FBRL_RAPL_HOME, FBRL_ROBOT_MOVE_HOME, 0, 0},
    {FBRL_RAPL_JOG, FBRL_ROBOT_MOVE_JOG, 3, 3},       {FBRL_RAPL_DEPART, FBRL_ROBOT_MOVE_DEPART, 1, 1},
    {FBRL_RAPL_JOINT, FBRL_ROBOT_MOVE_DJOINTS, 2, 2}, {FBRL_RAPL_MOTOR, FBRL_ROBOT_MOVE_MOTOR, 2, 2},
    {FBRL_RAPL_MA, FBRL_ROBOT_MOVE_JOINTS, 5, 6},     {FBRL_RAPL_MI, FBRL_ROBOT_MOVE_DJOINTS, 5, 6},
};

void rb_line_move(const char *line, size_t len, fbrl_robot_move *m)
{
    fbrl_rapl_cmd cmd;
    double v[6];
    size_t n = 0, i = 0, f = 0;
    int s = 0;
    memset(m, 0, sizeof *m);
    m->kind = FBRL_ROBOT_MOVE_OTHER; /* what the guard cannot follow: MOVE, APPRO to a controller
                                      * location, ALIGN, RUN ... */
    if (rb_line_cmd(line, len, &cmd) != RB_LINE_CMD)
        return;
    while (f < sizeof follow / sizeof follow[0] && follow[f].cmd != cmd)
        f++;
    if (f == sizeof follow / sizeof follow[0])
        return;
    while (i < len && line[i] == ' ')
        i++;
    while (i < len && line[i] != ' ' && line[i] != ',')
        i++;
    if (i < len) /* the first separator: a space or a comma */
        i++;
    /* the numbers, comma-separated, and a last S (",S": a straight line) */
    while (i < len) {
        size_t e = i, a, b;
        while (e < len && line[e] != ',')
            e++;
        for (a = i; a < e && line[a] == ' '; a++)
            ;
        for (b = e; b > a && line[b - 1] == ' '; b--)
            ;
        if (b - a == 1 && upper(line[a]) == 'S' && e == len)
            s = 1;
        else if (n >= follow[f].nmax || fbrl_rapl_parse_real(line + a, b - a, &v[n++]) != FBRL_OK)
            return;
        i = e + 1;
    }
    if (n < follow[f].nmin)
        return;
    m->kind = (fbrl_robot_move_kind)follow[f].kind;
    m->straight = s;
    switch (cmd) {
    case FBRL_RAPL_JOG:
        m->straight = 1;
        memcpy(m->v, v, 3 * sizeof v[0]);
        break;
    case FBRL_RAPL_DEPART: m->dist = v[0]; break;
    case FBRL_RAPL_JOINT: /* JOINT j,degrees */
        if (v[0] < 1 || v[0] > 6 || v[0] != (double)(int)v[0])
            m->kind = FBRL_ROBOT_MOVE_OTHER;
        else
            m->v[(int)v[0] - 1] = v[1];
        break;
    case FBRL_RAPL_MOTOR: memcpy(m->v, v, 2 * sizeof v[0]); break;
    case FBRL_RAPL_MA:
    case FBRL_RAPL_MI: /* radians on the wire */
        for (size_t k = 0; k < n; k++)
            m->v[k] = v[k] * (180.0 / 3.14159265358979323846);
        break;
    default: break;
    }
}
