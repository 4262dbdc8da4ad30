\ bad.fs - an error on line 4, inside a definition
: GOOD 1 ;
: HALF
   2 NO-SUCH-WORD ;
