/*
 * Startup for mps2-an386 (Cortex-M4F): vector table, reset handler (data copy, bss clear, FPU on),
 * then main(); its return value becomes QEMU's exit code through semihosting.
 */
#include <stdint.h>

#include "board.h"
#include "../common/cortex_m_startup.h" /* by path, as board.h includes the console */

int main(void);
void tvo_reset_handler(void);
void tvo_fault_handler(void);

/* Coprocessor access control: CP10 and CP11 (the FPU) full access. */
#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)

void tvo_reset_handler(void)
{
    tvo_startup_init_memory();
#if defined(__ARM_FP)
    SCB_CPACR |= CPACR_CP10_CP11_FULL; /* before any float instruction runs */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    tvo_board_exit(main());
}

void tvo_fault_handler(void)
{
    tvo_startup_report_fault();
}

/* Initial stack pointer, then the 15 system exception vectors. */
__attribute__((section(".vectors"), used)) static const tvo_vector_t vector_table[16] = {
    (tvo_vector_t)(uintptr_t)__stack_top__,
    tvo_reset_handler,
    tvo_fault_handler, /* NMI */
    tvo_fault_handler, /* HardFault */
    tvo_fault_handler, /* MemManage */
    tvo_fault_handler, /* BusFault */
    tvo_fault_handler, /* UsageFault */
    0, 0, 0, 0,
    tvo_fault_handler, /* SVCall */
    tvo_fault_handler, /* DebugMonitor */
    0,
    tvo_fault_handler, /* PendSV */
    tvo_board_systick_handler, /* the monotonic clock's wraps (tvo_board_clock_start) */
};
