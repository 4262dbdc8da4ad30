( comment ) \ line comment
2 .