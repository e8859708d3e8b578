/*
 * CPU 0 (Cortex-A53, AArch64 EL1) of QEMU's xlnx-zcu102: QEMU keeps every
 * other CPU powered off, so this starts the first Cortex-R5 (CPU 4, MPIDR 4)
 * at the firmware's entry with PSCI CPU_ON (SMC64 function 0xC4000003,
 * answered by QEMU itself through smc #0) and then sleeps for good.
 * r5_entry is defined at link time (the R5 image's load address).
 */
    .text
    .global _start
_start:
    ldr     x0, =0xC4000003     /* PSCI CPU_ON */
    mov     x1, #4              /* target MPIDR: RPU core 0 */
    ldr     x2, =r5_entry       /* entry point (AArch32, ARM state) */
    mov     x3, #0              /* context id: r0 of the R5 */
    smc     #0
1:  wfi
    b       1b
