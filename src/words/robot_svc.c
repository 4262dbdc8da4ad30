/* robot_svc.c - what every robot word uses from the VM: throwing an error (with the
 * word's name), Ctrl-C while a word waits, console output and the host's clock. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "robot_internal.h"

fbrl_status rb_fail(fbrl_robot *r, int code, const char *msg) { return fbrl_vm_throw(r->vm, code, msg); }

fbrl_status rb_fail_st(fbrl_robot *r, const rb_word *w, fbrl_status st, const char *what)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s: %s%s%s", w->name, what ? what : "", what ? ": " : "", fbrl_status_str(st));
    return rb_fail(r, FBRL_VM_THROW_OF_STATUS(st), msg);
}

/* Ctrl-C while a robot word waits on the controller: take the VM's interrupt request
 * here (the engine would deliver it only after the word returns) and throw -28. A
 * command the controller already has stays with the link (the next robot word, or
 * fbrl_robot_safe_stop, lets it end first); the arm keeps moving until the host stops
 * it (fbrl_robot_safe_stop: fbrlmon does on every Ctrl-C). */
fbrl_status rb_interrupted(fbrl_robot *r)
{
    if (!fbrl_vmx_take_interrupt(r->vm)) return FBRL_OK;
    return rb_fail(r, FBRL_THROW_INTERRUPT, "user interrupt");
}

void rb_puts(fbrl_robot *r, const char *s) { fbrl_vmx_write(r->vm, s, strlen(s)); }

fbrl_status rb_now_ms(fbrl_robot *r, uint64_t *ms)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->now_us) return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    *ms = h->now_us(h->user) / 1000u;
    return FBRL_OK;
}

fbrl_status rb_sleep_ms(fbrl_robot *r, uint32_t ms)
{
    const fbrl_vm_host *h = fbrl_vmx_host(r->vm);
    if (!h->sleep_ms) return rb_fail(r, FBRL_THROW_UNSUPPORTED, "no clock in this host");
    if (ms) h->sleep_ms(h->user, ms);
    return FBRL_OK;
}
