#!/bin/sh
# SPDX-License-Identifier: MIT
# package_test.sh SRCDIR WORKDIR - the Debian packages, built as a packager would
# (label package, docs/packaging.md):
#   - a copy of the source tree (no build directories, no .git) in WORKDIR;
#   - dpkg-buildpackage -us -uc -b there (DEB_BUILD_OPTIONS=nocheck: the suite already ran;
#     parallel=2) must produce libfbrlN (N the soname), libfbrl-dev, fbrl-tools, python3-fbrl and fbrl-station;
#   - lintian on the .changes: no errors;
#   - dpkg -c: each package holds the files it should;
#   - unpacked into a fresh root, fbrlsim --version runs, the Python package imports
#     against the packaged library and fbrl-station --version runs on both.
# Exit 77 (skipped) when dpkg-buildpackage or lintian is not installed, or a build
# dependency of debian/control is missing.
src=$1 work=$2
for t in dpkg-buildpackage lintian fakeroot dh; do
    command -v "$t" >/dev/null 2>&1 || { echo "package: $t not installed: skipped"; exit 77; }
done
# Build-Depends (debian/control) must be installed: dpkg-buildpackage would refuse anyway
if ! (cd "$src" && dpkg-checkbuilddeps >"${TMPDIR:-/tmp}/fbrl-builddeps.$$" 2>&1); then
    echo "package: build dependencies missing (scripts/deps.sh installs them): skipped"
    cat "${TMPDIR:-/tmp}/fbrl-builddeps.$$"
    rm -f "${TMPDIR:-/tmp}/fbrl-builddeps.$$"
    exit 77
fi
rm -f "${TMPDIR:-/tmp}/fbrl-builddeps.$$"
version=$(sed -n '1s/.*(\(.*\)).*/\1/p' "$src/debian/changelog")
upstream=${version%-*}
major=${upstream%%.*} # the soname's number: the library's package is libfbrl$major
arch=$(dpkg --print-architecture)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
rm -rf "$work" && mkdir -p "$work" || exit 1
tree=$work/libfbrl-$upstream
mkdir "$tree" || exit 1
# the tree as a release tarball has it: no build trees, no VCS, no Python caches
(cd "$src" && tar cf - --exclude=./.git --exclude='./build*' --exclude='./obj-*' --exclude=__pycache__ \
    --exclude=.pytest_cache .) | (cd "$tree" && tar xf -) || exit 1

fails=0
fail() { fails=$((fails + 1)); echo "FAIL: $*"; }

echo "package: dpkg-buildpackage in $tree"
if ! (cd "$tree" && DEB_BUILD_OPTIONS="nocheck parallel=2" dpkg-buildpackage -us -uc -b >"$work/build.log" 2>&1); then
    tail -40 "$work/build.log"
    echo "FAIL: dpkg-buildpackage (log: $work/build.log)"
    exit 1
fi
for p in libfbrl$major libfbrl-dev fbrl-tools; do
    [ -f "$work/${p}_${version}_$arch.deb" ] || fail "no ${p}_${version}_$arch.deb"
done
[ -f "$work/python3-fbrl_${version}_all.deb" ] || fail "no python3-fbrl_${version}_all.deb"
[ -f "$work/fbrl-station_${version}_all.deb" ] || fail "no fbrl-station_${version}_all.deb"
[ $fails = 0 ] || exit 1

# lintian: errors fail; warnings are printed
changes=$work/libfbrl_${version}_$arch.changes
lintian --tag-display-limit 0 "$changes" >"$work/lintian.txt" 2>&1
cat "$work/lintian.txt"
if grep -q '^E:' "$work/lintian.txt"; then
    fail "lintian reports errors"
fi
echo "package: lintian: $(grep -c '^E:' "$work/lintian.txt") errors, $(grep -c '^W:' "$work/lintian.txt") warnings"

