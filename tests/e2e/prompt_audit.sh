#!/bin/sh
# SPDX-License-Identifier: MIT
# prompt_audit.sh FBRLMON FBRLSIM FBRL-AUDIT WORKDIR
#
# Issue 30: an action at fbrlmon's prompt that changes state (a place defined, a parameter
# set) is a record of the audit trail, by the operator's name, and the session ends with a
# seal: typed at a real terminal (tmux) with --run-log, the chain then verifies as intact and
# sealed (fbrl-audit, not the writer, is the judge), and holds each typed line in order.
mon=$1 sim=$2 audit=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
name=prompt-audit
. "$here/tmux_session.sh"
tmux -L "$sock" new-session -d -s said -x 100 -y 30 \
    "'$mon' --port '$work/robot' --run-log '$work/trail.jsonl' --operator ann; echo fbrlmon-exit=\$?; sleep 600"
wait_for "BYE or Ctrl-D ends" || exit 1
type_line "CREATE-LOC SPOT 14E0 2E0 8E0 0E0 -90E0 0E0 SPOT DEFINE-LOC" || exit 1
type_line "HOME 7 SPEED" || exit 1
tmux -L "$sock" send-keys -t said -l -- "BYE"
tmux -L "$sock" send-keys -t said Enter
wait_for "fbrlmon-exit=0" || exit 1
out=$("$audit" verify trail.jsonl)
echo "$out" | grep -q "trail.jsonl: 4 records, intact, sealed" || fail "fbrl-audit verify: $out"
python3 - <<'PY' || fail "the typed lines are not the trail's records"
import json
recs = [json.loads(l) for l in open("trail.jsonl")]
typed = [(r["user"], r["what"]) for r in recs if r.get("type") == "action" and r.get("action") == "forth"]
assert typed == [("ann", "CREATE-LOC SPOT 14E0 2E0 8E0 0E0 -90E0 0E0 SPOT DEFINE-LOC"),
                 ("ann", "HOME 7 SPEED"), ("ann", "BYE")], typed
assert recs[-1]["type"] == "seal", recs[-1]
PY
[ $fails -eq 0 ] && echo "prompt_audit: all checks passed"
exit $((fails > 0))
