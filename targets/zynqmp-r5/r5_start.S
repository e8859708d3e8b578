/*
 * Entry of the Cortex-R5 firmware (ARM state, SVC mode, as PSCI CPU_ON
 * leaves the core): interrupts off, the stack set, .bss zeroed (QEMU's
 * loader puts .text/.data in place; on a board the boot loader does), then
 * fw_main. The image has no C library start-up.
 */
    .syntax unified
    .arm
    .section .text.start, "ax"
    .global _r5_start
_r5_start:
    cpsid   if
    ldr     sp, =_estack
    ldr     r0, =_sbss
    ldr     r1, =_ebss
    mov     r2, #0
1:  cmp     r0, r1
    strlo   r2, [r0], #4
    blo     1b
    bl      fw_main
2:  b       2b
