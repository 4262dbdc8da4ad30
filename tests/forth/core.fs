\ core.fs - Forth-2012 CORE word set
DECIMAL
0 CONSTANT 0S   0 INVERT CONSTANT 1S
1S 1 RSHIFT CONSTANT MAX-INT   MAX-INT INVERT CONSTANT MIN-INT
1S CONSTANT MAX-UINT
0S CONSTANT <FALSE>   1S CONSTANT <TRUE>

\ basic assumptions and booleans
T{ -> }T
T{ : BITSSET? IF 0 0 ELSE 0 THEN ; -> }T
T{ 0 BITSSET? -> 0 }T
T{ 1 BITSSET? -> 0 0 }T
T{ 0 0 AND -> 0 }T   T{ 1 1 AND -> 1 }T   T{ 0S 1S AND -> 0S }T
T{ 0S 0S OR -> 0S }T  T{ 0S 1S OR -> 1S }T
T{ 1S 1S XOR -> 0S }T T{ 0S 1S XOR -> 1S }T
T{ 0S INVERT -> 1S }T T{ 1S INVERT -> 0S }T

\ shifts
T{ 1 2* -> 2 }T   T{ 4000 2* -> 8000 }T   T{ 1S 2* 1 XOR -> 1S }T
T{ MIN-INT 2* -> 0S }T
T{ 1 2/ -> 0 }T   T{ 4000 2/ -> 2000 }T   T{ 1S 2/ -> 1S }T   T{ MIN-INT 2/ MIN-INT AND -> MIN-INT }T
T{ 1 0 LSHIFT -> 1 }T  T{ 1 1 LSHIFT -> 2 }T  T{ 1 2 LSHIFT -> 4 }T  T{ 1S 1 LSHIFT 1 XOR -> 1S }T
T{ 1 0 RSHIFT -> 1 }T  T{ 1 1 RSHIFT -> 0 }T  T{ 4 2 RSHIFT -> 1 }T  T{ MIN-INT 1 RSHIFT MIN-INT AND -> 0 }T

\ comparisons
T{ 0 0= -> <TRUE> }T  T{ 1 0= -> <FALSE> }T  T{ -1 0= -> <FALSE> }T
T{ 0 0 = -> <TRUE> }T T{ 1 -1 = -> <FALSE> }T
T{ 0 0< -> <FALSE> }T T{ -1 0< -> <TRUE> }T T{ MIN-INT 0< -> <TRUE> }T
T{ 0 1 < -> <TRUE> }T T{ 1 2 < -> <TRUE> }T T{ -1 0 < -> <TRUE> }T T{ MIN-INT MAX-INT < -> <TRUE> }T
T{ 0 0 < -> <FALSE> }T T{ MAX-INT MIN-INT < -> <FALSE> }T
T{ 0 1 > -> <FALSE> }T T{ 1 0 > -> <TRUE> }T T{ MAX-INT MIN-INT > -> <TRUE> }T
T{ 0 1 U< -> <TRUE> }T T{ 1 2 U< -> <TRUE> }T T{ 0 MAX-UINT U< -> <TRUE> }T T{ MAX-UINT 0 U< -> <FALSE> }T
T{ 0 1 MIN -> 0 }T T{ MIN-INT MAX-INT MIN -> MIN-INT }T T{ -1 1 MIN -> -1 }T
T{ 0 1 MAX -> 1 }T T{ MIN-INT MAX-INT MAX -> MAX-INT }T T{ -1 1 MAX -> 1 }T

\ stack
T{ 1 2 2DROP -> }T     T{ 1 2 2DUP -> 1 2 1 2 }T  T{ 1 2 3 4 2OVER -> 1 2 3 4 1 2 }T
T{ 1 2 3 4 2SWAP -> 3 4 1 2 }T  T{ 0 ?DUP -> 0 }T  T{ 1 ?DUP -> 1 1 }T  T{ -1 ?DUP -> -1 -1 }T
T{ DEPTH -> 0 }T  T{ 0 DEPTH -> 0 1 }T  T{ 0 1 DEPTH -> 0 1 2 }T
T{ 0 DROP -> }T  T{ 1 2 DROP -> 1 }T  T{ 1 DUP -> 1 1 }T  T{ 1 2 OVER -> 1 2 1 }T
T{ 1 2 3 ROT -> 2 3 1 }T  T{ 1 2 SWAP -> 2 1 }T

