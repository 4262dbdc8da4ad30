/* mon_recover.h - fbrlmon's side of corrective actions (mon_recover.c): the operator is
 * asked at the terminal, and each action taken is told there. */
#ifndef FBRLMON_RECOVER_H
#define FBRLMON_RECOVER_H

#include "fbrl/recover.h"

struct mon;
/* Install the words (fbrl_recover_install) with m's robot, asking and telling through m. */
fbrl_status mon_recover_install(struct mon *m);

#endif
