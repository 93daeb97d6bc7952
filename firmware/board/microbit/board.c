/* microbit (nRF51822) board support: TIMER0 as the cycle counter; see board.h. */
#include "board.h"

/* TIMER0 (nRF51 Series Reference Manual v3.0, chapter 18 "TIMER"). */
#define TIMER0_BASE 0x40008000u
#define TIMER_REG(offset) (*(volatile uint32_t *)(TIMER0_BASE + (offset)))
#define TIMER_TASKS_START TIMER_REG(0x000u)
#define TIMER_TASKS_STOP TIMER_REG(0x004u)
#define TIMER_TASKS_CLEAR TIMER_REG(0x00Cu)
#define TIMER_TASKS_CAPTURE0 TIMER_REG(0x040u)
#define TIMER_MODE TIMER_REG(0x504u)
#define TIMER_BITMODE TIMER_REG(0x508u)
#define TIMER_PRESCALER TIMER_REG(0x510u)
#define TIMER_CC0 TIMER_REG(0x540u)
#define TIMER_MODE_TIMER 0u
#define TIMER_BITMODE_32 3u
#define TIMER_PRESCALER_16MHZ 0u

void tvo_board_cycle_counter_start(void)
{
    TIMER_TASKS_STOP = 1u;
    TIMER_MODE = TIMER_MODE_TIMER;
    TIMER_BITMODE = TIMER_BITMODE_32;
    TIMER_PRESCALER = TIMER_PRESCALER_16MHZ;
    TIMER_TASKS_CLEAR = 1u;
    TIMER_TASKS_START = 1u;
}

uint32_t tvo_board_cycle_counter_read(void)
{
    TIMER_TASKS_CAPTURE0 = 1u;
    return TIMER_CC0;
}

uint32_t tvo_board_cycle_counter_elapsed(uint32_t start, uint32_t end)
{
    return end - start; /* counts up, modulo 2^32 */
}
