/* SPDX-License-Identifier: MIT */
/* fuzz_replay.c - runs files (a seed corpus, crash reproducers) through the fuzz
 * entry point without libFuzzer, so the normal (gcc, ASan) build always tests it.
 *
 *   fuzz_replay FILE_OR_DIR...      exit 0 when every input ran; 1 if none was read
 *
 * An input that runs longer than REPLAY_INPUT_SECONDS is a hang: the replay
 * names it and fails at once instead of waiting for ctest's timeout. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#define REPLAY_INPUT_SECONDS 60

static const char *volatile current;

static void on_alarm(int sig)
{
    const char *msg = "fuzz_replay: input runs too long (a hang): ";
    const char *p = current;
    (void)sig;
    if (write(STDERR_FILENO, msg, strlen(msg)) < 0 || (p && write(STDERR_FILENO, p, strlen(p)) < 0) ||
        write(STDERR_FILENO, "\n", 1) < 0)
        _exit(1);
    _exit(1);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    long n;
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "fuzz_replay: cannot read %s\n", path);
        if (f != NULL)
            fclose(f);
        return -1;
    }
    /* A separate allocation of exactly n bytes lets ASan catch reads past the end. */
    buf = malloc(n > 0 ? (size_t)n : 1);
    if (buf == NULL || fread(buf, 1, (size_t)n, f) != (size_t)n) {
        fprintf(stderr, "fuzz_replay: cannot read %s\n", path);
        free(buf);
        fclose(f);
        return -1;
    }
    fclose(f);
    current = path;
    alarm(REPLAY_INPUT_SECONDS);
    LLVMFuzzerTestOneInput(buf, (size_t)n);
    alarm(0);
    free(buf);
    return 0;
}

static int run_path(const char *path, unsigned *count)
{
    struct stat st;
    DIR *d;
    struct dirent *e;
    int rc = 0;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "fuzz_replay: no such file %s\n", path);
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        if (run_file(path) != 0)
            return -1;
        ++*count;
        return 0;
    }
    d = opendir(path);
    if (d == NULL)
        return -1;
    while ((e = readdir(d)) != NULL) {
        char sub[4096];
        if (e->d_name[0] == '.')
            continue;
        snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
        if (run_path(sub, count) != 0)
            rc = -1;
    }
    closedir(d);
    return rc;
}

int main(int argc, char **argv)
{
    unsigned count = 0;
    int i, rc = 0;
    signal(SIGALRM, on_alarm);
    for (i = 1; i < argc; i++)
        if (run_path(argv[i], &count) != 0)
            rc = 1;
    printf("fuzz_replay: %u inputs\n", count);
    return rc != 0 || count == 0;
}
