/*
 * What every board's startup shares: the C runtime's memory (the linker script's symbols) and the
 * fault report. Each board keeps its own vector table and reset handler around these. Board code
 * only; inline, so a board's build lists no extra source.
 */
#ifndef TVO_CORTEX_M_STARTUP_H
#define TVO_CORTEX_M_STARTUP_H

#include <stdint.h>

#include "semihosting_console.h"

extern uint32_t __data_load__[];
extern uint32_t __data_start__[];
extern uint32_t __data_end__[];
extern uint32_t __bss_start__[];
extern uint32_t __bss_end__[];
extern uint32_t __stack_top__[];

/** .data copied from flash, .bss cleared: before any C code reads a static. */
static inline void tvo_startup_init_memory(void)
{
    for (uint32_t *src = __data_load__, *dst = __data_start__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }
}

/** A processor fault: say so on the console and end with exit code 99. */
static inline void tvo_startup_report_fault(void)
{
    tvo_board_puts("FATAL: processor fault\n");
    tvo_board_exit(99);
}

typedef void (*tvo_vector_t)(void);

#endif /* TVO_CORTEX_M_STARTUP_H */
