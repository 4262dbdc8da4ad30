/* SPDX-License-Identifier: MIT */
/* link_e2e_fair: one thread drives 16 robots (16 fbrlsim processes at 9600 baud) through
 * fbrl_link_poll_many() and every robot gets its share: each completes at least half of
 * the mean number of commands (the old scan from link 0 left most of them at 0), and each
 * emulator's --log holds exactly the commands its link reported as done. Counts, not
 * speed: the rates are in bench_transport. Usage: link_e2e_fair FBRLSIM */
#include "rapl_harness.h"

#define ROBOTS    16
#define PER_ROBOT 40 /* mean commands per robot before the run stops */
#define CMD       "SPEED 50"

static rig rigs[ROBOTS];
static char logs[ROBOTS][160];

/* Lines "SPEED 50" in an emulator's log. */
static long count_in_log(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[256];
    long n = 0;
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f))
        n += strncmp(line, CMD, strlen(CMD)) == 0 && (line[strlen(CMD)] == '\n' || line[strlen(CMD)] == '\0');
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return 2;
    char dir[64];
    rig_tmpdir(dir, sizeof dir, "fair");
    if (!dir[0])
        return 1;
    fbrl_link_config cfg;
    fbrl_link_config_init(&cfg);
    fbrl_link *links[ROBOTS];
    for (int k = 0; k < ROBOTS; k++) {
        snprintf(logs[k], sizeof logs[k], "%s/log%d", dir, k);
        const char *args[] = {"--baud", "9600", "--log", logs[k], NULL};
        if (rig_start(&rigs[k], argv[1], args, 9600, FBRL_FLOW_NONE, &cfg) != 0 ||
            fbrl_link_connect(&rigs[k].link) != FBRL_OK) {
            fprintf(stderr, "robot %d: no start\n", k);
            return 1;
        }
        links[k] = &rigs[k].link;
    }
    /* bad input first: too many links */
    size_t idx;
    if (fbrl_link_poll_many(links, FBRL_LINK_POLL_MANY_MAX + 1, 0, &idx) != FBRL_EINVAL) {
        fprintf(stderr, "n > FBRL_LINK_POLL_MANY_MAX accepted\n");
        return 1;
    }
    long done[ROBOTS] = {0}, total = 0;
    int failures = 0;
    for (int k = 0; k < ROBOTS; k++)
        if (fbrl_link_start(links[k], CMD, FBRL_LINK_REPLY_NONE) != FBRL_OK)
            return 1;
    uint64_t end = fbrl_clock_now_us() + 60000000u;
    while (total < (long)ROBOTS * PER_ROBOT && fbrl_clock_now_us() < end) {
        fbrl_status st = fbrl_link_poll_many(links, ROBOTS, 100, &idx);
        if (idx >= ROBOTS)
            continue;
        if (st != FBRL_OK) {
            fprintf(stderr, "robot %zu: %s\n", idx, fbrl_status_name(st));
            failures++;
        } else {
            done[idx]++;
            total++;
        }
        if (total < (long)ROBOTS * PER_ROBOT &&
            fbrl_link_start(links[idx], CMD, FBRL_LINK_REPLY_NONE) != FBRL_OK)
            failures++;
    }
    /* the commands still running finish, so the logs are complete */
    for (;;) {
        fbrl_status st = fbrl_link_poll_many(links, ROBOTS, 2000, &idx);
        if (st == FBRL_EEMPTY || idx >= ROBOTS)
            break;
        if (st == FBRL_OK)
            done[idx]++;
    }
    long min = done[0], max = done[0];
    for (int k = 0; k < ROBOTS; k++) {
        min = done[k] < min ? done[k] : min;
        max = done[k] > max ? done[k] : max;
    }
    for (int k = 0; k < ROBOTS; k++)
        rig_stop(&rigs[k]);
    for (int k = 0; k < ROBOTS; k++) {
        long in_log = count_in_log(logs[k]);
        if (in_log != done[k]) {
            fprintf(stderr, "robot %d: link reported %ld done, the emulator's log holds %ld\n", k, done[k],
                    in_log);
            failures++;
        }
        if (done[k] * 2 < PER_ROBOT) {
            fprintf(stderr, "robot %d starved: %ld commands of a mean of %d\n", k, done[k], PER_ROBOT);
            failures++;
        }
        remove(logs[k]);
    }
    rmdir(dir);
    printf("%d robots from one thread: %ld commands, per robot %ld..%ld, %s\n", ROBOTS, total, min, max,
           failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
