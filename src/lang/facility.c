/* SPDX-License-Identifier: MIT */
/* facility.c - the FACILITY EXT words the engine did not have: AT-XY PAGE (ANSI terminal
 * sequences on the console output), EKEY EKEY? EKEY>CHAR EKEY>FKEY EMIT? and the K-
 * key constants. Keys come from the host's key callback (a firmware without one throws
 * -21, as KEY does). EKEY decodes the common ANSI/VT100 sequences of cursor and function
 * keys (ESC [ A, ESC O P, ESC [ 3 ~ ...) when the rest of the sequence is already there
 * (key_ready); anything else is a character event, one byte. */
#include <stdio.h>
#include <string.h>
#include "words.h"

#define KEV_FKEY  0x10000L /* a function key event: KEV_FKEY + its number */
#define KEV_SHIFT 0x20000L
#define KEV_CTRL  0x40000L
#define KEV_ALT   0x80000L
#define ESC       27

enum {
    K_LEFT = 1,
    K_RIGHT,
    K_UP,
    K_DOWN,
    K_HOME,
    K_END,
    K_PRIOR,
    K_NEXT,
    K_INSERT,
    K_DELETE,
    K_F1,
    K_F2,
    K_F3,
    K_F4,
    K_F5,
    K_F6,
    K_F7,
    K_F8,
    K_F9,
    K_F10,
    K_F11,
    K_F12
};

static int no_input(fbrl_vm *vm)
{
    return fbrl__throw_msg(vm, FBRL_THROW_UNSUPPORTED, "no console input in this host");
}

static int ready(fbrl_vm *vm) { return vm->host.key_ready && vm->host.key_ready(vm->host.user); }

/* the next byte of a sequence, or -1 if none is waiting */
static int next_byte(fbrl_vm *vm) { return ready(vm) ? vm->host.key(vm->host.user) : -1; }

static fbrl_cell decode_escape(fbrl_vm *vm)
{
    int c = next_byte(vm);
    if (c == 'O') { /* SS3: F1-F4, and HOME/END on some terminals */
        c = next_byte(vm);
        switch (c) {
        case 'P': return KEV_FKEY + K_F1;
        case 'Q': return KEV_FKEY + K_F2;
        case 'R': return KEV_FKEY + K_F3;
        case 'S': return KEV_FKEY + K_F4;
        case 'H': return KEV_FKEY + K_HOME;
        case 'F': return KEV_FKEY + K_END;
        default: return ESC;
        }
    }
    if (c != '[')
        return ESC;
    int n = 0, mod = 0, digits = 0;
    for (;;) {
        c = next_byte(vm);
        if (c >= '0' && c <= '9') {
            n = n * 10 + (c - '0');
            digits = 1;
            if (n > 99)
                return ESC;
        } else if (c == ';') { /* ESC [ 1 ; mod X: shift 2, alt 3, ctrl 5 */
            mod = 0;
            while ((c = next_byte(vm)) >= '0' && c <= '9')
                mod = mod * 10 + (c - '0');
            break;
        } else {
            break;
        }
    }
    fbrl_cell m = 0;
    if (mod >= 2) {
        int b = mod - 1;
        m = (b & 1 ? KEV_SHIFT : 0) | (b & 2 ? KEV_ALT : 0) | (b & 4 ? KEV_CTRL : 0);
    }
    switch (c) {
    case 'A': return KEV_FKEY + K_UP + m;
    case 'B': return KEV_FKEY + K_DOWN + m;
    case 'C': return KEV_FKEY + K_RIGHT + m;
    case 'D': return KEV_FKEY + K_LEFT + m;
    case 'H': return KEV_FKEY + K_HOME + m;
    case 'F': return KEV_FKEY + K_END + m;
    case '~': {
        static const struct {
            int n, k;
        } t[] = {{1, K_HOME}, {2, K_INSERT}, {3, K_DELETE}, {4, K_END}, {5, K_PRIOR},
                 {6, K_NEXT}, {15, K_F5},    {17, K_F6},    {18, K_F7}, {19, K_F8},
                 {20, K_F9},  {21, K_F10},   {23, K_F11},   {24, K_F12}};
        for (size_t i = 0; digits && i < sizeof t / sizeof t[0]; i++)
            if (t[i].n == n)
                return KEV_FKEY + t[i].k + m;
        return ESC;
    }
    default: return ESC;
    }
}

static fbrl_status w_ekey(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (!vm->host.key)
        return fbrl__cthrow(vm, no_input(vm));
    int c = vm->host.key(vm->host.user);
    if (c < 0)
        return fbrl__cthrow(vm, FBRL_THROW_CHAR_IO);
    fbrl_cell ev = c == ESC && ready(vm) ? decode_escape(vm) : (fbrl_cell)(unsigned char)c;
    return fbrl__cthrow(vm, fbrl__cpush(vm, ev));
}

