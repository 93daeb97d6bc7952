/* The board interface on the host, for running bench.c under valgrind --tool=callgrind (which
 * counts instructions itself: the cycle counter here reads 0). */
#include <stdio.h>
#include <stdlib.h>

#include "board.h"

void tvo_board_putc(char c)
{
    (void)putchar(c);
}

void tvo_board_puts(const char *s)
{
    (void)fputs(s, stdout);
}

void tvo_board_put_u32(uint32_t value)
{
    (void)printf("%lu", (unsigned long)value);
}

void tvo_board_put_i32(int32_t value)
{
    (void)printf("%ld", (long)value);
}

void tvo_board_exit(int code)
{
    exit(code);
}

void tvo_board_cycle_counter_start(void)
{
}

uint32_t tvo_board_cycle_counter_read(void)
{
    return 0u;
}

uint32_t tvo_board_cycle_counter_elapsed(uint32_t start, uint32_t end)
{
    return start - end;
}
