# SPDX-License-Identifier: MIT
"""A method run (fbrl/run.h): the methods an Engine loaded, started with parameter values,
paused, resumed, aborted and answered from any thread, watched as snapshots and events.

    with fbrl.Engine(link=link) as fb:
        run = fbrl.Run(fb)
        fb.include("examples/methods/sample_prep.fbrl")
        run.on_event(print)                            # on the thread that runs it
        result = run.start("SAMPLE-PREP", {"#SAMPLES": 2})
        result["outcome"]                              # "completed", "partial", "failed", "aborted"
        result["samples"]  # [{"sample": 1, "outcome": "failed", "reason": "..."}, ...]

start() runs the method on the calling thread (the engine is single-threaded) and returns
the run's last snapshot; pause(), resume(), abort(), answer() and snapshot() may be called
from any other thread meanwhile. Samples are numbered from 1, as in the run log. Thin: the
run, its outcomes and its rules are the library's (docs/c-programs.md, "Method runs").
"""
from ._ffi import ffi, lib, alloc, declared_later, opaque_later
from ._errors import Error, check
from ._errors import status_code as _status

ffi.cdef("""
typedef struct fbrl_method_set fbrl_method_set;
typedef struct fbrl_recover fbrl_recover;
typedef struct fbrl_run fbrl_run;
typedef struct fbrl_method_param {
    char name[32];
    char unit[16];
    char text[96];
    long min, max, def;
    fbrl_cell addr;
} fbrl_method_param;
typedef struct fbrl_method_step {
    char name[32];
    char text[96];
    fbrl_cell xt;
    int per_sample;
} fbrl_method_step;
typedef struct fbrl_method {
    char name[32];
    char text[96];
    fbrl_method_param params[12];
    size_t nparams;
    fbrl_method_step steps[24];
    size_t nsteps;
    int samples;
    fbrl_cell abort_xt;
    int complete;
    fbrl_cell addr;
} fbrl_method;
typedef struct fbrl_run_sample {
    uint8_t outcome;
    char reason[96];
} fbrl_run_sample;
typedef struct fbrl_run_snap {
    unsigned long version;
    int state;
    int outcome;
    char method[32];
    long nsteps;
    char step_name[24][32];
    uint8_t per_sample[24];
    long step_runs[24];
    long step_done[24];
    uint8_t step_failed[24];
    long step;
    long sample;
    long samples;
    long samples_done;
    fbrl_run_sample outcomes[96];
    int question;
    char question_text[256];
    char error[256];
    char who[64];
    long elapsed_ms;
    long remaining_ms;
} fbrl_run_snap;
typedef struct fbrl_run_event {
    int kind;
    const fbrl_method *method;
    long step;
    long sample;
    int outcome;
    int choice;
    fbrl_status status;
    const char *text;
    const char *who;
    const char *where;
    const char *kind_name, *action;
} fbrl_run_event;
typedef int (*fbrl_run_observer_fn)(void *ctx, fbrl_run *r, const fbrl_run_event *ev);
fbrl_status fbrl_method_install(fbrl_vm *vm, fbrl_method_set *s);
const fbrl_method *fbrl_method_at(const fbrl_method_set *s, size_t i);
fbrl_status fbrl_method_param_get(const fbrl_method_set *s, const fbrl_method *m, size_t k, long *v);
fbrl_status fbrl_recover_install(fbrl_vm *vm, fbrl_recover *rc, fbrl_robot *robot);
fbrl_status fbrl_run_install(fbrl_run *r, fbrl_vm *vm, fbrl_method_set *methods, fbrl_recover *rc,
                             fbrl_robot *robot);
fbrl_status fbrl_run_observe(fbrl_run *r, fbrl_run_observer_fn fn, void *ctx);
fbrl_status fbrl_run_start(fbrl_run *r, const char *method, const long *values, size_t n, size_t *bad);
fbrl_status fbrl_run_predict(fbrl_run *r, const char *method, const double *ms, size_t n);
fbrl_status fbrl_run_pause(fbrl_run *r, const char *who);
fbrl_status fbrl_run_resume(fbrl_run *r, const char *who);
fbrl_status fbrl_run_abort(fbrl_run *r, const char *who);
fbrl_status fbrl_run_answer(fbrl_run *r, int choice, const char *who);
fbrl_status fbrl_run_snapshot(const fbrl_run *r, fbrl_run_snap *out);
const char *fbrl_run_state_name(int s);
const char *fbrl_run_outcome_name(int o);
const char *fbrl_run_sample_name(int o);
""", override=True)


opaque_later("fbrl_method_set", "fbrl_recover", "fbrl_run")
declared_later("fbrl_run_snap", "fbrl_run_event", "fbrl_method")

