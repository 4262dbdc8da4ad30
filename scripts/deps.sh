#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what libfbrl needs to build and test, only when something is missing.
# Debian/Ubuntu (apt-get); elsewhere it says what to install and stops.
# Usage: deps.sh [EXTRA-PACKAGE...]   (extras are required too, e.g. gforth pforth for benchmarks)
set -eu

# Node and npm run fbrl-station's client test (tests/station/node, from its lock file): Debian's
# nodejs and npm, unless a node and an npm are on PATH already (NodeSource's nodejs carries its
# own npm and conflicts with Debian's npm package).
NODE_PACKAGES="nodejs npm"
if command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then NODE_PACKAGES=""; fi
REQUIRED="build-essential cmake ninja-build pkg-config libcmocka-dev libedit-dev libsodium-dev qemu-system-x86 locales
 libncurses-dev tmux gcc-arm-none-eabi picolibc-arm-none-eabi qemu-system-arm
 python3-cffi python3-pytest debhelper dpkg-dev fakeroot lintian abigail-tools scdoc
 librsvg2-bin bash-completion
 python3-grpcio python3-protobuf protobuf-compiler protobuf-compiler-grpc python3-zeroconf python3-cryptography
 python3-lxml python3-aiohttp libjs-three chromium python3-websocket python3-pil liburdfdom-tools $NODE_PACKAGES $*"
# what each is for: ncurses/tmux the operator console and its tests; the ARM toolchain,
# picolibc and qemu-system-arm the Cortex-M firmware; cffi/pytest the Python bindings;
# debhelper..scdoc the Debian packages, ABI check and man pages; rsvg the work-cell pictures;
# libsodium the audit trail, users and signatures (SHA-256, Argon2id, Ed25519).
# grpcio..cryptography fbrl-station (SiLA 2: gRPC, the protobuf modules made at build time,
# mDNS, its TLS certificate), lxml its tests (the standard's XML schema); aiohttp and
# libjs-three its page (--http), chromium, websocket and pil the page's browser test;
# liburdfdom-tools checks fbrl-urdf's output (check_urdf).
# Optional: the build works without them (fewer features or tests).
OPTIONAL="libserialport-dev clang libclang-rt-14-dev"

is_installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
# The suite also runs under a German locale (decimal comma) to prove that numbers do not
# follow the host's locale (tests/e2e/locale.cmake): generate de_DE.UTF-8 if it is missing.
have_de() { locale -a 2>/dev/null | grep -qi '^de_DE\.utf-\?8$'; }
gen_de() {
    have_de && return 0
    command -v localedef >/dev/null 2>&1 || { echo "deps: no localedef; de_DE.UTF-8 not generated" >&2; return 0; }
    S=; [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && S=sudo
    $S localedef -i de_DE -f UTF-8 de_DE.UTF-8 >&2 ||
        echo "deps: could not generate de_DE.UTF-8 (the locale tests will generate it in the build directory)" >&2
}

missing=""; opt_missing=""
if command -v dpkg-query >/dev/null 2>&1; then
    for p in $REQUIRED; do is_installed "$p" || missing="$missing $p"; done
    for p in $OPTIONAL; do is_installed "$p" || opt_missing="$opt_missing $p"; done
else
    missing="$REQUIRED"
fi
if [ -z "$missing$opt_missing" ]; then gen_de; exit 0; fi

if ! command -v apt-get >/dev/null 2>&1; then
    echo "deps: cannot check or install packages here (no apt-get)." >&2
    echo "deps: libfbrl needs: a C99 compiler, cmake, ninja or make, pkg-config, cmocka, libedit, libsodium, qemu-system-i386," >&2
    echo "deps: ncurses, tmux, arm-none-eabi gcc + picolibc, qemu-system-arm, python3 cffi + pytest, debhelper, lintian, abigail, scdoc, rsvg;" >&2
    echo "deps: for fbrl-station: python3 grpcio, protobuf, zeroconf, cryptography, lxml, protoc + grpc_python_plugin, node + npm;" >&2
    echo "deps: optional: libserialport, clang with libFuzzer. Install them, then run the build again." >&2
    exit 1
fi
SUDO=
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
        echo "deps: missing:$missing$opt_missing; run as root so apt-get can install them" >&2
        exit 1
    fi
fi
export DEBIAN_FRONTEND=noninteractive
echo "deps: installing$missing$opt_missing" >&2
$SUDO apt-get update -qq >&2 || { echo "deps: apt-get update failed (no network or no package source?)" >&2; exit 1; }
if [ -n "$missing" ]; then
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq --no-install-recommends $missing >&2 ||
        { echo "deps: apt-get could not install:$missing" >&2; exit 1; }
fi
for p in $opt_missing; do
    $SUDO apt-get install -y -qq --no-install-recommends "$p" >&2 ||
        echo "deps: optional package $p not available; continuing without it" >&2
done
gen_de
exit 0
