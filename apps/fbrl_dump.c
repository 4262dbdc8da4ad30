/* SPDX-License-Identifier: MIT */
/* fbrl_dump.c - fbrl-dump: a typed data file or a workspace as JSON or CSV.
 *
 *   fbrl-dump [--format json|csv] FILE
 *
 * The file is opened with the library (fbrl_file_open: the whole file is verified first,
 * so a damaged file prints nothing but the reason). Every record comes out with its type;
 * a workspace's records (user records tagged WH, WL ...) come out as named objects with
 * named numbers. The output formats are described in docs/files.md ("Reading the files
 * from other languages"). */
#include <errno.h>
#include <getopt.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fbrl/fileio.h"
#include "fbrl/version.h"
#include "fbrl/workspace.h"

enum { EXIT_BAD_FILE = 1, EXIT_USAGE = 2 };
enum { FORMAT_JSON, FORMAT_CSV };

#define NAME_MAX_LEN 255 /* a workspace name's length is one byte */
#define VALUES_MAX   18  /* the most numbers a workspace record holds (CREATE-CAL) */
#define DOUBLE_BYTES 8

/* A workspace record kind: its tag, what it is, its numbers' names in file order. */
typedef struct ws_kind {
    uint16_t tag;
    const char *kind;
    size_t n;
    const char *const *fields;
} ws_kind;

static const char *const f_head[] = {"version"};
static const char *const f_loc[] = {"x", "y", "z", "o", "a", "t"};
static const char *const f_rect[] = {"base_x", "base_y", "base_z", "base_o", "base_a",
                                     "base_t", "dx",     "dy",     "dz"};
static const char *const f_rad[] = {"base_x", "base_y",    "base_z",    "base_o", "base_a",
                                    "base_t", "inc_angle", "ring_dist", "z_off"};
static const char *const f_cal[] = {"p1_x", "p1_y", "p1_z", "p1_o", "p1_a", "p1_t", "p2_x", "p2_y", "p2_z",
                                    "p2_o", "p2_a", "p2_t", "p3_x", "p3_y", "p3_z", "p3_o", "p3_a", "p3_t"};
static const char *const f_stru[] = {"r11", "r12", "r13", "r21", "r22", "r23",
                                     "r31", "r32", "r33", "tx",  "ty",  "tz"};
static const char *const f_dev[] = {"port", "output", "pulse_ms"};
static const char *const f_set[] = {"map_on", "base_dx", "base_dy", "base_dz", "base_do"};

#define KIND(tag, kind, f)                   \
    {                                        \
        tag, kind, sizeof f / sizeof f[0], f \
    }
static const ws_kind ws_kinds[] = {
    KIND(FBRL_WORKSPACE_TAG_HEAD, "header", f_head),     KIND(FBRL_WORKSPACE_TAG_LOC, "location", f_loc),
    KIND(FBRL_WORKSPACE_TAG_RECTMAT, "rectmat", f_rect), KIND(FBRL_WORKSPACE_TAG_RADMAT, "radmat", f_rad),
    KIND(FBRL_WORKSPACE_TAG_CAL, "calibration", f_cal),  KIND(FBRL_WORKSPACE_TAG_CALSTRU, "calstru", f_stru),
    KIND(FBRL_WORKSPACE_TAG_DEVICE, "device", f_dev),    KIND(FBRL_WORKSPACE_TAG_SET, "settings", f_set),
};

#define WORKSPACE_NAME "FBRL-WORKSPACE" /* the header record's name */

/* One record as read. */
typedef struct record {
    uint32_t index;
    fbrl_ftype type;
    unsigned char *bytes; /* the payload as the file holds it (type.size bytes) */
    double num;           /* CHR, INTEGER, LONG, REAL */
    fbrl_loc loc;         /* LOCATION */
    /* a workspace record, decoded */
    const ws_kind *ws;
    char name[NAME_MAX_LEN + 1];
    double v[VALUES_MAX];
} record;

static const char *type_name(fbrl_ftype_code c)
{
    switch (c) {
    case FBRL_FT_CHR: return "CHR";
    case FBRL_FT_INTEGER: return "INTEGER";
    case FBRL_FT_LONG: return "LONG";
    case FBRL_FT_REAL: return "REAL";
    case FBRL_FT_LOCATION: return "LOCATION";
    default: return "USER";
    }
}

