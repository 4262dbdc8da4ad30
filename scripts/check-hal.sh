#!/bin/sh
# SPDX-License-Identifier: MIT
# The HAL boundary, checked on the compiled objects: no library module may allocate,
# print, exit or abort; only the OS modules below may call the operating system.
# Usage: check-hal.sh OBJ...   (prints each violation; exit 1 if any)
set -u
os_modules="uart_posix uart_serialport clock_posix fileio_posix audit_posix port"
never='^(malloc|calloc|realloc|free|printf|fprintf|vfprintf|puts|fputs|putchar|perror|exit|_exit|abort|__assert_fail|system)$'
# Text <-> number through the C library follows the host's locale (LC_NUMERIC): the library
# converts with fbrl_num (docs/language.md, "Numbers do not depend on the locale").
locale_calls='^(strtod|strtof|strtold|atof|sscanf|vsscanf|localeconv|setlocale)$'
os_calls='^(open|open64|openat|close|read|write|poll|select|ioctl|fcntl|fcntl64|tcgetattr|tcsetattr|fopen|fopen64|fclose|fread|fwrite|fsync|rename|unlink|socket|connect|clock_gettime|nanosleep|usleep|sleep|pthread_[a-z_]*|signal|sigaction|getenv|time)$'
bad=0
for obj in "$@"; do
    mod=$(basename "$obj"); mod=${mod%.o}; mod=${mod%.c}
    os_ok=0
    case " $os_modules " in *" $mod "*) os_ok=1 ;; esac
    # one awk per object (a grep per symbol took a minute on a loaded machine)
    out=$(nm -u "$obj" | awk -v mod="$mod" -v os_ok="$os_ok" -v never="$never" -v loc="$locale_calls" \
        -v os="$os_calls" -v mods="$os_modules" '
        { s = $NF; sub(/@.*/, "", s)
          if (s ~ never) print "hal: " mod " calls " s " (the library never allocates, prints, exits or aborts)"
          else if (s ~ loc) print "hal: " mod " calls " s " (locale-dependent numbers; use fbrl_num)"
          else if (s ~ os && !os_ok) print "hal: " mod " calls " s " (only " mods " may touch the OS)" }')
    if [ -n "$out" ]; then
        printf '%s\n' "$out"
        bad=1
    fi
done
[ $bad -eq 0 ] && echo "hal: $# objects checked, boundary holds"
exit $bad
