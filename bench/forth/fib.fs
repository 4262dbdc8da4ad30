\ fib.fs - doubly recursive Fibonacci fib(30), five times: calls, returns, branches.
: fib ( n -- fib[n] )  dup 2 < if exit then  dup 1- recurse  swap 2 - recurse + ;
: fibs ( -- n )  0  5 0 do drop 30 fib loop ;
fibs . cr
