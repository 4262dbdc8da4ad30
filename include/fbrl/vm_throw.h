/* SPDX-License-Identifier: MIT */
/* vm_throw.h - names for the FBRL engine's THROW codes (Forth-2012 table 9.1), used by the
 * engine and by every word set. FBRL_VM_THROW_OF_STATUS(st) (vm.h) is the code of a libfbrl
 * status; any other code a program THROWs is its own. fbrl_vm_last_error() reports them. */
#ifndef FBRL_VM_THROW_H
#define FBRL_VM_THROW_H

enum fbrl_throw {
    FBRL_THROW_ABORT = -1,               /* ABORT */
    FBRL_THROW_ABORTQ = -2,              /* ABORT" with a message */
    FBRL_THROW_STACK_OVERFLOW = -3,      /* stack overflow */
    FBRL_THROW_STACK_UNDERFLOW = -4,     /* stack underflow */
    FBRL_THROW_RSTACK_OVERFLOW = -5,     /* return stack overflow */
    FBRL_THROW_RSTACK_UNDERFLOW = -6,    /* return stack underflow */
    FBRL_THROW_DO_NESTING = -7,          /* do-loops nested too deeply */
    FBRL_THROW_DICT_OVERFLOW = -8,       /* dictionary overflow */
    FBRL_THROW_BAD_ADDRESS = -9,         /* invalid memory address */
    FBRL_THROW_DIV_ZERO = -10,           /* division by zero */
    FBRL_THROW_RESULT_RANGE = -11,       /* result out of range */
    FBRL_THROW_TYPE_MISMATCH = -12,      /* argument type mismatch */
    FBRL_THROW_UNDEFINED = -13,          /* undefined word */
    FBRL_THROW_COMPILE_ONLY = -14,       /* interpreting a compile-only word */
    FBRL_THROW_BAD_FORGET = -15,         /* invalid FORGET */
    FBRL_THROW_NO_NAME = -16,            /* attempt to use zero-length string as a name */
    FBRL_THROW_PICTURED_OVERFLOW = -17,  /* pictured numeric output string overflow */
    FBRL_THROW_PARSED_OVERFLOW = -18,    /* parsed string overflow */
    FBRL_THROW_NAME_TOO_LONG = -19,      /* definition name too long */
    FBRL_THROW_READ_ONLY = -20,          /* write to a read-only location */
    FBRL_THROW_UNSUPPORTED = -21,        /* unsupported operation */
    FBRL_THROW_CONTROL_MISMATCH = -22,   /* control structure mismatch */
    FBRL_THROW_ALIGNMENT = -23,          /* address alignment exception */
    FBRL_THROW_BAD_NUMBER = -24,         /* invalid numeric argument */
    FBRL_THROW_RSTACK_IMBALANCE = -25,   /* return stack imbalance */
    FBRL_THROW_NO_LOOP = -26,            /* loop parameters unavailable */
    FBRL_THROW_BAD_RECURSION = -27,      /* invalid recursion */
    FBRL_THROW_INTERRUPT = -28,          /* user interrupt */
    FBRL_THROW_COMPILER_NESTING = -29,   /* compiler nesting */
    FBRL_THROW_OBSOLESCENT = -30,        /* obsolescent feature */
    FBRL_THROW_TO_BODY = -31,            /* >BODY used on non-CREATEd definition */
    FBRL_THROW_BAD_NAME_ARG = -32,       /* invalid name argument */
    FBRL_THROW_BLOCK_READ = -33,         /* block read exception */
    FBRL_THROW_BLOCK_WRITE = -34,        /* block write exception */
    FBRL_THROW_BAD_BLOCK = -35,          /* invalid block number */
    FBRL_THROW_BAD_FILE_POSITION = -36,  /* invalid file position */
    FBRL_THROW_FILE_IO = -37,            /* file I/O exception */
    FBRL_THROW_NO_FILE = -38,            /* non-existent file */
    FBRL_THROW_UNEXPECTED_EOF = -39,     /* unexpected end of file */
    FBRL_THROW_FLOAT_BASE = -40,         /* invalid BASE for floating point conversion */
    FBRL_THROW_PRECISION_LOSS = -41,     /* loss of precision */
    FBRL_THROW_FDIV_ZERO = -42,          /* floating-point divide by zero */
    FBRL_THROW_FRESULT_RANGE = -43,      /* floating-point result out of range */
    FBRL_THROW_FSTACK_OVERFLOW = -44,    /* floating-point stack overflow */
    FBRL_THROW_FSTACK_UNDERFLOW = -45,   /* floating-point stack underflow */
    FBRL_THROW_FBAD_ARG = -46,           /* floating-point invalid argument */
    FBRL_THROW_WORDLIST_DELETED = -47,   /* compilation word list deleted */
    FBRL_THROW_BAD_POSTPONE = -48,       /* invalid POSTPONE */
    FBRL_THROW_SEARCH_OVERFLOW = -49,    /* search-order overflow */
    FBRL_THROW_SEARCH_UNDERFLOW = -50,   /* search-order underflow */
    FBRL_THROW_WORDLIST_CHANGED = -51,   /* compilation word list changed */
    FBRL_THROW_CF_OVERFLOW = -52,        /* control-flow stack overflow */
    FBRL_THROW_EXCEPTION_OVERFLOW = -53, /* exception stack overflow */
    FBRL_THROW_FUNDERFLOW = -54,         /* floating-point underflow */
    FBRL_THROW_FFAULT = -55,             /* floating-point unidentified fault */
    FBRL_THROW_QUIT = -56,               /* QUIT */
    FBRL_THROW_CHAR_IO = -57,            /* exception in sending or receiving a character */
    FBRL_THROW_BRACKET_IF = -58,         /* [IF], [ELSE], or [THEN] exception */
};

#endif
