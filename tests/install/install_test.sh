#!/bin/sh
# SPDX-License-Identifier: MIT
# Installed means usable (issue 27 item 7): scripts/install.sh installs the built tree into
# a scratch prefix that stands for a user's ~/.local, and everything then runs from the
# installed files alone (no build tree, no FBRL_LIBRARY, no PYTHONPATH):
#   - a program built against it three ways: find_package(fbrl) shared and static, pkg-config;
#   - docs/c-programs.md's hello_arm.c and CMakeLists.txt exactly as shown, built with CMake
#     (runs as it is: rpath), pkg-config (LD_LIBRARY_PATH, as the page says) and
#     pkg-config --static with -static (no libfbrl.so needed), each moving the installed
#     fbrlsim's arm;
#   - `import fbrl` in Debian's python3, loading the installed library, driving fbrlsim;
# and, staged with DESTDIR under /usr/local, the files land where python3 and the dynamic
# linker look; as root, ldconfig runs for a directory the dynamic linker searches (a stand-in
# ldconfig on PATH records it: the machine's own cache is not touched).
# Not in sanitizer builds (.ci/run): a plain program cannot link sanitized objects.
set -eu
build=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
unset FBRL_LIBRARY PYTHONPATH LD_LIBRARY_PATH DESTDIR
fail() { echo "FAIL: $*"; exit 1; }
py=/usr/bin/python3
[ -x $py ] || py=$(command -v python3)

# a stand-in ldconfig: says which directories it would search, records what it was asked
mkdir "$tmp/fake"
cat >"$tmp/fake/ldconfig" <<EOF
#!/bin/sh
case "\$*" in *N*) echo "\$FAKE_SEARCHED: (from the test)"; exit 0 ;; esac
echo "ldconfig \$*" >>"$tmp/ldconfig.log"
EOF
chmod +x "$tmp/fake/ldconfig"
install_sh() { # PREFIX [VAR=VALUE...]: scripts/install.sh from the built tree
    p=$1; shift
    env PATH="$tmp/fake:$PATH" FAKE_SEARCHED=/nowhere FBRL_BUILD_DIR="$build" "$@" sh "$src/scripts/install.sh" "$p"
}

# 1. a user's install: ~/.local stands in as the user base python3 reads (PYTHONUSERBASE)
home=$tmp/user/.local
out=$(install_sh "$home" PYTHONUSERBASE="$home")
echo "$out"
echo "$out" | grep -q "is not on the dynamic linker's path" || fail "no word on the dynamic linker's path"
[ ! -e "$tmp/ldconfig.log" ] || fail "ldconfig ran for a directory nobody searches"
prefix=$home
site=$(PYTHONUSERBASE="$home" $py -c 'import site; print(site.getusersitepackages())')
[ -f "$site/fbrl/__init__.py" ] && [ -f "$site/fbrl/_installed.py" ] || fail "no Python package in $site"

cmake -S "$src/tests/install" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/cm" >/dev/null
"$tmp/cm/consumer_shared" # the rpath CMake gives a program built against an installed library
"$tmp/cm/consumer_static"
pcdir=$(dirname "$(find "$prefix" -name fbrl.pc | head -n 1)")
flags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs fbrl)
# shellcheck disable=SC2086
cc -std=c99 -o "$tmp/consumer_pc" "$src/tests/install/consumer.c" $flags
LD_LIBRARY_PATH="$prefix/lib" "$tmp/consumer_pc"

# docs/c-programs.md: its program and CMakeLists.txt exactly as shown (the blocks marked
# <!-- file: NAME -->), built the three ways the page shows, run against the installed fbrlsim.
doc=$src/docs/c-programs.md
mkdir "$tmp/doc"
awk -v dir="$tmp/doc" '
    /^<!-- file: .* -->$/ { name = $3; next }
    /^```/ && !on { on = 1; if (name != "") target = dir "/" name; name = ""; next }
    /^```$/ && on { on = 0; target = ""; next }
    on && target != "" { print > target }
    { if ($0 != "") name = "" }' "$doc"
[ -s "$tmp/doc/hello_arm.c" ] && [ -s "$tmp/doc/CMakeLists.txt" ] ||
    fail "$doc lacks hello_arm.c or CMakeLists.txt"
grep -q 'cc -std=c99 -static -o hello_arm hello_arm.c $(pkg-config --static --cflags --libs fbrl)' "$doc" ||
    fail "$doc does not show the static build this test makes"
lines=$(wc -l <"$tmp/doc/hello_arm.c")
cmake -S "$tmp/doc" -B "$tmp/doc/build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/doc/build" >/dev/null
# shellcheck disable=SC2046
(cd "$tmp/doc" && PKG_CONFIG_PATH="$pcdir" cc -std=c99 -Wall -Wextra -Wpedantic -Werror \
    -o hello_arm_pc hello_arm.c $(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs fbrl))
