/* sim_state.c - the controller's battery-backed memory: a text state file,
 * written to a temporary file, flushed to disk and renamed into place so a
 * crash never leaves a half-written file. */
#include "sim_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAGIC "FBRLSIM-STATE 1"

int sim_state_save(fbrl_sim *s)
{
    char tmp[4096];
    FILE *f;
    int i, j, ok;
    double q[FBRL_SIM_ARM_AXES];

    if (!s->state_path)
        return 0;
    if (snprintf(tmp, sizeof tmp, "%s.tmp", s->state_path) >= (int)sizeof tmp)
        return -1;
    f = fopen(tmp, "w");
    if (!f)
        return -1;
    /* A motion in progress is saved at its end point: the arm is on its way there. */
    memcpy(q, s->moving ? s->qt : s->q, sizeof q);
    fprintf(f, "%s\n", MAGIC);
    fprintf(f, "SPEED %.17g\n", s->speed);
    fprintf(f, "JOINTS %.17g %.17g %.17g %.17g %.17g\n", q[0], q[1], q[2], q[3], q[4]);
    fprintf(f, "EXTRA %.17g %.17g\n", s->xmoving ? s->xtarget : s->xpos, s->xhome);
    fprintf(f, "GRIPPER %.17g %.17g\n", s->grip, s->grip_force);
    fprintf(f, "OUTPUTS ");
    for (i = 0; i < SIM_IO; i++)
        fputc(s->out_[i] ? '1' : '0', f);
    fputc('\n', f);
    if (s->tool_set)
        fprintf(f, "TOOL %s %.17g %.17g %.17g %.17g %.17g %.17g\n", s->tool_name, s->tool[0],
                s->tool[1], s->tool[2], s->tool[3], s->tool[4], s->tool[5]);
    fprintf(f, "FLASH %d\n", s->flash);
    for (i = 0; i < 2; i++)
        fprintf(f, "CONFIG %d %ld %c %d %d %c %d\n", i, s->chan[i].baud, s->chan[i].parity,
                s->chan[i].data, s->chan[i].stop, s->chan[i].handshake, s->chan[i].echo);
    for (i = 1; i <= FBRL_SIM_ARM_AXES; i++)
        fprintf(f, "GAIN %d %.17g\n", i, s->gain[i]);
    for (i = 0; i < s->nvars; i++)
        fprintf(f, "VAR %s %.17g\n", s->vars[i].name, s->vars[i].v);
    for (i = 0; i < s->nlocs; i++) {
        const sim_loc *l = &s->locs[i];
        if (l->precision)
            fprintf(f, "PLOC %s %ld %ld %ld %ld %ld\n", l->name, l->p[0], l->p[1], l->p[2], l->p[3],
                    l->p[4]);
        else
            fprintf(f, "LOC %s %.17g %.17g %.17g %.17g %.17g %.17g\n", l->name, l->v[0], l->v[1],
                    l->v[2], l->v[3], l->v[4], l->v[5]);
    }
    for (i = 0; i < s->nprogs; i++) {
        fprintf(f, "PROGRAM %s\n", s->progs[i].name);
        for (j = 0; j < s->progs[i].n; j++)
            fprintf(f, "  %s\n", s->progs[i].lines[j]);
        fprintf(f, "END\n");
    }
    ok = fflush(f) == 0 && fsync(fileno(f)) == 0;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, s->state_path) != 0) {
        unlink(tmp);
        return -1;
    }
    return 0;
}

static int add_prog_line(sim_prog *p, const char *text)
{
    char **l = realloc(p->lines, (size_t)(p->n + 1) * sizeof *l);
    char *d;
    size_t n = strlen(text);
    if (!l)
        return -1;
    p->lines = l;
    if (n > SIM_LINE_MAX)
        return -1;
    d = malloc(n + 1);
    if (!d)
        return -1;
    memcpy(d, text, n + 1);
    p->lines[p->n++] = d;
    return 0;
}

static int good_name(const char *n)
{
    size_t i, len = strlen(n);
    if (len == 0 || len > SIM_NAME_MAX || !((n[0] >= 'A' && n[0] <= 'Z')))
        return 0;
    for (i = 0; i < len; i++)
        if (!((n[i] >= 'A' && n[i] <= 'Z') || (n[i] >= '0' && n[i] <= '9') || n[i] == '_'))
            return 0;
    return 1;
}

