\ chain.fs - an error three words deep, for test_vm.c's backtraces (line numbers matter)
: INNER ( n -- ) 0 / DROP ;
: MIDDLE ( n -- )
   5 +
   INNER ;
: OUTER ( -- ) 3 MIDDLE ;
: CAUGHT ( -- n ) ['] OUTER CATCH ;
