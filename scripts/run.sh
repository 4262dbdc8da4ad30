#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds, and runs the main program: the fbrlmon monitor
# against the built-in emulated controller (arguments are passed on to it).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh"
"$here/scripts/build.sh" "$here/build" >/dev/null
if [ -x "$here/build/apps/fbrlmon" ]; then
    exec "$here/build/apps/fbrlmon" "$@"
fi
exec "$here/build/examples/rack" "$@"
