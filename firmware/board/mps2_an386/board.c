/* mps2-an386 board support: SysTick, UART0 (the console is common/semihosting_console.c); see board.h. */
#include "board.h"

/* SysTick registers (ARMv7-M architecture reference manual, B3.3). */
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_CSR_ENABLE (1u << 0)
#define SYST_CSR_TICKINT (1u << 1)
#define SYST_CSR_CLKSOURCE_CPU (1u << 2)
#define SYST_RELOAD_MAX 0x00FFFFFFu

/* Interrupt control and state register (ARMv7-M ARM, B3.2.4): SysTick pending, and its clear. */
#define SCB_ICSR (*(volatile uint32_t *)0xE000ED04u)
#define SCB_ICSR_PENDSTSET (1u << 26)
#define SCB_ICSR_PENDSTCLR (1u << 25)

/* The monotonic clock: SysTick counts CLOCK_TICKS_PER_US per microsecond (25 MHz core clock) and
 * wraps every CLOCK_PERIOD_US, a whole number of microseconds (2^19 us = 0.52 s, the largest power of
 * two its 24 bits hold): the wrap interrupt is rare, and a wrap is lost only if the interrupt is held
 * off for a whole period. */
#define CLOCK_TICKS_PER_US 25u
#define CLOCK_PERIOD_US (1u << 19)
#define CLOCK_PERIOD_TICKS (CLOCK_TICKS_PER_US * CLOCK_PERIOD_US)
_Static_assert(CLOCK_PERIOD_TICKS - 1u <= SYST_RELOAD_MAX, "the clock period must fit SysTick's reload");
/* Polls for the counter's first reload; one SysTick clock on hardware, a little more under QEMU. */
#define CLOCK_START_POLLS 1000000u
/* A read is retried when the wrap interrupt ran during it; it runs once per period, so twice is plenty. */
#define CLOCK_READ_ATTEMPTS 3u

static volatile uint32_t clock_wraps;   /* periods completed, counted by the SysTick interrupt */
static volatile uint8_t clock_running;
static int64_t clock_last_us;            /* the last reading (main code only) */

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

void tvo_board_systick_handler(void)
{
    ++clock_wraps;
}

int tvo_board_clock_start(void)
{
    clock_running = 0u;
    SYST_CSR = 0u;
    SYST_RVR = CLOCK_PERIOD_TICKS - 1u;
    SYST_CVR = 0u;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_CLKSOURCE_CPU;
    /* A count of 0 must mean "a period just ended" (see tvo_board_now_us): wait for the reload that
     * follows the clear, which pends nothing, before the wrap interrupt is enabled. */
    uint32_t polls = 0u;
    while (SYST_CVR == 0u) {
        if (++polls >= CLOCK_START_POLLS) {
            SYST_CSR = 0u;
            return -1;
        }
    }
    SCB_ICSR = SCB_ICSR_PENDSTCLR;
    clock_wraps = 0u;
    clock_last_us = 0;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE_CPU;
    clock_running = 1u;
    return 0;
}

int64_t tvo_board_now_us(void)
{
    if (clock_running == 0u) {
        return -1;
    }
    for (uint32_t attempt = 0u; attempt < CLOCK_READ_ATTEMPTS; ++attempt) {
        const uint32_t wraps = clock_wraps;
        uint32_t count = SYST_CVR;
        int64_t now_us = clock_last_us;
        if ((SCB_ICSR & SCB_ICSR_PENDSTSET) != 0u) {
            /* A wrap the interrupt has not counted yet: `count` may be from either side of it, so
             * read again, now surely after it (0: the wrap's own tick), into the next period. */
            count = SYST_CVR;
            const uint32_t ticks = (count == 0u) ? 0u : CLOCK_PERIOD_TICKS - count;
            now_us = (int64_t)(((uint64_t)wraps + 1u) * CLOCK_PERIOD_US + ticks / CLOCK_TICKS_PER_US);
        } else if (count != 0u) {
            now_us = (int64_t)((uint64_t)wraps * CLOCK_PERIOD_US + (CLOCK_PERIOD_TICKS - count) / CLOCK_TICKS_PER_US);
        }
        /* else the counter sits on a wrap the interrupt may or may not have counted yet (QEMU shows 0
         * until its timer fires; hardware for one tick, possibly after the interrupt ran): the clock
         * is at that wrap, no earlier than the last reading, so that reading stands. */
        if (clock_wraps == wraps) {
            clock_last_us = now_us;
            return now_us;
        }
    }
    return -1;
}

void tvo_board_cycle_counter_start(void)
{
    clock_running = 0u;
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
    /* Empty the receive register. Under QEMU this read also tells the -serial backend the receiver
     * has room (enabling it does not): without it, bytes already waiting sit there until QEMU's main
     * loop wakes for another reason (measured: half a second, until SysTick's timer fired). */
    (void)UART_DATA;
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

/* Placed by the linker script at the provisioned region's start (the region no image writes). */
extern const uint8_t tvo_board_provisioned_region_start[];

const uint8_t *tvo_board_provisioned_region(void)
{
    return tvo_board_provisioned_region_start;
}