/* A little-endian IEEE-754 double from 8 bytes (docs/workspace.md). */
static double le_double(const unsigned char *b)
{
    uint64_t bits = 0;
    double d;
    for (int i = DOUBLE_BYTES - 1; i >= 0; i--)
        bits = bits << 8 | b[i];
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* Decodes a user record as a workspace record of its tag; 0 if it is not one. */
static int ws_decode(record *r)
{
    size_t k;
    const unsigned char *b = r->bytes;
    for (k = 0; k < sizeof ws_kinds / sizeof ws_kinds[0]; k++)
        if (ws_kinds[k].tag == r->type.tag)
            break;
    if (r->type.code != FBRL_FT_USER || k == sizeof ws_kinds / sizeof ws_kinds[0] || r->type.size < 1 ||
        r->type.size != 1u + b[0] + DOUBLE_BYTES * ws_kinds[k].n)
        return 0;
    r->ws = &ws_kinds[k];
    memcpy(r->name, b + 1, b[0]);
    r->name[b[0]] = 0;
    for (size_t i = 0; i < r->ws->n; i++)
        r->v[i] = le_double(b + 1 + b[0] + DOUBLE_BYTES * i);
    return 1;
}

/* ---- output ---- */

static void json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20 || c >= 0x7f)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

static void csv_string(const char *s)
{
    if (strpbrk(s, ",\"\r\n") == NULL) {
        fputs(s, stdout);
        return;
    }
    putchar('"');
    for (; *s; s++) {
        if (*s == '"')
            putchar('"');
        putchar(*s);
    }
    putchar('"');
}

/* %.17g: every double reads back to the same bits. */
static void number(double d) { printf("%.17g", d); }

static void hex(const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        printf("%02x", b[i]);
}

static void json_record(const record *r, int first)
{
    printf("%s\n    {\"index\": %lu, \"type\": \"%s\"", first ? "" : ",", (unsigned long)r->index,
           type_name(r->type.code));
    if (r->type.code == FBRL_FT_LOCATION) {
        printf(", \"value\": {");
        for (int i = 0; i < 6; i++) {
            double v[6] = {r->loc.x, r->loc.y, r->loc.z, r->loc.o, r->loc.a, r->loc.t};
            printf("%s\"%s\": ", i ? ", " : "", f_loc[i]);
            number(v[i]);
        }
        printf("}}");
        return;
    }
    if (r->type.code != FBRL_FT_USER) {
        printf(", \"value\": ");
        number(r->num);
        putchar('}');
        return;
    }
    printf(", \"tag\": %u, \"size\": %lu", (unsigned)r->type.tag, (unsigned long)r->type.size);
    if (r->ws) {
        printf(", \"kind\": \"%s\", \"name\": ", r->ws->kind);
        json_string(r->name);
        printf(", \"values\": {");
        for (size_t i = 0; i < r->ws->n; i++) {
            printf("%s\"%s\": ", i ? ", " : "", r->ws->fields[i]);
            number(r->v[i]);
        }
        putchar('}');
    } else {
        printf(", \"hex\": \"");
        hex(r->bytes, r->type.size);
        putchar('"');
    }
    putchar('}');
}

/* One CSV row: index,type,tag,kind,name,field,value */
static void csv_row(const record *r, const char *field, double v, int is_hex)
{
    printf("%lu,%s,%u,%s,", (unsigned long)r->index, type_name(r->type.code), (unsigned)r->type.tag,
           r->ws ? r->ws->kind : "");
    csv_string(r->ws ? r->name : "");
    printf(",%s,", field);
    if (is_hex)
        hex(r->bytes, r->type.size);
    else
        number(v);
    printf("\r\n");
}

static void csv_record(const record *r)
{
    if (r->type.code == FBRL_FT_LOCATION) {
        double v[6] = {r->loc.x, r->loc.y, r->loc.z, r->loc.o, r->loc.a, r->loc.t};
        for (int i = 0; i < 6; i++)
            csv_row(r, f_loc[i], v[i], 0);
    } else if (r->type.code != FBRL_FT_USER) {
        csv_row(r, "value", r->num, 0);
    } else if (r->ws) {
        for (size_t i = 0; i < r->ws->n; i++)
            csv_row(r, r->ws->fields[i], r->v[i], 0);
    } else {
        csv_row(r, "hex", 0.0, 1);
    }
}

/* ---- reading ---- */

static int fail(const char *path, fbrl_status st)
{
    fprintf(stderr, "fbrl-dump: %s: %s\n", path, fbrl_status_str(st));
    return EXIT_BAD_FILE;
}

/* Reads the record at the file's position (its type known) into r. */
static fbrl_status read_record(fbrl_file *f, record *r)
{
    union {
        unsigned char c;
        int16_t i16;
        int32_t i32;
        double d;
    } u;
    fbrl_status st;
    switch (r->type.code) {
    case FBRL_FT_CHR:
    case FBRL_FT_INTEGER:
    case FBRL_FT_LONG:
    case FBRL_FT_REAL:
        st = fbrl_file_read(f, r->type, &u);
        r->num = r->type.code == FBRL_FT_CHR       ? u.c
                 : r->type.code == FBRL_FT_INTEGER ? u.i16
                 : r->type.code == FBRL_FT_LONG    ? u.i32
                                                   : u.d;
        return st;
    case FBRL_FT_LOCATION: return fbrl_file_read(f, r->type, &r->loc);
    default:
        st = fbrl_file_read(f, r->type, r->bytes);
        if (st == FBRL_OK)
            ws_decode(r);
        return st;
    }
}

