/* SPDX-License-Identifier: MIT */
/* errors.c - throw codes: their standard texts (Forth-2012 table 9.1) and throws that
 * carry a message of their own. */
#include <string.h>
#include "words.h"

/* ---- throw codes and their standard texts (Forth-2012 table 9.1) ---- */
/* Code -n's text is the n-th after code 0's (empty), each ending in its NUL: one string, not
 * a table of pointers; an uncaught error is rare and counting is cheap. */
static const char throw_texts[] = "\0"
                                  "aborted\0"
                                  "aborted\0"
                                  "stack overflow\0"
                                  "stack underflow\0"
                                  "return stack overflow\0"
                                  "return stack underflow\0"
                                  "do-loops nested too deeply\0"
                                  "dictionary overflow\0"
                                  "invalid memory address\0"
                                  "division by zero\0"
                                  "result out of range\0"
                                  "argument type mismatch\0"
                                  "undefined word\0"
                                  "interpreting a compile-only word\0"
                                  "invalid FORGET\0"
                                  "attempt to use zero-length string as a name\0"
                                  "pictured numeric output string overflow\0"
                                  "parsed string overflow\0"
                                  "definition name too long\0"
                                  "write to a read-only location\0"
                                  "unsupported operation\0"
                                  "control structure mismatch\0"
                                  "address alignment exception\0"
                                  "invalid numeric argument\0"
                                  "return stack imbalance\0"
                                  "loop parameters unavailable\0"
                                  "invalid recursion\0"
                                  "user interrupt\0"
                                  "compiler nesting\0"
                                  "obsolescent feature\0"
                                  ">BODY used on non-CREATEd definition\0"
                                  "invalid name argument\0"
                                  "block read exception\0"
                                  "block write exception\0"
                                  "invalid block number\0"
                                  "invalid file position\0"
                                  "file I/O exception\0"
                                  "non-existent file\0"
                                  "unexpected end of file\0"
                                  "invalid BASE for floating point conversion\0"
                                  "loss of precision\0"
                                  "floating-point divide by zero\0"
                                  "floating-point result out of range\0"
                                  "floating-point stack overflow\0"
                                  "floating-point stack underflow\0"
                                  "floating-point invalid argument\0"
                                  "compilation word list deleted\0"
                                  "invalid POSTPONE\0"
                                  "search-order overflow\0"
                                  "search-order underflow\0"
                                  "compilation word list changed\0"
                                  "control-flow stack overflow\0"
                                  "exception stack overflow\0"
                                  "floating-point underflow\0"
                                  "floating-point unidentified fault\0"
                                  "QUIT\0"
                                  "exception in sending or receiving a character\0"
                                  "[IF], [ELSE], or [THEN] exception";

const char *fbrl__throw_text(int code)
{
    const char *t = throw_texts, *end = throw_texts + sizeof throw_texts;
    for (int k = code; k < 0 && t < end; k++)
        t += strlen(t) + 1;
    if (code < 0 && t < end)
        return t;
    if (code <= FBRL_THROW_STATUS(0) && code >= FBRL_THROW_STATUS(FBRL_STATUS_MIN))
        return fbrl_status_str((fbrl_status)(code - FBRL_THROW_STATUS(0)));
    return "user exception";
}

/* Raise with a message other than the standard one (the message is copied). */
int fbrl__throw_msg(fbrl_vm *vm, int code, const char *msg)
{
    vm->pending_code = code;
    size_t n = strlen(msg);
    if (n >= sizeof vm->throw_msg)
        n = sizeof vm->throw_msg - 1;
    memcpy(vm->throw_msg, msg, n);
    vm->throw_msg[n] = 0;
    vm->pending_msg = vm->throw_msg;
    return code;
}
