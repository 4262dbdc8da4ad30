\ sieve.fs - the Byte sieve of Eratosthenes (8190 flags), repeated: memory, loops.
8190 constant size
create flags size allot
: sieve ( -- count )
  flags size 1 fill
  0 size 0 do
    flags i + c@ if
      i 2* 3 +  dup i +
      begin dup size < while  0 over flags + c!  over + repeat
      drop drop 1+
    then
  loop ;
: sieves ( n -- count )  0 swap 0 do drop sieve loop ;
400 sieves . cr
