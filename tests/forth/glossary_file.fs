\ glossary_file.fs - typed data files (thesis appendix I-9) and SAVE-CAL / LOAD-CAL.
\ Run by tests/unit/test_glossary.c in a fresh empty directory, with 8 KB of records per file.
DECIMAL
FVARIABLE INF-BITS  HEX 7FF0000000000000 DECIMAL INF-BITS !
: +INF ( F: -- inf ) INF-BITS F@ ;  \ F/ refuses to divide by zero, so build it from its bits
: ~0 ( F: r -- r' ) FDUP FABS 1E-9 F< IF FDROP 0E0 THEN ;
CREATE-LOC L1  CREATE-LOC L2
CREATE B 16 ALLOT   CREATE B2 16 ALLOT   FVARIABLE R
: CLEAR ( -- ) B2 16 ERASE  0E0 R F! ;

\ write one record of each type
T{ CREATE-FILE data1.fbd -> }T
T{ OPEN-FILE H1 data1.fbd -> }T
T{ 65 B C! B CHR H1 WRITE-FILE -> }T
T{ -1234 B W! B INTEGER H1 WRITE-FILE -> }T
T{ 1 B C! 2 B 1+ C! 3 B 2 + C! 250 B 3 + C! B LONG-INTEGER H1 WRITE-FILE -> }T
T{ 3.25E0 R F! R REAL H1 WRITE-FILE -> }T
T{ 1E0 -2E0 3.5E0 90E0 -90E0 45E0 L1 DEFINE-LOC L1 LOCATION H1 WRITE-FILE -> }T
T{ S" HELLO WORLD!" B SWAP MOVE B 12 H1 WRITE-FILE -> }T   \ a user type: 12 bytes
T{ H1 CLOSE-FILE -> 0 }T

\ read them back, each with its type
T{ OPEN-FILE H1 data1.fbd -> }T                            \ the handle word is reused
T{ CLEAR B2 CHR H1 READ-FILE B2 C@ -> 65 }T
T{ CLEAR R REAL H1 ' READ-FILE CATCH NIP NIP NIP R F@ -> -314 0E0 }T   \ wrong type: refused
T{ CLEAR B2 LOCATION H1 ' READ-FILE CATCH NIP NIP NIP -> -314 }T
T{ CLEAR B2 INTEGER H1 READ-FILE B2 W@ -> -1234 65535 AND }T            \ then read right
T{ CLEAR B2 LONG-INTEGER H1 READ-FILE B2 C@ B2 1+ C@ B2 2 + C@ B2 3 + C@ B2 4 + C@ -> 1 2 3 250 0 }T
T{ CLEAR R REAL H1 READ-FILE R F@ -> 3.25E0 }T
T{ L2 LOCATION H1 READ-FILE L2 GETX L2 GETY L2 GETZ L2 GETO L2 GETA L2 GETT -> 1E0 -2E0 3.5E0 90E0 -90E0 45E0 }T
T{ CLEAR B2 13 H1 ' READ-FILE CATCH NIP NIP NIP -> -314 }T              \ 13 bytes is another type
T{ CLEAR B2 12 H1 READ-FILE B2 12 S" HELLO WORLD!" COMPARE -> 0 }T
T{ B2 CHR H1 ' READ-FILE CATCH NIP NIP NIP -> -315 }T                    \ end of file

\ RESET-FILE, APPEND-FILE, and writing over a record
T{ H1 RESET-FILE B2 CHR H1 READ-FILE B2 C@ -> 65 }T
T{ H1 APPEND-FILE B2 CHR H1 ' READ-FILE CATCH NIP NIP NIP -> -315 }T
T{ 66 B C! B CHR H1 WRITE-FILE -> }T                      \ appended
T{ H1 RESET-FILE 67 B C! B CHR H1 WRITE-FILE -> }T        \ replaces record 0
T{ H1 CLOSE-FILE -> 0 }T
T{ OPEN-FILE H2 data1.fbd -> }T
T{ CLEAR B2 CHR H2 READ-FILE B2 C@ B2 INTEGER H2 READ-FILE B2 W@ -> 67 -1234 65535 AND }T
T{ H2 APPEND-FILE -> }T
T{ CLEAR B2 CHR H2 ' READ-FILE CATCH NIP NIP NIP -> -315 }T
T{ H2 RESET-FILE H2 CLOSE-FILE -> 0 }T

\ a file that was never closed keeps its old contents on disk until CLOSE-FILE
T{ OPEN-FILE H1 data1.fbd H1 APPEND-FILE 68 B C! B CHR H1 WRITE-FILE -> }T
T{ OPEN-FILE H3 data1.fbd H3 APPEND-FILE -> }T             \ a second snapshot of the file
T{ 0 B C! B CHR H3 WRITE-FILE H3 CLOSE-FILE -> 0 }T
T{ H1 CLOSE-FILE -> 0 }T                                    \ the last commit wins, whole
T{ OPEN-FILE H3 data1.fbd -> }T
: SKIP7 ( h -- ) >R B2 CHR R@ READ-FILE B2 INTEGER R@ READ-FILE B2 LONG-INTEGER R@ READ-FILE
   R REAL R@ READ-FILE L2 LOCATION R@ READ-FILE B2 12 R@ READ-FILE B2 CHR R> READ-FILE ;
T{ H3 SKIP7 B2 CHR H3 READ-FILE B2 C@ -> 68 }T
T{ H3 CLOSE-FILE -> 0 }T

\ bad handles, bad arguments
T{ L1 ' RESET-FILE CATCH NIP -> -12 }T                      \ not a handle
T{ 0 ' APPEND-FILE CATCH NIP -> -12 }T
T{ H3 ' RESET-FILE CATCH NIP -> -325 }T                     \ closed
T{ H3 ' CLOSE-FILE CATCH NIP -> -325 }T
T{ B CHR H3 ' WRITE-FILE CATCH NIP NIP NIP -> -325 }T
T{ ' OPEN-FILE CATCH H4 no-such-file.fbd -> -309 }T
[DEFINED] H4 0= CONSTANT NO-H4
T{ NO-H4 -> TRUE }T                                         \ a failed OPEN-FILE makes no handle
T{ ' OPEN-FILE CATCH L1 data1.fbd -> -12 }T                 \ L1 is not a handle
T{ OPEN-FILE H1 data1.fbd -> }T
T{ ' OPEN-FILE CATCH H1 data1.fbd -> -325 }T                \ already open
T{ B 0 H1 ' WRITE-FILE CATCH NIP NIP NIP -> -24 }T          \ type 0
T{ 0 CHR H1 ' WRITE-FILE CATCH NIP NIP NIP -> -9 }T         \ not in data space
T{ +INF R F! R REAL H1 ' WRITE-FILE CATCH NIP NIP NIP -> -303 }T   \ no infinities
T{ H1 CLOSE-FILE -> 0 }T
T{ ' CREATE-FILE CATCH no-dir/x.fbd -> -309 }T

\ the file full: 8 KB per open file holds 146 locations of 56 bytes
: WRITE-ALL ( h -- n ) 0 BEGIN OVER L1 LOCATION ROT WRITE-FILE 1+ AGAIN ;
T{ CREATE-FILE full.fbd OPEN-FILE H5 full.fbd -> }T
T{ H5 ' WRITE-ALL CATCH NIP -> -304 }T
T{ H5 RESET-FILE H5 ' WRITE-ALL CATCH NIP -> -304 }T           \ replacing keeps the count
T{ H5 CLOSE-FILE -> 0 }T

\ SAVE-CAL / LOAD-CAL
CREATE-CAL-STRU S1  CREATE-CAL-STRU S2  CREATE-CAL-STRU S3
: STRU ( s -- ) ( F: -- 12 entries ) 13 1 DO DUP I CAL-STRU@ ~0 LOOP DROP ;
T{ 0E0 S1 1 CAL-STRU! -1E0 S1 2 CAL-STRU! 10E0 S1 4 CAL-STRU! 1E0 S1 5 CAL-STRU! 0E0 S1 6 CAL-STRU! 5E0 S1 8 CAL-STRU! -> }T
T{ CREATE-FILE cal.fbd OPEN-FILE HC cal.fbd -> }T
T{ S1 HC SAVE-CAL 3.25E0 R F! R REAL HC WRITE-FILE HC CLOSE-FILE -> 0 }T
T{ OPEN-FILE HC cal.fbd -> }T
T{ B2 12 HC ' READ-FILE CATCH NIP NIP NIP -> -314 }T         \ not a 12-byte record
T{ S2 HC LOAD-CAL S2 STRU -> S1 STRU }T
T{ S3 HC ' LOAD-CAL CATCH NIP NIP S3 1 CAL-STRU@ -> -314 1E0 }T  \ a REAL is next: refused
T{ R REAL HC READ-FILE R F@ -> 3.25E0 }T
T{ S3 HC ' LOAD-CAL CATCH NIP NIP -> -315 }T
T{ 2E0 S3 1 CAL-STRU! S3 HC ' SAVE-CAL CATCH NIP NIP -> -325 }T   \ not a rigid motion
T{ L1 HC ' SAVE-CAL CATCH NIP NIP -> -12 }T
T{ HC CLOSE-FILE -> 0 }T
T{ CREATE-FILE cal2.fbd OPEN-FILE HC cal2.fbd PAD 108 HC WRITE-FILE HC RESET-FILE -> }T
T{ S2 HC ' LOAD-CAL CATCH NIP NIP -> -314 }T                \ 108 bytes, but not a calibration
T{ PAD 108 HC READ-FILE HC CLOSE-FILE -> 0 }T
