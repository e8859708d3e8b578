/*
 * Minimal start-up for the Cortex-M3 size build: the vector table, a reset
 * handler that copies .data, zeroes .bss and calls main, and a default
 * handler for every other exception. No C library start-up (crt0, atexit,
 * constructors): the image holds only what the firmware uses.
 */
#include <stdint.h>

extern uint32_t _sidata[]; /* start of the .data image in flash */
extern uint32_t _sdata[];  /* .data in RAM */
extern uint32_t _edata[];
extern uint32_t _sbss[];   /* .bss */
extern uint32_t _ebss[];
extern uint32_t _estack[]; /* top of the stack */

int main(void);
void Reset_Handler(void);
void Default_Handler(void);
void CAN1_RX0_IRQHandler(void);

void Default_Handler(void)
{
    for (;;) {
    }
}

void Reset_Handler(void)
{
    const uint32_t *src = _sidata;

    for (uint32_t *dst = _sdata; dst < _edata; dst++) {
        *dst = *src;
        src++;
    }
    for (uint32_t *dst = _sbss; dst < _ebss; dst++) {
        *dst = 0U;
    }
    (void)main();
    for (;;) {
    }
}

typedef void (*vector_t)(void);

/* System exceptions, then the STM32F1 interrupts up to CAN1 RX0 (IRQ 20);
 * the CAN RX interrupt is the only one the firmware uses. */
__attribute__((section(".isr_vector"), used)) static const vector_t vectors[16 + 21] = {
    (vector_t)(uintptr_t)_estack,
    Reset_Handler,
    Default_Handler, /* NMI */
    Default_Handler, /* HardFault */
    Default_Handler, /* MemManage */
    Default_Handler, /* BusFault */
    Default_Handler, /* UsageFault */
    0, 0, 0, 0,
    Default_Handler, /* SVCall */
    Default_Handler, /* DebugMon */
    0,
    Default_Handler, /* PendSV */
    Default_Handler, /* SysTick */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 0..3 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 4..7 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 8..11 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 12..15 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 16..19 */
    CAN1_RX0_IRQHandler,                                                /* IRQ 20 */
};
