\ file.fs - the standard FILE and FILE EXT words (a host with a file system), after
\ FORTH-2012 puts the standard CREATE-FILE ... before the thesis's typed files
DECIMAL
FORTH-2012
: FN S" fbrl-file-test.txt" ;  : FN2 S" fbrl-file-test2.txt" ;
VARIABLE FID
CREATE LBUF 100 ALLOT
T{ FN R/W CREATE-FILE SWAP FID ! -> 0 }T
T{ S" one" FID @ WRITE-LINE  S" two2" FID @ WRITE-LINE -> 0 0 }T
T{ S" 3" FID @ WRITE-FILE -> 0 }T                     \ a last line without its end
T{ FID @ FILE-SIZE -> 10 0 0 }T
T{ FID @ FILE-POSITION -> 10 0 0 }T
T{ 0 0 FID @ REPOSITION-FILE -> 0 }T
T{ LBUF 100 FID @ READ-LINE -> 3 TRUE 0 }T
T{ LBUF 3 S" one" COMPARE -> 0 }T
T{ LBUF 2 FID @ READ-LINE -> 2 TRUE 0 }T               \ a line longer than the buffer
T{ LBUF 100 FID @ READ-LINE -> 2 TRUE 0 }T             \ the rest of it
T{ LBUF 100 FID @ READ-LINE -> 1 TRUE 0 }T
T{ LBUF 100 FID @ READ-LINE -> 0 FALSE 0 }T            \ the end
T{ 4 0 FID @ REPOSITION-FILE LBUF 3 FID @ READ-FILE -> 0 3 0 }T
T{ LBUF 3 S" two" COMPARE -> 0 }T
T{ 2 0 FID @ RESIZE-FILE FID @ FILE-SIZE -> 0 2 0 0 }T
T{ FID @ FLUSH-FILE FID @ CLOSE-FILE -> 0 0 }T
T{ FID @ CLOSE-FILE 0= -> FALSE }T                     \ a closed fileid is refused
T{ FN FILE-STATUS NIP -> 0 }T
T{ FN FN2 RENAME-FILE FN FILE-STATUS NIP FN2 FILE-STATUS NIP -> 0 -38 0 }T
T{ FN2 R/O OPEN-FILE SWAP FID ! -> 0 }T
T{ S" x" FID @ WRITE-FILE 0= -> FALSE }T                \ read only
T{ FID @ CLOSE-FILE FN2 DELETE-FILE FN2 DELETE-FILE -> 0 0 -38 }T
T{ FN2 R/O OPEN-FILE NIP -> -38 }T
\ INCLUDE-FILE interprets the file
T{ FN W/O CREATE-FILE DROP FID ! S" 1234 CONSTANT FROM-FILE" FID @ WRITE-LINE FID @ CLOSE-FILE -> 0 0 }T
T{ FN R/O OPEN-FILE DROP INCLUDE-FILE FROM-FILE -> 1234 }T
T{ FN DELETE-FILE -> 0 }T
ONLY FORTH
