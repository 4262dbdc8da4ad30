\ loops.fs - nested DO loops with I and J: loop overhead and stack arithmetic.
: inner ( acc -- acc' )  1000 0 do  1000 0 do  i j xor +  loop loop ;
: loops ( -- n )  0  30 0 do inner loop ;
loops . cr
