\ method.fs - the method words: declaring, running, parameters with their ranges.
\ Run by tests/unit/test_method.c (which also watches the runs through the C observer).
\ A declaration takes the rest of its line as its description, so each stands on its own line.
DECIMAL
VARIABLE TRACE   0 TRACE !
: T+ ( n -- ) TRACE @ 10 * + TRACE ! ;
: PREP ( -- ) 1 T+ ;
: EACH ( i -- ) 2 + T+ ;
: SAFE ( -- ) 9 T+ ;
METHOD DEMO  a demonstration method
1 5 2 SAMPLES-PARAM #TUBES tubes  how many tubes
0 60 10 PARAM SOAK-MIN min  soaking time
' PREP STEP Prepare  get ready
' EACH SAMPLE-STEP Treat  treat one tube
' SAFE ON-ABORT
END-METHOD
T{ #TUBES SOAK-MIN -> 2 10 }T
T{ DEMO RUN-METHOD TRACE @ -> 123 }T
4 PARAM! #TUBES
T{ 0 TRACE !  #TUBES -> 4 }T
T{ DEMO RUN-METHOD TRACE @ -> 12345 }T
\ out of range is refused and changes nothing
: SET-TUBES ( n -- ) S" PARAM! #TUBES" EVALUATE ;
T{ 6 ' SET-TUBES CATCH NIP #TUBES -> -24 4 }T
T{ 0 ' SET-TUBES CATCH NIP #TUBES -> -24 4 }T
T{ 3 ' SET-TUBES CATCH #TUBES -> 0 3 }T
\ declarations need a method being declared
: BAD-DEFAULT ( -- ) S" 1 5 9 PARAM X n x" EVALUATE ;
: EACH-STEP ( -- ) S" ' EACH SAMPLE-STEP Each each" EVALUATE ;
T{ ' END-METHOD CATCH -> -32 }T
T{ ' BAD-DEFAULT CATCH -> -32 }T
METHOD EMPTY  nothing in it yet
T{ ' END-METHOD CATCH -> -32 }T    \ a method needs a step
T{ ' BAD-DEFAULT CATCH -> -24 }T   \ default 9 outside 1..5
T{ ' EACH-STEP CATCH -> -32 }T     \ a SAMPLE-STEP needs a SAMPLES-PARAM
T{ EMPTY ' RUN-METHOD CATCH NIP -> -32 }T   \ not complete
' PREP STEP Only  the only step
END-METHOD
T{ 0 TRACE !  EMPTY RUN-METHOD TRACE @ -> 1 }T
T{ 5 ' RUN-METHOD CATCH NIP -> -12 }T    \ not a method
\ a step that fails ends the run
: BOOM ( -- ) 7 T+ -77 THROW ;
METHOD FAILING  a step throws
' PREP STEP One  one
' BOOM STEP Two  two
' PREP STEP Three  three
END-METHOD
T{ 0 TRACE !  FAILING ' RUN-METHOD CATCH NIP TRACE @ -> -77 17 }T
\ a method declared again is replaced, not added
METHOD EMPTY  declared again
' SAFE STEP Again  again
END-METHOD
T{ 0 TRACE !  EMPTY RUN-METHOD TRACE @ -> 9 }T
T{ DEMO .METHOD -> }T
T{ METHODS -> }T
\ a method composed of DEMO's steps shares DEMO's parameters
METHOD PART  DEMO's second step alone
DEMO USE-PARAMS
' EACH SAMPLE-STEP Treat  treat one tube
END-METHOD
T{ 0 TRACE !  2 PARAM! #TUBES  PART RUN-METHOD TRACE @ #TUBES -> 23 2 }T
T{ DEMO ' USE-PARAMS CATCH NIP -> -32 }T   \ no method is being declared