# shellcheck disable=SC2046
(cd "$tmp/doc" && cc -std=c99 -static -o hello_arm_static hello_arm.c \
    $(PKG_CONFIG_PATH="$pcdir" pkg-config --static --cflags --libs fbrl) 2>"$tmp/static.err") ||
    fail "static build: $(cat "$tmp/static.err")" # glibc warns of getaddrinfo (tcp: ports): docs/c-programs.md
if readelf -d "$tmp/doc/hello_arm_static" 2>/dev/null | grep -q 'NEEDED.*libfbrl'; then
    fail "pkg-config --static with -static linked the shared libfbrl"
fi
sed 's/fbrl_rapl_real(14.0)/fbrl_rapl_real(40.0)/' "$tmp/doc/hello_arm.c" >"$tmp/doc/far.c"
# shellcheck disable=SC2046
cc -std=c99 -o "$tmp/doc/far" "$tmp/doc/far.c" $(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs fbrl)
"$prefix/bin/fbrlsim" --link "$tmp/robot" --log "$tmp/sim.log" >/dev/null 2>&1 &
simpid=$!
trap 'kill $simpid 2>/dev/null || :; rm -rf "$tmp"' EXIT
i=0
while [ ! -e "$tmp/robot" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
hello() { # COMMAND...: run it on the robot; it must say where the arm went
    got=$("$@" "$tmp/robot")
    [ "$got" = "arm at x 14.00 y 2.00 z 8.00 in" ] || fail "$* printed '$got'"
}
hello "$tmp/doc/build/hello_arm"
hello env LD_LIBRARY_PATH="$prefix/lib" "$tmp/doc/hello_arm_pc"
hello "$tmp/doc/hello_arm_static"
got=$(LD_LIBRARY_PATH="$prefix/lib" "$tmp/doc/far" "$tmp/robot" 2>&1) && fail "a point out of reach succeeded"
# the page shows the message: it must be the program's
want=$(grep '^hello_arm: move: controller error 029' "$doc")
[ -n "$want" ] && [ "$got" = "$want" ] || fail "out of reach: '$got'"

# import fbrl: Debian's python3 with the user base and nothing else; the library it loads is
# the installed one, and it drives the installed fbrlsim
got=$(cd "$tmp" && PYTHONUSERBASE="$home" $py -c '
import sys, fbrl
lib = [l.split()[-1] for l in open("/proc/self/maps") if "libfbrl.so" in l][0]
with fbrl.Port(sys.argv[1]) as port:
    link = fbrl.Link(port, echo_timeout_ms=500)
    link.home()
    print(lib, fbrl.version(), "x %.2f" % link.where().world.x)
' "$tmp/robot") || fail "import fbrl from the installed files: $got"
case $got in
"$prefix/lib/libfbrl.so."*" x 14.00") ;; # where hello_arm left the arm
*) fail "python3 used '$got', not $prefix/lib" ;;
esac
kill $simpid 2>/dev/null && wait $simpid 2>/dev/null || :
grep -qx HOME "$tmp/sim.log" || fail "no HOME in fbrlsim's log"

# 2. staged for packaging (DESTDIR) under /usr/local: the directories python3 and the
# dynamic linker read there; no ldconfig (the files are not in place yet)
out=$(install_sh /usr/local DESTDIR="$tmp/root" FAKE_SEARCHED=/usr/local/lib)
want=$($py -c 'import sys; print([p for p in sys.path if p.startswith("/usr/local/lib/python3") and p.endswith("-packages")][0])')
[ -f "$tmp/root$want/fbrl/_ffi.py" ] || fail "DESTDIR: no Python package in $want: $out"
[ -e "$tmp/root/usr/local/lib/libfbrl.so.1" ] || fail "DESTDIR: no library in /usr/local/lib"
[ ! -e "$tmp/ldconfig.log" ] || fail "DESTDIR: ldconfig ran"

# 3. as root into a directory the dynamic linker searches: ldconfig refreshes its cache
if [ "$(id -u)" -eq 0 ]; then
    out=$(install_sh "$tmp/opt" FAKE_SEARCHED="$tmp/opt/lib")
    [ "$(cat "$tmp/ldconfig.log" 2>/dev/null)" = "ldconfig " ] || fail "root, searched: ldconfig did not run: $out"
    echo "$out" | grep -q "ldconfig: programs find libfbrl.so.1 in $tmp/opt/lib" || fail "no word of ldconfig: $out"
    ldnote="ldconfig ran as root for a searched directory"
else
    ldnote="ldconfig (root only) not tried"
fi
echo "install test: install.sh into a user prefix; find_package (shared, static) and pkg-config consumers ran;" \
    "docs/c-programs.md's $lines-line program built with CMake, pkg-config and pkg-config --static and moved the arm;" \
    "python3 imported the installed fbrl ($got); DESTDIR staging under /usr/local right; $ldnote"
