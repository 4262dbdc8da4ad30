\ glossary_audit.fs - the glossary words no other test exercised directly (found by the
\ audit of docs/glossary.md); run by tests/unit/test_glossary_words.c in a VM with the
\ data glossary and the robot words installed offline.
DECIMAL

\ I-1: the low-level twins work on the same queue as the high-level words
T{ 4 CREATE-Q AQ -> }T
T{ 65 AQ ENQ-L 66 AQ ENQ AQ Q-COUNT -> 2 }T
T{ AQ DEQ-L AQ DEQ AQ EMPTY-Q?-L -> 65 66 TRUE }T
T{ 1 AQ ENQ 2 AQ ENQ 3 AQ ENQ 4 AQ ENQ AQ FULL-Q?-L -> TRUE }T
T{ AQ DEQ-L AQ DEQ-L AQ DEQ-L AQ DEQ-L -> 1 2 3 4 }T
T{ AQ ' DEQ-L CATCH NIP -> -305 }T               \ empty, as DEQ
T{ PAD ' DEQ-L CATCH NIP -> -12 }T              \ not a queue

\ (ROBOT-TIB): GET-CAL-POINTS' line buffer, a variable in the data space
T{ (ROBOT-TIB) ALIGNED (ROBOT-TIB) = -> TRUE }T
T{ (ROBOT-TIB) C@ 7 (ROBOT-TIB) C! (ROBOT-TIB) C@ SWAP (ROBOT-TIB) C! -> 7 }T
