#!/bin/bash
# SPDX-License-Identifier: MIT
# completion_test.sh COMPLETION_FILE BINDIR... - bash completion of fbrlmon and fbrlsim, as
# bash-completion runs it: option names (from the program's --help), values of options,
# "--opt=" forms. BINDIRs are put first on PATH (the built programs).
comp=$1
shift
for d in "$@"; do PATH=$d:$PATH; done
bc=/usr/share/bash-completion/bash_completion
[ -r "$bc" ] || { echo "completion: bash-completion not installed: skipped"; exit 77; }
# shellcheck disable=SC1090
. "$bc"
# shellcheck disable=SC1090
. "$comp"
fails=0
count=0
# expect "COMMAND LINE" WORD... : completing the last word of LINE offers every WORD
expect() {
    local line=$1
    shift
    count=$((count + 1))
    read -r -a COMP_WORDS <<<"$line"
    [[ $line == *" " ]] && COMP_WORDS+=("")
    COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
    COMP_LINE=$line
    COMP_POINT=${#line}
    COMPREPLY=()
    _fbrl_complete "${COMP_WORDS[0]}" "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}"
    local w
    for w in "$@"; do
        if ! printf '%s\n' "${COMPREPLY[@]}" | grep -qxF -- "$w"; then
            fails=$((fails + 1))
            echo "FAIL: '$line' does not offer '$w' (offers: ${COMPREPLY[*]})"
        fi
    done
}
expect "fbrlmon --di" --dict
expect "fbrlmon --sim-m" --sim-model
expect "fbrlmon --sim-model " a255 a465
expect "fbrlmon --ar" --arm
expect "fbrlmon --arm " a255 a465
expect "fbrlsim --model " a255 a465
expect "fbrlmon --parity " none even odd
expect "fbrlmon --flow x" xonxoff
expect "fbrlmon --low-latency o" on off
expect "fbrlmon --ver" --version
expect "fbrlsim --ti" --time-scale
if command -v fbrl-station >/dev/null 2>&1; then  # built when its Python modules are there
    expect "fbrl-station --no-d" --no-discovery
    expect "fbrl-station --sila " 127.0.0.1:50052 off
    expect "fbrl-station --la" --lab
fi
expect "fbrlsim --parity " N E O
expect "fbrlsim --model a4" a465
expect "fbrlsim --ver" --version
expect "fbrlmon --port tc" tcp:
expect "fbrl-dump --fo" --format
expect "fbrl-dump --format " json csv
echo "completion: $count cases, $fails failed"
[ $fails = 0 ]
