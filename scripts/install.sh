#!/bin/sh
# SPDX-License-Identifier: MIT
# Installs what is missing, builds, and installs libfbrl, fbrlmon, fbrlsim and the Python
# package fbrl under PREFIX (default: /usr/local as root, ~/.local otherwise), so that
# programs built against it and `import fbrl` (Debian's python3) work; then says what, if
# anything, is still to do (PATH, PYTHONPATH, the dynamic linker's path).
# Usage: install.sh [PREFIX]
# Environment: DESTDIR stages the files under a root (packaging: no ldconfig then);
# FBRL_BUILD_DIR installs from a tree already built there (no dependency check, no build).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -ge 1 ]; then
    prefix=$1
elif [ "$(id -u)" -eq 0 ]; then
    prefix=/usr/local
else
    prefix=$HOME/.local
fi
case $prefix in /*) ;; *) prefix=$(pwd)/$prefix ;; esac
dest=${DESTDIR:-}
if [ -n "${FBRL_BUILD_DIR:-}" ]; then
    build=$FBRL_BUILD_DIR
else
    build=$here/build
    "$here/scripts/deps.sh"
    "$here/scripts/build.sh" "$build" >/dev/null
fi
cmake --install "$build" --prefix "$prefix" >/dev/null
echo "installed fbrlmon, fbrlsim and libfbrl under $prefix"
libdir=$prefix/$(sed -n 's/^CMAKE_INSTALL_LIBDIR:[A-Z]*=//p' "$build/CMakeCache.txt")
lib=$(readelf -d "$dest$libdir/libfbrl.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p') # libfbrl.so.1

# The Python package, for Debian's python3: into the directory of PREFIX it already reads
# (/usr/local: lib/python3.X/dist-packages; ~/.local: the user's site-packages), with a
# note of where its library lies, so `import fbrl` finds this libfbrl without
# LD_LIBRARY_PATH or ldconfig (the cffi bindings load it by path; docs/python.md).
py=/usr/bin/python3
[ -x "$py" ] || py=$(command -v python3 || true)
if [ -z "$py" ]; then
    echo "no python3: the Python package fbrl was not installed"
else
    pydir=$("$py" - "$prefix" <<'EOF'
import os, site, sys
prefix = os.path.realpath(sys.argv[1])
def below(p):
    rel = os.path.relpath(os.path.realpath(p), prefix)
    return not rel.startswith("..") and rel.startswith("lib")
if site.ENABLE_USER_SITE and os.path.realpath(site.getuserbase()) == prefix:
    print(site.getusersitepackages())
else:
    dirs = [p for p in sys.path if p.endswith("-packages") and below(p)]
    print(dirs[0] if dirs else os.path.join(sys.argv[1], "lib", "python3", "dist-packages"))
EOF
)
    mkdir -p "$dest$pydir/fbrl"
    cp "$here"/python/fbrl/*.py "$dest$pydir/fbrl/"
    rel=$("$py" -c 'import os, sys; print(os.path.relpath(sys.argv[1], sys.argv[2]))' "$libdir/$lib" "$pydir/fbrl")
    {
        echo "# SPDX-License-Identifier: MIT"
        echo "# Written by scripts/install.sh: the library installed with this package, relative to it."
        echo "LIBRARY = \"$rel\""
    } >"$dest$pydir/fbrl/_installed.py"
    echo "installed the Python package fbrl in $pydir"
    if ! "$py" -c 'import sys; sys.exit(sys.argv[1] not in sys.path)' "$pydir"; then
        echo "$pydir is not on python3's path; add it: export PYTHONPATH=\"$pydir\""
    fi
fi

# The shared library for C programs: a directory the dynamic linker searches needs its
# cache refreshed (ldconfig, as root); other prefixes are not searched at all, and no
# rpath is forced on the programs built against them (docs/c-programs.md says how).
searched() {
    want=$(realpath -m "$1")
    ldconfig -vN 2>/dev/null | sed -n 's/^\(\/[^:]*\):.*/\1/p' | while read -r d; do
        [ "$(realpath -m "$d")" = "$want" ] && echo yes && break
    done
}
if [ -n "$dest" ]; then
    :
elif [ "$(searched "$libdir")" = yes ]; then
    if [ "$(id -u)" -eq 0 ]; then
        ldconfig
        echo "ldconfig: programs find $lib in $libdir"
    else
        echo "run ldconfig as root so that programs find $lib in $libdir"
    fi
else
    echo "$libdir is not on the dynamic linker's path: programs built with CMake find $lib (rpath);" \
        "others need LD_LIBRARY_PATH=\"$libdir\" or libfbrl linked statically (docs/c-programs.md)"
fi
case ":$PATH:" in
*":$prefix/bin:"*) ;;
*) echo "$prefix/bin is not on your PATH; add it: export PATH=\"$prefix/bin:\$PATH\"" ;;
esac
