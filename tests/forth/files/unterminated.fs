\ unterminated.fs - a definition left open at the end of the file
: OPEN 1 2
