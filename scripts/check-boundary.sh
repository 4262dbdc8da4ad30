#!/bin/sh
# SPDX-License-Identifier: MIT
# The boundary between the language engine (src/lang/) and its word sets: a word set uses
# the public headers (fbrl/vm.h, fbrl/vmx.h ...) and its own folder's headers, never the
# engine's insides. Checked on the sources: includes, and names only the engine has; and the
# one face every word set has (one row type, one table call, one way to take parameters).
# Usage: check-boundary.sh FILE...   (prints each violation; exit 1 if any)
set -u
tmp=$(mktemp) || exit 2
trap 'rm -f "$tmp"' EXIT
# engine-private names: fbrl__* functions, the header table, word kinds, opcodes, input
# sources, the engine's own constants (struct fbrl_vm itself is opaque outside the engine)
private='fbrl__[A-Za-z0-9_]*|\<HDR\(|\<fbrl_hdr\>|\<fbrl_src\>|\<K_(PRIM|COLON|VAR|CREATE|CONST|2CONST|FCONST|VALUE|2VALUE|FVALUE|DEFER|CFUNC|MARKER)\>|\<OP_[A-Z0-9_]+\>|\<SRC_(TEXT|FILE|STRING)\>|\<FBRL_(XT_BASE|NAME_MAX|LINE_MAX|THROW_STATUS)\>'
# the one face (docs/language.md, "Writing a word set"): words are fbrl_vmx_reg rows defined by
# fbrl_vmx_define_table and take their parameters with fbrl_vmx_check, never by hand
face='\<(fbrl_vm_define|fbrl_vmx_define|fbrl_vm_prim|fbrl_vm_pop|fbrl_vm_fpop)\>'
bad=0
n=0
for f in "$@"; do
    n=$((n + 1))
    dir=$(dirname "$f")
    # includes: <system>, "fbrl/..." (public), or a header next to the file
    grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | while IFS= read -r line; do
        h=$(printf '%s\n' "$line" | sed 's/.*include[[:space:]]*"\([^"]*\)".*/\1/')
        case "$h" in
        fbrl/*) ;;
        */*) echo "boundary: $f includes \"$h\" (a word set includes public headers and its own only)"; echo x >>"$tmp" ;;
        *) [ -f "$dir/$h" ] || { echo "boundary: $f includes \"$h\", which is not in $dir"; echo x >>"$tmp"; } ;;
        esac
    done
    hits=$(grep -nE "$private" "$f" | grep -vE '^[0-9]+:[[:space:]]*(/\*|\*)')
    if [ -n "$hits" ]; then
        printf '%s\n' "$hits" | sed "s|^|boundary: $f:|; s|\$| (an engine internal: use fbrl/vmx.h)|"
        bad=1
    fi
    hits=$(grep -nE "$face" "$f" | grep -vE '^[0-9]+:[[:space:]]*(/\*|\*)')
    if [ -n "$hits" ]; then
        printf '%s\n' "$hits" | sed "s|^|boundary: $f:|; s|\$| (a word set's words are fbrl_vmx_reg rows: fbrl_vmx_define_table, fbrl_vmx_check)|"
        bad=1
    fi
done
[ -s "$tmp" ] && bad=1
[ $bad -eq 0 ] && echo "boundary: $n word-set files use only the public interface"
exit $bad
