#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds libfbrl with warnings as errors, and runs every test.
# Every test reads /dev/null, not the terminal this was typed at: a program under test that
# reads its standard input (fbrlmon, a test's editor) never waits for keys nobody types.
# The tests that need a terminal make their own (tmux, script, a pty).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/deps.sh"
"$here/scripts/build.sh" "$here/build" -DFBRL_WERROR=ON
cd "$here/build"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@" </dev/null
