/* SPDX-License-Identifier: MIT */
/* recover.c - corrective actions per step of a plan (include/fbrl/recover.h,
 * docs/debugging.md): rules ON-FAILURE declares, and ATTEMPT, which runs a step and on a
 * failure applies the first rule of that step and kind that still has tries left. The
 * loop is Forth (CATCH); the decision is (RECOVER) here. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fbrl/rapl_reply.h"
#include "fbrl/recover.h"
#include "fbrl/vm_throw.h"
#include "fbrl/vmx.h"

#define MAX_COUNT 1000 /* RETRY / RUN counts: 1 .. MAX_COUNT */

static const struct {
    const char *name, *text;
} kinds[FBRL_RECOVER_KINDS] = {
    [FBRL_RECOVER_REACH] = {"REACH", "the place is out of the arm's reach"},
    [FBRL_RECOVER_JOINT_LIMIT] = {"JOINT-LIMIT", "a joint would pass its limit"},
    [FBRL_RECOVER_COLLISION] = {"COLLISION", "the move would collide with the work cell"},
    [FBRL_RECOVER_CONTROLLER] = {"CONTROLLER", "the controller refused a command"},
    [FBRL_RECOVER_COMM_LOST] = {"COMM-LOST", "the controller stopped answering"},
    [FBRL_RECOVER_GRIP_EMPTY] = {"GRIP-EMPTY", "the gripper closed on nothing"},
    [FBRL_RECOVER_PART_MISSING] = {"PART-MISSING", "a sensor says the part is missing"},
    [FBRL_RECOVER_DEVICE_TIMEOUT] = {"DEVICE-TIMEOUT", "a device did not answer in time"},
};

static const struct {
    const char *name;
    fbrl_recover_action action;
    int counted; /* takes a count (and RUN a word first) */
} actions[] = {
    {"RETRY", FBRL_RECOVER_RETRY, 1}, {"RUN", FBRL_RECOVER_RUN, 1},   {"SKIP", FBRL_RECOVER_SKIP, 0},
    {"ASK", FBRL_RECOVER_ASK, 0},     {"STOP", FBRL_RECOVER_STOP, 0},
};
#define NACTIONS (sizeof actions / sizeof actions[0])

const char *fbrl_recover_kind_name(fbrl_recover_kind kind)
{
    return kind > FBRL_RECOVER_NONE && kind < FBRL_RECOVER_KINDS ? kinds[kind].name : "";
}

const char *fbrl_recover_kind_text(fbrl_recover_kind kind)
{
    return kind > FBRL_RECOVER_NONE && kind < FBRL_RECOVER_KINDS ? kinds[kind].text : "";
}

fbrl_recover_kind fbrl_recover_classify(const fbrl_recover *rc, int code)
{
    if (code <= FBRL_RECOVER_THROW(FBRL_RECOVER_REACH) && code > FBRL_RECOVER_THROW(FBRL_RECOVER_KINDS))
        return (fbrl_recover_kind)(FBRL_RECOVER_THROW(0) - code);
    if (code == FBRL_VM_THROW_OF_STATUS(FBRL_EDISCONNECTED) ||
        code == FBRL_VM_THROW_OF_STATUS(FBRL_EOFFLINE) || code == FBRL_VM_THROW_OF_STATUS(FBRL_ETIMEOUT) ||
        code == FBRL_VM_THROW_OF_STATUS(FBRL_EMAYBE))
        return FBRL_RECOVER_COMM_LOST;
    if (code == FBRL_VM_THROW_OF_STATUS(FBRL_ECONTROLLER)) {
        switch (fbrl_rapl_error_class(rc && rc->robot ? fbrl_robot_last_error(rc->robot) : -1)) {
        case FBRL_RAPL_ERRC_REACH: return FBRL_RECOVER_REACH;
        case FBRL_RAPL_ERRC_JOINT_LIMIT: return FBRL_RECOVER_JOINT_LIMIT;
        case FBRL_RAPL_ERRC_COLLISION: return FBRL_RECOVER_COLLISION;
        default: return FBRL_RECOVER_CONTROLLER;
        }
    }
    return FBRL_RECOVER_NONE;
}

static fbrl_status word_text(fbrl_vm *vm, char *buf, size_t cap)
{
    const char *p;
    size_t n;
    fbrl_status st = fbrl_vm_parse_name(vm, &p, &n);
    if (st != FBRL_OK)
        return st;
    if (n >= cap)
        n = cap - 1;
    memcpy(buf, p, n);
    buf[n] = 0;
    return FBRL_OK;
}

