\ bubble.fs - bubble sort of 3000 pseudo-random cells, three times: nested
\ loops, indexed memory access, compare and swap. Prints a checksum of the
\ sorted array (and -1 if it is not in order).
3000 constant items
create sortlist items cells allot
variable seed
: random ( -- n )  seed @ 1103515245 * 12345 + 2147483647 and dup seed ! ;
: fill-sortlist ( -- )  items 0 do  random 1000000 mod  sortlist i cells + !  loop ;
: bubble ( -- )
  items 1 do
    sortlist  items i - 0 do
      dup @ over cell+ @  2dup > if  2 pick !  over cell+ !  else 2drop then
      cell+
    loop drop
  loop ;
: sorted? ( -- flag )
  true  items 1- 0 do  sortlist i cells + dup @ swap cell+ @ > if drop false then  loop ;
: checksum ( -- n )  0  items 0 do  31 *  sortlist i cells + @ +  loop ;
: bubbles ( -- n )  0  3 0 do  i seed !  fill-sortlist bubble  checksum +  sorted? and  loop ;
bubbles . cr
