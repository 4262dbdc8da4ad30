\ matrix.fs - integer matrix product C = A x B of 40 x 40 matrices, 150
\ times: nested loops, index arithmetic, stack shuffling, fetches through two
\ strides. Prints the sum of C's elements.
40 constant n
: matrix ( "name" -- )  create n n * cells allot ;
matrix ma  matrix mb  matrix mc
: elem ( m row col -- a )  swap n * + cells + ;
: init ( -- )
  n 0 do  n 0 do
    i j + 7 mod 3 -  ma j i elem !
    i j * 5 mod 2 -  mb j i elem !
  loop loop ;
: dot ( a-row b-col -- n )
  0  n 0 do  2 pick @  2 pick @  * +  rot cell+  rot n cells +  rot  loop  nip nip ;
: product ( -- )
  n 0 do  n 0 do  ma j 0 elem  mb 0 i elem  dot  mc j i elem !  loop loop ;
: sum ( m -- n )  0  n n * 0 do  over i cells + @ +  loop  nip ;
: products ( -- n )  init  0  150 0 do  product  mc sum +  loop ;
products . cr
