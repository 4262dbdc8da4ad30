\ cell_words.fs - the work-cell words offline (docs/workcell.md): describing the cell, and
\ the bad descriptions each refused with its own error; run by tests/unit/test_glossary_words.c.
DECIMAL
T{ 0E0 CELL-TABLE -> }T
T{ 0.5E0 0.25E0 CELL-TOOL -> }T
T{ 10E0 -2E0 0E0 14E0 2E0 1.5E0 CELL-BOX HEATER -> }T
T{ 8E0 5E0 0E0 11E0 7E0 20E0 CELL-KEEPOUT NO-GO -> }T
T{ 14E0 6E0 0E0 1E0 4E0 CELL-CYLINDER VIAL -> }T
T{ 0 0 0 1 1 1 CELL-BOX INTS -> }T                      \ integers count as reals
\ blocks: obstacles after CELL-BLOCK ride on that calibration until CELL-WORLD
T{ CREATE-CAL-STRU RACK-CAL -> }T
T{ CELL-BLOCK RACK-CAL -> }T
T{ 2E0 -9E0 0E0 6E0 -7E0 3E0 CELL-BOX RACK -> }T
T{ CELL-WORLD -> }T
T{ CELL-GUARD-OFF CELL-GUARD-ON -> }T
\ bad descriptions: a name twice, a size not positive, a location inside
T{ S" 0E0 0E0 0E0 1E0 1E0 1E0 CELL-BOX heater" ' EVALUATE CATCH NIP NIP -> -324 }T
T{ S" 0E0 0E0 0E0 -1E0 1E0 1E0 CELL-BOX NEGATIVE" ' EVALUATE CATCH NIP NIP -> -302 }T
T{ S" 0E0 0E0 0E0 1E0 -2E0 CELL-CYLINDER DOWN" ' EVALUATE CATCH NIP NIP -> -302 }T
T{ S" -1E0 0E0 CELL-TOOL" ' EVALUATE CATCH NIP NIP -> -302 }T
T{ CREATE-LOC INSIDE 20E0 0E0 1E0 0E0 -90E0 0E0 INSIDE DEFINE-LOC -> }T
T{ S" 19E0 -1E0 0E0 21E0 1E0 2E0 CELL-BOX COVER" ' EVALUATE CATCH NIP NIP -> -302 }T
T{ S" CELL-BOX NONE" ' EVALUATE CATCH NIP NIP -> -45 }T        \ the six numbers missing
\ nothing of a refused obstacle stays: COVER, NEGATIVE are not in the cell
T{ 19E0 -1E0 3E0 21E0 1E0 4E0 CELL-BOX NEGATIVE -> }T
T{ CELL-CLEAR S" 19E0 -1E0 0E0 21E0 1E0 2E0 CELL-BOX COVER" ' EVALUATE CATCH NIP NIP -> -302 }T
T{ S" x.svg" ' CELL-SVG CATCH NIP NIP -> -21 }T      \ no file output in this host
T{ .CELL -> }T
\ racks: the picture draws every position of a RECTMAT or RADMAT, given its rows and columns
CREATE-LOC R0  10E0 -2E0 3E0 0E0 -90E0 0E0 R0 DEFINE-LOC
R0 0.75E0 0.75E0 0E0 RECTMAT TUBES
R0 0.1E0 1E0 0E0 RADMAT CAROUSEL
T{ 4 6 CELL-RACK TUBES -> }T
T{ 2 8 CELL-RACK carousel -> }T
T{ 4 5 CELL-RACK TUBES -> }T                            \ described again: the new size
T{ S" 4 6 CELL-RACK R0" ' EVALUATE CATCH NIP NIP -> -324 }T      \ a location, not a matrix
T{ S" 4 6 CELL-RACK NOTHING" ' EVALUATE CATCH NIP NIP -> -324 }T
T{ S" 0 6 CELL-RACK TUBES" ' EVALUATE CATCH NIP NIP -> -302 }T   \ 1 to 64 rows and columns
T{ S" 4 65 CELL-RACK TUBES" ' EVALUATE CATCH NIP NIP -> -302 }T
