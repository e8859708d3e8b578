/*
 * ARM semihosting (svc 0x123456 in ARM state): the firmware's command line,
 * console output, host files and exit, answered by QEMU
 * (-semihosting-config enable=on,target=native). Only these calls are used.
 */
#ifndef FW_SEMIHOST_H
#define FW_SEMIHOST_H

#include <stdint.h>

/** Copy the command line (QEMU's arg=... values, joined by blanks) into
 *  @p buf, NUL-terminated. Returns 0, or -1 (none, or too long). */
int sh_cmdline(char *buf, uint32_t cap);
/** Write a NUL-terminated string to the console. */
void sh_puts(const char *s);
/** Open host file @p name (mode: 3 "r+b", 7 "w+b"); handle or -1. */
int32_t sh_open(const char *name, uint32_t mode);
/** Length of an open file, or -1. */
int32_t sh_flen(int32_t fd);
/** Seek to absolute @p pos; 0 on success. */
int32_t sh_seek(int32_t fd, uint32_t pos);
/** Read / write @p len bytes: returns the number NOT transferred (0: all). */
uint32_t sh_read(int32_t fd, void *buf, uint32_t len);
uint32_t sh_write(int32_t fd, const void *buf, uint32_t len);
/** Stop the emulator: status 0 (@p ok non-zero) or 1. */
void sh_exit(int ok);

#endif /* FW_SEMIHOST_H */