int sim_state_load(fbrl_sim *s, char *err, size_t errlen)
{
    FILE *f = fopen(s->state_path, "r");
    char line[512], name[64];
    int lineno = 0, i;
    sim_prog *prog = NULL;

    if (!f) {
        if (errno == ENOENT)
            return 0; /* a new controller: empty memory */
        sim_seterr(err, errlen, "%s: %s", s->state_path, strerror(errno));
        return -1;
    }
    if (!fgets(line, sizeof line, f) || strncmp(line, MAGIC, strlen(MAGIC)) != 0) {
        sim_seterr(err, errlen, "%s: not an fbrlsim state file", s->state_path);
        fclose(f);
        return -1;
    }
    lineno = 1;
    while (fgets(line, sizeof line, f)) {
        double d[8];
        long p[5];
        char c1, c2;
        int k, bad = 0;
        lineno++;
        line[strcspn(line, "\r\n")] = 0;
        if (prog) {
            char *t = line;
            while (*t == ' ')
                t++;
            if (!strcmp(t, "END"))
                prog = NULL;
            else if (add_prog_line(prog, t) != 0)
                bad = 1;
        } else if (!line[0] || line[0] == '#') {
            continue;
        } else if (sscanf(line, "SPEED %lf", &d[0]) == 1) {
            bad = !(d[0] > 0 && d[0] <= 100);
            s->speed = d[0];
        } else if (sscanf(line, "JOINTS %lf %lf %lf %lf %lf", &d[0], &d[1], &d[2], &d[3], &d[4]) == 5) {
            for (i = 0; i < FBRL_SIM_ARM_AXES; i++)
                s->q[i] = s->qt[i] = d[i];
            bad = fbrl_sim_arm_check(s->q) != 0;
        } else if (sscanf(line, "EXTRA %lf %lf", &d[0], &d[1]) == 2) {
            s->xpos = d[0];
            s->xhome = d[1];
        } else if (sscanf(line, "GRIPPER %lf %lf", &d[0], &d[1]) == 2) {
            s->grip = d[0];
            s->grip_force = d[1];
        } else if (sscanf(line, "OUTPUTS %63s", name) == 1) {
            bad = strlen(name) != SIM_IO;
            for (i = 0; !bad && i < SIM_IO; i++)
                s->out_[i] = name[i] == '1';
        } else if (sscanf(line, "TOOL %63s %lf %lf %lf %lf %lf %lf", name, &d[0], &d[1], &d[2], &d[3],
                          &d[4], &d[5]) == 7) {
            bad = !good_name(name);
            if (!bad) {
                s->tool_set = 1;
                strcpy(s->tool_name, name);
                memcpy(s->tool, d, sizeof s->tool);
            }
        } else if (sscanf(line, "FLASH %d", &k) == 1) {
            s->flash = k != 0;
        } else if (sscanf(line, "CONFIG %d %lf %c %lf %lf %c %lf", &k, &d[0], &c1, &d[1], &d[2], &c2,
                          &d[3]) == 7) {
            bad = k < 0 || k > 1;
            if (!bad) {
                s->chan[k].baud = (long)d[0];
                s->chan[k].parity = c1;
                s->chan[k].data = (int)d[1];
                s->chan[k].stop = (int)d[2];
                s->chan[k].handshake = c2;
                s->chan[k].echo = d[3] != 0;
            }
        } else if (sscanf(line, "GAIN %d %lf", &k, &d[0]) == 2) {
            bad = k < 1 || k > FBRL_SIM_ARM_AXES;
            if (!bad)
                s->gain[k] = d[0];
        } else if (sscanf(line, "VAR %63s %lf", name, &d[0]) == 2) {
            bad = !good_name(name) || s->nvars == SIM_MAX_VARS;
            if (!bad) {
                strcpy(s->vars[s->nvars].name, name);
                s->vars[s->nvars++].v = d[0];
            }
        } else if (sscanf(line, "PLOC %63s %ld %ld %ld %ld %ld", name, &p[0], &p[1], &p[2], &p[3],
                          &p[4]) == 6) {
            bad = !good_name(name) || s->nlocs == SIM_MAX_LOCS;
            if (!bad) {
                sim_loc *l = &s->locs[s->nlocs++];
                memset(l, 0, sizeof *l);
                strcpy(l->name, name);
                l->precision = 1;
                memcpy(l->p, p, sizeof l->p);
            }
        } else if (sscanf(line, "LOC %63s %lf %lf %lf %lf %lf %lf", name, &d[0], &d[1], &d[2], &d[3],
                          &d[4], &d[5]) == 7) {
            bad = !good_name(name) || s->nlocs == SIM_MAX_LOCS;
            if (!bad) {
                sim_loc *l = &s->locs[s->nlocs++];
                memset(l, 0, sizeof *l);
                strcpy(l->name, name);
                memcpy(l->v, d, sizeof l->v);
            }
        } else if (sscanf(line, "PROGRAM %63s", name) == 1) {
            sim_prog *np = realloc(s->progs, (size_t)(s->nprogs + 1) * sizeof *np);
            bad = !good_name(name) || !np;
            if (np) {
                s->progs = np;
                if (!bad) {
                    prog = &s->progs[s->nprogs++];
                    memset(prog, 0, sizeof *prog);
                    strcpy(prog->name, name);
                }
            }
        } else {
            bad = 1;
        }
        if (bad) {
            sim_seterr(err, errlen, "%s:%d: bad line '%s'", s->state_path, lineno, line);
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    if (prog) {
        sim_seterr(err, errlen, "%s: PROGRAM %s has no END", s->state_path, prog->name);
        return -1;
    }
    return 0;
}
