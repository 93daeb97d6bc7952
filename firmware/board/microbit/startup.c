/*
 * Startup for the microbit (nRF51822, Cortex-M0): vector table, reset handler (data copy, bss
 * clear), then main(); its return value becomes QEMU's exit code through semihosting.
 */
#include <stdint.h>

#include "board.h"

extern uint32_t __data_load__[];
extern uint32_t __data_start__[];
extern uint32_t __data_end__[];
extern uint32_t __bss_start__[];
extern uint32_t __bss_end__[];
extern uint32_t __stack_top__[];

int main(void);
void tvo_reset_handler(void);
void tvo_fault_handler(void);

void tvo_reset_handler(void)
{
    for (uint32_t *src = __data_load__, *dst = __data_start__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }
    tvo_board_exit(main());
}

void tvo_fault_handler(void)
{
    tvo_board_puts("FATAL: processor fault\n");
    tvo_board_exit(99);
}

typedef void (*tvo_vector_t)(void);

/* Initial stack pointer, then ARMv6-M's system exception vectors (no interrupts are used). */
__attribute__((section(".vectors"), used)) static const tvo_vector_t vector_table[16] = {
    (tvo_vector_t)(uintptr_t)__stack_top__,
    tvo_reset_handler,
    tvo_fault_handler, /* NMI */
    tvo_fault_handler, /* HardFault */
    0, 0, 0, 0, 0, 0, 0,
    tvo_fault_handler, /* SVCall */
    0, 0,
    tvo_fault_handler, /* PendSV */
    tvo_fault_handler, /* SysTick: the nRF51 has none */
};
