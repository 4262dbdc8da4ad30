\ multiple
: m1
1 +
;
5 m1 .