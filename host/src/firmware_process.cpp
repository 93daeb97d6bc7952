// Child-process handling of the firmware node; see firmware_process.hpp.
#include "firmware_process.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace tvo_host {

namespace {
constexpr std::chrono::milliseconds kPollInterval{5};
constexpr std::chrono::milliseconds kTermGrace{1000};
}  // namespace

FirmwareProcess::~FirmwareProcess()
{
    if (spawned() && running()) {
        terminate();
    }
}

void FirmwareProcess::spawn(const std::string& path, const std::string& lcm_url, const std::string& key_file)
{
    if (access(path.c_str(), X_OK) != 0) {
        throw std::runtime_error("--firmware: cannot execute '" + path + "': " + std::strerror(errno));
    }
    // The node ends with us even when we die without a STOP (crash, kill -9); it still exits after STOP.
    std::vector<std::string> args{path, "--exit-with-parent"};
    if (!key_file.empty()) {
        args.emplace_back("--key-file");
        args.push_back(key_file);
    }
    if (!lcm_url.empty()) {
        args.emplace_back("--lcm-url");
        args.push_back(lcm_url);
    }
    std::vector<char*> argv;
    for (std::string& arg : args) {
        argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    // Same process group as the simulator: a terminal Ctrl-C reaches both.
    const int err = posix_spawn(&pid_, path.c_str(), nullptr, nullptr, argv.data(), environ);
    if (err != 0) {
        pid_ = -1;
        throw std::runtime_error("--firmware: cannot start '" + path + "': " + std::strerror(err));
    }
}

bool FirmwareProcess::running()
{
    if (!spawned() || exited_) {
        return false;
    }
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
        exited_ = true;
        wait_status_ = status;
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return false;
    }
    return done == 0;
}

std::string FirmwareProcess::exit_description() const
{
    if (!exited_) {
        return "still running";
    }
    if (WIFEXITED(wait_status_)) {
        return "exited with code " + std::to_string(WEXITSTATUS(wait_status_));
    }
    return "killed by signal " + std::to_string(WTERMSIG(wait_status_));
}

void FirmwareProcess::send_signal(int signo)
{
    if (spawned() && running()) {
        kill(pid_, signo);
    }
}

bool FirmwareProcess::wait_for_exit(std::chrono::milliseconds timeout)
{
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (running()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            return false;
        }
        std::this_thread::sleep_for(kPollInterval);
    }
    return true;
}

void FirmwareProcess::terminate()
{
    send_signal(SIGTERM);
    if (!wait_for_exit(kTermGrace)) {
        send_signal(SIGKILL);
        wait_for_exit(kTermGrace);
    }
}

}  // namespace tvo_host
