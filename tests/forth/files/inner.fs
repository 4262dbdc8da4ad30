\ inner.fs - included from outer.fs; REQUIRE must not load it twice
INNER-LOADS @ 1+ INNER-LOADS !
2 CONSTANT INNER-2
