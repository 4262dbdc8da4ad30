/* SPDX-License-Identifier: MIT */
/* mon_files.h - fbrlmon's file system for the standard FILE words (mon_files.c). */
#ifndef FBRL_MON_FILES_H
#define FBRL_MON_FILES_H

#include "fbrl/vm.h"

const fbrl_vm_files *mon_files(void);

#endif
