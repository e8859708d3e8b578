/* ARM semihosting calls (see semihost.h). */
#include "semihost.h"

#include <string.h>

#define SYS_OPEN        0x01U
#define SYS_WRITE0      0x04U
#define SYS_WRITE       0x05U
#define SYS_READ        0x06U
#define SYS_SEEK        0x0AU
#define SYS_FLEN        0x0CU
#define SYS_GET_CMDLINE 0x15U
#define SYS_EXIT        0x18U
#define ADP_STOPPED_APPLICATION_EXIT 0x20026U
#define ADP_STOPPED_RUN_TIME_ERROR   0x20023U

static uint32_t call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;

    /* on hardware the SVC would enter SVC mode: lr is clobbered */
    __asm__ volatile("svc 0x123456" : "+r"(r0) : "r"(r1) : "memory", "lr");
    return r0;
}

int sh_cmdline(char *buf, uint32_t cap)
{
    uint32_t blk[2];

    blk[0] = (uint32_t)(uintptr_t)buf;
    blk[1] = cap;
    if ((cap == 0U) || (call(SYS_GET_CMDLINE, blk) != 0U)) {
        return -1;
    }
    buf[cap - 1U] = '\0';
    return 0;
}

void sh_puts(const char *s)
{
    (void)call(SYS_WRITE0, s);
}

int32_t sh_open(const char *name, uint32_t mode)
{
    uint32_t blk[3];

    blk[0] = (uint32_t)(uintptr_t)name;
    blk[1] = mode;
    blk[2] = (uint32_t)strlen(name);
    return (int32_t)call(SYS_OPEN, blk);
}

int32_t sh_flen(int32_t fd)
{
    uint32_t blk[1];

    blk[0] = (uint32_t)fd;
    return (int32_t)call(SYS_FLEN, blk);
}

int32_t sh_seek(int32_t fd, uint32_t pos)
{
    uint32_t blk[2];

    blk[0] = (uint32_t)fd;
    blk[1] = pos;
    return (int32_t)call(SYS_SEEK, blk);
}

uint32_t sh_read(int32_t fd, void *buf, uint32_t len)
{
    uint32_t blk[3];

    blk[0] = (uint32_t)fd;
    blk[1] = (uint32_t)(uintptr_t)buf;
    blk[2] = len;
    return call(SYS_READ, blk);
}

uint32_t sh_write(int32_t fd, const void *buf, uint32_t len)
{
    uint32_t blk[3];

    blk[0] = (uint32_t)fd;
    blk[1] = (uint32_t)(uintptr_t)buf;
    blk[2] = len;
    return call(SYS_WRITE, blk);
}

void sh_exit(int ok)
{
    /* AArch32: the reason code itself is the parameter */
    (void)call(SYS_EXIT, (const void *)(uintptr_t)(ok ? ADP_STOPPED_APPLICATION_EXIT
                                                      : ADP_STOPPED_RUN_TIME_ERROR));
    for (;;) {
    }
}
