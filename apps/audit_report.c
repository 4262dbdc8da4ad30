/* SPDX-License-Identifier: MIT */
/* audit_report.c - fbrl-audit report: the chain as one HTML page a reviewer reads in a
 * browser, self-contained (no script, no font, nothing fetched): whether the chain is
 * intact, every run (who, when, which method version, the outcome, each sample, who
 * reviewed it) and every other record (sign-ins, users, methods, settings, actions). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fbrl_audit.h"

#define FIELD_MAX 2048

static void esc(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; i < n && s[i]; i++) {
        switch (s[i]) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(s[i], f);
        }
    }
}

static void esc_s(FILE *f, const char *s) { esc(f, s, strlen(s)); }

/* A string field, or "" (numbers as their text). */
static const char *str(const char *l, size_t n, const char *key, char *buf)
{
    const char *v;
    size_t vl;
    if (fbrl_audit_field_str(l, n, key, buf, FIELD_MAX) == FBRL_OK)
        return buf;
    if (fbrl_audit_field(l, n, key, &v, &vl) == FBRL_OK && vl < FIELD_MAX) {
        memcpy(buf, v, vl);
        buf[vl] = '\0';
        return buf;
    }
    buf[0] = '\0';
    return buf;
}

/* The body's members but the chain's own, as "key: value" text. */
static void members(FILE *f, const char *l, size_t n)
{
    static const char *const skip[] = {"seq", "utc", "user", "prev", "hash", "type", "t", "sig", "key"};
    size_t i = 1;
    int first = 1;
    while (i < n) {
        size_t k0, k1, v0;
        while (i < n && (l[i] == ',' || l[i] == ' '))
            i++;
        if (i >= n || l[i] != '"')
            return;
        k0 = ++i;
        while (i < n && l[i] != '"')
            i += l[i] == '\\' ? 2 : 1;
        k1 = i++;
        if (i >= n || l[i] != ':')
            return;
        v0 = ++i;
        int depth = 0, in_str = 0;
        for (; i < n; i++) {
            char c = l[i];
            if (in_str) {
                if (c == '\\')
                    i++;
                else if (c == '"')
                    in_str = 0;
            } else if (c == '"') {
                in_str = 1;
            } else if (c == '[' || c == '{') {
                depth++;
            } else if (c == ']' || c == '}') {
                if (depth-- == 0)
                    break;
            } else if (c == ',' && depth == 0) {
                break;
            }
        }
        int hide = 0;
        for (size_t s = 0; s < sizeof skip / sizeof skip[0]; s++)
            hide |= k1 - k0 == strlen(skip[s]) && memcmp(l + k0, skip[s], k1 - k0) == 0;
        if (!hide) {
            fputs(first ? "" : "; ", f);
            first = 0;
            fprintf(f, "<b>");
            esc(f, l + k0, k1 - k0);
            fprintf(f, "</b> ");
            const char *v = l + v0;
            size_t vl = i - v0;
            if (vl >= 2 && v[0] == '"')
                v++, vl -= 2;
            esc(f, v, vl > 300 ? 300 : vl);
            if (vl > 300)
                fputs("...", f);
        }
    }
}

typedef struct run_info {
    size_t header, end, seal; /* line indexes (0: none) */
} run_info;

