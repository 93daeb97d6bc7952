// A key file as tools/keygen writes it (64 hexadecimal digits and a newline, mode 0600), for the
// tests that key a bus with a key they choose. Test code (POSIX).
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "auth.h"

namespace tvo_test {

/// Replaces path with a key file holding key; false if it cannot be written.
inline bool write_key_file(const std::string& path, const std::uint8_t (&key)[TVO_AUTH_KEY_BYTES])
{
    std::remove(path.c_str());
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, S_IRUSR | S_IWUSR);
    if (fd < 0) {
        return false;
    }
    std::string hex;
    char digits[3];
    for (const std::uint8_t b : key) {
        std::snprintf(digits, sizeof(digits), "%02x", b);
        hex += digits;
    }
    hex += "\n";
    const bool written = write(fd, hex.data(), hex.size()) == static_cast<ssize_t>(hex.size());
    close(fd);
    return written;
}

}  // namespace tvo_test