\ return stack
T{ : GR1 >R R> ; -> }T  T{ : GR2 >R R@ R> DROP ; -> }T
T{ 123 GR1 -> 123 }T  T{ 123 GR2 -> 123 }T  T{ 1S GR1 -> 1S }T

\ arithmetic
T{ 0 5 + -> 5 }T T{ 5 0 + -> 5 }T T{ 0 -5 + -> -5 }T T{ -1 1 + -> 0 }T
T{ MAX-INT 1 + -> MIN-INT }T   \ wraps, no UB
T{ 0 5 - -> -5 }T T{ 5 0 - -> 5 }T T{ 0 -5 - -> 5 }T T{ MIN-INT 1 - -> MAX-INT }T
T{ 0 1+ -> 1 }T T{ -1 1+ -> 0 }T T{ 2 1- -> 1 }T T{ 0 1- -> -1 }T
T{ 0 NEGATE -> 0 }T T{ 1 NEGATE -> -1 }T T{ -2 NEGATE -> 2 }T T{ MIN-INT NEGATE -> MIN-INT }T
T{ 0 ABS -> 0 }T T{ -1 ABS -> 1 }T T{ MIN-INT ABS -> MIN-INT }T
T{ 0 S>D -> 0 0 }T T{ -1 S>D -> -1 -1 }T T{ MAX-INT S>D -> MAX-INT 0 }T
T{ 0 0 * -> 0 }T T{ 1 2 * -> 2 }T T{ -1 -1 * -> 1 }T T{ MAX-INT 2 * -> -2 }T
T{ 0 0 M* -> 0 S>D }T T{ -1 1 M* -> -1 S>D }T T{ -1 -1 M* -> 1 0 }T
T{ MAX-INT MAX-INT M* -> 1 MAX-INT 1 RSHIFT }T
T{ 0 0 UM* -> 0 0 }T T{ 2 3 UM* -> 6 0 }T T{ MAX-UINT 2 UM* -> MAX-UINT 1- 1 }T T{ MAX-UINT MAX-UINT UM* -> 1 MAX-UINT 1- }T
\ floored division (FBRL's / MOD /MOD */ are floored, as in F83 and F-PC)
T{ 7 2 / -> 3 }T T{ -7 2 / -> -4 }T T{ 7 -2 / -> -4 }T T{ -7 -2 / -> 3 }T
T{ 7 2 MOD -> 1 }T T{ -7 2 MOD -> 1 }T T{ 7 -2 MOD -> -1 }T T{ -7 -2 MOD -> -1 }T
T{ 7 2 /MOD -> 1 3 }T T{ -7 2 /MOD -> 1 -4 }T
T{ MIN-INT -1 / -> MIN-INT }T
T{ 0 S>D 1 FM/MOD -> 0 0 }T T{ 7 S>D 2 FM/MOD -> 1 3 }T T{ -7 S>D 2 FM/MOD -> 1 -4 }T T{ 7 S>D -2 FM/MOD -> -1 -4 }T
T{ 7 S>D 2 SM/REM -> 1 3 }T T{ -7 S>D 2 SM/REM -> -1 -3 }T T{ 7 S>D -2 SM/REM -> 1 -3 }T T{ -7 S>D -2 SM/REM -> -1 3 }T
T{ 0 0 1 UM/MOD -> 0 0 }T T{ 3 0 2 UM/MOD -> 1 1 }T T{ MAX-UINT 2 UM* 2 UM/MOD -> 0 MAX-UINT }T
T{ 5 7 3 */ -> 11 }T T{ -5 7 3 */ -> -12 }T T{ MAX-INT 2 4 */ -> MAX-INT 2/ }T
T{ 5 7 3 */MOD -> 2 11 }T
T{ 1 2 3 WITHIN -> <FALSE> }T T{ 2 2 3 WITHIN -> <TRUE> }T T{ 3 2 3 WITHIN -> <FALSE> }T T{ -1 -5 5 WITHIN -> <TRUE> }T

\ memory
HERE 1 ALLOT HERE CONSTANT 2NDA CONSTANT 1STA
T{ 1STA 2NDA U< -> <TRUE> }T
T{ 1STA 1+ -> 2NDA }T
HERE 1 , HERE 2 , CONSTANT 2ND CONSTANT 1ST
T{ 1ST 2ND U< -> <TRUE> }T T{ 1ST CELL+ -> 2ND }T T{ 1ST 1 CELLS + -> 2ND }T
T{ 1ST @ 2ND @ -> 1 2 }T T{ 5 1ST ! -> }T T{ 1ST @ 2ND @ -> 5 2 }T
T{ 1ST 2@ -> 2 5 }T T{ 3 4 1ST 2! 1ST @ 2ND @ -> 4 3 }T
T{ 0 1ST ! 1 1ST +! 1ST @ -> 1 }T T{ -1 1ST +! 1ST @ -> 0 }T
HERE 1 C, HERE 2 C, CONSTANT 2NDC CONSTANT 1STC
T{ 1STC C@ 2NDC C@ -> 1 2 }T T{ 3 1STC C! 1STC C@ -> 3 }T T{ 1STC CHAR+ -> 2NDC }T
ALIGN 1 ALLOT HERE ALIGN HERE 3 CELLS ALLOT CONSTANT A-ADDR CONSTANT UA-ADDR
T{ UA-ADDR ALIGNED -> A-ADDR }T
T{ 1 CELLS 1 CHARS MOD -> 0 }T T{ 1 CHARS -> 1 }T
VARIABLE V1
T{ 123 V1 ! V1 @ -> 123 }T
T{ 1 CELLS 8 = 1 CELLS 4 = OR -> <TRUE> }T
T{ PAD 20 CHAR A FILL PAD C@ PAD 19 + C@ -> CHAR A CHAR A }T
CREATE FBUF 10 ALLOT
T{ S" abc" FBUF SWAP MOVE FBUF C@ FBUF 2 + C@ -> CHAR a CHAR c }T
T{ FBUF 1+ FBUF 2 MOVE FBUF C@ -> CHAR b }T
T{ UNUSED 0> -> <TRUE> }T

\ control structures
T{ : GI1 IF 123 THEN ; -> }T T{ : GI2 IF 123 ELSE 234 THEN ; -> }T
T{ 0 GI1 -> }T T{ 1 GI1 -> 123 }T T{ -1 GI1 -> 123 }T T{ 0 GI2 -> 234 }T T{ 1 GI2 -> 123 }T
T{ : GI3 BEGIN DUP 5 < WHILE DUP 1+ REPEAT ; -> }T
T{ 0 GI3 -> 0 1 2 3 4 5 }T T{ 4 GI3 -> 4 5 }T T{ 5 GI3 -> 5 }T T{ 6 GI3 -> 6 }T
T{ : GI4 BEGIN DUP 1+ DUP 5 > UNTIL ; -> }T
T{ 3 GI4 -> 3 4 5 6 }T T{ 5 GI4 -> 5 6 }T T{ 6 GI4 -> 6 7 }T
T{ : GI5 BEGIN DUP 2 > WHILE DUP 5 < WHILE DUP 1+ REPEAT 123 ELSE 345 THEN ; -> }T
T{ 1 GI5 -> 1 345 }T T{ 2 GI5 -> 2 345 }T T{ 3 GI5 -> 3 4 5 123 }T T{ 4 GI5 -> 4 5 123 }T T{ 5 GI5 -> 5 123 }T
T{ : GI6 ( N -- 0,1,..N ) DUP IF DUP >R 1- RECURSE R> THEN ; -> }T
T{ 0 GI6 -> 0 }T T{ 1 GI6 -> 0 1 }T T{ 4 GI6 -> 0 1 2 3 4 }T
T{ : GD1 DO I LOOP ; -> }T
T{ 4 1 GD1 -> 1 2 3 }T T{ 2 -1 GD1 -> -1 0 1 }T
T{ : GD2 DO I -1 +LOOP ; -> }T
T{ 1 4 GD2 -> 4 3 2 1 }T T{ -1 2 GD2 -> 2 1 0 -1 }T
T{ : GD3 DO 1 0 DO J LOOP LOOP ; -> }T
T{ 4 1 GD3 -> 1 2 3 }T
T{ : GD5 123 SWAP 0 DO I 4 > IF DROP 234 LEAVE THEN LOOP ; -> }T
T{ 1 GD5 -> 123 }T T{ 5 GD5 -> 123 }T T{ 6 GD5 -> 234 }T
T{ : GD6 0 SWAP 0 DO I 1+ 0 DO I J + 3 = IF I UNLOOP I UNLOOP EXIT THEN 1+ LOOP LOOP ; -> }T
T{ 1 GD6 -> 1 }T T{ 2 GD6 -> 3 }T T{ 3 GD6 -> 4 1 2 }T
T{ : GD7 10 0 DO I 3 +LOOP ; -> }T  T{ GD7 -> 0 3 6 9 }T
T{ : GD8 0 10 DO I -3 +LOOP ; -> }T T{ GD8 -> 10 7 4 1 }T
T{ : GD9 0 0 ?DO I LOOP 123 ; -> }T T{ GD9 -> 123 }T

\ defining words
T{ 123 CONSTANT X123 -> }T T{ X123 -> 123 }T T{ : EQU CONSTANT ; -> }T T{ X123 EQU Y123 -> }T T{ Y123 -> 123 }T
T{ VARIABLE V2 -> }T T{ 222 V2 ! -> }T T{ V2 @ -> 222 }T
T{ : NOP : POSTPONE ; ; -> }T T{ NOP NOP1 NOP NOP2 -> }T T{ NOP1 -> }T
T{ : DOES1 DOES> @ 1 + ; -> }T T{ : DOES2 DOES> @ 2 + ; -> }T
T{ CREATE CR1 -> }T T{ CR1 -> HERE }T T{ ' CR1 >BODY -> HERE }T
T{ 1 , -> }T T{ CR1 @ -> 1 }T T{ DOES1 -> }T T{ CR1 -> 2 }T T{ DOES2 -> }T T{ CR1 -> 3 }T
T{ : WEIRD: CREATE DOES> 1 + DOES> 2 + ; -> }T T{ WEIRD: W1 -> }T
T{ ' W1 >BODY -> HERE }T T{ W1 -> HERE 1 + }T T{ W1 -> HERE 2 + }T
T{ : GT1 123 ; -> }T T{ ' GT1 EXECUTE -> 123 }T
T{ : GT2 ['] GT1 ; IMMEDIATE -> }T T{ GT2 EXECUTE -> 123 }T
HERE 3 C, CHAR G C, CHAR T C, CHAR 1 C, CONSTANT GT1STRING
HERE 3 C, CHAR G C, CHAR T C, CHAR 2 C, CONSTANT GT2STRING
T{ GT1STRING FIND -> ' GT1 -1 }T T{ GT2STRING FIND -> ' GT2 1 }T
T{ : GT3 GT2 LITERAL ; -> }T T{ GT3 -> ' GT1 }T
T{ GT1STRING COUNT -> GT1STRING CHAR+ 3 }T
T{ : GT4 POSTPONE GT1 ; IMMEDIATE -> }T T{ : GT5 GT4 ; -> }T T{ GT5 -> 123 }T
T{ : GT6 345 ; IMMEDIATE -> }T T{ : GT7 POSTPONE GT6 ; -> }T T{ GT7 -> 345 }T
T{ : GT8 STATE @ ; IMMEDIATE -> }T T{ GT8 -> 0 }T T{ : GT9 GT8 LITERAL ; -> }T T{ GT9 0= -> <FALSE> }T
T{ : GC1 [CHAR] X ; -> }T T{ : GC2 [CHAR] HELLO ; -> }T T{ GC1 -> 88 }T T{ GC2 -> 72 }T
T{ : GC3 [ GC1 ] LITERAL ; -> }T T{ GC3 -> 88 }T
T{ : GC4 S" XY" ; -> }T T{ GC4 SWAP DROP -> 2 }T T{ GC4 DROP DUP C@ SWAP CHAR+ C@ -> 88 89 }T
T{ CHAR X -> 88 }T T{ CHAR HELLO -> 72 }T
: GS1 S" SAMPLE" ;
T{ GS1 SWAP DROP -> 6 }T
T{ : GN2 BASE @ >R HEX BASE @ DECIMAL BASE @ R> BASE ! ; -> }T T{ GN2 -> 16 10 }T

\ EVALUATE, SOURCE, >IN, WORD
: GE1 S" 123" ; IMMEDIATE  : GE2 S" 123 1+" ; IMMEDIATE
: GE3 S" : GE4 345 ;" ;    : GE5 EVALUATE ; IMMEDIATE
T{ GE1 EVALUATE -> 123 }T T{ GE2 EVALUATE -> 124 }T T{ GE3 EVALUATE -> }T T{ GE4 -> 345 }T
T{ : GE6 GE1 GE5 ; -> }T T{ GE6 -> 123 }T T{ : GE7 GE2 GE5 ; -> }T T{ GE7 -> 124 }T
: GS3 WORD COUNT SWAP C@ ;
T{ BL GS3 HELLO -> 5 CHAR H }T T{ CHAR " GS3 GOODBYE" -> 7 CHAR G }T
T{ BL GS3
DROP -> 0 }T
T{ SOURCE SWAP DROP 0> -> <TRUE> }T
: GS4 SOURCE >IN ! DROP ;
T{ GS4 123 456
-> }T
T{ : RS3 ( -- ) ; -> }T

\ number conversion and text interpreter syntax
T{ #10 -> 10 }T T{ $10 -> 16 }T T{ %10 -> 2 }T T{ 'A' -> 65 }T T{ $-10 -> -16 }T T{ #-10 -> -10 }T
T{ 10. -> 10 0 }T T{ -10. -> -10 -1 }T
HEX T{ FF -> #255 }T T{ ff -> #255 }T DECIMAL
: S123 S" 123" ;
T{ 0 0 S123 >NUMBER -> 123 0 S123 + 0 }T
T{ 0 0 S" 12a" >NUMBER SWAP DROP -> 12 0 1 }T

\ pictured output
: PIC ( d -- a u ) <# #S #> ;
: PICSTR ( a u a2 u2 -- flag ) COMPARE 0= ;
T{ 123 0 PIC S" 123" PICSTR -> <TRUE> }T
T{ <# 1 0 # # #> S" 01" PICSTR -> <TRUE> }T
T{ <# -5 DUP ABS 0 #S ROT SIGN #> S" -5" PICSTR -> <TRUE> }T
T{ <# 0 0 #S CHAR X HOLD #> S" X0" PICSTR -> <TRUE> }T
T{ <# 12 0 #S S" ab" HOLDS #> S" ab12" PICSTR -> <TRUE> }T
HEX T{ #255 0 PIC S" FF" PICSTR -> <TRUE> }T DECIMAL
T{ MAX-UINT MAX-UINT PIC SWAP DROP 0> -> <TRUE> }T

\ case insensitivity (as in F-PC)
T{ : MixedCase 7 ; -> }T T{ mixedcase MIXEDCASE -> 7 7 }T T{ 1 dup DUP Dup -> 1 1 1 1 }T

\ comments
T{ ( a comment ) 1 -> 1 }T
T{ 2 \ rest of line
-> 2 }T
T{ : CM1 ( n -- n ) ( multi
line comment ) 1+ ; 1 CM1 -> 2 }T

\ ENVIRONMENT?
T{ S" MAX-N" ENVIRONMENT? -> MAX-INT <TRUE> }T
T{ S" NO-SUCH-QUERY" ENVIRONMENT? -> <FALSE> }T
T{ S" FLOORED" ENVIRONMENT? -> <TRUE> <TRUE> }T
