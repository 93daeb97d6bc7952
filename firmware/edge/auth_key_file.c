/* The host's key file: owner-only, 64 hex digits. */
#define _POSIX_C_SOURCE 200809L

#include "auth_key_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define KEY_HEX_DIGITS (2u * TVO_AUTH_KEY_BYTES)

static int hex_value(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

static int fail(uint8_t key[TVO_AUTH_KEY_BYTES], char *why, size_t why_size, const char *path, const char *what)
{
    memset(key, 0, TVO_AUTH_KEY_BYTES);
    if (why != NULL && why_size > 0u) {
        snprintf(why, why_size, "key file '%s': %s", path, what);
    }
    return -1;
}

int tvo_auth_key_file_read(const char *path, uint8_t key[TVO_AUTH_KEY_BYTES], char *why, size_t why_size)
{
    if (key == NULL) {
        return -1;
    }
    if (path == NULL) {
        return fail(key, why, why_size, "(null)", "no path");
    }
    const int fd = open(path, O_RDONLY | O_NOCTTY);
    if (fd < 0) {
        return fail(key, why, why_size, path, strerror(errno));
    }
    struct stat st;
    char text[KEY_HEX_DIGITS + 3u];
    ssize_t got = -1;
    const char *problem = NULL;
    if (fstat(fd, &st) != 0) {
        problem = strerror(errno);
    } else if (!S_ISREG(st.st_mode)) {
        problem = "not a regular file";
    } else if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
        problem = "group or others may access it: a key must be the owner's alone (chmod 600)";
    } else {
        got = read(fd, text, sizeof(text));
        if (got < 0) {
            problem = strerror(errno);
        }
    }
    close(fd);
    if (problem != NULL) {
        return fail(key, why, why_size, path, problem);
    }
    size_t length = (size_t)got;
    if (length > 0u && text[length - 1u] == '\n') {
        --length;
    }
    if (length != KEY_HEX_DIGITS) {
        memset(text, 0, sizeof(text));
        return fail(key, why, why_size, path, "expected 64 hexadecimal digits (32 bytes) and at most a newline");
    }
    for (size_t i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        const int high = hex_value(text[2u * i]);
        const int low = hex_value(text[2u * i + 1u]);
        if (high < 0 || low < 0) {
            memset(text, 0, sizeof(text));
            return fail(key, why, why_size, path, "a character that is not a hexadecimal digit");
        }
        key[i] = (uint8_t)((high << 4) | low);
    }
    memset(text, 0, sizeof(text));
    return 0;
}

uint64_t tvo_auth_wall_clock_counter(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_REALTIME, &ts) != 0 || ts.tv_sec < 0) {
        return 1u;
    }
    const uint64_t us = (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
    return us > 0u ? us : 1u;
}
