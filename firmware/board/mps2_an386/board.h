/*
 * Board support for QEMU's mps2-an386 (Cortex-M4F): console output and exit code through ARM
 * semihosting, SysTick as a monotonic microsecond clock or as a cycle counter, and UART0. Board
 * code only; the control core never sees it.
 *
 * Under `qemu-system-arm -icount shift=0` one instruction takes 1 ns of virtual time and SysTick
 * (25 MHz on this board) advances once per 40 instructions, deterministically.
 */
#ifndef TVO_BOARD_H
#define TVO_BOARD_H

#include <stdint.h>

#include "../common/semihosting_console.h" /* by path: a user's build needs no extra include folder */

/** Instructions per SysTick count under -icount shift=0 on mps2-an386: NUM / DEN. */
#define TVO_BOARD_INSTRUCTIONS_PER_TICK_NUM 40u
#define TVO_BOARD_INSTRUCTIONS_PER_TICK_DEN 1u

/**
 * Starts the monotonic clock: SysTick on the 25 MHz core clock, its wraps counted by the SysTick
 * interrupt. 0, or -1 if the counter does not run. SysTick is then the clock's: a program uses the
 * clock or the cycle counter below, not both.
 */
int tvo_board_clock_start(void);
/**
 * Microseconds since tvo_board_clock_start (64 bits: no wrap in practice), never decreasing; -1 if
 * the clock is not running. From main code, with interrupts enabled (the SysTick interrupt counts
 * the wraps), not from an interrupt handler.
 */
int64_t tvo_board_now_us(void);
/** The SysTick interrupt (the vector table's entry; counts the clock's wraps). */
void tvo_board_systick_handler(void);

/** Starts SysTick free-running from its 24-bit reload value, counting down on the CPU clock. */
void tvo_board_cycle_counter_start(void);
/** Current SysTick count (counts down; wraps every 2^24 ticks). */
uint32_t tvo_board_cycle_counter_read(void);
/** Ticks from start to end, for a span shorter than one wrap. */
uint32_t tvo_board_cycle_counter_elapsed(uint32_t start, uint32_t end);

/** UART0 (CMSDK APB UART; QEMU's first -serial), transmitter and receiver on. */
void tvo_board_uart_init(void);
/** Blocking write of length bytes. */
void tvo_board_uart_write(const uint8_t *data, uint32_t length);
/** Non-blocking read: 1 and *byte when a byte was waiting, else 0. */
int tvo_board_uart_read(uint8_t *byte);

/**
 * The provisioned region: a 256-byte flash area no image writes (the linker script places it and names
 * its address tvo_board_provisioned_region_start for the provisioner), written by whoever provisions
 * the board at every boot (tools/pil_run.py through QEMU's loader; on hardware, a boot counter the
 * bootloader keeps in flash and the key programmed once). Layout (little-endian):
 *   offset 0   "TVOB" (TVO_BOARD_BOOT_MAGIC)
 *   offset 4   int64 boot id, 1 .. 2^23 - 1: never the same twice for this board (the node announces it,
 *              a START must name it, and a keyed node signs with boot id << 40: firmware/edge/auth.h)
 *   offset 12  "TVOK" (TVO_BOARD_KEY_MAGIC), or anything else for no key
 *   offset 16  the 32-byte key
 * No boot magic: the node cannot run (it has no identity) and says so. No key magic: it runs
 * unauthenticated and says so.
 */
#define TVO_BOARD_BOOT_MAGIC "TVOB"
#define TVO_BOARD_BOOT_ID_OFFSET 4u
#define TVO_BOARD_KEY_MAGIC "TVOK"
#define TVO_BOARD_KEY_MAGIC_OFFSET 12u
#define TVO_BOARD_KEY_OFFSET 16u
#define TVO_BOARD_PROVISIONED_BYTES 48u
/** The provisioned region's first byte. */
const uint8_t *tvo_board_provisioned_region(void);

#endif /* TVO_BOARD_H */
