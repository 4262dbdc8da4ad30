/* SPDX-License-Identifier: MIT */
/* link_internal.h - what the link's files share inside the library (not installed). */
#ifndef FBRL_LINK_INTERNAL_H
#define FBRL_LINK_INTERNAL_H

#include "fbrl/link.h"

/* ---- link.c: the command machine ---- */

/* What the link is doing with the command (fbrl_link.phase). */
enum { PH_IDLE, PH_ERASE, PH_TYPE, PH_REPLY, PH_VERIFY, PH_CLEAN };
/* Which line it runs: the caller's, or a STATUS that settles its damaged reply. */
enum { ST_MAIN, ST_ERRQ };
/* What was sent after the CR and not answered yet (fbrl_link.probe_out). */
enum { PR_NONE, PR_IDLE, PR_VERIFY };
/* What the controller was last seen doing (fbrl_link.seen, fbrl_link_outcome.seen). */
enum {
    SEEN_NONE,
    SEEN_SILENT,
    SEEN_AMBIGUOUS,
    SEEN_STARTED,
    SEEN_BUSY,
    SEEN_UNREADABLE,
    SEEN_UNSETTLED,
    SEEN_SAME_ERROR
};

static inline uint64_t fbrli_ms(uint32_t v) { return (uint64_t)v * 1000u; }
/* The link's clock: cfg.now_us, or the uart backend's. */
uint64_t fbrli_link_now_us(const fbrl_link *l);
/* Write bytes to the uart (within echo_timeout_ms); the link's last activity is now. */
fbrl_status fbrli_link_send(fbrl_link *l, const uint8_t *p, size_t n);
/* Begin a command (fbrl_link_start with the prompt's deadline and whether it is safe to
 * type twice given, as the table says them). */
fbrl_status fbrli_link_start(fbrl_link *l, const char *line, fbrl_link_reply kind, uint32_t timeout_ms,
                             int safe);
/* The one place the controller's units (fbrl_link_units) are learned from a STATUS: its
 * units line when si has one; without it inches (the controller's default) when the reply
 * came whole, else nothing is learned. Whether the units are known now. */
int fbrli_link_learn_units(fbrl_link *l, const fbrl_rapl_status_info *si, int whole);

/* ---- link_aci.c ---- */

/* Switch a controller in ACI mode to terminal mode (one already in terminal mode: the
 * switch's first bytes are erased again). FBRL_ETIMEOUT nothing answers, FBRL_EPROTOCOL a
 * wrong answer, FBRL_EIO the port failed. */
fbrl_status fbrli_link_aci_switch(fbrl_link *l);

/* ---- link_probe.c: the probe and the parse of its echo (docs/link.md 3.3) ---- */

#define FBRLI_PROBE_MAX 8 /* bytes of a probe: [XON] ? CAN ? CAN m m m */

/* The next probe's bytes into out (with its leading XON when xon): new markers; its echo
 * not seen yet. How many bytes. */
size_t fbrli_probe_make(fbrl_link_probe *p, uint8_t out[FBRLI_PROBE_MAX], int xon);
/* A byte of the probe's echo (parse_it: also parse it as the answer to the first probe
 * after a CR). */
void fbrli_probe_echo(fbrl_link_probe *p, uint8_t b, int parse_it);
/* The latest probe's markers have just come (its echo is over), damaged before or not. */
int fbrli_probe_ended(const fbrl_link_probe *p);
/* Its echo has just ended undamaged: the line holds exactly its markers. */
int fbrli_probe_answered(const fbrl_link_probe *p);
/* Parsed whole: the characters its first CAN erased (1: its own '?', the line was empty;
 * more: what the line held before it, plus that '?'); -1 when the echo was not whole. */
long fbrli_probe_erased(const fbrl_link_probe *p);
/* b can be a byte of a probe's echo ('?', BS, SP or a marker), whatever of it was lost
 * before: a byte that cannot is the reply of what came before the probe. */
int fbrli_probe_may_echo(uint8_t b);

/* ---- link_query.c: believing a query's reply (docs/link.md 3.5) ---- */

/* A TYPEI/TYPEV value line (parsed: it is a number): the read's damage, the line's sum and
 * length, and the query's longest value line. */
void fbrli_query_value(fbrl_link *l, const char *s, size_t n, int flawed, int parsed);
/* The undamaged reply is believed: self-consistent, or the query_reads-th alike. */
int fbrli_query_confirmed(fbrl_link *l);

/* ---- link_settle.c: settling a damaged reply by STATUS (docs/link.md 3.5) ---- */

/* The controller's LAST ERROR is not known (fbrl_link.known_err; -1 is NONE). */
#define FBRLI_ERR_UNKNOWN (-2)

/* The command whose reply is settled, kept while STATUS is read for it; shaped: its
 * reply had an error line's shape. */
void fbrli_settle_begin(fbrl_link_settle *s, const char *line, size_t len, fbrl_link_reply kind,
                        unsigned attempts, int shaped);
/* One STATUS read for it ran with this result (reported after the command). */
void fbrli_settle_ran(fbrl_link_settle *s, fbrl_status result);
/* The command back, as it was before the reads. */
void fbrli_settle_end(const fbrl_link_settle *s, char *line, size_t *len, fbrl_link_reply *kind,
                      unsigned *attempts);
/* Its result from STATUS's LAST ERROR (-1 NONE) and the last the link proved before it:
 * FBRL_OK, FBRL_ECONTROLLER (refused: that code), FBRL_EMAYBE (success and the same
 * refusal look alike). */
fbrl_status fbrli_settle_verdict(const fbrl_link_settle *s, int last_error, int known_err);

/* ---- link_modes.c ---- */

/* A line ran (FBRL_OK) while the controller's units were `units`: keep it if it sets a
 * mode (or is a POINT a later TOOL may name). */
void fbrli_link_modes_note(fbrl_link_modes *m, const char *line, int units);
/* The units the lengths of mode line i were typed in (FBRL_LINK_UNITS_*), or
 * FBRLI_NO_LENGTHS for a line without lengths. */
#define FBRLI_NO_LENGTHS (-2)
int fbrli_link_modes_units(const fbrl_link_modes *m, size_t i);

#endif
