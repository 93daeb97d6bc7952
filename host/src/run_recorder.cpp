// CSV of the run; see run_recorder.hpp.
#include "run_recorder.hpp"

#include <stdexcept>

namespace tvo_host {

namespace {
// One large stdio buffer: rows are written every period and must not cost a syscall each.
constexpr std::size_t kBufferBytes = 1 << 20;
}  // namespace

RunRecorder::RunRecorder(const std::string& path) : file_(std::fopen(path.c_str(), "w"))
{
    if (file_ == nullptr) {
        throw std::runtime_error("cannot write " + path);
    }
    std::setvbuf(file_, nullptr, _IOFBF, kBufferBytes);
    std::fprintf(file_, "t_s,robot,x_m,y_m,heading_rad,target_x_m,target_y_m,error_m,"
                        "cmd_speed_mps,cmd_turn_rate_radps,status,flags,barrier_c,barrier_slack,regularization\n");
}

RunRecorder::~RunRecorder()
{
    close();
}

void RunRecorder::row(double t_s, std::size_t robot, const UnicycleState& state, const Eigen::Vector2d& target_m,
                      double error_m, const UnicycleInput& command, std::int32_t status, std::int32_t flags,
                      const StepTelemetry& telemetry)
{
    const int written = std::fprintf(file_, "%.6f,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d,%.9g,%.9g,%.9g\n",
                                     t_s, robot, state.position_m.x(), state.position_m.y(), state.heading_rad,
                                     target_m.x(), target_m.y(), error_m, command.speed_mps, command.turn_rate_radps,
                                     static_cast<int>(status), static_cast<int>(flags), telemetry.barrier_c,
                                     telemetry.barrier_slack, telemetry.regularization);
    ok_ = ok_ && written > 0;
}

bool RunRecorder::close()
{
    if (file_ != nullptr) {
        ok_ = (std::fclose(file_) == 0) && ok_;
        file_ = nullptr;
    }
    return ok_;
}

}  // namespace tvo_host
