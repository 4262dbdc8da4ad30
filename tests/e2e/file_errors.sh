#!/bin/sh
# SPDX-License-Identifier: MIT
# file_errors.sh FBRLMON WORKDIR - errors that say what happened (issue 28 item 5): saving
# and loading a workspace (the library's data files), INCLUDE, and the FILE words, where the
# operating system refuses: each is named, none is "input/output error", and nothing is lost.
#   - a loop of symbolic links; saving through a symlink updates its target (the link stays);
#   - a read-only file (mode a-w) and a read-only file system;
#   - permission denied (run as nobody when the test runs as root);
#   - a full disk: a 16 KB tmpfs filled up (mounted when the test may; else a file size
#     limit, ulimit -f, which the kernel reports as EFBIG; FBRL_TEST_NO_MOUNT=1 chooses it).
mon=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 2
chmod 755 "$work"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
mounted=""
trap 'for m in $mounted; do umount "$m" 2>/dev/null; done' EXIT
echo 'CREATE-LOC P 1E0 2E0 3E0 0E0 0E0 0E0 P DEFINE-LOC' >mk.fbrl
run() { "$mon" --offline mk.fbrl "$@" </dev/null >run.out 2>run.err; }
said() { grep -q -- "$1" run.err || fail "$2: want '$1': $(cat run.err)"; ! grep -q 'input/output error' run.err || fail "$2 says input/output error"; }

# a loop of symbolic links
ln -s loop2 loop1 && ln -s loop1 loop2
run -e 'SAVE-WORKSPACE loop1'
said "SAVE-WORKSPACE loop1: a loop of symbolic links" "saving through a link loop"
run -e 'LOAD-WORKSPACE loop1'
said "LOAD-WORKSPACE loop1: a loop of symbolic links" "loading through a link loop"

# through a symlink: the target is written, the link stays a link (also a link to a file
# not made yet, and a chain of two)
run -e 'SAVE-WORKSPACE real.ws' && ln -s real.ws link.ws && ln -s link.ws chain.ws
run -e '5E0 P SETX SAVE-WORKSPACE chain.ws' || fail "saving through a chain of links: $(cat run.err)"
[ -L link.ws ] && [ -L chain.ws ] && [ -f real.ws ] && [ ! -L real.ws ] || fail "a link was replaced: $(ls -l)"
run -e 'LOAD-WORKSPACE real.ws P GETX F.'
grep -q '^5\. ' run.out || fail "the link's target was not updated: $(cat run.out run.err)"
ln -s made-later.ws dangling.ws
run -e 'SAVE-WORKSPACE dangling.ws' || fail "saving through a link to a new file: $(cat run.err)"
[ -L dangling.ws ] && [ -f made-later.ws ] || fail "a link to a new file: $(ls -l)"
[ -z "$(ls -A | grep '\.tmp$')" ] || fail "temporaries left: $(ls -A)"

# a read-only file: not replaced behind its owner's back
cp real.ws ro.ws && chmod 444 ro.ws
run -e 'SAVE-WORKSPACE ro.ws'
said "SAVE-WORKSPACE ro.ws: read-only file or file system" "saving over a read-only file"
cmp -s real.ws ro.ws || fail "the read-only file changed"

# permission denied: a directory the user may not write, a file the user may not read
as_user() { if [ "$(id -u)" = 0 ]; then setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; else "$@"; fi; }
if [ "$(id -u)" != 0 ] || command -v setpriv >/dev/null 2>&1; then
    mkdir closed && chmod 555 closed && cp real.ws secret.ws && chmod 600 secret.ws
    [ "$(id -u)" = 0 ] && chmod 644 mk.fbrl
    as_user "$mon" --offline mk.fbrl -e 'SAVE-WORKSPACE closed/x.ws' </dev/null >run.out 2>run.err
    said "SAVE-WORKSPACE closed/x.ws: permission denied" "saving into a directory without write permission"
    [ "$(id -u)" = 0 ] || chmod 000 secret.ws
    as_user "$mon" --offline -e 'LOAD-WORKSPACE secret.ws' -e 'INCLUDE secret.ws' </dev/null >run.out 2>run.err
    said "LOAD-WORKSPACE secret.ws: permission denied" "loading an unreadable file"
    said "cannot open secret.ws: permission denied" "INCLUDE of an unreadable file"
else
    echo "permission: running as root without setpriv: not checked"
fi

# a full disk, and a read-only file system: a tmpfs when one can be mounted
disk=""
mkdir -p disk
if [ -z "${FBRL_TEST_NO_MOUNT:-}" ] && mount -t tmpfs -o size=16k tmpfs "$work/disk" 2>/dev/null; then
    mounted="$work/disk"
    disk=tmpfs
fi
if [ "$disk" = tmpfs ]; then
    run -e 'SAVE-WORKSPACE disk/w.ws' || fail "saving on the empty tmpfs: $(cat run.err)"
    cp disk/w.ws before.ws
    dd if=/dev/zero of=disk/filler bs=1024 count=64 2>/dev/null
    run -e '7E0 P SETX SAVE-WORKSPACE disk/w.ws'
    said "SAVE-WORKSPACE disk/w.ws: no space left on the disk" "saving on a full tmpfs"
    cmp -s before.ws disk/w.ws || fail "the workspace on the full disk changed"
    run -e 'SAVE-WORKSPACE disk/new.ws'
    said "SAVE-WORKSPACE disk/new.ws: no space left on the disk" "a new file on a full tmpfs"
    [ -z "$(ls -A disk | grep -v -e '^filler$' -e '^w\.ws$')" ] || fail "files left on the full disk: $(ls -A disk)"
    rm -f disk/filler
    mount -o remount,ro "$work/disk" 2>/dev/null && {
        run -e 'SAVE-WORKSPACE disk/w.ws'
        said "SAVE-WORKSPACE disk/w.ws: read-only file or file system" "saving on a read-only file system"
    }
    echo "full disk: a 16 KB tmpfs"
else
    # no mount here: a file size limit (RLIMIT_FSIZE) refuses the growth as EFBIG; the
    # messages go through a pipe, which the limit does not cover
    (ulimit -f 0 && exec "$mon" --offline mk.fbrl -e 'SAVE-WORKSPACE limited.ws' </dev/null 2>&1) | cat >run.err
    said "SAVE-WORKSPACE limited.ws: no space left on the disk" "saving past a file size limit"
    [ -z "$(ls -A | grep '\.tmp$')" ] || fail "temporaries left: $(ls -A)"
    echo "full disk: no tmpfs could be mounted; a file size limit (ulimit -f 0) instead"
fi

[ $fails = 0 ] && echo "file_errors: ok" && exit 0
exit 1
