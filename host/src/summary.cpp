// Summary table and JSON; see summary.hpp.
#include "summary.hpp"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace tvo_host {

namespace {
void line(std::ostream& out, const char* label, const std::string& value)
{
    out << "  " << std::left << std::setw(30) << label << value << '\n';
}

std::string sci(double value, const char* unit)
{
    std::ostringstream s;
    s << std::scientific << std::setprecision(3) << value << ' ' << unit;
    return s.str();
}
}  // namespace

void print_summary_table(std::ostream& out, const RunSummary& s, const SimOptions& o)
{
    std::ostringstream mode;
    mode << (o.realtime ? "realtime" : "lockstep") << ", h = " << o.period_us << " us, tau = " << o.delay_us
         << " us, compensation " << (o.delay_compensation ? "on" : "off") << ", "
         << (o.position_only ? "position only" : "pose measured") << ", sigma = " << o.sigma << ", "
         << o.robots << " robot(s), " << target_kind_name(o.target) << " target";
    out << "tvo_sim summary (" << mode.str() << ")\n";
    line(out, "final tracking error", sci(s.final_error_m, "m"));
    line(out, "RMS tracking error, last 5 s", sci(s.rms_error_last5s_m, "m"));
    line(out, "max |omega|", sci(s.max_abs_omega_radps, "rad/s"));
    line(out, "steps", std::to_string(s.steps));
    std::ostringstream rate;
    rate << std::fixed << std::setprecision(0) << s.steps_per_s << " /s (wall clock)";
    line(out, "steps per second", rate.str());
    line(out, "faults", std::to_string(s.faults) + " of " + std::to_string(s.commands) + " commands");
    line(out, "measurements dropped", std::to_string(s.drops));
    line(out, "late commands", std::to_string(s.late_commands));
}

void write_summary_json(const std::string& path, const RunSummary& s)
{
    const nlohmann::json json = {
        {"final_error_m", s.final_error_m},
        {"rms_error_last5s_m", s.rms_error_last5s_m},
        {"max_abs_omega_radps", s.max_abs_omega_radps},
        {"steps", s.steps},
        {"steps_per_s", s.steps_per_s},
        {"faults", s.faults},
    };
    std::ofstream file(path);
    file << json.dump(2) << '\n';
    if (!file) {
        throw std::runtime_error("cannot write " + path);
    }
}

}  // namespace tvo_host