# fbrl_run_event_kind, in its order (fbrl/run.h)
EVENTS = ("begin", "step_begin", "step_end", "sample", "recovery", "question", "answer", "pause", "resume",
          "abort", "safe_stop", "on_abort", "end", "wait")
CHOICES = {"retry": 1, "skip": 2, "stop": 3}
_CHOICE_NAMES = {v: k for k, v in CHOICES.items()}


def _s(p):
    return ffi.string(p).decode("utf-8", "replace") if p != ffi.NULL else None


def _name(fn, v):
    return ffi.string(fn(v)).decode()


class Run:
    """The method run of one Engine: installs the method words, the corrective actions
    (ON-FAILURE ...) and the run (RUN-METHOD, SAMPLE-FAILED ...) into it. Make it before
    loading method files."""

    def __init__(self, engine):
        self._engine = engine
        self._methods = alloc("fbrl_method_set")
        self._rc = alloc("fbrl_recover")
        self._run = alloc("fbrl_run")
        vm, robot = engine._vm, engine._robot.ptr
        check(lib.fbrl_method_install(vm, self._methods.ptr), "Run method words")
        check(lib.fbrl_recover_install(vm, self._rc.ptr, robot), "Run corrective actions")
        check(lib.fbrl_run_install(self._run.ptr, vm, self._methods.ptr, self._rc.ptr, robot), "Run")
        self._observers = []
        self._logs = []  # record()'s
        self._raised = None
        self._cb = ffi.callback("int(void *, fbrl_run *, const fbrl_run_event *)", self._event, onerror=self._onerror)
        check(lib.fbrl_run_observe(self._run.ptr, self._cb, ffi.NULL), "Run observer")

    # the methods
    def methods(self):
        """Every method declared: name, text, parameters (value, unit, range, default), steps."""
        out = []
        i = 0
        v = ffi.new("long *")
        while True:
            m = lib.fbrl_method_at(self._methods.ptr, i)
            if m == ffi.NULL:
                return out
            params = []
            for k in range(m.nparams):
                p = m.params[k]
                check(lib.fbrl_method_param_get(self._methods.ptr, m, k, v), "methods")
                params.append({"name": _s(p.name), "unit": _s(p.unit), "text": _s(p.text), "min": p.min,
                               "max": p.max, "default": getattr(p, "def"),
                               "value": v[0], "samples": m.samples == k})
            steps = [{"name": _s(m.steps[k].name), "text": _s(m.steps[k].text),
                      "per_sample": bool(m.steps[k].per_sample)} for k in range(m.nsteps)]
            out.append({"name": _s(m.name), "text": _s(m.text), "complete": bool(m.complete), "params": params,
                        "steps": steps})
            i += 1

    def predict(self, method, step_ms):
        """The time one run of each step takes (e.g. a dry run's), in ms: remaining_ms follows it."""
        ms = ffi.new("double[]", [float(x) for x in step_ms])
        check(lib.fbrl_run_predict(self._run.ptr, method.encode(), ms, len(step_ms)), "predict")

    # running
    def start(self, method, params=None):
        """Run method on this thread, its parameters set first (a dict by name, or a list in
        declaration order; all checked against their ranges before any is set). Returns the
        run's result (snapshot()). Raises fbrl.Error if the run could not begin (ValueError
        for a parameter out of range or unknown)."""
        values, n = ffi.NULL, 0
        if params is not None:
            m = next((x for x in self.methods() if x["name"].upper() == method.upper()), None)
            if m is None:
                raise Error(lib.fbrl_run_start(self._run.ptr, method.encode(), ffi.NULL, 0, ffi.NULL), method)
            if isinstance(params, dict):
                names = {p["name"].upper(): k for k, p in enumerate(m["params"])}
                unknown = [k for k in params if k.upper() not in names]
                if unknown:
                    raise ValueError("%s has no parameter %s" % (m["name"], ", ".join(unknown)))
                vals = [p["value"] for p in m["params"]]
                for k, x in params.items():
                    vals[names[k.upper()]] = x
            else:
                vals = list(params)
            for x in vals:
                if not isinstance(x, int) or isinstance(x, bool):
                    raise TypeError("a parameter is a whole number, not %r" % (x,))
            values, n = ffi.new("long[]", vals), len(vals)
        bad = ffi.new("size_t *")
        self._raised = None
        st = lib.fbrl_run_start(self._run.ptr, method.encode(), values, n, bad)
        if st == _status("FBRL_ERANGE"):
            p = self.methods()
            p = next(x for x in p if x["name"].upper() == method.upper())["params"][bad[0]]
            raise ValueError("%s: %d is outside %d..%d %s" % (p["name"], vals[bad[0]], p["min"], p["max"], p["unit"]))
        raised, self._raised = self._raised, None
        if raised is not None:  # an observer's, first: at "begin" it is why the run did not start
            raise raised
        if st == _status("FBRL_ETHROW"):  # it could not begin: the engine says why
            self._engine._fail(st, "run " + method)
        check(st, "run " + method)
        return self.snapshot()

    def pause(self, who=""):
        """After the current step (any thread)."""
        check(lib.fbrl_run_pause(self._run.ptr, who.encode()), "pause")

    def resume(self, who=""):
        check(lib.fbrl_run_resume(self._run.ptr, who.encode()), "resume")

    def abort(self, who=""):
        """The safe stop (halt, outputs off), then the method's ON-ABORT (any thread)."""
        check(lib.fbrl_run_abort(self._run.ptr, who.encode()), "abort")

    def answer(self, choice, who=""):
        """The pending question's answer: "retry", "skip" or "stop"."""
        if choice not in CHOICES:
            raise ValueError("an answer is one of %s" % ", ".join(CHOICES))
        check(lib.fbrl_run_answer(self._run.ptr, CHOICES[choice], who.encode()), "answer")

    # watching
    def snapshot(self):
        """The run as it stands (any thread): state, method, steps, samples and their
        outcomes, the question, elapsed and remaining ms (None unknown)."""
        s = ffi.new("fbrl_run_snap *")
        check(lib.fbrl_run_snapshot(self._run.ptr, s), "snapshot")
        steps = [{"name": _s(s.step_name[k]), "per_sample": bool(s.per_sample[k]), "runs": s.step_runs[k],
                  "done": s.step_done[k], "failed": bool(s.step_failed[k])} for k in range(s.nsteps)]
        samples = [{"sample": i + 1, "outcome": _name(lib.fbrl_run_sample_name, s.outcomes[i].outcome),
                    "reason": _s(s.outcomes[i].reason)} for i in range(s.samples)]
        return {"version": s.version, "state": _name(lib.fbrl_run_state_name, s.state),
                "outcome": _name(lib.fbrl_run_outcome_name, s.outcome) or None, "method": _s(s.method),
                "steps": steps, "step": s.step if s.step >= 0 else None,
                "sample": s.sample + 1 if s.sample >= 0 else None, "samples_done": s.samples_done,
                "samples": samples, "question": _s(s.question_text) if s.question else None,
                "question_number": s.question or None,
                "error": _s(s.error) or None, "who": _s(s.who) or None, "elapsed_ms": s.elapsed_ms,
                "remaining_ms": s.remaining_ms if s.remaining_ms >= 0 else None}

    def on_event(self, fn):
        """fn(event) for every event of every run, on the thread running it. event is a dict:
        kind (EVENTS), step, sample (from 1), outcome, choice, text, who ... An exception in fn
        refuses the run at "begin", else it is raised by start() once the run has ended."""
        self._observers.append(fn)
        return fn

    def record(self, log):
        """Every event of the runs from now on in log (an fbrl.RunLog: the library's records
        of it, fbrl_runlog_event), until unrecord(log). Returns log."""
        self._logs = self._logs + [log]
        return log

    def unrecord(self, log):
        self._logs = [x for x in self._logs if x is not log]

    def _event(self, ctx, r, ev):
        for log in self._logs:
            log.event(r, ev)
        kind = EVENTS[ev.kind]
        if kind == "wait" or not self._observers:
            return 0
        e = {"kind": kind, "method": _s(ev.method.name) if ev.method != ffi.NULL else None,
             "step": ev.step if ev.step >= 0 else None, "sample": ev.sample + 1 if ev.sample >= 0 else None,
             "text": _s(ev.text), "who": _s(ev.who)}
        if ev.method != ffi.NULL and ev.step >= 0:
            e["step_name"] = _s(ev.method.steps[ev.step].name)
        if kind == "sample":
            e["outcome"] = _name(lib.fbrl_run_sample_name, ev.outcome)
        elif kind == "end":
            e["outcome"] = _name(lib.fbrl_run_outcome_name, ev.outcome)
        elif kind == "answer":
            e["choice"] = _CHOICE_NAMES.get(ev.choice)
        elif kind == "safe_stop":
            e["status"] = ev.status
        elif kind == "recovery":
            e.update(where=_s(ev.where), failure=_s(ev.kind_name), action=_s(ev.action))
        for fn in self._observers:
            fn(e)
        return 0

    def _onerror(self, exc_type, exc, tb):
        """An observer raised: kept for start() to raise; at "begin" the run is refused."""
        if self._raised is None:
            self._raised = exc
        return 1