# has DEB PATTERN... - every pattern (grep -E on dpkg -c's paths) matches a file in DEB
has() {
    deb=$work/$1
    shift
    dpkg -c "$deb" | awk '{print $6}' >"$work/contents.txt"
    for pat in "$@"; do
        grep -Eq "$pat" "$work/contents.txt" || fail "$(basename "$deb") has no file matching $pat"
    done
}
L=usr/lib/$multiarch
has "libfbrl${major}_${version}_$arch.deb" "^\./$L/libfbrl\.so\.$major(\.|$)" "^\./usr/share/doc/libfbrl$major/copyright$"
has "libfbrl-dev_${version}_$arch.deb" "^\./usr/include/fbrl/fbrl\.h$" "^\./usr/include/fbrl/version\.h$" \
    "^\./usr/include/fbrl/export\.h$" "^\./usr/include/fbrlsim\.h$" "^\./$L/libfbrl\.so$" "^\./$L/libfbrl\.a$" \
    "^\./$L/libfbrlsim\.a$" "^\./$L/pkgconfig/fbrl\.pc$" "^\./$L/cmake/fbrl/fbrlConfig\.cmake$" \
    "^\./usr/share/doc/libfbrl-dev/examples/sample_prep\.c$" "^\./usr/share/doc/libfbrl-dev/abi\.md" \
    "^\./usr/share/man/man3/libfbrl\.3\.gz$"
has "fbrl-tools_${version}_$arch.deb" "^\./usr/bin/fbrlmon$" "^\./usr/bin/fbrlsim$" "^\./usr/bin/fbrl-dump$" \
    "^\./usr/share/man/man1/fbrl-dump\.1\.gz$" \
    "^\./usr/share/man/man1/fbrlmon\.1\.gz$" "^\./usr/share/man/man1/fbrlsim\.1\.gz$" \
    "^\./usr/share/bash-completion/completions/fbrlmon$" "^\./usr/share/bash-completion/completions/fbrlsim$"
has "python3-fbrl_${version}_all.deb" "^\./usr/lib/python3/dist-packages/fbrl/__init__\.py$" \
    "^\./usr/lib/python3/dist-packages/fbrl/_ffi\.py$" "^\./usr/share/doc/python3-fbrl/examples/sample_prep\.py"
has "fbrl-station_${version}_all.deb" "^\./usr/bin/fbrl-station$" "^\./usr/share/fbrl-station/fbrl_station/server\.py$" \
    "^\./usr/share/fbrl-station/fbrl_station/features/ArmController\.sila\.xml$" \
    "^\./usr/share/fbrl-station/fbrl_station/_gen/ArmController_pb2_grpc\.py$" \
    "^\./usr/share/man/man1/fbrl-station\.1\.gz$" "^\./usr/share/doc/fbrl-station/sila\.md"
# nothing internal: no build paths, no test programs
for deb in "$work"/*.deb; do
    if dpkg -c "$deb" | grep -Eq 'obj-|/tests?/|__pycache__'; then
        fail "$(basename "$deb") holds build or test files"
    fi
done

# a fresh root with all five unpacked
root=$work/root
for deb in "$work"/*.deb; do dpkg -x "$deb" "$root" || fail "dpkg -x $deb"; done
out=$("$root/usr/bin/fbrlsim" --version 2>&1) || fail "packaged fbrlsim --version: $out"
echo "package: $out"
case $out in "fbrlsim (libfbrl) $upstream") ;; *) fail "fbrlsim --version says '$out'" ;; esac
if [ -x /usr/bin/python3 ] && /usr/bin/python3 -c 'import cffi' 2>/dev/null; then
    v=$(cd "$work" && PYTHONPATH="$root/usr/lib/python3/dist-packages" FBRL_LIBRARY="$root/$L/libfbrl.so.$major" \
        /usr/bin/python3 -c 'import fbrl; print(fbrl.version())' 2>&1) || fail "python3 -c 'import fbrl': $v"
    [ "$v" = "$upstream" ] || fail "fbrl.version() says '$v'"
    echo "package: python3-fbrl imports, library version $v"
    if /usr/bin/python3 -c 'import grpc, google.protobuf, zeroconf, cryptography' 2>/dev/null; then
        v=$(cd "$work" && PYTHONPATH="$root/usr/share/fbrl-station:$root/usr/lib/python3/dist-packages" \
            FBRL_LIBRARY="$root/$L/libfbrl.so.$major" /usr/bin/python3 -m fbrl_station --version 2>&1) ||
            fail "packaged fbrl-station --version: $v"
        [ "$v" = "fbrl-station (libfbrl) $upstream" ] || fail "fbrl-station --version says '$v'"
        echo "package: $v"
    fi
fi
# the packaged manual pages render
for page in usr/share/man/man1/fbrlmon.1.gz usr/share/man/man1/fbrlsim.1.gz usr/share/man/man1/fbrl-station.1.gz \
    usr/share/man/man3/libfbrl.3.gz; do
    MANWIDTH=80 man -l -P cat "$root/$page" 2>/dev/null | grep -q '^NAME' || fail "man -l $page"
done
echo "package: 5 packages, $fails failures"
[ $fails = 0 ]
