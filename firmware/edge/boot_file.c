/* The host node's boot counter: a locked text file, incremented at every start. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* flock */

#include "boot_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* Longest path handled (the folder walk copies it). */
#define BOOT_PATH_BYTES 4096u
/* A boot id and its newline, with room to see that a file holds more. */
#define BOOT_TEXT_BYTES 32u

static int fail(char *why, size_t why_size, const char *format, ...) __attribute__((format(printf, 3, 4)));
static int fail(char *why, size_t why_size, const char *format, ...)
{
    if (why != NULL && why_size > 0u) {
        va_list args;
        va_start(args, format);
        vsnprintf(why, why_size, format, args);
        va_end(args);
    }
    return -1;
}

int tvo_boot_file_default_path(char *out, size_t size, char *why, size_t why_size)
{
    if (out == NULL || size == 0u) {
        return fail(why, why_size, "no room for the boot file's path");
    }
    const char *state = getenv("XDG_STATE_HOME");
    const char *home = getenv("HOME");
    int written = -1;
    if (state != NULL && state[0] == '/') {
        written = snprintf(out, size, "%s/%s", state, TVO_BOOT_FILE_RELATIVE_PATH);
    } else if (home != NULL && home[0] == '/') {
        written = snprintf(out, size, "%s/.local/state/%s", home, TVO_BOOT_FILE_RELATIVE_PATH);
    } else {
        out[0] = '\0';
        return fail(why, why_size, "neither XDG_STATE_HOME nor HOME is an absolute path: give the boot file's path");
    }
    if (written < 0 || (size_t)written >= size) {
        out[0] = '\0';
        return fail(why, why_size, "the boot file's default path is longer than %zu bytes", size - 1u);
    }
    return 0;
}

/* mkdir -p of path's folders (not of its last component), each new one mode 0700. */
static int make_folders(const char *path, char *why, size_t why_size)
{
    char copy[BOOT_PATH_BYTES];
    const size_t length = strlen(path);
    if (length >= sizeof(copy)) {
        return fail(why, why_size, "boot file '%s': the path is longer than %u bytes", path, BOOT_PATH_BYTES - 1u);
    }
    memcpy(copy, path, length + 1u);
    for (size_t i = 1u; i < length; ++i) {
        if (copy[i] != '/') {
            continue;
        }
        copy[i] = '\0';
        if (mkdir(copy, 0700) != 0 && errno != EEXIST) {
            return fail(why, why_size, "boot file '%s': cannot create the folder '%s': %s", path, copy, strerror(errno));
        }
        copy[i] = '/';
    }
    return 0;
}

/* The last boot id in text[0 .. length): empty is 0; else decimal digits and at most a newline. */
static int parse_boot_id(const char *text, size_t length, int64_t *value)
{
    if (length > 0u && text[length - 1u] == '\n') {
        --length;
    }
    int64_t v = 0;
    for (size_t i = 0u; i < length; ++i) {
        if (text[i] < '0' || text[i] > '9' || v > TVO_BOOT_FILE_MAX_ID) {
            return -1;
        }
        v = v * 10 + (text[i] - '0');
    }
    *value = v;
    return 0;
}

int tvo_boot_file_next(const char *path, int64_t *boot_id, char *why, size_t why_size)
{
    if (boot_id != NULL) {
        *boot_id = 0;
    }
    if (path == NULL || path[0] == '\0' || boot_id == NULL) {
        return fail(why, why_size, "boot file: no path");
    }
    if (make_folders(path, why, why_size) != 0) {
        return -1;
    }
    const int fd = open(path, O_RDWR | O_CREAT | O_NOCTTY | O_CLOEXEC, 0600);
    if (fd < 0) {
        return fail(why, why_size, "boot file '%s': cannot open it for reading and writing: %s", path, strerror(errno));
    }
    int status = 0;
    struct stat st;
    char text[BOOT_TEXT_BYTES + 1u];
    ssize_t got = 0;
    int64_t last = 0;
    if (flock(fd, LOCK_EX) != 0) { /* waits while another node takes its number */
        status = fail(why, why_size, "boot file '%s': cannot lock it: %s", path, strerror(errno));
    } else if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        status = fail(why, why_size, "boot file '%s': not a regular file", path);
    } else if ((got = pread(fd, text, BOOT_TEXT_BYTES, 0)) < 0) {
        status = fail(why, why_size, "boot file '%s': cannot read it: %s", path, strerror(errno));
    } else if (got == (ssize_t)BOOT_TEXT_BYTES || parse_boot_id(text, (size_t)got, &last) != 0) {
        for (ssize_t i = 0; i < got; ++i) { /* the contents as a line of printable text */
            text[i] = (text[i] >= ' ' && text[i] <= '~') ? text[i] : '?';
        }
        text[got] = '\0';
        status = fail(why, why_size,
                      "boot file '%s': expected the last boot id (a whole number 0 .. %lld and a newline), found '%.20s%s'; "
                      "a node's boot ids must never repeat, so fix the file by hand (a number above every id used) "
                      "rather than removing it",
                      path, (long long)TVO_BOOT_FILE_MAX_ID, text, got > 20 ? "..." : "");
    } else if (last >= TVO_BOOT_FILE_MAX_ID) {
        status = fail(why, why_size, "boot file '%s': every boot id up to %lld is used (a node signs with boot id << 40)",
                      path, (long long)TVO_BOOT_FILE_MAX_ID);
    } else {
        const int64_t next = last + 1;
        const int length = snprintf(text, sizeof(text), "%lld\n", (long long)next);
        if (length <= 0 || pwrite(fd, text, (size_t)length, 0) != (ssize_t)length || ftruncate(fd, length) != 0 ||
            fsync(fd) != 0) {
            status = fail(why, why_size, "boot file '%s': cannot write the next boot id: %s", path, strerror(errno));
        } else {
            *boot_id = next;
        }
    }
    close(fd); /* releases the lock */
    return status;
}
