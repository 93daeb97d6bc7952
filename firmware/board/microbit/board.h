/*
 * Board support for QEMU's microbit (nRF51822, Cortex-M0): console and exit code through
 * semihosting, and TIMER0 as a cycle counter. The nRF51 has no SysTick, so the counter is TIMER0
 * at its full 16 MHz, 32 bits wide. Board code only; the control core never sees it.
 *
 * Under `qemu-system-arm -icount shift=0` one instruction takes 1 ns of virtual time, so a 16 MHz
 * count is 62.5 instructions, deterministically.
 */
#ifndef TVO_BOARD_H
#define TVO_BOARD_H

#include <stdint.h>

#include "../common/semihosting_console.h" /* by path: a user's build needs no extra include folder */

/** Instructions per TIMER0 count under -icount shift=0: NUM / DEN = 62.5. */
#define TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM 125u
#define TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN 2u

/** Starts TIMER0 counting up from 0 at 16 MHz, 32 bits wide. */
void tvo_board_cycle_counter_start(void);
/** Current TIMER0 count (captured into CC[0]). */
uint32_t tvo_board_cycle_counter_read(void);
/** Counts from start to end, for a span shorter than one wrap (4.5 min of 16 MHz). */
uint32_t tvo_board_cycle_counter_elapsed(uint32_t start, uint32_t end);

#endif /* TVO_BOARD_H */
