/* SPDX-License-Identifier: MIT */
/* mon_teach.h - TEACH, fbrlmon's keyboard teach pendant (docs/fbrlmon.md "TEACH"). */
#ifndef FBRLMON_TEACH_H
#define FBRLMON_TEACH_H

#include "mon.h"

/* Define TEACH (and its helper (TEACH)) in m's VM. Needs the glossary and robot
 * words installed (TEACH stores through ARM-HERE). */
fbrl_status mon_teach_install(mon *m);

#endif
