/*
 * The host node's boot counter: a small text file holding the last boot id used (decimal, a newline),
 * incremented under an exclusive flock at every start, so a boot id never repeats however many nodes
 * start at once on one machine (they share the file, and each takes the next number). A board keeps
 * the same counter in its provisioned region (firmware/board/.../board.h); tools/pil_run.py
 * increments this file for it. Host code (POSIX).
 */
#ifndef TVO_BOOT_FILE_H
#define TVO_BOOT_FILE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Where the counter lives under the state folder ($XDG_STATE_HOME, else $HOME/.local/state). */
#define TVO_BOOT_FILE_RELATIVE_PATH "tvo-flat/node-boot-id"

/** The largest boot id the counter hands out (a node signs with boot_id << 40: auth.h). */
#define TVO_BOOT_FILE_MAX_ID ((int64_t)8388607)

/**
 * The default path: $XDG_STATE_HOME/tvo-flat/node-boot-id if XDG_STATE_HOME is an absolute path, else
 * $HOME/.local/state/tvo-flat/node-boot-id. 0; or -1 with a sentence in why (neither is set, or the
 * path does not fit out).
 */
int tvo_boot_file_default_path(char *out, size_t size, char *why, size_t why_size);

/**
 * Creates the file's folders (mode 0700) and the file (mode 0600) if missing, locks it, reads the
 * last boot id (an empty file counts as 0), writes and flushes the next one and returns it in
 * *boot_id (1 .. TVO_BOOT_FILE_MAX_ID). 0; or -1 with a sentence in why naming the path and what is
 * wrong (a folder that cannot be made, a file that cannot be opened, locked, read or written, contents
 * that are not a boot id, the counter used up) and *boot_id 0: the node must not start.
 */
int tvo_boot_file_next(const char *path, int64_t *boot_id, char *why, size_t why_size);

#ifdef __cplusplus
}
#endif

#endif /* TVO_BOOT_FILE_H */