int audit_report(const char *path, const char *out, const audit_keys *keys)
{
    static fbrl_audit_verifier v;
    static char a[FIELD_MAX], b[FIELD_MAX], c[FIELD_MAX], d[FIELD_MAX];
    unsigned char (*hashes)[FBRL_AUDIT_HASH_SIZE] = NULL;
    audit_text t;
    FILE *f;
    fbrl_status st = audit_verify(path, keys, &v, &hashes);
    free(hashes);
    if (st != FBRL_OK && st != FBRL_ECHECKSUM) {
        fprintf(stderr, "fbrl-audit: %s: %s\n", path, fbrl_status_str(st));
        return AUDIT_EXIT_BROKEN;
    }
    if (audit_text_read(path, &t) != 0) {
        fprintf(stderr, "fbrl-audit: %s: cannot be read\n", path);
        return AUDIT_EXIT_BROKEN;
    }
    f = out ? fopen(out, "w") : stdout;
    if (f == NULL) {
        fprintf(stderr, "fbrl-audit: %s: cannot be written\n", out);
        audit_text_free(&t);
        return AUDIT_EXIT_USAGE;
    }
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>Audit report: ");
    esc_s(f, path);
    fprintf(f, "</title>\n<style>\nbody{font-family:sans-serif;margin:1.5em;color:#222}"
               "table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{border:1px solid #bbb;padding:.25em .5em;"
               "vertical-align:top;text-align:left;font-size:90%%}th{background:#eee}.ok{color:#060}.bad{color:#b00;"
               "font-weight:bold}.muted{color:#777}code{font-size:85%%}\n</style></head><body>\n<h1>Audit report</h1>\n"
               "<p>File <code>");
    esc_s(f, path);
    fprintf(f, "</code>: %llu records. ", (unsigned long long)v.records);
    if (st == FBRL_ECHECKSUM) {
        fprintf(f, "<span class=\"bad\">BROKEN: ");
        esc_s(f, v.where);
        fprintf(f, ". Records from there on are not trustworthy.</span>");
    } else {
        fprintf(f, "<span class=\"ok\">Intact%s</span>; %lu signature%s verified with the public keys of ",
                v.sealed ? " and sealed" : " (not sealed: a run open or its end lost)", v.signatures,
                v.signatures == 1 ? "" : "s");
        esc_s(f, keys->n ? keys->source : "the chain's user records");
        fprintf(f, ".");
    }
    if (v.recoveries) {
        fprintf(f, " <span class=\"bad\">%lu recorded recover%s: ", v.recoveries, v.recoveries == 1 ? "y" : "ies");
        esc_s(f, v.recovered);
        fprintf(f, "</span>");
    }
    fprintf(f, "</p>\n<p class=\"muted\">Checked by fbrl-audit: every record's SHA-256, the order of the records, the "
               "head file, and each signature with Ed25519. Times are UTC.</p>\n");

    /* the runs */
    fprintf(f, "<h2>Runs</h2>\n<table><tr><th>#</th><th>method</th><th>version</th><th>operator</th><th>started "
               "(UTC)</th><th>outcome</th><th>samples</th><th>counts</th><th>reviewed</th></tr>\n");
    size_t nrun = 0;
    for (size_t i = 0; i < t.nlines; i++) {
        const char *l = t.buf + t.start[i];
        size_t n = t.start[i + 1] - t.start[i];
        n -= n > 0 && l[n - 1] == '\n';
        if (strcmp(str(l, n, "type", a), "header") != 0)
            continue;
        run_info r = {i + 1, 0, 0};
        for (size_t j = i + 1; j < t.nlines; j++) {
            const char *m = t.buf + t.start[j];
            size_t mn = t.start[j + 1] - t.start[j] - 1;
            str(m, mn, "type", a);
            if (strcmp(a, "summary") == 0)
                r.end = j + 1;
            if (strcmp(a, "seal") == 0 || strcmp(a, "header") == 0) {
                r.seal = strcmp(a, "seal") == 0 ? j + 1 : 0;
                break;
            }
        }
        fprintf(f, "<tr><td>%zu</td><td>", ++nrun);
        esc_s(f, str(l, n, "method", a));
        fprintf(f, "<br><span class=\"muted\">");
        esc_s(f, str(l, n, "source", a));
        fprintf(f, "</span></td><td>");
        if (i > 0) { /* the run's method_run record, just before its header: version and state */
            const char *p = t.buf + t.start[i - 1];
            size_t pn = t.start[i] - t.start[i - 1] - 1;
            if (strcmp(str(p, pn, "type", b), "method_run") == 0) {
                fprintf(f, "<code>");
                esc(f, str(p, pn, "version", a), 12);
                fprintf(f, "</code> ");
                esc_s(f, str(p, pn, "state", a));
                if (strcmp(str(p, pn, "drafts_allowed", c), "1") == 0)
                    fprintf(f, " (Drafts allowed)");
            }
        }
        fprintf(f, "</td><td>");
        esc_s(f, str(l, n, "user", a));
        fprintf(f, "</td><td>");
        esc_s(f, str(l, n, "utc", a));
        fprintf(f, "</td>");
        if (r.end) {
            const char *m = t.buf + t.start[r.end - 1];
            size_t mn = t.start[r.end] - t.start[r.end - 1] - 1;
            str(m, mn, "outcome", a);
            fprintf(f, "<td class=\"%s\">", strcmp(a, "completed") == 0 ? "ok" : "bad");
            esc_s(f, a);
            fprintf(f, "</td><td>");
            esc_s(f, str(m, mn, "samples", b));
            fprintf(f, "</td><td>%s commands, %s refused, %s errors, %s ms</td>", str(m, mn, "commands", a),
                    str(m, mn, "refused", b), str(m, mn, "errors", c), str(m, mn, "elapsed_ms", d));
        } else {
            fprintf(f, "<td class=\"bad\">no summary (the run did not end)</td><td></td><td></td>");
        }
        fprintf(f, "<td>");
        /* signatures of the run's records: its seal or summary */
        for (size_t j = 0; j < t.nlines; j++) {
            const char *m = t.buf + t.start[j];
            size_t mn = t.start[j + 1] - t.start[j] - 1;
            long long signs;
            if (strcmp(str(m, mn, "type", a), "signature") != 0 ||
                fbrl_audit_field_num(m, mn, "signs", &signs) != FBRL_OK ||
                ((size_t)signs != r.seal && (size_t)signs != r.end))
                continue;
            esc_s(f, str(m, mn, "meaning", a));
            fprintf(f, " by ");
            esc_s(f, str(m, mn, "user", a));
            fprintf(f, " at ");
            esc_s(f, str(m, mn, "utc", a));
            fprintf(f, "<br>");
        }
        fprintf(f, "%s</td></tr>\n", r.seal ? "" : "<span class=\"bad\">not sealed</span>");
    }
    fprintf(f, "</table>\n%s", nrun ? "" : "<p>No runs.</p>\n");

    /* everything but the runs' own records */
    fprintf(f, "<h2>Actions, sign-ins, users, methods, settings, signatures</h2>\n<table><tr><th>record</th><th>time "
               "(UTC)</th><th>user</th><th>what</th><th>details</th></tr>\n");
    static const char *const run_types[] = {"header", "step_start", "step_end", "command", "device", "wait", "text",
                                            "note", "error", "summary", "poll", "method_run"};
    int in_run = 0;
    for (size_t i = 0; i < t.nlines; i++) {
        const char *l = t.buf + t.start[i];
        size_t n = t.start[i + 1] - t.start[i];
        int runrec = 0;
        n -= n > 0 && l[n - 1] == '\n';
        str(l, n, "type", a);
        for (size_t k = 0; k < sizeof run_types / sizeof run_types[0]; k++)
            runrec |= strcmp(a, run_types[k]) == 0;
        if (strcmp(a, "header") == 0)
            in_run = 1;
        if (strcmp(a, "seal") == 0)
            in_run = 0;
        if (runrec || (in_run && strcmp(a, "signature") != 0 && strcmp(a, "login") != 0 && strcmp(a, "action") != 0))
            continue;
        fprintf(f, "<tr><td>%s</td><td>", str(l, n, "seq", b));
        esc_s(f, str(l, n, "utc", b));
        fprintf(f, "</td><td>");
        esc_s(f, str(l, n, "user", b));
        fprintf(f, "</td><td%s>", strcmp(a, "recovery") == 0 || strcmp(str(l, n, "outcome", c), "wrong password") == 0 ||
                                          strcmp(c, "locked") == 0
                                      ? " class=\"bad\""
                                      : "");
        esc_s(f, a);
        fprintf(f, "</td><td>");
        members(f, l, n);
        fprintf(f, "</td></tr>\n");
    }
    fprintf(f, "</table>\n</body></html>\n");
    if (out)
        fclose(f);
    audit_text_free(&t);
    return st == FBRL_OK ? AUDIT_EXIT_OK : AUDIT_EXIT_BROKEN;
}
