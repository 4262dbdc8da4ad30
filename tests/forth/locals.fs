\ locals.fs - the LOCALS word set: {: args | vals -- outs :}, TO, (LOCAL), LOCALS|
DECIMAL
T{ : L1 {: A B :} B A ; 1 2 L1 -> 2 1 }T
T{ : L2 {: A | B C -- D :} B C A ; 5 L2 -> 0 0 5 }T
T{ : L3 {: A :} A 10 + TO A A ; 1 L3 -> 11 }T
\ locals stay usable inside DO loops and around >R R>, where the return stack is busy
T{ : L4 {: N :} 0 N 0 DO I N + + LOOP ; 3 L4 -> 12 }T
T{ : L5 {: A :} 7 >R A R> + ; 1 L5 -> 8 }T
\ EXIT inside a definition with locals drops its frame: the caller's stay intact
: L6 {: A :} A 0= IF 99 EXIT THEN A ;
T{ : L7 {: X :} 0 L6 1 L6 X ; 42 L7 -> 99 1 42 }T
\ recursion: every call has its own frame
T{ : L8 {: N :} N 0= IF 1 ELSE N 1- RECURSE N * THEN ; 6 L8 -> 720 }T
\ THROW through definitions with locals: CATCH puts the locals stack back
: L9 {: A :} A 0= IF -77 THROW THEN A ;
T{ : L10 {: B :} 0 ['] L9 CATCH NIP B ; 5 L10 -> -77 5 }T
\ DOES> ends the creating part's locals; the DOES> part may have its own
T{ : L11 {: N :} CREATE N , DOES> @ {: V :} V 2* ; 21 L11 L12 L12 -> 42 }T
\ LOCALS| and (LOCAL): the first name takes the top of the stack
T{ : L13 LOCALS| A B | A B ; 1 2 L13 -> 2 1 }T
\ locals are compile-only
T{ S" {: A :}" ' EVALUATE CATCH NIP NIP -> -14 }T
\ a local shadows a word of the same name only inside its definition
T{ : L15 {: DUP :} DUP ; 3 L15 4 DUP -> 3 4 4 }T