static fbrl_status w_ekeyq(fbrl_vm *vm, void *arg)
{
    (void)arg;
    if (!vm->host.key_ready)
        return fbrl__cthrow(vm, no_input(vm));
    return fbrl__cthrow(vm, fbrl__cpush(vm, ready(vm) ? -1 : 0));
}

/* EKEY>CHAR ( x -- char true | x false ) and EKEY>FKEY ( x -- u flag ) */
static fbrl_status w_ekey_to(fbrl_vm *vm, void *arg)
{
    if (fbrl__cneed(vm, 1))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell x = vm->sp[-1];
    int fkey = x >= KEV_FKEY;
    return fbrl__cthrow(vm, fbrl__cpush(vm, (arg ? fkey : !fkey && x >= 0) ? -1 : 0));
}

static fbrl_status w_emitq(fbrl_vm *vm, void *arg)
{
    (void)arg;
    return fbrl__cthrow(vm, fbrl__cpush(vm, vm->host.write ? -1 : 0));
}

static fbrl_status w_at_xy(fbrl_vm *vm, void *arg)
{
    char b[48];
    (void)arg;
    if (fbrl__cneed(vm, 2))
        return fbrl__cthrow(vm, FBRL_THROW_STACK_UNDERFLOW);
    fbrl_cell row = vm->sp[-1], col = vm->sp[-2];
    vm->sp -= 2;
    if (row < 0 || col < 0 || row > 9999 || col > 9999)
        return fbrl__cthrow(vm, FBRL_THROW_BAD_NUMBER);
    snprintf(b, sizeof b, "\033[%ld;%ldH", (long)row + 1, (long)col + 1);
    fbrl__puts(vm, b);
    return FBRL_OK;
}

static fbrl_status w_page(fbrl_vm *vm, void *arg)
{
    (void)arg;
    fbrl__puts(vm, "\033[2J\033[H");
    return FBRL_OK;
}

static fbrl_status w_kconst(fbrl_vm *vm, void *arg)
{
    return fbrl__cthrow(vm, fbrl__cpush(vm, (fbrl_cell)(intptr_t)arg));
}

#define KC(name, v)                                                                                          \
    {                                                                                                        \
        name, w_kconst, (void *)(intptr_t)(v), 0, FBRL_DOC("( -- u )", "the key event EKEY gives for " name) \
    }

static const fbrl_cword words[] = {
    {"EKEY", w_ekey, NULL, 0,
     FBRL_DOC("( -- x )", "wait for a key event (a character, or a cursor or function key)")},
    {"EKEY?", w_ekeyq, NULL, 0, FBRL_DOC("( -- flag )", "true if a key event is waiting")},
    {"EKEY>CHAR", w_ekey_to, NULL, 0,
     FBRL_DOC("( x -- x flag )", "flag true if the key event is a character")},
    {"EKEY>FKEY", w_ekey_to, (void *)1, 0,
     FBRL_DOC("( x -- x flag )", "flag true if the key event is a special key")},
    {"EMIT?", w_emitq, NULL, 0, FBRL_DOC("( -- flag )", "true if EMIT can send (the host has an output)")},
    {"AT-XY", w_at_xy, NULL, 0,
     FBRL_DOC("( col row -- )", "move the terminal's cursor (ANSI; 0 0 is top left)")},
    {"PAGE", w_page, NULL, 0, FBRL_DOC("( -- )", "clear the terminal (ANSI)")},
    KC("K-LEFT", KEV_FKEY + K_LEFT),
    KC("K-RIGHT", KEV_FKEY + K_RIGHT),
    KC("K-UP", KEV_FKEY + K_UP),
    KC("K-DOWN", KEV_FKEY + K_DOWN),
    KC("K-HOME", KEV_FKEY + K_HOME),
    KC("K-END", KEV_FKEY + K_END),
    KC("K-PRIOR", KEV_FKEY + K_PRIOR),
    KC("K-NEXT", KEV_FKEY + K_NEXT),
    KC("K-INSERT", KEV_FKEY + K_INSERT),
    KC("K-DELETE", KEV_FKEY + K_DELETE),
    KC("K-F1", KEV_FKEY + K_F1),
    KC("K-F2", KEV_FKEY + K_F2),
    KC("K-F3", KEV_FKEY + K_F3),
    KC("K-F4", KEV_FKEY + K_F4),
    KC("K-F5", KEV_FKEY + K_F5),
    KC("K-F6", KEV_FKEY + K_F6),
    KC("K-F7", KEV_FKEY + K_F7),
    KC("K-F8", KEV_FKEY + K_F8),
    KC("K-F9", KEV_FKEY + K_F9),
    KC("K-F10", KEV_FKEY + K_F10),
    KC("K-F11", KEV_FKEY + K_F11),
    KC("K-F12", KEV_FKEY + K_F12),
    KC("K-SHIFT-MASK", KEV_SHIFT),
    KC("K-CTRL-MASK", KEV_CTRL),
    KC("K-ALT-MASK", KEV_ALT),
};

int fbrl__facility_words(fbrl_vm *vm)
{
    return fbrl__define_words(vm, words, sizeof words / sizeof words[0]);
}
