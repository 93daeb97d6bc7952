/* Unity configuration for the target build: output through the board's semihosting console. */
#ifndef TVO_TARGET_UNITY_CONFIG_H
#define TVO_TARGET_UNITY_CONFIG_H

void tvo_board_putc(char c);
#define UNITY_OUTPUT_CHAR(a) tvo_board_putc((char)(a))
#define UNITY_INCLUDE_DOUBLE
#define UNITY_SUPPORT_64

#endif
