#!/bin/sh
# SPDX-License-Identifier: MIT
# console_audit.sh FBRLMON FBRLSIM WORKDIR SRCDIR
#
# Issue 30 at the console (tmux, a real fbrlsim): a lab with an operator, a method
# developer and a reviewer; SAMPLE-PREP submitted and released with the reviewer's
# signature. The operator ann signs in (a wrong password first), cannot go up a level,
# runs the Released method (a parameter changed, paused, resumed), cannot run a Draft, and
# cannot run the Released method once one character of a file it includes is changed (the
# file is named). The reviewer is locked out by five wrong passwords and then cannot sign.
# A second session signs out by itself when idle. The chain holds each action with the
# name, and verifies intact.
mon=$1 sim=$2 work=$3 src=$4
here=$(cd "$(dirname "$0")" && pwd)
command -v tmux >/dev/null 2>&1 || { echo "SKIP: no tmux"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "SKIP: no python3"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
bin=$(dirname "$mon")
users=$bin/fbrl-users audit=$bin/fbrl-audit
name=console-audit
sim_scale=50
sim_args="--inputs $src/examples/tube_present.inputs"
mkdir -p lib/methods && cp "$src/examples/methods/sample_prep.fbrl" lib/methods/ &&
    cp "$src/examples/asps_cell.fbrl" "$src/examples/asps_cell_objects.fbrl" lib/ || exit 1
cat >lib/methods/draft_one.fbrl <<'EOF2'
: NOTHING ( -- ) ;
METHOD DRAFT-ONE  a method nobody released
' NOTHING STEP Nothing  does nothing
END-METHOD
EOF2
export FBRL_LAB="$work/lab"
printf 'admin pass 1\n' | "$users" setup admin >/dev/null || exit 1
for u in "ann operator ann-pass-1" "dev developer dev-pass-1" "rev reviewer rev-pass-1"; do
    set -- $u
    printf 'admin pass 1\n%s\n' "$3" | "$users" --as admin add "$1" "$2" >/dev/null || exit 1
done
printf "dev-pass-1\n" | "$audit" method submit lib/methods/sample_prep.fbrl --as dev || exit 1
printf "rev-pass-1\n" | "$audit" method release lib/methods/sample_prep.fbrl --as rev || exit 1

. "$here/tmux_session.sh"
start() {
    tmux -L "$sock" new-session -d -s said -x 80 -y 24 \
        "'$mon' --port '$work/robot' --console --methods '$work/lib/methods' --lab '$work/lab' \
         -e '60 CONSTANT TIME-SCALE'; echo fbrlmon-exit=\$?; sleep 600"
}
key() { tmux -L "$sock" send-keys -t said "$@"; }
shot() { tmux -L "$sock" capture-pane -p -t said >"screen-$1.txt"; }
sign_in() { key -l "$1"; key Enter; key -l "$2"; key Enter; }
start
wait_for "sign in: name:" || exit 1
shot sign-in
# nothing but signing in: Enter on the library does not open a method
key Enter
sign_in ann "not-ann-pass"
wait_for "name or password not accepted" || exit 1
sign_in ann "ann-pass-1"
wait_for "signed in: ann (operator)" || exit 1
key F9; key 3
wait_for "ann's role (operator) allows the operator level"
# ---- the Released method (the library's second: DRAFT-ONE sorts first): a parameter
# changed, paused, resumed, to the end
key Down; key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
key -l 1; key Down Down Down; key -l 1
wait_for "REACTION-MIN   [1 "
key F5
wait_long "RUNNING" 10 || exit 1
wait_long "->  3 Reagent" 20
key F6
wait_long "PAUSED" 20 || exit 1
key F7
wait_long "RUNNING" 10
wait_long "DONE" 60 || exit 1
shot released-run
# ---- a Draft: refused for an operator, nothing sent
key F2
wait_for "DRAFT-ONE"
before=$(wc -l <sim.log)
key Up; key Enter
wait_for "Parameters of DRAFT-ONE" || exit 1
key F5
wait_for "is Draft, not Released" || exit 1
shot draft-refused
[ "$(wc -l <sim.log)" = "$before" ] || fail "a refused Draft sent commands"
# ---- one character of a file the Released method includes: refused, the file named
sed -i '0,/ 2\.5E0/s// 2.6E0/' lib/asps_cell.fbrl
cmp -s lib/asps_cell.fbrl "$src/examples/asps_cell.fbrl" && fail "the edit changed nothing"
key F2; key Down; key Enter
wait_for "Parameters of SAMPLE-PREP" || exit 1
key F5
wait_for "SAMPLE-PREP: refused: ../asps_cell.fbrl changed since its release" || exit 1
shot changed-refused
# ---- the reviewer: five wrong passwords lock the account
key F9; key s
wait_for "signed out" || exit 1
for i in 1 2 3 4 5; do sign_in rev "wrong-pass-$i"; sleep 0.6; done
wait_for "rev is locked until" || exit 1
shot locked
key F10
wait_for "fbrlmon-exit=0"
# a locked-out user cannot sign, even with the right password
seal=$(python3 -c "
import json
recs=[json.loads(l) for l in open('lab/audit.jsonl')]
print([r['seq'] for r in recs if r['type']=='seal' and r['seq']>[x['seq'] for x in recs if x['type']=='header'][0]][0])")
out=$(printf "rev-pass-1\n" | "$audit" sign lab/audit.jsonl --as rev --record "$seal" 2>&1) &&
    fail "a locked-out reviewer signed: $out"
echo "$out" | grep -q "rev is locked until" || fail "the refusal does not say the lock: $out"
# ---- a second session, idle: signed out by itself
tmux -L "$sock" kill-session -t said
printf 'admin pass 1\n' | "$users" --as admin set idle_s 2 >/dev/null || exit 1
start
wait_for "sign in: name:" || exit 1
sign_in ann "ann-pass-1"
wait_for "signed in: ann (operator)" || exit 1
wait_long "signed out: the console was idle" 10 || exit 1
shot idle
key F10
wait_for "fbrlmon-exit=0"

# ---- the chain: intact, and each action with its user's name
"$audit" verify lab/audit.jsonl || fail "the chain does not verify"
python3 - lab/audit.jsonl "$work" <<'PY' || fail "the chain lacks an action"
import json, sys
recs = [json.loads(l) for l in open(sys.argv[1])]
def has(user, typ, **kv):
    for r in recs:
        if r["user"] == user and r["type"] == typ and all(k in r and str(v) in str(r[k]) for k, v in kv.items()):
            return r
    sys.exit("no %s record by %s with %s" % (typ, user, kv))
has("ann", "login", purpose="console", outcome="wrong password")
has("ann", "login", purpose="console", outcome="accepted")
has("ann", "action", action="parameter", what="SAMPLE-PREP #SAMPLES", detail="3 -> 1 tubes")
run = has("ann", "method_run", method="SAMPLE-PREP", state="Released", role="operator")
has("ann", "header", method="SAMPLE-PREP", operator="ann")
has("ann", "note", event="pause")
has("ann", "note", event="resume")
has("ann", "summary", outcome="completed")
has("ann", "method_refused", method="DRAFT-ONE", reason="an operator runs only Released methods")
has("ann", "method_refused", method="SAMPLE-PREP", reason="asps_cell.fbrl changed since its release")
has("ann", "action", action="logout", detail="signed out")
locked = [r for r in recs if r["type"] == "login" and r["user"] == "rev" and r["purpose"] == "console"]
assert [r["outcome"] for r in locked][:5] == ["wrong password"] * 5, locked
assert "locked_until" in locked[4] and "locked_until" not in locked[3], locked
has("rev", "login", purpose="signature", outcome="locked")
has("ann", "action", action="logout", detail="idle for 2 s")
assert not [r for r in recs if r["type"] == "signature" and r["user"] == "rev" and r["meaning"] == "run reviewed"]
print("the chain: %d records; every action of the session with its user's name" % len(recs))
PY
[ $fails -eq 0 ] || exit 1
echo "console_audit: passed"
