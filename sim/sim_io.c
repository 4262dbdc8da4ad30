/* SPDX-License-Identifier: MIT */
/* sim_io.c - where the line's bytes come from and go to: a pseudo-terminal
 * (with an optional stable symlink) or one TCP client on 127.0.0.1. Pacing and
 * faults are the line's (sim_line.c); this file only opens, accepts and closes. */
#include "sim_internal.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

int sim_io_open_pty(sim_io *io, int greet, char *err, size_t errlen)
{
    struct termios tio;
    io->master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (io->master < 0 || grantpt(io->master) != 0 || unlockpt(io->master) != 0 ||
        ptsname_r(io->master, io->path, sizeof io->path) != 0) {
        sim_seterr(err, errlen, "pseudo-terminal: %s", strerror(errno));
        return -1;
    }
    /* Holding the slave open keeps the master from hanging up between clients. */
    io->slave = open(io->path, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (io->slave < 0 || tcgetattr(io->slave, &tio) != 0) {
        sim_seterr(err, errlen, "%s: %s", io->path, strerror(errno));
        return -1;
    }
    cfmakeraw(&tio);
    tcsetattr(io->slave, TCSANOW, &tio);
    fcntl(io->master, F_SETFL, fcntl(io->master, F_GETFL) | O_NONBLOCK);
    io->fd = io->master;
    /* --greet-pty: a terminal program opening the device is the pty's "connect": the
     * kernel tells us through inotify (our own open above came before the watch). A
     * controller on a serial line cannot see that, so by default nothing is sent. */
    io->ino = greet ? inotify_init1(IN_NONBLOCK | IN_CLOEXEC) : -1;
    if (io->ino >= 0 && inotify_add_watch(io->ino, io->path, IN_OPEN) < 0) {
        close(io->ino);
        io->ino = -1;
    }
    if (io->link_path) {
        struct stat st;
        if (lstat(io->link_path, &st) == 0 && !S_ISLNK(st.st_mode)) {
            sim_seterr(err, errlen, "link %s: exists and is not a symlink", io->link_path);
            free(io->link_path);
            io->link_path = NULL;
            return -1;
        }
        unlink(io->link_path); /* a stale link from an earlier run */
        if (symlink(io->path, io->link_path) != 0) {
            sim_seterr(err, errlen, "link %s: %s", io->link_path, strerror(errno));
            free(io->link_path);
            io->link_path = NULL;
            return -1;
        }
    }
    return 0;
}

int sim_io_open_tcp(sim_io *io, int port, char *err, size_t errlen)
{
    struct sockaddr_in a;
    socklen_t alen = sizeof a;
    int one = 1;
    io->lfd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (io->lfd < 0) {
        sim_seterr(err, errlen, "socket: %s", strerror(errno));
        return -1;
    }
    setsockopt(io->lfd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((unsigned short)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(io->lfd, (struct sockaddr *)&a, sizeof a) != 0 || listen(io->lfd, SIM_LISTEN_BACKLOG) != 0 ||
        getsockname(io->lfd, (struct sockaddr *)&a, &alen) != 0) {
        sim_seterr(err, errlen, "tcp port %d: %s", port, strerror(errno));
        return -1;
    }
    fcntl(io->lfd, F_SETFL, fcntl(io->lfd, F_GETFL) | O_NONBLOCK);
    snprintf(io->path, sizeof io->path, "tcp:127.0.0.1:%d", ntohs(a.sin_port));
    return 0;
}

/* One client at a time, like one serial line. A second one is told so and closed
 * at once: nothing it sent is read, so nothing it typed can ever run (before, it
 * waited in the listen queue and its bytes ran after the first client left). */
static void refuse(int fd)
{
    static const char msg[] = "fbrlsim: the controller is busy: another client is connected\r\n";
    char sink[512];
    ssize_t w = write(fd, msg, sizeof msg - 1);
    (void)w;
    shutdown(fd, SHUT_WR);
    /* Discard what already arrived: closing with unread data would send a reset
     * that can overtake the message. */
    while (read(fd, sink, sizeof sink) > 0)
        ;
    close(fd);
}

int sim_io_accept(sim_io *io)
{
    int fd = accept4(io->lfd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0)
        return 0;
    if (io->conn >= 0) {
        refuse(fd);
        return 0;
    }
    {
        /* The line hands each character over when its last bit is through: Nagle's
         * algorithm would hold small writes back and deliver them in bursts. */
        int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    }
    io->conn = io->fd = fd;
    return 1;
}

/* How many times the pty was opened since the last call. */
int sim_io_pty_opened(sim_io *io)
{
    char buf[sizeof(struct inotify_event) * 16];
    int opens = 0;
    ssize_t n;
    while ((n = read(io->ino, buf, sizeof buf)) > 0) {
        ssize_t off = 0;
        while (off + (ssize_t)sizeof(struct inotify_event) <= n) {
            struct inotify_event e;
            memcpy(&e, buf + off, sizeof e);
            opens += (e.mask & IN_OPEN) != 0;
            off += (ssize_t)sizeof e + (ssize_t)e.len;
        }
    }
    return opens;
}

/* Only a TCP client can go away; a pty stays. */
int sim_io_close_client(sim_io *io)
{
    if (io->conn < 0)
        return 0;
    close(io->conn);
    io->conn = -1;
    io->fd = -1;
    return 1;
}

void sim_io_close(sim_io *io)
{
    if (io->conn >= 0)
        close(io->conn);
    if (io->lfd >= 0)
        close(io->lfd);
    if (io->master >= 0)
        close(io->master);
    if (io->slave >= 0)
        close(io->slave);
    if (io->ino >= 0)
        close(io->ino);
    io->conn = io->lfd = io->master = io->slave = io->fd = io->ino = -1;
    if (io->link_path) {
        char target[sizeof io->path];
        ssize_t n = readlink(io->link_path, target, sizeof target - 1);
        if (n > 0) {
            target[n] = 0;
            if (!strcmp(target, io->path)) /* still ours, not a newer emulator's */
                unlink(io->link_path);
        }
    }
    free(io->link_path);
    io->link_path = NULL;
}

int sim_io_host_ixon(const sim_io *io)
{
    struct termios t;
    if (io->conn >= 0 || io->slave < 0 || tcgetattr(io->slave, &t) != 0)
        return -1;
    return (t.c_iflag & IXON) != 0;
}