static int dump(const char *path, int format)
{
    static fbrl_file f;
    struct stat sb;
    unsigned char *buf, *payload;
    size_t cap;
    record r;
    fbrl_status st;
    uint32_t count = 0;
    int workspace = 0, rc = 0;

    if (stat(path, &sb) != 0)
        return fail(path, errno == ENOENT ? FBRL_ENOENT : FBRL_EIO);
    cap = sb.st_size > 0 ? (size_t)sb.st_size : 1; /* the records are never larger than the file */
    buf = malloc(cap);
    payload = malloc(cap);
    if (buf == NULL || payload == NULL) {
        free(buf);
        free(payload);
        return fail(path, FBRL_ENOSPC);
    }
    st = fbrl_file_open(&f, path, buf, cap);
    if (st != FBRL_OK) {
        free(buf);
        free(payload);
        return fail(path, st);
    }
    fbrl_file_tell(&f, NULL, &count);
    /* a workspace starts with its header record */
    memset(&r, 0, sizeof r);
    r.bytes = payload;
    if (fbrl_file_peek(&f, &r.type) == FBRL_OK && r.type.code == FBRL_FT_USER &&
        r.type.tag == FBRL_WORKSPACE_TAG_HEAD && read_record(&f, &r) == FBRL_OK && r.ws &&
        strcmp(r.name, WORKSPACE_NAME) == 0)
        workspace = 1;
    fbrl_file_reset(&f);

    if (format == FORMAT_JSON)
        printf("{\n  \"format\": \"%s\",\n  \"file_version\": %u,\n  \"count\": %lu,\n  \"records\": [",
               workspace ? "fbrl-workspace" : "fbrl-data", FBRL_FILE_VERSION, (unsigned long)count);
    else
        printf("index,type,tag,kind,name,field,value\r\n");
    for (uint32_t i = 0; i < count; i++) {
        memset(&r, 0, sizeof r);
        r.bytes = payload;
        r.index = i;
        st = fbrl_file_peek(&f, &r.type);
        if (st == FBRL_OK)
            st = read_record(&f, &r);
        if (st != FBRL_OK) { /* cannot happen after open's checks: say so rather than stop silently */
            rc = fail(path, st);
            break;
        }
        if (format == FORMAT_JSON)
            json_record(&r, i == 0);
        else
            csv_record(&r);
    }
    if (format == FORMAT_JSON)
        printf("%s]\n}\n", count ? "\n  " : "");
    fbrl_file_discard(&f);
    free(buf);
    free(payload);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "fbrl-dump: writing the output failed\n");
        return EXIT_BAD_FILE;
    }
    return rc;
}

static void usage(FILE *out)
{
    fputs("usage: fbrl-dump [options] FILE\n"
          "Print a typed data file (CREATE-FILE, fbrl_file_*) or a workspace\n"
          "(SAVE-WORKSPACE) as JSON (default) or CSV: every record with its type; a\n"
          "workspace's objects with their names and named numbers (docs/files.md).\n"
          "\n"
          "options:\n"
          "  -f, --format F   json (default) or csv\n"
          "  -h, --help       show this help and exit\n"
          "  -V, --version    show the version and exit\n"
          "\n"
          "exit status: 0 printed, 1 the file cannot be read (damaged, not a data file),\n"
          "             2 bad command line\n",
          out);
}

int main(int argc, char **argv)
{
    static const struct option longs[] = {{"format", required_argument, NULL, 'f'},
                                          {"help", no_argument, NULL, 'h'},
                                          {"version", no_argument, NULL, 'V'},
                                          {NULL, 0, NULL, 0}};
    int c, format = FORMAT_JSON;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":f:hV", longs, NULL)) != -1) {
        switch (c) {
        case 'f':
            if (strcmp(optarg, "json") == 0) {
                format = FORMAT_JSON;
            } else if (strcmp(optarg, "csv") == 0) {
                format = FORMAT_CSV;
            } else {
                fprintf(stderr, "fbrl-dump: --format: json or csv, not '%s'\n", optarg);
                return EXIT_USAGE;
            }
            break;
        case 'h': usage(stdout); return 0;
        case 'V': printf("fbrl-dump (libfbrl) %s\n", fbrl_version()); return 0;
        case ':': fprintf(stderr, "fbrl-dump: %s needs an argument\n", argv[optind - 1]); return EXIT_USAGE;
        default: fprintf(stderr, "fbrl-dump: unknown option '%s'\n", argv[optind - 1]); return EXIT_USAGE;
        }
    }
    if (optind != argc - 1) {
        usage(stderr);
        return EXIT_USAGE;
    }
    return dump(argv[optind], format);
}
