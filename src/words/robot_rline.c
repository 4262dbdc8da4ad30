/* SPDX-License-Identifier: MIT */
/* robot_rline.c - what a RAPL line typed by hand is (RAPL, SEND-CR, TYPE-COM, a line on
 * the link): the command it starts with, whether it can move the arm, and the motion it
 * makes, for the guard. The one place the robot words read a raw line's command. */
#include <string.h>

#include "fbrl/rapl_reply.h"
#include "robot_internal.h"

static char upper(char c) { return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c; }

rb_line_kind rb_line_cmd(const char *line, size_t len, fbrl_rapl_cmd *cmd)
{
    char word[12];
    size_t i = 0, k = 0;
    while (i < len && line[i] == ' ')
        i++;
    while (i + k < len && line[i + k] != ' ' && line[i + k] != ',' && line[i + k] != '=') {
        if (k + 1 >= sizeof word)
            return RB_LINE_UNKNOWN;
        word[k] = upper(line[i + k]);
        k++;
    }
    word[k] = '\0';
    size_t j = i + k;
    while (j < len && line[j] == ' ')
        j++;
    if (k > 0 && j < len && line[j] == '=')
        return RB_LINE_ASSIGN;
    if (word[0] == '/') { /* the thesis's /NNN token form */
        int tok = 0;
        for (size_t d = 1; d < k; d++)
            tok = (word[d] >= '0' && word[d] <= '9') ? tok * 10 + (word[d] - '0') : -1000;
        for (int c = 0; c < FBRL_RAPL_NCMDS && tok > 0; c++)
            if (fbrl_rapl_cmd_info((fbrl_rapl_cmd)c)->token == tok) {
                *cmd = (fbrl_rapl_cmd)c;
                return RB_LINE_CMD;
            }
        return RB_LINE_UNKNOWN;
    }
    if (k == 0)
        return len == i ? RB_LINE_EMPTY : RB_LINE_UNKNOWN;
    return fbrl_rapl_cmd_find(word, cmd) == FBRL_OK ? RB_LINE_CMD : RB_LINE_UNKNOWN;
}

int rb_line_moves(rb_line_kind k, fbrl_rapl_cmd cmd)
{
    if (k == RB_LINE_UNKNOWN) /* a program's name, a word the host does not know: it might */
        return 1;
    if (k != RB_LINE_CMD)
        return 0;
    return (fbrl_rapl_cmd_info(cmd)->flags & FBRL_RAPL_F_MOTION) != 0 || cmd == FBRL_RAPL_RUN;
}

int rb_line_loses(rb_line_kind k, fbrl_rapl_cmd cmd)
{
    /* HALT stops the arm somewhere on its way; LIMP lets it be moved by hand; MANUAL and TEACH
     * give it to the pendant */
    return k == RB_LINE_CMD && (cmd == FBRL_RAPL_HALT || cmd == FBRL_RAPL_LIMP || cmd == FBRL_RAPL_MANUAL ||
                                cmd == FBRL_RAPL_TEACH);
}

/* The numbers after the command word, comma-separated; a trailing S (",S") sets *straight.
 * FBRL_OK when exactly want numbers (want_max at most) were there. */
static fbrl_status numbers(const char *p, size_t len, double *v, size_t want, size_t want_max, size_t *got,
                           int *straight)
{
    size_t n = 0, i = 0;
    *straight = 0;
    while (i < len) {
        size_t e = i;
        while (e < len && p[e] != ',')
            e++;
        size_t a = i, b = e;
        while (a < b && p[a] == ' ')
            a++;
        while (b > a && p[b - 1] == ' ')
            b--;
        if (b - a == 1 && upper(p[a]) == 'S' && e == len && n >= want)
            *straight = 1;
        else if (n >= want_max || fbrl_rapl_parse_real(p + a, b - a, &v[n++]) != FBRL_OK)
            return FBRL_ESYNTAX;
        i = e + 1;
    }
    *got = n;
    return n >= want && n <= want_max ? FBRL_OK : FBRL_ESYNTAX;
}

void rb_line_move(const char *line, size_t len, fbrl_robot_move *m)
{
    fbrl_rapl_cmd cmd;
    double v[FBRL_RAPL_ARM_AXES_MAX];
    size_t n = 0;
    int s = 0;
    memset(m, 0, sizeof *m);
    m->kind = FBRL_ROBOT_MOVE_OTHER; /* what the guard cannot follow */
    if (rb_line_cmd(line, len, &cmd) != RB_LINE_CMD)
        return;
    size_t i = 0;
    while (i < len && line[i] == ' ')
        i++;
    while (i < len && line[i] != ' ' && line[i] != ',')
        i++;
    const char *args = line + i;
    size_t alen = len - i;
    while (alen > 0 && *args == ' ') /* the first separator is a space (or a comma) */
        args++, alen--;
    if (alen > 0 && *args == ',')
        args++, alen--;
    switch (cmd) {
    case FBRL_RAPL_READY:
        if (alen == 0)
            m->kind = FBRL_ROBOT_MOVE_READY;
        break;
    case FBRL_RAPL_HOME:
        if (alen == 0)
            m->kind = FBRL_ROBOT_MOVE_HOME;
        break;
    case FBRL_RAPL_JOG:
        if (numbers(args, alen, v, 3, 3, &n, &s) == FBRL_OK && !s) {
            m->kind = FBRL_ROBOT_MOVE_JOG;
            m->straight = 1;
            memcpy(m->v, v, 3 * sizeof v[0]);
        }
        break;
    case FBRL_RAPL_DEPART:
        if (numbers(args, alen, v, 1, 1, &n, &s) == FBRL_OK) {
            m->kind = FBRL_ROBOT_MOVE_DEPART;
            m->straight = s;
            m->dist = v[0];
        }
        break;
    case FBRL_RAPL_JOINT:
        if (numbers(args, alen, v, 2, 2, &n, &s) == FBRL_OK && !s && v[0] >= 1 && v[0] <= 6 &&
            v[0] == (double)(int)v[0]) {
            m->kind = FBRL_ROBOT_MOVE_DJOINTS;
            m->v[(int)v[0] - 1] = v[1];
        }
        break;
    case FBRL_RAPL_MOTOR:
        if (numbers(args, alen, v, 2, 2, &n, &s) == FBRL_OK && !s) {
            m->kind = FBRL_ROBOT_MOVE_MOTOR;
            m->v[0] = v[0];
            m->v[1] = v[1];
        }
        break;
    case FBRL_RAPL_MA:
    case FBRL_RAPL_MI: /* radians on the wire */
        if (numbers(args, alen, v, 5, FBRL_RAPL_ARM_AXES_MAX, &n, &s) == FBRL_OK) {
            m->kind = cmd == FBRL_RAPL_MA ? FBRL_ROBOT_MOVE_JOINTS : FBRL_ROBOT_MOVE_DJOINTS;
            m->straight = s;
            for (size_t k = 0; k < n && k < 6; k++)
                m->v[k] = v[k] * (180.0 / 3.14159265358979323846);
        }
        break;
    default: break; /* MOVE, APPRO to a controller location, ALIGN, RUN ...: not followed */
    }
}
