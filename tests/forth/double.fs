\ double.fs - DOUBLE-NUMBER basics
DECIMAL
0 INVERT CONSTANT MAX-UINT   MAX-UINT 1 RSHIFT CONSTANT MAX-INT   MAX-INT INVERT CONSTANT MIN-INT
T{ 1. -> 1 0 }T T{ -2. -> -2 -1 }T
T{ 1 2 3 4 D+ -> 4 6 }T T{ -1. 1. D+ -> 0. }T T{ MAX-UINT 0 1. D+ -> 0 1 }T
T{ 4 6 3 4 D- -> 1 2 }T T{ 0. 1. D- -> -1. }T T{ 0 1 1. D- -> MAX-UINT 0 }T
T{ 1. DNEGATE -> -1. }T T{ 0. DNEGATE -> 0. }T T{ 0 1 DNEGATE -> 0 -1 }T
T{ -5. DABS -> 5. }T T{ 5. DABS -> 5. }T
T{ 1. 1. D= -> TRUE }T T{ 1. 2. D= -> FALSE }T T{ 0 1 0 2 D= -> FALSE }T
T{ 1. 2. D< -> TRUE }T T{ -1. 1. D< -> TRUE }T T{ 1. -1. D< -> FALSE }T T{ 0 1 MAX-UINT 0 D< -> FALSE }T
T{ 0. D0= 1. D0= 0 1 D0= -> TRUE FALSE FALSE }T
T{ -1. D0< 1. D0< -> TRUE FALSE }T
T{ 1. D2* -> 2. }T T{ MAX-UINT 0 D2* -> MAX-UINT 1- 1 }T T{ 0 1 D2/ -> MIN-INT 0 }T T{ -2. D2/ -> -1. }T
T{ 1. 2. DMAX -> 2. }T T{ 1. 2. DMIN -> 1. }T T{ -1. 1. DMAX -> 1. }T
T{ 1. 5 M+ -> 6. }T T{ MAX-UINT 0 1 M+ -> 0 1 }T T{ 5. -6 M+ -> -1. }T
T{ 5 S>D -> 5. }T T{ -5 S>D D>S -> -5 }T T{ 5. D>S -> 5 }T
T{ 2. 3 2 M*/ -> 3. }T T{ -2. 3 2 M*/ -> -3. }T T{ MAX-INT S>D 2 2 M*/ -> MAX-INT S>D }T
T{ 1. 1 0 ' M*/ CATCH NIP NIP NIP NIP -> -10 }T
T{ 5 6 2CONSTANT 2C 2C -> 5 6 }T
T{ 2VARIABLE 2V 7 8 2V 2! 2V 2@ -> 7 8 }T
T{ : 2L [ 9 10 ] 2LITERAL ; 2L -> 9 10 }T
T{ 1 2 3 4 5 6 2ROT -> 3 4 5 6 1 2 }T
T{ 1. 2. DU< MAX-UINT 0 1. DU< -> TRUE FALSE }T
: PIC <# #S #> ;
T{ 1 CELLS 8 = [IF] 0 1 PIC S" 18446744073709551616" COMPARE [ELSE] 0 [THEN] -> 0 }T
\ M*/ keeps a triple-cell intermediate: the extremes come back whole
0 INVERT 1 RSHIFT CONSTANT MAX-N  MAX-N INVERT CONSTANT MIN-N
T{ 0 MIN-N MAX-N DUP M*/ -> 0 MIN-N }T
T{ -1 MAX-N MAX-N DUP M*/ -> -1 MAX-N }T
: M*/-CODE ( d n +n -- code ) ['] M*/ CATCH >R 2DROP 2DROP R> ;
T{ 0 MIN-N MAX-N NEGATE MAX-N M*/-CODE -> -11 }T  \ -MIN-2INT does not fit
T{ 0 MIN-N 2 1 M*/-CODE -> -11 }T
