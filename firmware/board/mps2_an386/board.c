/* mps2-an386 board support: semihosting console and exit, SysTick; see board.h. */
#include "board.h"

/* ARM semihosting operations (ARM DUI 0471 / the semihosting specification). */
#define SEMIHOSTING_SYS_WRITEC 0x03u
#define SEMIHOSTING_SYS_WRITE0 0x04u
#define SEMIHOSTING_SYS_EXIT_EXTENDED 0x20u
#define SEMIHOSTING_ADP_STOPPED_APPLICATION_EXIT 0x20026u

/* SysTick registers (ARMv7-M architecture reference manual, B3.3). */
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_CSR_ENABLE (1u << 0)
#define SYST_CSR_CLKSOURCE_CPU (1u << 2)
#define SYST_RELOAD_MAX 0x00FFFFFFu

/* CMSDK APB UART0 of the mps2 boards (ARM DDI 0479, CMSDK, "APB UART"). */
#define UART0_BASE 0x40004000u
#define UART_DATA (*(volatile uint32_t *)(UART0_BASE + 0x000u))
#define UART_STATE (*(volatile uint32_t *)(UART0_BASE + 0x004u))
#define UART_CTRL (*(volatile uint32_t *)(UART0_BASE + 0x008u))
#define UART_BAUDDIV (*(volatile uint32_t *)(UART0_BASE + 0x010u))
#define UART_STATE_TX_FULL (1u << 0)
#define UART_STATE_RX_FULL (1u << 1)
#define UART_CTRL_TX_EN (1u << 0)
#define UART_CTRL_RX_EN (1u << 1)
#define UART_BAUDDIV_MIN 16u /* the smallest divider the UART accepts */

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
    char digits[11];
    uint32_t n = 0u;
    do {
        digits[n++] = (char)('0' + (value % 10u));
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

void tvo_board_cycle_counter_start(void)
{
    SYST_CSR = 0u;
    SYST_RVR = SYST_RELOAD_MAX;
    SYST_CVR = 0u;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_CLKSOURCE_CPU;
}

uint32_t tvo_board_cycle_counter_read(void)
{
    return SYST_CVR;
}

uint32_t tvo_board_cycle_counter_elapsed(uint32_t start, uint32_t end)
{
    return (start - end) & SYST_RELOAD_MAX; /* counts down, modulo 2^24 */
}

void tvo_board_uart_init(void)
{
    UART_BAUDDIV = UART_BAUDDIV_MIN;
    UART_CTRL = UART_CTRL_TX_EN | UART_CTRL_RX_EN;
}

void tvo_board_uart_write(const uint8_t *data, uint32_t length)
{
    for (uint32_t i = 0; i < length; ++i) {
        while ((UART_STATE & UART_STATE_TX_FULL) != 0u) {
            /* wait for room: bounded by the UART draining, which it always does */
        }
        UART_DATA = data[i];
    }
}

int tvo_board_uart_read(uint8_t *byte)
{
    if ((UART_STATE & UART_STATE_RX_FULL) == 0u) {
        return 0;
    }
    *byte = (uint8_t)UART_DATA;
    return 1;
}
