\ outer.fs - includes a file by a path relative to this file's directory
VARIABLE INNER-LOADS  0 INNER-LOADS !
1 CONSTANT OUTER-1
INCLUDE inner.fs
OUTER-1 INNER-2 + CONSTANT OUTER-SUM
REQUIRE inner.fs