static fbrl_recover_kind kind_named(const char *s)
{
    for (int k = FBRL_RECOVER_REACH; k < FBRL_RECOVER_KINDS; k++)
        if (strcasecmp(s, kinds[k].name) == 0)
            return (fbrl_recover_kind)k;
    return FBRL_RECOVER_NONE;
}

static const char *kind_list(void)
{
    return "REACH JOINT-LIMIT COLLISION CONTROLLER COMM-LOST GRIP-EMPTY PART-MISSING DEVICE-TIMEOUT";
}

/* ON-FAILURE ( "step" "kind" "action" [ "word" ] [ "count" ] -- ) */
static fbrl_status w_on_failure(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    fbrl_recover_rule r;
    char step[64], kind[32], act[16], arg[64];
    fbrl_status st;
    (void)word;
    memset(&r, 0, sizeof r);
    if ((st = word_text(vm, step, sizeof step)) != FBRL_OK ||
        (st = word_text(vm, kind, sizeof kind)) != FBRL_OK ||
        (st = word_text(vm, act, sizeof act)) != FBRL_OK)
        return st;
    if (!step[0] || !kind[0] || !act[0])
        return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ,
                               "ON-FAILURE: say the step, the kind and the action, "
                               "e.g. ON-FAILURE PICK-UP GRIP-EMPTY RETRY 1");
    if (strcmp(step, "*") != 0 && fbrl_vmx_find(vm, step, strlen(step), &r.step) != FBRL_OK)
        return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ,
                               "ON-FAILURE: %.40s is not a word (a step is a word, or *)", step);
    snprintf(r.step_name, sizeof r.step_name, "%.31s", step);
    r.kind = (uint8_t)kind_named(kind);
    if (r.kind == FBRL_RECOVER_NONE)
        return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ, "%.16s is not a failure kind: %s", kind, kind_list());
    size_t a = 0;
    while (a < NACTIONS && strcasecmp(act, actions[a].name) != 0)
        a++;
    if (a == NACTIONS)
        return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ,
                               "ON-FAILURE: %.20s is not an action (RETRY n, RUN word n, "
                               "SKIP, ASK, STOP)",
                               act);
    r.action = (uint8_t)actions[a].action;
    if (r.action == FBRL_RECOVER_RUN) {
        if ((st = word_text(vm, arg, sizeof arg)) != FBRL_OK)
            return st;
        snprintf(r.word_name, sizeof r.word_name, "%.31s", arg);
        if (!arg[0] || fbrl_vmx_find(vm, arg, strlen(arg), &r.word) != FBRL_OK)
            return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ,
                                   "ON-FAILURE: RUN needs a recovery word, %.40s is none",
                                   arg[0] ? arg : "and got nothing");
    }
    if (actions[a].counted) {
        char *end;
        if ((st = word_text(vm, arg, sizeof arg)) != FBRL_OK)
            return st;
        long n = strtol(arg, &end, 10);
        if (!arg[0] || *end || n < 1 || n > MAX_COUNT)
            return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ, "ON-FAILURE: %s needs a count 1..%d, not \"%.20s\"",
                                   actions[a].name, MAX_COUNT, arg);
        r.limit = (uint16_t)n;
    }
    if (rc->nrules >= FBRL_RECOVER_RULES)
        return fbrl_vmx_throwf(vm, FBRL_THROW_ABORTQ, "ON-FAILURE: too many rules (%d)", FBRL_RECOVER_RULES);
    rc->rules[rc->nrules++] = r;
    return FBRL_OK;
}

/* (ATTEMPT-START) ( xt -- ): a step begins: its rules' tries are counted anew */
static fbrl_status w_attempt_start(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    fbrl_vmx_val v[1];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    if (st != FBRL_OK)
        return st;
    fbrl_cell xt = v[0].i;
    for (size_t i = 0; i < rc->nrules; i++)
        if (rc->rules[i].step == xt || rc->rules[i].step == 0)
            rc->rules[i].used = 0;
    return FBRL_OK;
}

static void note(fbrl_recover *rc, fbrl_recover_kind k, const char *what, const char *action)
{
    if (rc->note)
        rc->note(rc->note_ctx, rc->step, fbrl_recover_kind_name(k), what, action, rc->sample);
}

