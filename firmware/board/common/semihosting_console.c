/* Semihosting console and exit; see semihosting_console.h. */
#include "semihosting_console.h"

/* ARM semihosting operations (ARM DUI 0471 / the semihosting specification). */
#define SEMIHOSTING_SYS_WRITEC 0x03u
#define SEMIHOSTING_SYS_WRITE0 0x04u
#define SEMIHOSTING_SYS_EXIT_EXTENDED 0x20u
#define SEMIHOSTING_ADP_STOPPED_APPLICATION_EXIT 0x20026u

static uint32_t semihosting_call(uint32_t operation, const void *argument)
{
    register uint32_t r0 __asm__("r0") = operation;
    register const void *r1 __asm__("r1") = argument;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void tvo_board_putc(char c)
{
    (void)semihosting_call(SEMIHOSTING_SYS_WRITEC, &c);
}

void tvo_board_puts(const char *s)
{
    (void)semihosting_call(SEMIHOSTING_SYS_WRITE0, s);
}

void tvo_board_put_u32(uint32_t value)
{
    tvo_board_put_u64(value);
}

void tvo_board_put_u64(uint64_t value)
{
    char digits[21];
    uint32_t n = 0u;
    do {
        digits[n++] = (char)('0' + (char)(value % 10u));
        value /= 10u;
    } while (value != 0u && n < sizeof(digits));
    while (n > 0u) {
        tvo_board_putc(digits[--n]);
    }
}

void tvo_board_put_i32(int32_t value)
{
    if (value < 0) {
        tvo_board_putc('-');
        tvo_board_put_u32(0u - (uint32_t)value);
    } else {
        tvo_board_put_u32((uint32_t)value);
    }
}

void tvo_board_exit(int code)
{
    const uint32_t block[2] = {SEMIHOSTING_ADP_STOPPED_APPLICATION_EXIT, (uint32_t)code};
    (void)semihosting_call(SEMIHOSTING_SYS_EXIT_EXTENDED, block);
    for (;;) {
        /* not reached under QEMU; on a board without a debugger, stay here */
    }
}
