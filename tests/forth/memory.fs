\ memory.fs - the MEMORY word set on the heap inside the VM block
DECIMAL
VARIABLE M1  VARIABLE M2
T{ 100 ALLOCATE SWAP M1 ! -> 0 }T
T{ M1 @ 100 1 FILL M1 @ 99 + C@ -> 1 }T
T{ 50 ALLOCATE SWAP M2 ! -> 0 }T
T{ M1 @ M2 @ = -> FALSE }T
T{ M1 @ 1000 RESIZE SWAP M1 ! -> 0 }T
T{ M1 @ 99 + C@ M1 @ C@ -> 1 1 }T              \ the contents move with the block
T{ M1 @ FREE M2 @ FREE -> 0 0 }T
\ freeing twice, or an address ALLOCATE did not give, is an ior, not a crash
T{ M1 @ FREE -> -9 }T
T{ PAD FREE HERE 10 RESIZE NIP -> -9 -9 }T
\ no room: an ior, and the heap still works
T{ -1 1 RSHIFT ALLOCATE NIP -> -8 }T
T{ 10 ALLOCATE SWAP FREE -> 0 0 }T
\ freed blocks merge: the whole heap can be taken again
T{ UNUSED-HEAP ALLOCATE SWAP FREE -> 0 0 }T
\ a program that overwrites a block's header gets iors; nothing outside the heap changes
T{ 64 ALLOCATE DROP DUP 2 CELLS - -1 SWAP ! FREE -> -9 }T
T{ 32 ALLOCATE NIP -> -9 }T
