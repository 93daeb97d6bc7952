/*
 * Startup for the microbit (nRF51822, Cortex-M0): vector table, reset handler (data copy, bss
 * clear), then main(); its return value becomes QEMU's exit code through semihosting.
 */
#include <stdint.h>

#include "board.h"
#include "../common/cortex_m_startup.h" /* by path, as board.h includes the console */

int main(void);
void tvo_reset_handler(void);
void tvo_fault_handler(void);

void tvo_reset_handler(void)
{
    tvo_startup_init_memory();
    tvo_board_exit(main());
}

void tvo_fault_handler(void)
{
    tvo_startup_report_fault();
}

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
