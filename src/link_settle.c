/* SPDX-License-Identifier: MIT */
/* link_settle.c - settling a damaged reply (docs/link.md 3.5): a command whose reply did
 * not come whole is judged by the controller's STATUS, never guessed. Its own state: the
 * command while STATUS is read for it, and those reads; and the rule that turns STATUS's
 * LAST ERROR into the command's result. The link does the reading. No link, no OS. */
#include "link_internal.h"

void fbrli_settle_begin(fbrl_link_settle *s, const char *line, size_t len, fbrl_link_reply kind,
                        unsigned attempts, int shaped)
{
    for (size_t k = 0; k <= len; k++)
        s->line[k] = line[k];
    s->len = len;
    s->kind = kind;
    s->attempts = attempts;
    s->shaped = shaped;
    s->ok = s->bad = s->maybe = 0;
}

void fbrli_settle_ran(fbrl_link_settle *s, fbrl_status result)
{
    if (result == FBRL_OK)
        s->ok++;
    else if (result == FBRL_EMAYBE)
        s->maybe++;
    else
        s->bad++;
}

void fbrli_settle_end(const fbrl_link_settle *s, char *line, size_t *len, fbrl_link_reply *kind,
                      unsigned *attempts)
{
    for (size_t k = 0; k <= s->len; k++)
        line[k] = s->line[k];
    *len = s->len;
    *kind = s->kind;
    *attempts = s->attempts;
}

/* A reply with an error line's shape was refused (the code is STATUS's); otherwise a code
 * other than the one the link last proved is this command's refusal; NONE means no
 * command ever failed, so it succeeded; the same code as before cannot tell success from
 * the same refusal again, and the command "may have run" rather than be guessed. */
fbrl_status fbrli_settle_verdict(const fbrl_link_settle *s, int last_error, int known_err)
{
    if (s->shaped)
        return last_error >= 0 ? FBRL_ECONTROLLER : FBRL_EMAYBE;
    if (last_error < 0)
        return FBRL_OK;
    if (known_err != FBRLI_ERR_UNKNOWN && last_error != known_err)
        return FBRL_ECONTROLLER;
    return FBRL_EMAYBE;
}
