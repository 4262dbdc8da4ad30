# SPDX-License-Identifier: MIT
# bash completion for fbrlmon, fbrlsim, fbrl-dump and fbrl-station (installed as
# /usr/share/bash-completion/completions/fbrlmon, .../fbrlsim, .../fbrl-dump and .../fbrl-station). The option names come
# from the program's own --help, so a new option completes without a change here; the
# values below are those the programs accept (the arm models also from --help).

_fbrl_ports()
{
    local p
    for p in /dev/serial/by-id/* /dev/ttyUSB* /dev/ttyACM* /dev/ttyS*; do
        [[ -e $p ]] && printf '%s\n' "$p"
    done
    printf '%s\n' tcp:
}

_fbrl_complete()
{
    local cur prev words cword split
    _init_completion -s || return

    local prog=${1##*/}
    case $prev in
        --port)
            COMPREPLY=($(compgen -W '$(_fbrl_ports)' -- "$cur"))
            [[ $cur != tcp:* ]] && _filedir
            return
            ;;
        --parity)
            if [[ $prog == fbrlsim ]]; then
                COMPREPLY=($(compgen -W 'N E O' -- "$cur"))
            else
                COMPREPLY=($(compgen -W 'none even odd' -- "$cur"))
            fi
            return
            ;;
        -f | --format)
            COMPREPLY=($(compgen -W 'json csv' -- "$cur"))
            return
            ;;
        --flow)
            COMPREPLY=($(compgen -W 'none xonxoff' -- "$cur"))
            return
            ;;
        --low-latency)
            COMPREPLY=($(compgen -W 'on off' -- "$cur"))
            return
            ;;
        --arm | --sim-model | --model)
            # the arm models, as --help lists them ("--arm a255|a465")
            COMPREPLY=($(compgen -W "$("$1" --help 2>/dev/null |
                sed -n 's/^ *--\(arm\|model\) \([a-z0-9|]*\) .*/\2/p' | tr '|' ' ')" -- "$cur"))
            return
            ;;
        --data-bits)
            COMPREPLY=($(compgen -W '5 6 7 8' -- "$cur"))
            return
            ;;
        --stop-bits)
            COMPREPLY=($(compgen -W '1 2' -- "$cur"))
            return
            ;;
        --baud)
            COMPREPLY=($(compgen -W '300 1200 2400 4800 9600 19200 38400 57600 115200' -- "$cur"))
            return
            ;;
        -e | --dict | --axes | --tcp | --rx-buffer | --time-scale | --cmd-time | --faults | --sim-time-scale)
            return
            ;;
        --sila | --http)
            COMPREPLY=($(compgen -W '127.0.0.1:50052 0.0.0.0:50052 off' -- "$cur"))
            return
            ;;
        --sim-state | --sim-inputs | --workspace | --printer | --state | --log | --inputs | --control | --link | \
            --sim-log)
            _filedir
            return
            ;;
        --data | --methods | --lab)
            _filedir -d
            return
            ;;
    esac
    $split && return

    if [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W '$(_parse_help "$1")' -- "$cur"))
        [[ ${COMPREPLY-} == *= ]] && compopt -o nospace
        return
    fi
    # fbrlmon's operands are FBRL source files, fbrl-dump's a data file; fbrlsim takes none
    [[ $prog != fbrlsim ]] && _filedir
}
complete -F _fbrl_complete fbrlmon fbrlsim fbrl-dump fbrl-station
