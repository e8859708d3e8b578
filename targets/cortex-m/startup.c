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
/* The handlers an image may define; the others run Default_Handler. */
void SysTick_Handler(void) __attribute__((weak, alias("Default_Handler")));
void USB_HP_CAN1_TX_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void CAN1_RX0_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void CAN1_RX1_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));
void CAN1_SCE_IRQHandler(void) __attribute__((weak, alias("Default_Handler")));

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

/* System exceptions, then the STM32F1 interrupts up to CAN1 SCE (IRQ 22):
 * CAN1 TX (19, shared with USB high priority), RX0 (20), RX1 (21), status
 * change / error (22). */
__attribute__((section(".isr_vector"), used)) static const vector_t vectors[16 + 23] = {
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
    SysTick_Handler,
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 0..3 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 4..7 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 8..11 */
    Default_Handler, Default_Handler, Default_Handler, Default_Handler, /* IRQ 12..15 */
    Default_Handler, Default_Handler, Default_Handler,                  /* IRQ 16..18 */
    USB_HP_CAN1_TX_IRQHandler,                                          /* IRQ 19 */
    CAN1_RX0_IRQHandler,                                                /* IRQ 20 */
    CAN1_RX1_IRQHandler,                                                /* IRQ 21 */
    CAN1_SCE_IRQHandler,                                                /* IRQ 22 */
};