/* The failure in plain words: the kind's, and the controller's advice when it said one. */
static void describe(const fbrl_recover *rc, fbrl_recover_kind k, char *buf, size_t cap)
{
    const char *help = NULL;
    if (k == FBRL_RECOVER_REACH || k == FBRL_RECOVER_JOINT_LIMIT || k == FBRL_RECOVER_COLLISION ||
        k == FBRL_RECOVER_CONTROLLER)
        help = rc->robot ? fbrl_rapl_error_help(fbrl_robot_last_error(rc->robot)) : NULL;
    snprintf(buf, cap, "%s%s%s", fbrl_recover_kind_text(k), help ? ": " : "", help ? help : "");
}

static fbrl_status stop_safely(fbrl_vm *vm, fbrl_recover *rc, fbrl_recover_kind k, const char *what)
{
    fbrl_robot_stop s;
    const char *how = "";
    fbrl_status st = rc->robot ? fbrl_robot_safe_stop(rc->robot, &s) : FBRL_EOFFLINE;
    if (st == FBRL_EOFFLINE)
        how = " (no controller)";
    else if (st != FBRL_OK)
        how = " (the controller could not be reached: check the arm)";
    char where[32] = "";
    if (rc->sample > 0)
        snprintf(where, sizeof where, " at sample %ld", rc->sample);
    (void)what; /* told in the note before */
    return fbrl_vmx_throwf(vm, FBRL_RECOVER_THROW_STOPPED, "stopped safely: %.31s failed%s: %s%s", rc->step,
                           where, fbrl_recover_kind_name(k), how);
}

/* (RECOVER) ( code xt -- 0 | code ): after the step xt threw code: 0 to run it again (a
 * retry, after a recovery word or the operator's Retry); the code itself when no rule
 * takes it (ATTEMPT throws it on); a skip or a safe stop is thrown from here. */
static fbrl_status w_recover(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    fbrl_vmx_val v[2];
    fbrl_status cst = fbrl_vmx_check(vm, word, v);
    if (cst != FBRL_OK)
        return cst;
    fbrl_cell code = v[0].i, xt = v[1].i;
    fbrl_recover_kind k = fbrl_recover_classify(rc, (int)code);
    fbrl_recover_rule *r = NULL;
    const char *nm;
    size_t nl;
    if (fbrl_vmx_name(vm, xt, &nm, &nl) != FBRL_OK || nl == 0)
        nm = "a step", nl = 6;
    snprintf(rc->step, sizeof rc->step, "%.*s", (int)(nl < sizeof rc->step ? nl : sizeof rc->step - 1), nm);
    for (size_t i = 0; k != FBRL_RECOVER_NONE && i < rc->nrules && !r; i++) {
        fbrl_recover_rule *c = &rc->rules[i];
        if ((c->step == xt || c->step == 0) && c->kind == k &&
            !((c->action == FBRL_RECOVER_RETRY || c->action == FBRL_RECOVER_RUN) && c->used >= c->limit))
            r = c;
    }
    if (!r)
        return fbrl_vm_push(vm, code);
    char what[256], action[64];
    describe(rc, k, what, sizeof what);
    switch ((fbrl_recover_action)r->action) {
    case FBRL_RECOVER_RETRY:
    case FBRL_RECOVER_RUN:
        r->used++;
        if (r->action == FBRL_RECOVER_RUN)
            snprintf(action, sizeof action, "run %s, retry %u of %u", r->word_name, (unsigned)r->used,
                     (unsigned)r->limit);
        else
            snprintf(action, sizeof action, "retry %u of %u", (unsigned)r->used, (unsigned)r->limit);
        note(rc, k, what, action);
        if (r->action == FBRL_RECOVER_RUN) {
            fbrl_status st = fbrl_vmx_execute(vm, r->word);
            if (st != FBRL_OK)
                return st;
        }
        return fbrl_vm_push(vm, 0);
    case FBRL_RECOVER_SKIP:
        note(rc, k, what, "skip the sample");
        snprintf(rc->skip_reason, sizeof rc->skip_reason, "%s failed (%s): sample skipped", rc->step,
                 fbrl_recover_kind_name(k));
        return fbrl_vmx_throwf(vm, FBRL_RECOVER_THROW_SKIP, "%s", rc->skip_reason);
    case FBRL_RECOVER_ASK:
        if (rc->ask) {
            char q[400];
            char at[32] = "";
            if (rc->sample > 0)
                snprintf(at, sizeof at, " (sample %ld)", rc->sample);
            snprintf(q, sizeof q, "%s failed%s: %s.", rc->step, at, what);
            int answer = rc->ask(rc->ask_ctx, q);
            if (answer == 'R') {
                note(rc, k, what, "ask: retry");
                return fbrl_vm_push(vm, 0);
            }
            if (answer == 'S') {
                note(rc, k, what, "ask: skip the sample");
                snprintf(rc->skip_reason, sizeof rc->skip_reason, "%s failed (%s): the operator skipped the sample",
                         rc->step, fbrl_recover_kind_name(k));
                return fbrl_vmx_throwf(vm, FBRL_RECOVER_THROW_SKIP, "%s", rc->skip_reason);
            }
            note(rc, k, what, "ask: abort");
        } else {
            note(rc, k, what, "ask: no operator, stop");
        }
        return stop_safely(vm, rc, k, what);
    case FBRL_RECOVER_STOP: note(rc, k, what, "stop"); return stop_safely(vm, rc, k, what);
    }
    return fbrl_vm_push(vm, code);
}

