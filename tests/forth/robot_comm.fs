\ robot_comm.fs - the I-4 communication words on the link's uart (a pty to fbrlsim):
\ setup words applied with SETUPUART / COMM-SETUP, raw output (the controller echoes
\ it, so GET-COM reads it back), RESET-COMM bringing the link back in step.

LOG-SKIP
T{ OUT-CLEAR .COMM OUT" 38400 baud, 8 data bits, parity N, 1 stop bit, XON/XOFF" -> TRUE }T

\ settings are collected, then applied by SETUPUART
T{ 19200 SETBAUDRATE ASC E SETPARITY 2 SETSTOPBITS 7 SETWORDLENGTH -> }T
T{ OUT-CLEAR .COMM OUT" 38400 baud" -> TRUE }T
T{ 1 SETUPUART -> }T
T{ OUT-CLEAR .COMM OUT" 19200 baud, 7 data bits, parity E, 2 stop bits" -> TRUE }T
T{ HOME -> }T  LOG: HOME
T{ 9600 ASC O 1 8 COMMSET 1 SETUPUART -> }T
T{ OUT-CLEAR .COMM OUT" 9600 baud, 8 data bits, parity O, 1 stop bit" -> TRUE }T
T{ 1 38400 ASC N 1 8 COMM-SETUP -> }T
T{ OUT-CLEAR .COMM OUT" 38400 baud, 8 data bits, parity N, 1 stop bit" -> TRUE }T
T{ READY -> }T  LOG: READY
\ parameters after the word, as the thesis's examples
T{ SETPARITY E SETBAUDRATE 4800 SETUPUART 1 -> }T
T{ OUT-CLEAR .COMM OUT" 4800 baud, 8 data bits, parity E" -> TRUE }T
T{ COMM-SETUP 1 38400 N 1 8 -> }T
\ bad settings change nothing
T{ 9 ' SETWORDLENGTH CATCH NIP -> -24 }T
T{ 3 ' SETSTOPBITS CATCH NIP -> -24 }T
T{ ASC X ' SETPARITY CATCH NIP -> -24 }T
T{ 0 ' SETBAUDRATE CATCH NIP -> -24 }T
T{ 2400 ASC E 1 9 ' COMMSET CATCH NIP NIP NIP NIP -> -24 }T
T{ 2 ' SETUPUART CATCH NIP -> -24 }T
T{ OUT-CLEAR .COMM OUT" 38400 baud, 8 data bits, parity N, 1 stop bit" -> TRUE }T

\ raw output: the controller echoes every character (upper case)
T{ ASC a EMIT-COM GET-COM -> 65 }T
T{ S" bc" SWAP TYPE-COM GET-COM GET-COM -> 66 67 }T
T{ -123 .-COM GET-COM GET-COM GET-COM GET-COM -> 45 49 50 51 }T
T{ 2.5E0 F.-COM GET-COM GET-COM GET-COM -> 50 46 53 }T
T{ ASC Z DIRECT-WRITE-COM GET-COM -> 90 }T
T{ 17 ' EMIT-COM CATCH NIP -> -24 }T
\ RESET-COMM erases what was typed (the controller never executes it) and resyncs: the
\ connect's handshake, NOHELP and STATUS (the controller's units)
T{ 1 RESET-COMM -> }T  LOG: NOHELP
                       LOG: STATUS
T{ GET-COM -> -1 }T
T{ LOG-COUNT" ABC-1232.5Z" -> 0 }T
\ a whole command typed raw: the controller runs it; RESET-COMM drops its reply
T{ S" SPEED 20" SWAP TYPE-COM 13 EMIT-COM -> }T
T{ 1 RESET-COMM -> }T  LOG: SPEED 20
                       LOG: NOHELP
                       LOG: STATUS
T{ OUT-CLEAR ROBOT-STATUS OUT" SPEED (% OF FULL) :    +20" -> TRUE }T  LOG: STATUS
T{ ASC E -> 69 }T
: PAR-E ASC E ;
T{ PAR-E -> 69 }T
\ a stream started raw never goes quiet: RESET-COMM still returns and the link works
T{ S" W1" SWAP TYPE-COM 13 EMIT-COM -> }T
T{ 1 RESET-COMM -> }T  LOG: W1
                       LOG: NOHELP
                       LOG: STATUS
T{ 30 SPEED -> }T  LOG: SPEED 30
\ PRINT-LOC writes to the communication port: the controller's line (it rejects the
\ text as a command); the robot discards the answer and resynchronises the link
CREATE-LOC PL  1E0 2E0 3E0 0E0 -90E0 0E0 PL DEFINE-LOC
T{ PL PRINT-LOC -> }T  LOG: X*+1.0000*Y*+2.0000*Z*+3.0000*-90.000*
                       LOG: NOHELP
                       LOG: STATUS
T{ 40 SPEED -> }T  LOG: SPEED 40
