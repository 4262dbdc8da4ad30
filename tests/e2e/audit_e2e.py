#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Issue 30's "must show" for the audit trail, against real programs:

a lab made with fbrl-users; a complete and an aborted sample-prep run by fbrlmon against a
real fbrlsim (its --log is the controller's truth), written as the chain; a reviewer's
signature; then

- 1,000 random tamperings of that chain (a value edited, a record deleted, two swapped, one
  repeated, the tail cut at a record or inside one, a signature moved to another record by
  a forger who re-hashes everything after it): fbrl-audit verify, offline with only the
  public keys, refuses every one (exit 1) and names the record the edit was made at;
- fbrl-audit replay: both runs reproduce fbrlsim's log byte for byte, and a run whose
  recorded command the controller logs otherwise is reported (the check can fail);
- the review report is one self-contained HTML page naming who ran what, with which outcome.

The forger's hashing is Python's hashlib, not the library.

usage: audit_e2e.py FBRLMON FBRLSIM FBRL_AUDIT FBRL_USERS WORKDIR SRCDIR [SEED]
"""
import hashlib
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

mon, sim, audit, users, work, src = [os.path.abspath(a) for a in sys.argv[1:7]]
seed = int(sys.argv[7]) if len(sys.argv) > 7 else 30
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.chdir(work)
lab = os.path.join(work, "lab")
os.makedirs(lab)
chain = os.path.join(lab, "audit.jsonl")
env = dict(os.environ, FBRL_LAB=lab)


def run(args, stdin="", check=True):
    p = subprocess.run(args, input=stdin, capture_output=True, text=True, env=env, timeout=300)
    if check and p.returncode != 0:
        sys.exit("FAIL: %s: exit %d\n%s%s" % (" ".join(args), p.returncode, p.stdout, p.stderr))
    return p


def fail(msg):
    sys.exit("FAIL: " + msg)


# ---- the lab: an administrator made at set-up, a reviewer
run([users, "setup", "admin"], "admin pass 1\n")
run([users, "--as", "admin", "add", "rev", "reviewer"], "admin pass 1\nreview pass\n")
st = os.stat(os.path.join(lab, "users"))
if st.st_mode & 0o777 != 0o600:
    fail("the users file is %o, not 600" % (st.st_mode & 0o777))

# ---- two runs against a real fbrlsim: complete, then aborted by Ctrl-C
os.makedirs("m")
shutil.copy(os.path.join(src, "examples/methods/sample_prep.fbrl"), "m/")
for f in ("asps_cell.fbrl", "asps_cell_objects.fbrl"):
    shutil.copy(os.path.join(src, "examples", f), ".")
simp = subprocess.Popen([sim, "--time-scale", "50", "--inputs", os.path.join(src, "examples/tube_present.inputs"),
                         "--log", "sim.log", "--link", os.path.join(work, "robot")],
                        stdout=open("sim.out", "w"), stderr=subprocess.STDOUT)
try:
    for _ in range(200):
        if os.path.exists("robot"):
            break
        time.sleep(0.02)
    base = [mon, "--port", os.path.join(work, "robot"), "--run-log", chain, "--operator", "ann",
            "-e", "60 CONSTANT TIME-SCALE", "m/sample_prep.fbrl"]
    p = run(base + ["-e", "HOME 3 PARAM! #SAMPLES SAMPLE-PREP RUN-METHOD"])
    if "prepared 3 of 3 samples" not in p.stdout:
        fail("the complete run did not prepare 3 samples:\n" + p.stdout + p.stderr)
    p2 = subprocess.Popen(base + ["-e", "3 PARAM! #SAMPLES SAMPLE-PREP RUN-METHOD"], stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
    time.sleep(4)
    p2.send_signal(signal.SIGINT)
    p2.communicate(timeout=60)
finally:
    simp.send_signal(signal.SIGTERM)
    simp.wait(timeout=30)

recs = [json.loads(l) for l in open(chain)]
sums = [r for r in recs if r.get("type") == "summary"]
if [s["outcome"] for s in sums] != ["completed", "aborted"]:
    fail("the runs' outcomes: %s" % [s["outcome"] for s in sums])
if any(r["user"] != "ann" for r in recs if r.get("type") in ("header", "command", "summary")):
    fail("a run's record is not by ann")
# each run's commands stand in fbrlsim's log as they were recorded, one run after the other
simlog = [l.rstrip("\n") for l in open("sim.log")]
at = 0
for h in [i for i, r in enumerate(recs) if r.get("type") == "header"]:
    cmds = []
    for r in recs[h:]:
        if r.get("type") == "seal":
            break
        if r.get("type") == "command":
            cmds += [r["line"]] * r.get("count", 1)  # a folded poll: that many times
    while at < len(simlog) and simlog[at:at + len(cmds)] != cmds:
        at += 1
    if at >= len(simlog):
        fail("a run's %d commands are not in fbrlsim's log in their order" % len(cmds))
    at += len(cmds)

# ---- the reviewer signs the complete run's seal
h1 = [r["seq"] for r in recs if r.get("type") == "header"][0]
seal1 = [r["seq"] for r in recs if r.get("type") == "seal" and r["seq"] > h1][0]
run([audit, "sign", chain, "--as", "rev", "--record", str(seal1), "--meaning", "run reviewed"], "review pass\n")
keys = os.path.join(work, "keys")
open(keys, "w").write(run([users, "keys"]).stdout)
# only the public keys, offline
p = run([audit, "verify", "--keys", keys, chain])
n = sum(1 for _ in open(chain))
if not p.stdout.startswith("%s: %d records, intact, sealed\n" % (chain, n)) or "1 signature verified" not in p.stdout:
    fail("verify of the intact chain: " + p.stdout)
print(p.stdout.strip())

lines = open(chain, "rb").read().split(b"\n")[:-1]
head = open(chain + ".head", "rb").read()
N = len(lines)
sigs = [i for i, l in enumerate(lines) if b'"type":"signature"' in l]
if not sigs:
    fail("no signature record")


def rehash(ls, start):
    """A forger's chain: record start and every one after re-hashed, prev re-linked."""
    out = list(ls)
    prev = re.search(rb'"hash":"([0-9a-f]{64})"\}$', out[start - 1]).group(1) if start else b"0" * 64
    for i in range(start, len(out)):
        l = re.sub(rb'"prev":"[0-9a-f]{64}"', b'"prev":"' + prev + b'"', out[i], count=1)
        body = l[:l.rindex(b',"hash":"')]
        prev = hashlib.sha256(body).hexdigest().encode()
        out[i] = body + b',"hash":"' + prev + b'"}'
    return out, b"fbrl-audit-head 1 %d %s\n" % (len(out), prev)


def tamper(rng):
    """(kind, lines, head, record K the verifier must name)."""
    kind = rng.choice(["edit", "delete", "swap", "repeat", "cut", "cut-inside", "signature"])
    ls = list(lines)
    if kind == "edit":
        i = rng.randrange(N)
        spots = [m.start() for m in re.finditer(rb"[0-9A-Za-z]", ls[i])]
        p = rng.choice(spots)
        c = ls[i][p:p + 1]
        alphabet = b"0123456789" if c.isdigit() else b"abcdefghijklmnopqrstuvwxyz" if c.islower() else \
            b"ABCDEFGHIJKLMNOPQRSTUVWXYZ"
        new = bytes([rng.choice([x for x in alphabet if x != c[0]])])
        ls[i] = ls[i][:p] + new + ls[i][p + 1:]
        return kind, ls, head, i + 1
    if kind == "delete":
        i = rng.randrange(N)
        del ls[i]
        return kind, ls, head, i + 1
    if kind == "swap":
        i, j = sorted(rng.sample(range(N), 2))
        ls[i], ls[j] = ls[j], ls[i]
        return kind, ls, head, i + 1
    if kind == "repeat":
        i = rng.randrange(N)
        ls.insert(i + 1, ls[i])
        return kind, ls, head, i + 2
    if kind == "cut":
        m = rng.randrange(1, N)
        return kind, ls[:m], head, m + 1
    if kind == "cut-inside":
        m = rng.randrange(1, N)
        part = ls[m][:rng.randrange(1, len(ls[m]))]
        return kind, ls[:m] + [part], head, m + 1
    # a signature moved to another record, made to look whole: its record number (and, half
    # the time, the signed hash too) changed to another record's, every hash after re-made,
    # the head file rewritten
    s = rng.choice(sigs)
    target = rng.choice([k for k in range(1, s + 1) if b'"signs":%d,' % k not in ls[s]])
    l = re.sub(rb'"signs":\d+', b'"signs":%d' % target, ls[s])
    if rng.random() < 0.5:
        th = re.search(rb'"hash":"([0-9a-f]{64})"\}$', ls[target - 1]).group(1)
        l = re.sub(rb'"signed_hash":"[0-9a-f]{64}"', b'"signed_hash":"' + th + b'"', l)
    ls[s] = l
    ls, h = rehash(ls, s)
    return kind, ls, h, s + 1


rng = random.Random(seed)
t_chain = os.path.join(work, "t.jsonl")
counts = {}
for k in range(1000):
    kind, ls, h, K = tamper(rng)
    with open(t_chain, "wb") as f:
        f.write(b"\n".join(ls) + (b"\n" if kind != "cut-inside" else b""))
    open(t_chain + ".head", "wb").write(h)
    p = run([audit, "verify", "--keys", keys, t_chain], check=False)
    want = "%s: record %d (line %d): " % (t_chain, K, K)
    if p.returncode != 1 or not p.stdout.startswith(want):
        fail("tampering %d (%s at record %d) not refused there: exit %d: %s" % (k, kind, K, p.returncode,
                                                                                   p.stdout.strip()))
    counts[kind] = counts.get(kind, 0) + 1
    if k < 7 or k % 250 == 0:
        print("  %-10s -> %s" % (kind, p.stdout.strip()[len(t_chain) + 2:]))
print("1000 tamperings, every one refused at its record: %s" % ", ".join("%s %d" % kv for kv in sorted(counts.items())))

# ---- replay: both runs reproduce fbrlsim's log byte for byte
for r in (1, 2):
    p = run([audit, "replay", chain, "--run", str(r), "--fbrlsim", sim])
    if "byte for byte" not in p.stdout:
        fail("replay of run %d: %s" % (r, p.stdout))
    print(p.stdout.strip())
# a recorded command the controller logs otherwise (lower case: fbrlsim logs it upper case)
# is found: the comparison can fail. The chain is re-made whole, as a writer would.
ls = lines[:sigs[0]]  # before the review: a re-made chain would no longer carry its signature
cmd_at = [i for i, l in enumerate(ls) if b'"type":"command"' in l and b'"line":"READY"' in l][0]
ls[cmd_at] = ls[cmd_at].replace(b'"line":"READY"', b'"line":"ready"')
ls, h = rehash(ls, cmd_at)
open(t_chain, "wb").write(b"\n".join(ls) + b"\n")
open(t_chain + ".head", "wb").write(h)
p = run([audit, "replay", t_chain, "--run", "1", "--fbrlsim", sim], check=False)
if p.returncode != 1 or "differs from the recorded commands" not in p.stdout or "recorded 'ready', logged 'READY'" not in p.stdout:
    fail("a replay that differs was not reported: %d %s" % (p.returncode, p.stdout))
print("a differing replay is reported: " + p.stdout.strip()[len(t_chain) + 2:])
# and a tampered chain is not replayed at all
open(t_chain, "wb").write(b"\n".join(lines[:5] + lines[6:]) + b"\n")
open(t_chain + ".head", "wb").write(head)
p = run([audit, "replay", t_chain, "--fbrlsim", sim], check=False)
if p.returncode != 1 or "not replayed" not in p.stdout:
    fail("a tampered chain was replayed: " + p.stdout)

# ---- the review report: one page, nothing fetched
run([audit, "report", chain, "-o", "report.html"])
page = open("report.html").read()
for want in ("Intact and sealed", "SAMPLE-PREP", ">ann<", ">completed<", ">aborted<", "run reviewed by rev"):
    if want not in page:
        fail("the report lacks %r" % want)
if re.search(r"(src|href)=\"?(https?:)?//", page) or "<script" in page:
    fail("the report fetches something or runs a script")
print("report.html: %d bytes, the runs with their outcomes and the review" % len(page))
print("audit_e2e: passed")