/* (SAMPLE+) ( -- ): RUN-SAMPLE counts samples for the notes */
static fbrl_status w_sample_next(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    (void)vm;
    (void)word;
    rc->sample++;
    return FBRL_OK;
}

/* (SKIPPED) ( -- ): RUN-SAMPLE gave its sample up: tell who asked (the method run) */
static fbrl_status w_skipped(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    (void)vm;
    (void)word;
    if (rc->skip)
        rc->skip(rc->skip_ctx, rc->skip_reason);
    return FBRL_OK;
}

/* (FAILURE) ( kind -- ): throw the failure the plan saw */
static fbrl_status w_failure_run(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_vmx_val v[1];
    fbrl_status st = fbrl_vmx_check(vm, word, v);
    (void)ctx;
    if (st != FBRL_OK)
        return st;
    fbrl_cell k = v[0].i;
    return fbrl_vmx_throwf(vm, FBRL_RECOVER_THROW(k), "%s: %s", fbrl_recover_kind_name((fbrl_recover_kind)k),
                           fbrl_recover_kind_text((fbrl_recover_kind)k));
}

/* FAILURE ( "kind" -- ): raise the failure now, or compiled: when the definition runs */
static fbrl_status w_failure(fbrl_vm *vm, void *ctx, const void *word)
{
    char kind[32];
    fbrl_cell run;
    fbrl_status st = word_text(vm, kind, sizeof kind);
    (void)word;
    (void)ctx;
    if (st != FBRL_OK)
        return st;
    fbrl_recover_kind k = kind_named(kind);
    if (k != FBRL_RECOVER_GRIP_EMPTY && k != FBRL_RECOVER_PART_MISSING && k != FBRL_RECOVER_DEVICE_TIMEOUT)
        return fbrl_vmx_throwf(
            vm, FBRL_THROW_ABORTQ,
            "FAILURE: %.30s is not a failure a plan raises (GRIP-EMPTY PART-MISSING DEVICE-TIMEOUT)", kind);
    if ((st = fbrl_vmx_find(vm, "(FAILURE)", 9, &run)) != FBRL_OK)
        return st;
    if (fbrl_vmx_compiling(vm)) {
        if ((st = fbrl_vmx_compile_lit(vm, (fbrl_cell)k)) != FBRL_OK)
            return st;
        return fbrl_vmx_compile_xt(vm, run);
    }
    if ((st = fbrl_vm_push(vm, (fbrl_cell)k)) != FBRL_OK)
        return st;
    return fbrl_vmx_execute(vm, run);
}

/* RECOVERY-RULES ( -- ) */
static fbrl_status w_rules(fbrl_vm *vm, void *ctx, const void *word)
{
    fbrl_recover *rc = ctx;
    char line[160];
    (void)word;
    if (rc->nrules == 0)
        fbrl_vmx_puts(vm, "no corrective actions declared (ON-FAILURE)\n");
    for (size_t i = 0; i < rc->nrules; i++) {
        const fbrl_recover_rule *r = &rc->rules[i];
        const char *an = "";
        for (size_t a = 0; a < NACTIONS; a++)
            if (actions[a].action == r->action)
                an = actions[a].name;
        int n = snprintf(line, sizeof line, "ON-FAILURE %s %s %s%s%s", r->step ? r->step_name : "*",
                         fbrl_recover_kind_name((fbrl_recover_kind)r->kind), an,
                         r->action == FBRL_RECOVER_RUN ? " " : "",
                         r->action == FBRL_RECOVER_RUN ? r->word_name : "");
        if (r->action == FBRL_RECOVER_RETRY || r->action == FBRL_RECOVER_RUN)
            snprintf(line + n, sizeof line - (size_t)n, " %u", (unsigned)r->limit);
        fbrl_vmx_puts(vm, line);
        fbrl_vmx_puts(vm, "\n");
    }
    return FBRL_OK;
}

