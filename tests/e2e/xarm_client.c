/* SPDX-License-Identifier: MIT */
/* xarm_client.c DEVICE - drives fbrlsim with a client the project did not write: the York
 * University "Xarm" serial code for the CRSPLUS 250 (1992; murray484/MediaMathConveyor,
 * xarmopen.c, compiled unmodified beside this file when FBRL_XARM_DIR names a checkout).
 * It opens the line, then sends each command with its own SerialCommand(): a character
 * every 50 ms and a newline, then reads until it has seen two '>' (the prompt). A read()
 * wrapper (ld --wrap=read) keeps what the client read for each command: the command is in
 * sync when that reply begins with its own echo. A controller that sends anything nobody
 * typed for (a prompt when the port is opened) puts the client one reply behind for good.
 * Prints "in sync N/M"; exits 0 when every reply was the command's own. */
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

/* what xarmopen.c takes from its program (flags.h) */
char *SerialPortName;
int SetTermFlag = 1;
extern int fd; /* xarmopen.c's line */
int conveyor_init(void);
int SerialCommand(char *comm);

static char g_seen[4096];
static size_t g_len;

ssize_t __real_read(int f, void *buf, size_t n);
ssize_t __wrap_read(int f, void *buf, size_t n)
{
    ssize_t r = __real_read(f, buf, n);
    if (r > 0 && f == fd && g_len + (size_t)r < sizeof g_seen) {
        memcpy(g_seen + g_len, buf, (size_t)r);
        g_len += (size_t)r;
    }
    return r;
}

int main(int argc, char **argv)
{
    /* No command's reply holds a 'J' or a '>': the client stops reading at either. */
    static const char *const cmds[] = {"NOHELP",     "SPEED 20",  "HOME",      "READY",
                                       "POINT P1,14,2,8,0,-90,0", "MOVE P1", "FINISH",
                                       "HERE P2",    "OUTPUT 3",  "OUTPUT -3", "V1=5",
                                       "TYPEV V1",   "GAIN 0",    "FREE",      "DIR",
                                       "CLOSE",      "OPEN",      "GRIP 1.5",  "SPEED 30",
                                       "MOVE P2",    "FINISH",    "READY",     "FINISH"};
    size_t n = sizeof cmds / sizeof cmds[0], in_sync = 0;
    if (argc != 2) {
        fprintf(stderr, "usage: xarm_client DEVICE\n");
        return 2;
    }
    SerialPortName = argv[1];
    if (conveyor_init() != 0) {
        fprintf(stderr, "xarm_client: the client could not open %s\n", argv[1]);
        return 2;
    }
    for (size_t i = 0; i < n; i++) {
        char cmd[64];
        snprintf(cmd, sizeof cmd, "%s", cmds[i]);
        g_len = 0;
        SerialCommand(cmd);
        g_seen[g_len] = 0;
        int ok = strncmp(g_seen, cmds[i], strlen(cmds[i])) == 0;
        in_sync += ok;
        printf("%-26s %s  read: ", cmds[i], ok ? "in sync" : "BEHIND ");
        for (size_t k = 0; k < g_len && k < 40; k++)
            putchar(g_seen[k] >= ' ' && g_seen[k] < 127 ? g_seen[k] : '.');
        putchar('\n');
    }
    printf("in sync %zu/%zu\n", in_sync, n);
    return in_sync == n ? 0 : 1;
}
