// One progress line on stderr for the long host runs (tvo_soak, tvo_study): what runs, n of N,
// elapsed and an estimate of what is left. The C++ side of tools/progress.py, with its rules: shown
// only when stderr is a terminal, CI is unset, TERM is not "dumb" and TVO_PROGRESS is not "0";
// redrawn at most four times a second; cleared when the object goes, so the tables read the same.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

namespace tvo_host {

class ProgressLine {
public:
    ProgressLine(std::string label, std::int64_t total)
        : label_(std::move(label)), total_(total), enabled_(wanted()), started_(Clock::now()),
          last_draw_(started_ - kMinInterval)  // the first update draws at once
    {
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    ~ProgressLine() { clear(); }

    // True when the line is drawn at all (a terminal, not CI): callers may skip work for it otherwise.
    static bool wanted()
    {
        const char* progress = std::getenv("TVO_PROGRESS");
        const char* term = std::getenv("TERM");
        return isatty(STDERR_FILENO) == 1 && std::getenv("CI") == nullptr &&
               !(progress != nullptr && std::strcmp(progress, "0") == 0) &&
               !(term != nullptr && std::strcmp(term, "dumb") == 0);
    }

    // done of total finished; what (if not empty) names the part running now. Safe from any thread.
    void update(std::int64_t done, const std::string& what = {})
    {
        if (!enabled_) {
            return;
        }
        const std::lock_guard<std::mutex> lock(mutex_);
        const Clock::time_point now = Clock::now();
        if (!what.empty()) {
            what_ = what;
        }
        if (now - last_draw_ < kMinInterval) {
            return;
        }
        last_draw_ = now;
        const double elapsed_s = std::chrono::duration<double>(now - started_).count();
        std::string line = label_ + ": " + (what_.empty() ? "" : what_ + " ") + "[" + std::to_string(done) + "/" +
                           std::to_string(total_) + "], " + duration_text(elapsed_s) + " elapsed";
        if (done > 0 && done < total_) {
            const double left_s = elapsed_s / static_cast<double>(done) * static_cast<double>(total_ - done);
            line += ", ~" + duration_text(left_s) + " left";
        }
        std::fprintf(stderr, "\r\x1b[K%s", line.c_str());
        std::fflush(stderr);
        drawn_ = true;
    }

    void clear()
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (drawn_) {
            std::fputs("\r\x1b[K", stderr);
            std::fflush(stderr);
            drawn_ = false;
        }
    }

private:
    using Clock = std::chrono::steady_clock;
    static constexpr std::chrono::milliseconds kMinInterval{250};

    static std::string duration_text(double seconds)
    {
        const long s = std::lround(std::max(0.0, seconds));
        char text[32];
        if (s >= 3600) {
            std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
        } else if (s >= 60) {
            std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
        } else {
            std::snprintf(text, sizeof text, "%lds", s);
        }
        return text;
    }

    std::string label_;
    std::string what_;
    std::int64_t total_;
    bool enabled_;
    bool drawn_{false};
    Clock::time_point started_;
    Clock::time_point last_draw_;
    std::mutex mutex_;
};

}  // namespace tvo_host
