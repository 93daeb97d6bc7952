/*
 * The host's key file: 64 hexadecimal digits (the 32-byte pre-shared key) and an optional newline,
 * in a regular file that only its owner may read or write (mode 0600 or 0400). tools/keygen makes one.
 * Host code (POSIX): a board keeps its key in a flash region of its own.
 */
#ifndef TVO_AUTH_KEY_FILE_H
#define TVO_AUTH_KEY_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "auth.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Reads the key at path into key. 0 on success; -1 with a sentence in why (naming the file and what
 * is wrong: missing, a group- or world-accessible mode, not 64 hex digits) and key zeroed.
 */
int tvo_auth_key_file_read(const char *path, uint8_t key[TVO_AUTH_KEY_BYTES], char *why, size_t why_size);

/**
 * The first counter for a host sender: microseconds since the Unix epoch (CLOCK_REALTIME), so a
 * restarted sender starts above every counter it used before as long as it sent fewer than one
 * message per microsecond and the clock did not go back; at least 1.
 */
uint64_t tvo_auth_wall_clock_counter(void);

#ifdef __cplusplus
}
#endif

#endif /* TVO_AUTH_KEY_FILE_H */
