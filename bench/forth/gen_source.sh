#!/bin/sh
# SPDX-License-Identifier: MIT
# gen_source.sh N - write a large standard-Forth source text to stdout: N colon
# definitions, each compiled and then run by an interpreted line, for the
# "compile and interpret" benchmark. MARKER forgets each batch of 100 so the
# text fits small dictionaries (pforth's). The checksum printed at the end lets
# the runner compare the systems' answers.
n=${1:-5000}
awk -v n="$n" 'BEGIN {
  print "\\ generated: " n " definitions, compiled then interpreted";
  print "variable acc  0 acc !";
  print "marker batch";
  for (i = 1; i <= n; i++) {
    printf ": cw%d ( n -- n2 )  dup %d + swap 2* xor 65535 and\n", i, i;
    printf "  dup 1 and if 3 + else 7 + then  ( odd? ) dup 3 rshift + ;\n";
    printf "%d cw%d acc +!  \\ run it once\n", (i * 7919) % 1000, i;
    if (i % 100 == 0) print "batch marker batch";
  }
  print "acc @ . cr";
}'
