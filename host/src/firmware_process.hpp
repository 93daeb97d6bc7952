// The firmware node as a child process of the simulator: spawn, watch, signal, reap.
#pragma once

#include <chrono>
#include <string>

#include <sys/types.h>

namespace tvo_host {

class FirmwareProcess {
public:
    FirmwareProcess() = default;
    FirmwareProcess(const FirmwareProcess&) = delete;
    FirmwareProcess& operator=(const FirmwareProcess&) = delete;
    /// Terminates a child still running (SIGTERM, then SIGKILL).
    ~FirmwareProcess();

    /// Starts `path --exit-with-parent --lcm-url url` (no URL argument when url is empty).
    /// std::runtime_error on failure.
    /// With a key_file, also `--key-file key_file`.
    void spawn(const std::string& path, const std::string& lcm_url, const std::string& key_file = "");

    bool spawned() const { return pid_ > 0; }
    /// False once the child has exited (reaps it).
    bool running();
    /// "exited with code N" / "killed by signal N" once it has exited.
    std::string exit_description() const;
    int exit_code() const { return exit_code_; }

    void send_signal(int signo);
    /// Waits up to timeout for the child to exit; true if it did.
    bool wait_for_exit(std::chrono::milliseconds timeout);
    /// SIGTERM, then SIGKILL if it lingers.
    void terminate();

private:
    pid_t pid_{-1};
    bool exited_{false};
    int wait_status_{0};
    int exit_code_{0};
};

}  // namespace tvo_host
