/*
 * Startup for mps2-an386 (Cortex-M4F): vector table, reset handler (data copy, bss clear, FPU on),
 * then main(); its return value becomes QEMU's exit code through semihosting.
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

/* Coprocessor access control: CP10 and CP11 (the FPU) full access. */
#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)

void tvo_reset_handler(void)
{
    for (uint32_t *src = __data_load__, *dst = __data_start__; dst < __data_end__;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = __bss_start__; dst < __bss_end__;) {
        *dst++ = 0u;
    }
#if defined(__ARM_FP)
    SCB_CPACR |= CPACR_CP10_CP11_FULL; /* before any float instruction runs */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    tvo_board_exit(main());
}

void tvo_fault_handler(void)
{
    tvo_board_puts("FATAL: processor fault\n");
    tvo_board_exit(99);
}

typedef void (*tvo_vector_t)(void);

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
