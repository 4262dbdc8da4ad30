\ fploop.fs - a floating-point loop: sum of 1/k^2 (tends to pi^2/6) and a
\ Newton square root per step: float stack, arithmetic, int/float conversion.
: fsqrt-newton ( F: x -- sqrt[x] )  fdup  8 0 do  fover fover f/ f+ 0.5e0 f*  loop  fswap fdrop ;
: basel ( n -- ) ( F: -- sum )
  0e0  1+ 1 do  1e0 i s>f fdup f* f/ f+  i s>f fsqrt-newton fdrop  loop ;
1000000 basel  1000000e0 f* f>s . cr
