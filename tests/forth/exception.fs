\ exception.fs - CATCH THROW ABORT ABORT"
DECIMAL
: T1 9 ;
: C1 1 2 3 ['] T1 CATCH ;
T{ C1 -> 1 2 3 9 0 }T
: T2 8 0 THROW ;
T{ 1 2 ' T2 CATCH -> 1 2 8 0 }T
: T3 7 8 9 99 THROW ;
: C3 1 2 ['] T3 CATCH ;
T{ C3 -> 1 2 99 }T
: T4 1- DUP 0> IF RECURSE ELSE 999 THROW -222 THEN ;
: C4 3 4 5 10 ['] T4 CATCH -111 ;
T{ C4 -> 3 4 5 0 999 -111 }T
: T5 2DROP 2DROP 9999 THROW ;
: C5 1 2 3 4 ['] T5 CATCH DEPTH >R DROP 2DROP 2DROP R> ;
T{ C5 -> 5 }T
\ nested CATCH frames unwind one at a time
: INNER 1 THROW ;
: MIDDLE ['] INNER CATCH 10 + THROW ;
T{ ' MIDDLE CATCH -> 11 }T
\ the float stack is restored too
: TF 1E0 2E0 3 THROW ;
T{ 5E0 ' TF CATCH -> 3 5E0 }T
\ ABORT and ABORT"
T{ ' ABORT CATCH -> -1 }T
: AB1 ( flag -- ) ABORT" abort message" 42 ;
T{ 0 ' AB1 CATCH -> 42 0 }T
T{ 1 ' AB1 CATCH NIP -> -2 }T
\ system errors are THROW codes
T{ 1 0 ' / CATCH NIP NIP -> -10 }T
T{ ' DROP CATCH -> -4 }T
T{ 0 ' @ CATCH NIP -> -9 }T
T{ S" NO-SUCH-WORD" ' EVALUATE CATCH NIP NIP -> -13 }T
T{ 1E0 0E0 ' F/ CATCH FDROP -> 0 }T  \ IEEE: +Inf, no exception
T{ : TH0 0 THROW 5 ; TH0 -> 5 }T
\ user codes pass through unchanged
T{ -1000 ' THROW CATCH NIP -> -1000 }T
T{ 12345 ' THROW CATCH NIP -> 12345 }T
\ CATCH inside a DO loop keeps the loop intact
: CL 0 5 0 DO I 2 = IF ['] INNER CATCH + ELSE I + THEN LOOP ;
T{ CL -> 9 }T
\ errors in EVALUATE inside CATCH restore the input source
T{ S" 1 2 NO-SUCH-WORD" ' EVALUATE CATCH NIP NIP -> -13 }T
T{ 77 -> 77 }T
