\ string.fs - STRING word set
DECIMAL
: S1 S" abcdefghijklmnopqrstuvwxyz" ;
: S2 S" abc" ;  : S3 S" jklmn" ;  : S4 S" z" ;  : S5 S" mnoq" ;  : S6 S" 12345" ;  : S7 S" " ;
T{ S1 S2 SEARCH -> S1 TRUE }T
T{ S1 S3 SEARCH -> S1 9 /STRING TRUE }T
T{ S1 S4 SEARCH -> S1 25 /STRING TRUE }T
T{ S1 S5 SEARCH -> S1 FALSE }T
T{ S1 S6 SEARCH -> S1 FALSE }T
T{ S1 S7 SEARCH -> S1 TRUE }T
T{ S2 S1 SEARCH -> S2 FALSE }T
T{ S1 5 /STRING -> S1 SWAP 5 + SWAP 5 - }T
T{ S1 10 /STRING -4 /STRING -> S1 6 /STRING }T
T{ S1 0 /STRING -> S1 }T
: S8 S" abc  " ;  : S9 S"    " ;
T{ S8 -TRAILING -> S8 2 - }T T{ S9 -TRAILING -> S9 DROP 0 }T T{ S2 -TRAILING -> S2 }T T{ S7 -TRAILING -> S7 }T
T{ S2 S2 COMPARE -> 0 }T T{ S2 S" abd" COMPARE -> -1 }T T{ S" abd" S2 COMPARE -> 1 }T
T{ S2 S" ab" COMPARE -> 1 }T T{ S" ab" S2 COMPARE -> -1 }T T{ S7 S7 COMPARE -> 0 }T T{ S7 S2 COMPARE -> -1 }T
T{ S" ABC" S2 COMPARE -> -1 }T
CREATE BUF 20 ALLOT
T{ BUF 20 BLANK BUF C@ BUF 19 + C@ -> BL BL }T
T{ S2 BUF SWAP CMOVE BUF 3 S2 COMPARE -> 0 }T
T{ BUF BUF 1+ 3 CMOVE BUF 4 S" aaaa" COMPARE -> 0 }T
T{ S2 BUF SWAP CMOVE BUF 1+ BUF 2 CMOVE> BUF 3 S" ccc" COMPARE -> 0 }T
T{ S2 BUF SWAP CMOVE BUF BUF 1+ 3 CMOVE> BUF 4 S" aabc" COMPARE -> 0 }T
T{ : SL [ S2 ] SLITERAL ; SL S2 COMPARE -> 0 }T
T{ S1 DROP 0 S7 COMPARE -> 0 }T
\ SEARCH of and for empty strings (found at once, the address kept)
T{ S1 DROP 0 S1 DROP 0 SEARCH ROT S1 DROP = -> 0 TRUE TRUE }T
T{ S1 S1 DROP 0 SEARCH -> S1 TRUE }T
T{ S1 DROP 0 S1 SEARCH ROT DROP -> 0 FALSE }T
\ REPLACES SUBSTITUTE UNESCAPE
CREATE SB 64 ALLOT
T{ S" robot" S" arm" REPLACES -> }T
T{ S" the %arm% moves 100%%" SB 64 SUBSTITUTE ROT SB = -> 20 1 TRUE }T
T{ SB 20 S" the robot moves 100%" COMPARE -> 0 }T
T{ S" %ARM%" SB 64 SUBSTITUTE NIP NIP -> 1 }T              \ names match in any case
T{ S" %nope% %" SB 64 SUBSTITUTE NIP NIP -> 0 }T          \ unknown names stay
T{ S" long %arm%" SB 5 SUBSTITUTE NIP NIP 0< -> TRUE }T   \ too long: n < 0
T{ S" 50%" SB UNESCAPE S" 50%%" COMPARE -> 0 }T
T{ S" 50%" SB UNESCAPE SB 32 + 32 SUBSTITUTE ROT ROT S" 50%" COMPARE -> 0 0 }T
T{ S" crane" S" arm" REPLACES S" %arm%" SB 64 SUBSTITUTE DROP S" crane" COMPARE -> 0 }T
