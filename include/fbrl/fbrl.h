/* SPDX-License-Identifier: MIT */
/* fbrl.h - libfbrl's portable public headers. Include this, or only the modules you use.
 * It includes no OS header, so it compiles in a freestanding build (the test
 * fbrl_h_freestanding checks that); the OS-specific backends have their own headers:
 * fbrl/uart_posix.h (termios, ptys, TCP) and fbrl/uart_serialport.h (libserialport). */
#ifndef FBRL_FBRL_H
#define FBRL_FBRL_H

#include "fbrl/version.h"
#include "fbrl/abi.h"
#include "fbrl/status.h"
#include "fbrl/crc32.h"
#include "fbrl/ring.h"
#include "fbrl/clock.h"
#include "fbrl/uart.h"
#include "fbrl/uart_8250.h"
#include "fbrl/uart_pl011.h"
#include "fbrl/port.h"
#include "fbrl/rapl_encode.h"
#include "fbrl/rapl_reply.h"
#include "fbrl/link.h"
#include "fbrl/num.h"
#include "fbrl/arm.h"
#include "fbrl/loc.h"
#include "fbrl/units.h"
#include "fbrl/matrix.h"
#include "fbrl/calib.h"
#include "fbrl/fileio.h"
#include "fbrl/vm.h"
#include "fbrl/glossary.h"
#include "fbrl/robot.h"
#include "fbrl/runlog.h"
#include "fbrl/method.h"
#include "fbrl/recover.h"
#include "fbrl/run.h"
#include "fbrl/audit.h"
#include "fbrl/users.h"
#include "fbrl/release.h"

#endif
