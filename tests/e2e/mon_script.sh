#!/bin/sh
# mon_script.sh FBRLMON SRCDIR TMPDIR - fbrlmon on script files, -e texts and
# piped standard input: exact output, error lines and exit status. (Offline:
# the connection has its own test, mon_conn.sh.)
mon=$1
src=$2
tmp=$3
mkdir -p "$tmp" || exit 2
cd "$tmp" || exit 2
fails=0
count=0

# t NAME STATUS STDOUT STDERR STDIN [ARG...]
# STDOUT and STDERR are exact (printf %b escapes); STDOUT "*" is not compared
# (the caller looks at out.txt); a STDERR starting with '~'
# is a grep -E pattern matching stderr's first line, the only one besides a backtrace's
# indented lines ("~*": any line).
t() {
    name=$1 want_st=$2 want_out=$3 want_err=$4 input=$5
    shift 5
    count=$((count + 1))
    printf '%b' "$input" | "$mon" --offline "$@" >out.txt 2>err.txt
    st=$?
    printf '%b' "$want_out" >want_out.txt
    ok=1
    [ "$st" = "$want_st" ] || ok=0
    [ "$want_out" = "*" ] || cmp -s out.txt want_out.txt || ok=0
    case $want_err in
    "~*"*) grep -Eq -- "${want_err#\~\*}" err.txt || ok=0 ;;
    "~"*) [ "$(grep -vc '^  ' err.txt)" -eq 1 ] && head -n 1 err.txt | grep -Eq -- "${want_err#\~}" || ok=0 ;;
    *) printf '%b' "$want_err" >want_err.txt; cmp -s err.txt want_err.txt || ok=0 ;;
    esac
    if [ $ok = 0 ]; then
        fails=$((fails + 1))
        echo "FAIL: $name: status $st (want $want_st)"
        echo "  stdout: $(od -c out.txt | head -5)"
        echo "  want:   $(od -c want_out.txt | head -5)"
        echo "  stderr: $(cat err.txt)"
        echo "  want:   $want_err"
    fi
}

basic="9 8 \n5 4 3 2 1 \n3 \n"
t "script file" 0 "$basic" "" "" "$src/mon_basic.fbrl"
t "-e and files in order" 0 "${basic}100 " "" "" -e ': ten 10 ;' "$src/mon_basic.fbrl" -e 'ten square .'
t "piped input, definition over lines" 0 "7 " "" ': add3\n1 +\n2 +\n;\n4 add3 .\n'
t "piped input without final newline" 0 "3 " "" '1 2 + .'
t "CRLF lines" 0 "1 2 " "" '1 .\r\n2 .\r\n'
t "empty input" 0 "" "" ""
t "--offline" 0 "6 " "" '2 3 * .\n' --offline
t "error in a file: rest of it skipped, next file runs" 1 "1 2 $basic" \
    "$src/mon_error.fbrl:3: error: undefined word nosuchword\n" "" "$src/mon_error.fbrl" "$src/mon_basic.fbrl"
t "error in piped input: next line runs" 1 "1 2 " "stdin:2: error: undefined word foo\n" '1 .\nfoo\n2 .\n'
t "stacks reset after an error" 1 "0 0 " "~^stdin:1: error: .*$" '1 2 3 1.5e0 nosuch\ndepth . fdepth .\n'
t "error in an included file names it" 1 "1 2 5 " \
    "$src/mon_error.fbrl:3: error: undefined word nosuchword\n" "s\" $src/mon_error.fbrl\" included\n5 .\n"
t "error in -e text" 1 "" "~^-e:1: error: .*$" "" -e '1 0 /'
t "error on line 2 of -e text" 1 "" "~^-e:2: error: undefined word oops$" "" -e "1 drop
oops"
t "missing file" 1 "4 " "~^.*/nonexistent\\.fbrl: error: " '4 .\n' "$tmp/nonexistent.fbrl"
t "a directory as FILE" 1 "" "$tmp: error: cannot open $tmp: not a regular file (a device, FIFO or directory)\n" "" "$tmp"
printf ': half 1 2\n' >half.fbrl
t "unterminated definition at end of a file" 1 "5 " \
    "$tmp/half.fbrl:1: error: unterminated definition at end of file\n" '5 .\n' "$tmp/half.fbrl"
t "unterminated definition at end of -e text" 1 "5 " \
    "-e:1: error: unterminated definition at end of text\n" '5 .\n' -e ': half 1 2'
t "unterminated definition at end of piped input" 1 "" \
    "stdin:2: error: unterminated definition at end of input\n" ': half\n1 2\n'
printf '1 . bye\n2 .\n' >bye.fbrl
t "BYE in a file ends the session" 0 "1 " "" '3 .\n' "$tmp/bye.fbrl" "$src/mon_basic.fbrl"
t "BYE in piped input" 0 "1 " "" '1 .\nbye\n2 .\n'
t "KEY reads the bytes after the current line" 0 "AB3 " "" 'key emit key emit\nAB\n3 .\n'
printf '#!%s --offline\n: hi ." hello" cr ;\nhi\n' "$mon" >script.fbrl
chmod +x script.fbrl
count=$((count + 1))
if [ "$(./script.fbrl </dev/null)" != "hello" ]; then
    fails=$((fails + 1))
    echo "FAIL: executable plan file with #! line: $(./script.fbrl </dev/null 2>&1)"
fi
printf '#!fbrlmon\nnosuch\n' >lines.fbrl
t "#! line keeps line numbers" 1 "" "$tmp/lines.fbrl:2: error: undefined word nosuch\n" "" "$tmp/lines.fbrl"
t "WORDS lists the dictionary" 0 "*" "" 'words\n'
grep -qiw dup out.txt && grep -qiw words out.txt || { fails=$((fails + 1)); echo "FAIL: WORDS output lacks DUP/WORDS"; }
t "HELP shows a word's stack effect" 0 "*" "" 'help dup\n'
grep -qi 'dup' out.txt && grep -q -- '--' out.txt || { fails=$((fails + 1)); echo "FAIL: HELP DUP output: $(cat out.txt)"; }
t "--dict: a small dictionary runs out, the session goes on" 1 "7 " "~^stdin:1: error: dictionary overflow.*$" \
    ': fill-up 100000 0 do 0 , loop ; fill-up\n7 .\n' --dict 64K
t "--dict 0" 2 "" "~*bad size" "" --dict 0
t "--dict not a size" 2 "" "~*bad size" "" --dict lots
t "unknown option" 2 "" "~*unknown option" "" --bogus
t "-e without its text" 2 "" "~*needs an argument" "" -e
t "--help" 0 "*" "" "" --help
grep -q '^usage: fbrlmon' out.txt || { fails=$((fails + 1)); echo "FAIL: --help output"; }
t "--version" 0 "*" "" "" --version
grep -q '^fbrlmon (libfbrl) [0-9]' out.txt || { fails=$((fails + 1)); echo "FAIL: --version output"; }

echo "mon_script: $count runs, $fails failed"
[ "$fails" = 0 ]
