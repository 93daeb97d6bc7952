/*
 * Mbed TLS configuration for the board's cross builds: only what message authentication uses
 * (ChaCha20-Poly1305 and its zeroize), no platform layer, no time, no heap. The host links Debian's
 * full library of the same release instead.
 */
#ifndef TVO_MBEDTLS_CONFIG_H
#define TVO_MBEDTLS_CONFIG_H

#define MBEDTLS_CHACHA20_C
#define MBEDTLS_POLY1305_C
#define MBEDTLS_CHACHAPOLY_C

#include "mbedtls/check_config.h"

#endif /* TVO_MBEDTLS_CONFIG_H */
