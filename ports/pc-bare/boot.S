/* SPDX-License-Identifier: MIT */
/* boot.S - Multiboot v1 entry, flat GDT, and the interrupt stubs.
 *
 * QEMU's -kernel loads this ELF at 1 MiB and jumps to _start in 32-bit protected
 * mode with EAX = multiboot magic and EBX = the info block, but with GDTR undefined:
 * so the first thing is our own flat GDT (code 0x08, data 0x10). */

    .set MB_MAGIC, 0x1BADB002
    .set MB_FLAGS, 0x00000003          /* page-align modules, give memory info */

    .section .multiboot, "a"
    .align 4
    .long MB_MAGIC, MB_FLAGS, -(MB_MAGIC + MB_FLAGS)

    .section .bss
    .align 16
stack_bottom:
    .skip 16384
stack_top:

    .section .text
    .global _start
_start:
    cli
    mov $stack_top, %esp
    lgdt gdt_desc
    ljmp $0x08, $1f
1:  mov $0x10, %cx
    mov %cx, %ds
    mov %cx, %es
    mov %cx, %fs
    mov %cx, %gs
    mov %cx, %ss
    push %ebx
    push %eax
    call kmain                          /* never returns */
2:  cli
    hlt
    jmp 2b

/* Hardware interrupts: save the general registers, call the C handler, return.
 * The C code is built with -mgeneral-regs-only, so no FPU/SSE state to save. */
    .macro IRQ_STUB name, handler
    .global \name
\name:
    pusha
    cld
    call \handler
    popa
    iret
    .endm

    IRQ_STUB pc_irq_timer_stub, pc_irq_timer
    IRQ_STUB pc_irq_com_stub, pc_irq_com
    IRQ_STUB pc_irq_other_stub, pc_irq_other

/* CPU exceptions 0..31: push the vector and report it; pc_exception never returns. */
    .irp n, 0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,29,30,31
exc_\n:
    push $\n
    jmp exc_common
    .endr
exc_common:
    cld
    call pc_exception
3:  cli
    hlt
    jmp 3b

    .section .rodata
    .align 4
    .global pc_exception_stubs
pc_exception_stubs:
    .irp n, 0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,29,30,31
    .long exc_\n
    .endr

    .align 8
gdt:
    .quad 0x0000000000000000
    .quad 0x00CF9A000000FFFF            /* 0x08: code, base 0, 4 GiB, ring 0 */
    .quad 0x00CF92000000FFFF            /* 0x10: data */
gdt_desc:
    .word gdt_desc - gdt - 1
    .long gdt

    .section .note.GNU-stack, "", @progbits
