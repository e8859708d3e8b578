/*
 * Start-up code for the unit tests on QEMU's MPS2 AN385 board (Cortex-M3),
 * with the C library's I/O through semihosting (newlib's librdimon):
 * vector table, zeroed .bss, the program's arguments from the semihosting
 * command line (QEMU -semihosting-config ...,arg=...), main, and exit with
 * main's status (QEMU exits with it). A fault prints its name and exits
 * with status 3, so that a crash fails the test instead of hanging it.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern uint32_t __bss_start__[];
extern uint32_t __bss_end__[];
extern uint32_t __stack_top[];

int main(int argc, char **argv);
void initialise_monitor_handles(void);
void Reset_Handler(void);
void co_mps2_fault(void);

#define SYS_GET_CMDLINE 0x15
#define ARGV_MAX 8

static char cmdline[512];
static char *argv_buf[ARGV_MAX + 1];

/* One semihosting call (BKPT 0xAB on M-profile). */
static int semihost(int op, void *arg)
{
    register int r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;

    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* The command line split at spaces (no quoting: paths without spaces). */
static int get_args(void)
{
    struct {
        char *buf;
        int len;
    } block = {cmdline, (int)sizeof cmdline - 1};
    int argc = 0;
    char *p = cmdline;

    if (semihost(SYS_GET_CMDLINE, &block) != 0) {
        return 0;
    }
    cmdline[sizeof cmdline - 1U] = '\0';
    while ((*p != '\0') && (argc < ARGV_MAX)) {
        while (*p == ' ') {
            *p++ = '\0';
        }
        if (*p == '\0') {
            break;
        }
        argv_buf[argc++] = p;
        while ((*p != '\0') && (*p != ' ')) {
            p++;
        }
    }
    argv_buf[argc] = NULL;
    return argc;
}

void Reset_Handler(void)
{
    int argc;

    for (uint32_t *p = __bss_start__; p < __bss_end__; p++) {
        *p = 0U;
    }
    initialise_monitor_handles();
    argc = get_args();
    exit(main(argc, argv_buf));
}

/* The C library's init/fini hooks (crti/crtn, left out with -nostartfiles):
 * no constructors or destructors in C. */
void _init(void);
void _fini(void);
void _init(void)
{
}
void _fini(void)
{
}

void co_mps2_fault(void)
{
    fputs("mps2: fault (HardFault, MemManage, BusFault or UsageFault)\n", stderr);
    _Exit(3);
}

typedef void (*vector_t)(void);

/* Initial stack pointer, reset, NMI, the four faults; nothing else is
 * enabled. Pulled into every test program by -u co_mps2_vectors. */
__attribute__((section(".isr_vector"), used)) const vector_t co_mps2_vectors[8] = {
    (vector_t)(uintptr_t)__stack_top,
    Reset_Handler,
    co_mps2_fault, /* NMI */
    co_mps2_fault, /* HardFault */
    co_mps2_fault, /* MemManage */
    co_mps2_fault, /* BusFault */
    co_mps2_fault, /* UsageFault */
    NULL,
};
