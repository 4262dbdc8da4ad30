# SPDX-License-Identifier: MIT
"""A method's predicted step times from fbrlmon's dry run (docs/workcell.md: the plan against
the built-in emulator, every wait skipped on a simulated clock). The station gives them to the
run (fbrl.Run.predict), so the remaining time of a RunMethod comes from the dry run before
the first step ends. FBRL_MON names fbrlmon (the launcher sets it), else fbrlmon on PATH."""
import json
import os
import re
import subprocess

from . import programs

# A dry run skips every wait: a second or two even for an hour-long method. One that does not
# end in this time waits for something no one gives it (fbrlmon's run of a method whose
# ON-FAILURE rule asks waits for an answer): the run then goes without the prediction.
DRY_RUN_S = 10
STEP_RE = re.compile(r"^  step (\S+)\s+(?:(\d+) x ([0-9.]+) s = |not run)")
DURATION_RE = re.compile(r"^simulated duration ([0-9.]+) s")
CLOSEST_RE = re.compile(r"^smallest clearance (-?[0-9.]+) in to (\S+) at X (\S+) Y (\S+) Z (\S+) \((.*)\)$")
ERROR_RE = re.compile(r"^\s*[0-9.]+ s  error: (.*)$")
OUTCOME_RE = re.compile(r"^predicted run of \S+: (\S+)")
SAMPLE_RE = re.compile(r"^  sample (\d+): (.*)$")


def fbrlmon():
    return programs.find("fbrlmon", "FBRL_MON", "fbrlmon was not found for the dry run")


def argv(opts, prelude, method_file, method, values, picture, segments=None):
    """fbrlmon's command line for a dry run of method with values [(name, value)]: the
    station's own files and -e texts in their order, then the method's file and the run;
    segments: where fbrlmon writes the path, motion by motion (--dry-run-json)."""
    args = [fbrlmon(), "--dry-run", "--svg", picture] + (["--dry-run-json", segments] if segments else [])
    if opts.sim_inputs:
        args += ["--sim-inputs", os.path.abspath(opts.sim_inputs)]
    if opts.sim_model:
        args += ["--sim-model", opts.sim_model]
    args.append(prelude)
    for kind, what in opts.actions:
        args += ["-e", what] if kind == "eval" else [os.path.abspath(what)]
    run = " ".join("%d PARAM! %s" % (v, n) for n, v in values)
    return args + [os.path.abspath(method_file), "-e", "%s %s RUN-METHOD" % (run, method)]


def run(opts, prelude, method_file, method, values, workdir, segments=None):
    """fbrlmon's dry run of the method in workdir: (its report, its exit status, the picture's
    path); ValueError when it does not end in time."""
    picture = os.path.join(workdir, "dry-run.svg")
    try:
        p = subprocess.run(argv(opts, prelude, method_file, method, values, picture, segments), cwd=workdir,
                           stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=DRY_RUN_S)
    except subprocess.TimeoutExpired:
        raise ValueError("the dry run did not end within %d s (it may wait for an answer to a question)"
                         % DRY_RUN_S)
    return p.stdout, p.returncode, picture, p.stderr


def predict(opts, prelude, method_file, method, values, workdir):
    """The time one run of each step takes, ms, in step order (0: the dry run did not run it);
    OSError or ValueError saying why when there is none."""
    out, status, _, err = run(opts, prelude, method_file, method, values, workdir)
    steps = []
    for line in out.splitlines():
        m = STEP_RE.match(line)
        if m:  # a step that ran in no measurable time is 1 ms: 0 would tell the run "unknown"
            steps.append(max(float(m.group(3)) * 1000.0, 1.0) if m.group(2) else 0.0)
    if not steps:
        tail = (err or out).strip().splitlines()[-3:]
        raise ValueError("the dry run predicted no steps (fbrlmon exit %d): %s" % (status, " / ".join(tail)))
    return steps


def plan(opts, prelude, method_file, method, values, workdir):
    """The dry run as the page shows it (docs/workcell.md, "The dry run"): the predicted
    duration, outcome and per-sample outcomes, the motions the guard refused (each names its
    obstacle), the controller's errors, the smallest clearance and where, the 2-D picture, and
    the path motion by motion as the guard checked it (fbrlmon --dry-run-json, docs/workcell.md):
    each one's tool points, its clearance and the obstacle nearest, a refused one's contact."""
    segments = os.path.join(workdir, "dry-run.jsonl")
    out, status, picture, err = run(opts, prelude, method_file, method, values, workdir, segments)
    r = {"status": status, "duration_s": None, "outcome": None, "samples": [], "refused": [], "errors": [],
         "closest": None, "picture": None, "report": out + err, "segments": []}
    for line in out.splitlines():
        m = DURATION_RE.match(line)
        if m:
            r["duration_s"] = float(m.group(1))
        m = CLOSEST_RE.match(line)
        if m:
            r["closest"] = {"clearance": float(m.group(1)), "obstacle": m.group(2),
                            "at": [float(m.group(i)) for i in (3, 4, 5)], "word": m.group(6)}
        if line.startswith("refused: "):
            r["refused"].append(line[len("refused: "):])
        m = ERROR_RE.match(line)
        if m:
            r["errors"].append(m.group(1))
        m = OUTCOME_RE.match(line)
        if m:
            r["outcome"] = m.group(1)
        m = SAMPLE_RE.match(line)
        if m:
            r["samples"].append({"sample": int(m.group(1)), "outcome": m.group(2)})
    if os.path.isfile(segments):  # each motion the guard checked: its tool points, clearance, refusal
        with open(segments, encoding="utf-8") as f:
            r["segments"] = [json.loads(line) for line in f if line.strip()]
    if os.path.isfile(picture):
        with open(picture, encoding="utf-8") as f:
            r["picture"] = f.read()
    return r
