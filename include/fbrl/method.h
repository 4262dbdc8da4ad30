/* SPDX-License-Identifier: MIT */
/* method.h - methods as a thing: a named procedure a lab runs without programming.
 *
 * A method file declares, in FBRL:
 *
 *   METHOD SAMPLE-PREP  ASPS sample preparation (thesis chapter 3)
 *   1 24 3 SAMPLES-PARAM #SAMPLES samples  sample tubes in the heating block
 *   1 120 15 PARAM REACTION-MIN min  reaction time on the heated block
 *   ' RECALIBRATE STEP Recalibrate  teach the block's pins, recalibrate
 *   ' ADD-BUFFER SAMPLE-STEP Buffer  buffer from dispenser 1 into the tube
 *   ' TO-SAFE-PLACE ON-ABORT
 *   END-METHOD
 *
 * A parameter is a word that pushes its value (checked against its range whenever it is
 * set); a step is a word run once (STEP) or once per sample with the sample's index 0..
 * (SAMPLE-STEP). A run of a method (RUN-METHOD: the steps in order, per-sample and per-run
 * outcomes, pause, resume, abort) is fbrl/run.h's. docs/console.md describes the words and
 * the method library. */
#ifndef FBRL_METHOD_H
#define FBRL_METHOD_H

#include "fbrl/export.h"

#include <stddef.h>
#include "fbrl/status.h"
#include "fbrl/vm.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FBRL_METHOD_MAX        16 /* methods one VM knows */
#define FBRL_METHOD_MAX_PARAMS 12
#define FBRL_METHOD_MAX_STEPS  24
#define FBRL_METHOD_NAME_MAX   31
#define FBRL_METHOD_UNIT_MAX   15
#define FBRL_METHOD_TEXT_MAX   95

typedef struct fbrl_method_param {
    char name[FBRL_METHOD_NAME_MAX + 1];
    char unit[FBRL_METHOD_UNIT_MAX + 1];
    char text[FBRL_METHOD_TEXT_MAX + 1];
    long min, max, def;
    fbrl_cell addr; /* the parameter word's data field (holds the value) */
} fbrl_method_param;

typedef struct fbrl_method_step {
    char name[FBRL_METHOD_NAME_MAX + 1];
    char text[FBRL_METHOD_TEXT_MAX + 1];
    fbrl_cell xt;
    int per_sample; /* SAMPLE-STEP: run once per sample with ( index -- ) */
} fbrl_method_step;

typedef struct fbrl_method {
    char name[FBRL_METHOD_NAME_MAX + 1];
    char text[FBRL_METHOD_TEXT_MAX + 1];
    fbrl_method_param params[FBRL_METHOD_MAX_PARAMS];
    size_t nparams;
    fbrl_method_step steps[FBRL_METHOD_MAX_STEPS];
    size_t nsteps;
    int samples;        /* the parameter that counts samples (SAMPLES-PARAM), -1 none */
    fbrl_cell abort_xt; /* ON-ABORT: the way to a safe place, 0 none */
    int complete;       /* END-METHOD seen */
    fbrl_cell addr;     /* the method word's data field */
} fbrl_method;

/* The word set's state: caller-owned, at a fixed address while the VM runs. */
typedef struct fbrl_method_set {
    fbrl_vm *vm;
    fbrl_method methods[FBRL_METHOD_MAX];
    size_t count;
    fbrl_method *current;       /* being declared (METHOD .. END-METHOD) */
    const fbrl_method *running; /* set by the run (fbrl/run.h) while it runs */
} fbrl_method_set;

/* Bind METHOD PARAM SAMPLES-PARAM STEP SAMPLE-STEP ON-ABORT USE-PARAMS END-METHOD METHODS
 * .METHOD PARAM! into vm (RUN-METHOD is fbrl_run_install's). */
FBRL_API fbrl_status fbrl_method_install(fbrl_vm *vm, fbrl_method_set *s);

/* The declared methods (complete or not) by index, or by name (case-insensitive); NULL if none. */
FBRL_API const fbrl_method *fbrl_method_at(const fbrl_method_set *s, size_t i);
FBRL_API const fbrl_method *fbrl_method_find(const fbrl_method_set *s, const char *name);

/* A parameter's value, and setting it: FBRL_ERANGE outside min..max (nothing changes),
 * FBRL_EINVAL for a bad index, FBRL_ESTATE while the method runs. */
FBRL_API fbrl_status fbrl_method_param_get(const fbrl_method_set *s, const fbrl_method *m, size_t k, long *v);
FBRL_API fbrl_status fbrl_method_param_set(fbrl_method_set *s, const fbrl_method *m, size_t k, long v);

/* How many times step k runs with the current parameters (1, or the sample count). */
FBRL_API long fbrl_method_step_runs(const fbrl_method_set *s, const fbrl_method *m, size_t k);

#ifdef __cplusplus
}
#endif
#endif
