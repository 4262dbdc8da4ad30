#!/bin/sh
# SPDX-License-Identifier: MIT
# runlog_full.sh FBRLMON WORKDIR
#
# Issue 28, item 3: every write of the run log is checked. A method run whose run log is on
# a full small tmpfs (16 KB: mounted here as root, or in a user namespace with unshare; where
# neither is allowed, a file-size limit, RLIMIT_FSIZE, makes the writes fail the same way and
# the test says so) ends in a clear error on stderr and a non-zero exit status, and the log
# ends on a whole record (no record cut in the middle). A run log on /dev/full (nothing can be
# written) is refused when the run starts, with the reason. The run log is the audit chain
# (docs/compliance.md): its records are bigger, it starts with method_run, and /dev/full, no
# file a chain can be kept in, is refused as such.
mon=$1 work=$2
rm -rf "$work" && mkdir -p "$work/small" && cd "$work" || exit 2
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# 600 commands (SPEED, not a poll: each its own record, some 60 bytes): far over 16 KB
cat >plan.fbrl <<EOF2
RUN-LOG $work/small/run.jsonl
: FILL ( i -- ) DROP 60 0 DO 50 SPEED LOOP ;
METHOD FILL-LOG  many records
1 20 10 SAMPLES-PARAM N tubes  the samples
' FILL SAMPLE-STEP Fill  sixty commands
END-METHOD
FILL-LOG RUN-METHOD
EOF2
run() { "$mon" --sim plan.fbrl </dev/null >out.txt 2>err.txt; echo $? >status.txt; }
how=
if [ "$(id -u)" = 0 ] && mount -t tmpfs -o size=16k fbrl-test "$work/small" 2>/dev/null; then
    how="a 16 KB tmpfs"
    run
    cp small/run.jsonl run.jsonl
    umount "$work/small"
elif command -v unshare >/dev/null 2>&1 && unshare -rm true 2>/dev/null; then
    how="a 16 KB tmpfs in a user namespace"
    export mon work
    unshare -rm sh -c 'mount -t tmpfs -o size=16k fbrl-test "$work/small" || exit 99
        "$mon" --sim plan.fbrl </dev/null >out.txt 2>err.txt; echo $? >status.txt
        cp "$work/small/run.jsonl" "$work/run.jsonl"'
    [ $? = 99 ] && { echo "SKIP: no tmpfs in a user namespace"; exit 77; }
else
    how="a file-size limit (RLIMIT_FSIZE: no tmpfs can be mounted here)"
    (trap '' XFSZ; ulimit -f 32; run)
fi
echo "the run log on $how"
[ -f run.jsonl ] || cp small/run.jsonl run.jsonl 2>/dev/null
st=$(cat status.txt)
[ "$st" != 0 ] || fail "a run log that could not be written: exit status 0"
grep -Eq "^fbrlmon: error: run log $work/small/run.jsonl: a record was (cut short and taken back|not written): (No space left on device|File too large)$" err.txt ||
    fail "no clear error: $(cat err.txt)"
[ "$(grep -c 'run log' err.txt)" = 1 ] || fail "the error is not told once: $(cat err.txt)"
python3 - <<'PY' || fail "the run log ends in a cut record"
import json
lines = open("run.jsonl", "rb").read().split(b"\n")
assert lines[-1] == b"", lines[-1][:80]  # ends at a line's end
recs = [json.loads(l) for l in lines[:-1]]
assert recs[0]["type"] == "method_run" and recs[1]["type"] == "header" and 20 < len(recs) < 600, len(recs)
print("the log holds %d whole records, %d bytes" % (len(recs), sum(len(l) + 1 for l in lines[:-1])))
PY

# /dev/full: the run does not start, and says why
printf 'RUN-LOG /dev/full\n: STEP1 ( -- ) ;\nMETHOD ONE  one step\n'"' STEP1 STEP S  the step\nEND-METHOD\nONE RUN-METHOD\n" >full.fbrl
"$mon" --sim full.fbrl </dev/null >full.out 2>full.err
st=$?
[ $st = 1 ] || fail "run log on /dev/full: exit status $st, want 1"
grep -q "^fbrlmon: error: /dev/full: the audit trail cannot be opened: not a regular file" full.err ||
    fail "/dev/full: $(cat full.err)"
grep -q "the run could not start" full.err || fail "/dev/full: the run's refusal is not told: $(cat full.err)"
[ $fails -eq 0 ] && echo "runlog_full: all checks passed"
exit $((fails > 0))