fbrl_status fbrl_recover_set_ask(fbrl_recover *rc, fbrl_recover_ask_fn fn, void *ctx)
{
    if (!rc)
        return FBRL_EINVAL;
    rc->ask = fn;
    rc->ask_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_recover_set_note(fbrl_recover *rc, fbrl_recover_note_fn fn, void *ctx)
{
    if (!rc)
        return FBRL_EINVAL;
    rc->note = fn;
    rc->note_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_recover_set_skip(fbrl_recover *rc, fbrl_recover_skip_fn fn, void *ctx)
{
    if (!rc)
        return FBRL_EINVAL;
    rc->skip = fn;
    rc->skip_ctx = ctx;
    return FBRL_OK;
}

fbrl_status fbrl_recover_install(fbrl_vm *vm, fbrl_recover *rc, fbrl_robot *robot)
{
    static const char forth_fmt[] =
        ": ATTEMPT ( xt -- ) \\ run a step; a failure gets the step's corrective action (ON-FAILURE)\n"
        "  DUP (ATTEMPT-START) BEGIN DUP CATCH ?DUP WHILE OVER (RECOVER) ?DUP IF NIP THROW THEN REPEAT DROP "
        ";\n"
        ": RUN-SAMPLE ( xt -- flag ) \\ run one sample's steps: false if a corrective action skipped it\n"
        "  (SAMPLE+) CATCH DUP %d = IF DROP (SKIPPED) FALSE ELSE THROW TRUE THEN ;\n";
    char forth[sizeof forth_fmt + 16];
    static const fbrl_vmx_reg words[] = {
        {"ON-FAILURE", w_on_failure, "", 0, 0, 0,
         FBRL_DOC("( \"step\" \"kind\" \"action\" -- )",
                  "declare what a failure of a kind in a step does: RETRY n, RUN word n, SKIP, ASK, STOP")},
        {"FAILURE", w_failure, "", FBRL_VMX_IMMEDIATE | FBRL_VMX_STATE_SMART, 0, 0,
         FBRL_DOC("( \"kind\" -- )", "raise a failure the plan saw: GRIP-EMPTY, PART-MISSING or DEVICE-TIMEOUT")},
        {"RECOVERY-RULES", w_rules, "", 0, 0, 0, FBRL_DOC("( -- )", "list the corrective actions declared")},
        {"(ATTEMPT-START)", w_attempt_start, "I", 0, 0, 0,
         FBRL_DOC("( xt -- )", "ATTEMPT's helper: count the step's tries anew")},
        {"(RECOVER)", w_recover, "II", 0, 0, 0,
         FBRL_DOC("( code xt -- 0 | code )", "ATTEMPT's helper: apply the step's rule")},
        {"(SAMPLE+)", w_sample_next, "", 0, 0, 0, FBRL_DOC("( -- )", "RUN-SAMPLE's helper: the next sample")},
        {"(SKIPPED)", w_skipped, "", 0, 0, 0, FBRL_DOC("( -- )", "RUN-SAMPLE's helper: a sample given up")},
        {"(FAILURE)", w_failure_run, "I", 0, 0, 0,
         FBRL_DOC("( kind -- )", "FAILURE's run-time part: throw the failure")},
    };
    if (!vm || !rc)
        return FBRL_EINVAL;
    memset(rc, 0, sizeof *rc);
    rc->vm = vm;
    rc->robot = robot;
    fbrl_status st = fbrl_vmx_define_table(vm, words, sizeof words / sizeof words[0], rc);
    if (st != FBRL_OK)
        return st;
    int n = snprintf(forth, sizeof forth, forth_fmt, FBRL_RECOVER_THROW_SKIP);
    return fbrl_vm_eval(vm, forth, (size_t)n);
}
