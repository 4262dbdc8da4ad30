\ tools.fs - TOOLS and FACILITY words (their output is checked by test_vm.c)
DECIMAL
T{ 1 2 .S -> 1 2 }T
T{ 1E0 .S -> 1E0 }T
VARIABLE TV 5 TV !
T{ TV ? -> }T
T{ PAD 16 DUMP -> }T
T{ SEE DUP -> }T
T{ : SEEME 1 IF 2 ELSE 3 THEN ; SEE SEEME -> }T

T{ : AH AHEAD 1 THEN 2 ; AH -> 2 }T
T{ 0 MS -> }T
T{ TIME&DATE NIP NIP NIP NIP NIP 2000 > -> TRUE }T
T{ TIME&DATE DROP DROP DROP DROP 0 60 WITHIN SWAP 0 61 WITHIN -> TRUE TRUE }T
T{ UTIME UTIME 2SWAP D- D0< -> FALSE }T
T{ KEY? DUP 0= OR -> TRUE }T
T{ STATE @ -> 0 }T
\ [IF] skips by parsing words: a backslash does not hide what follows it
T{ 0 [IF] \ [ELSE] 11 [THEN] -> 11 }T
T{ 0 [IF] 1 \ [THEN] 22 [THEN] -> 22 }T
T{ 1 [IF] 33 [ELSE] \ [THEN] 44 [THEN] -> 33 44 }T
\ FACILITY EXT: key events and the terminal
T{ 65 EKEY>CHAR -> 65 TRUE }T
T{ K-UP EKEY>FKEY -> K-UP TRUE }T
T{ K-UP EKEY>CHAR NIP -> FALSE }T
T{ K-F1 K-F2 <> K-UP K-SHIFT-MASK OR K-UP <> -> TRUE TRUE }T
T{ EMIT? -> TRUE }T
\ CS-PICK CS-ROLL: control-flow entries as data for new control words
: ?REPEAT 0 CS-PICK POSTPONE UNTIL ; IMMEDIATE
T{ : CSP 0 BEGIN 1+ DUP 3 = ?REPEAT DUP 6 < UNTIL ; CSP -> 3 }T
: -WHILE POSTPONE IF 1 CS-ROLL ; IMMEDIATE
T{ : CSR BEGIN DUP 5 < -WHILE 1+ REPEAT ; 1 CSR -> 5 }T
\ N>R NR>
T{ : NRT 1 2 3 3 N>R 9 NR> ; NRT -> 9 1 2 3 3 }T
T{ : NRT0 0 N>R NR> ; NRT0 -> 0 }T
