#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds, and installs libfbrl, fbrlmon and fbrlsim under PREFIX
# (default: /usr/local as root, ~/.local otherwise), then says whether PREFIX/bin is on PATH.
# Usage: install.sh [PREFIX]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -ge 1 ]; then
    prefix=$1
elif [ "$(id -u)" -eq 0 ]; then
    prefix=/usr/local
else
    prefix=$HOME/.local
fi
"$here/scripts/deps.sh"
"$here/scripts/build.sh" "$here/build" >/dev/null
cmake --install "$here/build" --prefix "$prefix" >/dev/null
echo "installed fbrlmon, fbrlsim and libfbrl under $prefix"
case ":$PATH:" in
*":$prefix/bin:"*) ;;
*) echo "$prefix/bin is not on your PATH; add it: export PATH=\"$prefix/bin:\$PATH\"" ;;
esac
