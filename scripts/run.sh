#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds what it runs, and runs the main program: the fbrlmon
# monitor against the built-in emulated controller (arguments are passed on to it).
# Only fbrlmon and what it links are built (not the tests, firmware or packages):
# ./scripts/test.sh builds the rest.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh"
"$here/scripts/build.sh" "$here/build" --target fbrlmon >/dev/null
exec "$here/build/apps/fbrlmon" "$@"
