#!/bin/sh
# No call circles between the files of a folder, checked on the compiled objects: file A
# "calls" file B when A uses a symbol B defines. Within each folder given the edges must
# form no cycle (tsort finds them).
# Usage: check-calls.sh FOLDER... -- OBJ...   e.g. check-calls.sh src/words -- $(objects)
# A folder is matched against the object's path (CMake keeps the source path in it).
set -u
folders=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do folders="$folders $1"; shift; done
[ $# -gt 0 ] && shift
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
bad=0
for dir in $folders; do
    : >"$tmp/defs"
    : >"$tmp/uses"
    n=0
    for obj in "$@"; do
        path=$(printf '%s' "$obj" | sed 's#/\./#/#g') # objects of a target's own folder: dir.dir/./x.c.o
        case "$path" in */"$dir"/*) ;; *) continue ;; esac
        rest=${path##*/"$dir"/}
        case "$rest" in */*) continue ;; esac # only the folder itself, not below it
        f=${rest%.o}
        n=$((n + 1))
        nm --defined-only -g "$obj" | awk -v f="$f" 'NF == 3 {print $3, f}' >>"$tmp/defs"
        nm -u "$obj" | awk -v f="$f" '{print $NF, f}' | sed 's/@[^ ]*//' >>"$tmp/uses"
    done
    sort -o "$tmp/defs" "$tmp/defs"
    sort -o "$tmp/uses" "$tmp/uses"
    # edges "user definer" (self-edges make tsort list every file)
    join "$tmp/uses" "$tmp/defs" | awk '{print $2, $3} {print $2, $2}' | sort -u >"$tmp/edges"
    awk '{print $2, $2}' "$tmp/defs" | sort -u >>"$tmp/edges"
    if ! tsort "$tmp/edges" >/dev/null 2>"$tmp/err"; then
        echo "calls: a call circle between files of $dir:"
        sed 's/^tsort: /  /' "$tmp/err"
        bad=1
    else
        echo "calls: $dir: $n files, no call circle"
    fi
done
exit $bad
