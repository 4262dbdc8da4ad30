/* errors.c - throw codes: their standard texts (Forth-2012 table 9.1) and throws that
 * carry a message of their own. */
#include <string.h>
#include "words.h"

/* ---- throw codes and their standard texts (Forth-2012 table 9.1) ---- */
static const char *const throw_texts[] = {
    "",
    "aborted",
    "aborted",
    "stack overflow",
    "stack underflow",
    "return stack overflow",
    "return stack underflow",
    "do-loops nested too deeply",
    "dictionary overflow",
    "invalid memory address",
    "division by zero",
    "result out of range",
    "argument type mismatch",
    "undefined word",
    "interpreting a compile-only word",
    "invalid FORGET",
    "attempt to use zero-length string as a name",
    "pictured numeric output string overflow",
    "parsed string overflow",
    "definition name too long",
    "write to a read-only location",
    "unsupported operation",
    "control structure mismatch",
    "address alignment exception",
    "invalid numeric argument",
    "return stack imbalance",
    "loop parameters unavailable",
    "invalid recursion",
    "user interrupt",
    "compiler nesting",
    "obsolescent feature",
    ">BODY used on non-CREATEd definition",
    "invalid name argument",
    "block read exception",
    "block write exception",
    "invalid block number",
    "invalid file position",
    "file I/O exception",
    "non-existent file",
    "unexpected end of file",
    "invalid BASE for floating point conversion",
    "loss of precision",
    "floating-point divide by zero",
    "floating-point result out of range",
    "floating-point stack overflow",
    "floating-point stack underflow",
    "floating-point invalid argument",
    "compilation word list deleted",
    "invalid POSTPONE",
    "search-order overflow",
    "search-order underflow",
    "compilation word list changed",
    "control-flow stack overflow",
    "exception stack overflow",
    "floating-point underflow",
    "floating-point unidentified fault",
    "QUIT",
    "exception in sending or receiving a character",
    "[IF], [ELSE], or [THEN] exception",
};

const char *fbrl__throw_text(int code)
{
    if (code < 0 && -code < (int)(sizeof throw_texts / sizeof throw_texts[0]))
        return throw_texts[-code];
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
