/*
 * Console output and exit code through ARM semihosting (BKPT 0xAB), for every board QEMU runs:
 * QEMU prints the text on its semihosting console and exits with the program's code. Board code
 * only; the control core never sees it.
 */
#ifndef TVO_SEMIHOSTING_CONSOLE_H
#define TVO_SEMIHOSTING_CONSOLE_H

#include <stdint.h>

void tvo_board_putc(char c);
void tvo_board_puts(const char *s);
/** Decimal, without stdio. */
void tvo_board_put_u32(uint32_t value);
void tvo_board_put_u64(uint64_t value);
void tvo_board_put_i32(int32_t value);

/** Ends the program; QEMU exits with this code (semihosting SYS_EXIT_EXTENDED). */
void tvo_board_exit(int code) __attribute__((noreturn));

#endif /* TVO_SEMIHOSTING_CONSOLE_H */
