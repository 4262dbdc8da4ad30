#!/bin/sh
# Installs what libfbrl needs to build and test, only when something is missing.
# Debian/Ubuntu (apt-get); elsewhere it says what to install and stops.
set -eu

PKGS="build-essential cmake ninja-build pkg-config libcmocka-dev libedit-dev libserialport-dev qemu-system-x86 clang"
[ $# -gt 0 ] && PKGS="$PKGS $*"

missing=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0

if ! command -v apt-get >/dev/null 2>&1; then
    echo "deps: these packages are missing:$missing" >&2
    echo "deps: apt-get is not available here; install them with your package manager" >&2
    exit 1
fi
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
        echo "deps: missing:$missing; run as root (or install sudo) so apt-get can install them" >&2
        exit 1
    fi
else
    SUDO=
fi
echo "deps: installing$missing" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq >&2 || { echo "deps: apt-get update failed (no network or no package source?)" >&2; exit 1; }
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >&2 ||
    { echo "deps: apt-get could not install:$missing" >&2; exit 1; }
