// Scenario files; see scenario_file.hpp. The format is README.md's "Your own scenario"; every key
// below is one of its fields, and every range of a tvo_sim setting is sim_ranges.hpp's.
#include "scenario_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <sstream>

#include <Eigen/Geometry>
// yaml-cpp 0.7's node lookups trip GCC 12's -Wdangling-pointer (a false positive, gone in yaml-cpp 0.8).
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdangling-pointer"
#include <yaml-cpp/yaml.h>
#pragma GCC diagnostic pop
#else
#include <yaml-cpp/yaml.h>
#endif
#include <yaml-cpp/depthguard.h>  // YAML::DeepRecursion: not included by yaml.h

#include "lcm_messages.hpp"  // the session message's capacities
#include "sim_ranges.hpp"

namespace tvo_host {

namespace {

constexpr double kPi = 3.14159265358979323846;

using tvo_options::Interval;
using tvo_options::number;

std::string join(const std::string& parent, const std::string& key)
{
    return parent.empty() ? key : parent + "." + key;
}

std::string item(const std::string& sequence, std::size_t index)
{
    return sequence + "[" + std::to_string(index) + "]";
}

/// A YAML map whose keys were checked: each known, none twice.
struct Map {
    YAML::Mark mark;
    std::string field;
    std::vector<std::pair<std::string, YAML::Node>> entries;

    const YAML::Node* find(const std::string& key) const
    {
        for (const auto& [name, value] : entries) {
            if (name == key) {
                return &value;
            }
        }
        return nullptr;
    }
    std::string at(const std::string& key) const { return join(field, key); }
};

/// Reads one file's nodes into values; every refusal names the file, the node's line and column and
/// the field's path (robots[0].target.ellipse.period_s).
class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    /// The top-level key came from another file (a base): its errors name that file.
    void set_origin(const std::string& top_key, const std::string& file) { origins_.emplace_back(top_key, file); }

    /// FILE:LINE:COLUMN of a node of the field (the file is the base's for a key kept from it).
    std::string where(const YAML::Mark& mark, const std::string& field) const
    {
        const int line = mark.is_null() ? 1 : mark.line + 1;
        const int column = mark.is_null() ? 1 : mark.column + 1;
        return origin(field) + ":" + std::to_string(line) + ":" + std::to_string(column);
    }

    [[noreturn]] void fail(const YAML::Mark& mark, const std::string& field, const std::string& why) const
    {
        throw ScenarioFileError(where(mark, field) + ": " + (field.empty() ? "" : field + ": ") + why);
    }
    [[noreturn]] void fail(const YAML::Node& node, const std::string& field, const std::string& why) const
    {
        fail(node.Mark(), field, why);
    }

    Map map(const YAML::Node& node, const std::string& field, std::initializer_list<const char*> keys) const
    {
        if (!node.IsMap()) {
            fail(node, field, "expected a map of " + key_list(keys) + " (got " + shown(node) + ")");
        }
        Map out{node.Mark(), field, {}};
        for (auto it = node.begin(); it != node.end(); ++it) {
            const YAML::Node key = it->first;  // a copy: it-> is a temporary proxy
            if (!key.IsScalar()) {
                fail(key, field, "keys are names, got " + shown(key));
            }
            const std::string& name = key.Scalar();
            if (std::none_of(keys.begin(), keys.end(), [&name](const char* k) { return name == k; })) {
                fail(key, join(field, name), "unknown key (" + (field.empty() ? "the file" : field) + " takes " +
                                                 key_list(keys) + ")");
            }
            if (out.find(name) != nullptr) {
                fail(key, join(field, name), "given twice");
            }
            out.entries.emplace_back(name, it->second);
        }
        return out;
    }

    const YAML::Node& required(const Map& map, const std::string& key) const
    {
        const YAML::Node* node = map.find(key);
        if (node == nullptr) {
            fail(map.mark, map.at(key), "missing (required)");
        }
        return *node;
    }

    std::vector<YAML::Node> sequence(const YAML::Node& node, const std::string& field, std::size_t min_count,
                                     std::size_t max_count) const
    {
        if (!node.IsSequence()) {
            fail(node, field, "expected a list (got " + shown(node) + ")");
        }
        if (node.size() < min_count || node.size() > max_count) {
            fail(node, field, "expected " + std::to_string(min_count) + " .. " + std::to_string(max_count) +
                                  " items (got " + std::to_string(node.size()) + ")");
        }
        return std::vector<YAML::Node>(node.begin(), node.end());
    }

    double real(const YAML::Node& node, const std::string& field) const
    {
        double value = 0.0;
        if (!plain_scalar(node) || !tvo_options::read_real(node.Scalar(), &value)) {
            fail(node, field, "expected a finite number (got " + shown(node) + ")");
        }
        return value;
    }

    double real_in(const YAML::Node& node, const std::string& field, const Interval& range) const
    {
        const double value = real(node, field);
        if (!range.contains(value)) {
            fail(node, field, "must be in " + range.text() + " (got " + node.Scalar() + ")");
        }
        return value;
    }

    double positive(const YAML::Node& node, const std::string& field) const
    {
        const double value = real(node, field);
        if (!(value > 0.0)) {
            fail(node, field, "must be > 0 (got " + node.Scalar() + ")");
        }
        return value;
    }

    double non_negative(const YAML::Node& node, const std::string& field) const
    {
        const double value = real(node, field);
        if (!(value >= 0.0)) {
            fail(node, field, "must be >= 0 (got " + node.Scalar() + ")");
        }
        return value;
    }

    template <class T>
    T whole(const YAML::Node& node, const std::string& field, T lo, T hi) const
    {
        T value{};
        if (!plain_scalar(node) || !tvo_options::read_whole(node.Scalar(), &value)) {
            fail(node, field, "expected a whole number (got " + shown(node) + ")");
        }
        if (value < lo || value > hi) {
            fail(node, field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                                  node.Scalar() + ")");
        }
        return value;
    }

    bool boolean(const YAML::Node& node, const std::string& field) const
    {
        if (plain_scalar(node) && (node.Scalar() == "true" || node.Scalar() == "false")) {
            return node.Scalar() == "true";
        }
        fail(node, field, "expected true or false (got " + shown(node) + ")");
    }

    std::string text(const YAML::Node& node, const std::string& field) const
    {
        if (!node.IsScalar() || node.Scalar().empty()) {
            fail(node, field, "expected text (got " + shown(node) + ")");
        }
        return node.Scalar();
    }

    Eigen::Vector2d vec2(const YAML::Node& node, const std::string& field) const
    {
        const std::vector<YAML::Node> xy = sequence(node, field, 2, 2);
        return Eigen::Vector2d(real(xy[0], item(field, 0)), real(xy[1], item(field, 1)));
    }

    std::size_t robot_index(const YAML::Node& node, const std::string& field, std::size_t robot_count) const
    {
        return whole<std::size_t>(node, field, 0, robot_count - 1);
    }

    /// Two distinct robot indices [a, b].
    std::array<std::size_t, 2> robot_pair(const YAML::Node& node, const std::string& field,
                                          std::size_t robot_count) const
    {
        const std::vector<YAML::Node> ab = sequence(node, field, 2, 2);
        const std::size_t a = robot_index(ab[0], item(field, 0), robot_count);
        const std::size_t b = robot_index(ab[1], item(field, 1), robot_count);
        if (a == b) {
            fail(node, field, "two different robots are needed (got " + std::to_string(a) + " twice)");
        }
        return {a, b};
    }

private:
    static bool plain_scalar(const YAML::Node& node) { return node.IsScalar() && node.Tag() == "?"; }

    static std::string key_list(std::initializer_list<const char*> keys)
    {
        std::string out;
        for (const char* k : keys) {
            out += (out.empty() ? "" : ", ") + std::string(k);
        }
        return out;
    }

    static std::string shown(const YAML::Node& node)
    {
        switch (node.Type()) {
        case YAML::NodeType::Scalar: return node.Tag() == "?" ? "'" + node.Scalar() + "'" : "the text \"" + node.Scalar() + "\"";
        case YAML::NodeType::Sequence: return "a list";
        case YAML::NodeType::Map: return "a map";
        case YAML::NodeType::Null: return "nothing";
        case YAML::NodeType::Undefined: break;
        }
        return "nothing";
    }

    const std::string& origin(const std::string& field) const
    {
        const std::string top_key = field.substr(0, field.find_first_of(".["));
        for (const auto& [key, file] : origins_) {
            if (key == top_key) {
                return file;
            }
        }
        return file_;
    }

    std::string file_;
    std::vector<std::pair<std::string, std::string>> origins_;

public:
    /// Filled while reading (the readers take a const Reader): the last waypoint of each `through`.
    mutable std::vector<WaypointEnd> waypoint_ends;
};

/// Where the checks between sections point: the nodes of each robot's start position, each obstacle
/// and each half-space, in the order read.
struct Marks {
    std::vector<YAML::Mark> starts;
    std::vector<YAML::Mark> obstacles;
    std::vector<YAML::Mark> halfspaces;
};

/// A value the checks computed (a distance, a product), to 4 significant digits.
std::string approx(double value)
{
    std::ostringstream out;
    out << std::setprecision(4) << value;
    return out.str();
}

std::string point(const Eigen::Vector2d& p)
{
    return "[" + approx(p.x()) + ", " + approx(p.y()) + "]";
}

// ---- targets ---------------------------------------------------------------------------------

/// omega from omega_radps or period_s (exactly one of them): omega = 2 pi / period.
double angular_rate(const Reader& in, const Map& m)
{
    const YAML::Node* omega = m.find("omega_radps");
    const YAML::Node* period = m.find("period_s");
    if ((omega == nullptr) == (period == nullptr)) {
        in.fail(m.mark, m.field, "give exactly one of omega_radps and period_s");
    }
    if (omega != nullptr) {
        return in.real(*omega, m.at("omega_radps"));
    }
    return 2.0 * kPi / in.positive(*period, m.at("period_s"));
}

double optional_real(const Reader& in, const Map& m, const std::string& key, double fallback)
{
    const YAML::Node* node = m.find(key);
    return node != nullptr ? in.real(*node, m.at(key)) : fallback;
}

Eigen::Vector2d optional_vec2(const Reader& in, const Map& m, const std::string& key, const Eigen::Vector2d& fallback)
{
    const YAML::Node* node = m.find(key);
    return node != nullptr ? in.vec2(*node, m.at(key)) : fallback;
}

/// A velocity as [vx, vy] or as {speed_mps, heading_rad}.
Eigen::Vector2d velocity(const Reader& in, const YAML::Node& node, const std::string& field)
{
    if (!node.IsMap()) {
        return in.vec2(node, field);
    }
    const Map m = in.map(node, field, {"speed_mps", "heading_rad"});
    const double speed = in.real(in.required(m, "speed_mps"), m.at("speed_mps"));
    const double heading = in.real(in.required(m, "heading_rad"), m.at("heading_rad"));
    return speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
}

TargetPath polynomial_target(const Reader& in, const YAML::Node& node, const std::string& field)
{
    const Map m = in.map(node, field, {"x", "y"});
    PolyCoeffs coeff{};
    const char* axes[2] = {"x", "y"};
    for (std::size_t axis = 0; axis < 2; ++axis) {
        const std::string at = m.at(axes[axis]);
        const std::vector<YAML::Node> a = in.sequence(in.required(m, axes[axis]), at, 1, kPolyCoeffs);
        for (std::size_t j = 0; j < a.size(); ++j) {
            coeff[axis][j] = in.real(a[j], item(at, j));
        }
    }
    return TargetPath::polynomial(coeff);
}

/// The polynomial through waypoints; each gives its time and any of position, velocity, acceleration,
/// jerk (derivative orders 0..3), in this order, waypoint after waypoint.
TargetPath waypoint_target(const Reader& in, const YAML::Node& node, const std::string& field)
{
    static const char* const kOrders[] = {"position_m", "velocity_mps", "acceleration_mps2", "jerk_mps3"};
    std::vector<PathCondition> conditions;
    const std::vector<YAML::Node> points = in.sequence(node, field, 1, kPolyCoeffs);
    double previous_t_s = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::string at = item(field, i);
        const Map m = in.map(points[i], at, {"t_s", kOrders[0], kOrders[1], kOrders[2], kOrders[3]});
        const YAML::Node& t_node = in.required(m, "t_s");
        const double t_s = in.real(t_node, m.at("t_s"));
        // In time order: a waypoint out of order still determines a polynomial, but not the path meant.
        if (i > 0 && !(t_s > previous_t_s)) {
            in.fail(t_node, m.at("t_s"), "waypoint times must increase strictly: got " + t_node.Scalar() +
                                             " after " + item(field, i - 1) + ".t_s = " + number(previous_t_s));
        }
        previous_t_s = t_s;
        if (i + 1 == points.size()) {
            in.waypoint_ends.push_back({m.at("t_s"), in.where(t_node.Mark(), m.at("t_s")), t_s});
        }
        const std::size_t before = conditions.size();
        for (int order = 0; order < 4; ++order) {
            const YAML::Node* value = m.find(kOrders[order]);
            if (value != nullptr) {
                const std::string key = m.at(kOrders[order]);
                conditions.push_back({t_s, order, order == 1 ? velocity(in, *value, key) : in.vec2(*value, key)});
            }
        }
        if (conditions.size() == before) {
            in.fail(m.mark, at, "a waypoint needs at least one of position_m, velocity_mps, acceleration_mps2, jerk_mps3");
        }
    }
    if (conditions.size() > kPolyCoeffs) {
        in.fail(node, field, "at most " + std::to_string(kPolyCoeffs) + " conditions (polynomial degree <= " +
                                 std::to_string(kPolyCoeffs - 1) + " on board), got " + std::to_string(conditions.size()));
    }
    try {
        return TargetPath::through(conditions);
    } catch (const std::invalid_argument&) {
        in.fail(node, field, "the " + std::to_string(conditions.size()) + " conditions do not determine a polynomial of degree " +
                                 std::to_string(conditions.size() - 1) + " (the same value given twice?)");
    }
}

TargetPath ellipse_target(const Reader& in, const YAML::Node& node, const std::string& field)
{
    const Map m = in.map(node, field, {"center_m", "semi_axes_m", "omega_radps", "period_s", "phase_rad", "rotation_rad"});
    EllipseTarget e;
    e.center_m = optional_vec2(in, m, "center_m", Eigen::Vector2d::Zero());
    const std::string axes_at = m.at("semi_axes_m");
    const std::vector<YAML::Node> axes = in.sequence(in.required(m, "semi_axes_m"), axes_at, 2, 2);
    e.semi_axis_m = Eigen::Vector2d(in.positive(axes[0], item(axes_at, 0)), in.positive(axes[1], item(axes_at, 1)));
    e.omega_radps = angular_rate(in, m);
    e.phase_rad = optional_real(in, m, "phase_rad", 0.0);
    e.rotation_rad = optional_real(in, m, "rotation_rad", 0.0);
    return TargetPath::ellipse(e);
}

TargetPath circle_target(const Reader& in, const YAML::Node& node, const std::string& field)
{
    const Map m = in.map(node, field, {"center_m", "radius_m", "omega_radps", "period_s", "phase_rad"});
    const Eigen::Vector2d center = optional_vec2(in, m, "center_m", Eigen::Vector2d::Zero());
    const double radius = in.positive(in.required(m, "radius_m"), m.at("radius_m"));
    const double omega = angular_rate(in, m);
    return TargetPath::circle(center, radius, omega, optional_real(in, m, "phase_rad", 0.0));
}

/// A time function: exactly one of polynomial, through, ellipse, circle.
TargetPath time_function(const Reader& in, const YAML::Node& node, const std::string& field)
{
    const Map m = in.map(node, field, {"polynomial", "through", "ellipse", "circle"});
    if (m.entries.size() != 1) {
        in.fail(m.mark, field, "give exactly one of polynomial, through, ellipse, circle");
    }
    const auto& [kind, value] = m.entries.front();
    const std::string at = m.at(kind);
    if (kind == "polynomial") {
        return polynomial_target(in, value, at);
    }
    if (kind == "through") {
        return waypoint_target(in, value, at);
    }
    if (kind == "ellipse") {
        return ellipse_target(in, value, at);
    }
    return circle_target(in, value, at);
}

// ---- sections --------------------------------------------------------------------------------

void read_robots(const Reader& in, const YAML::Node& node, Scenario* s, Marks* marks)
{
    const std::vector<YAML::Node> robots = in.sequence(node, "robots", 1, kMaxRobots);
    s->robot_count = robots.size();
    for (std::size_t r = 0; r < robots.size(); ++r) {
        const std::string at = item("robots", r);
        const Map m = in.map(robots[r], at, {"start", "weights", "target"});
        const Map start = in.map(in.required(m, "start"), m.at("start"), {"position_m", "heading_rad"});
        const YAML::Node& position = in.required(start, "position_m");
        s->starts[r].position_m = in.vec2(position, start.at("position_m"));
        marks->starts.push_back(position.Mark());
        s->starts[r].heading_rad = optional_real(in, start, "heading_rad", 0.0);
        s->weights[r] = Eigen::Vector2d(1.0, 1.0);
        if (const YAML::Node* weights = m.find("weights")) {
            const std::string w_at = m.at("weights");
            const std::vector<YAML::Node> w = in.sequence(*weights, w_at, 2, 2);
            s->weights[r] = Eigen::Vector2d(in.positive(w[0], item(w_at, 0)), in.positive(w[1], item(w_at, 1)));
        }
        s->targets[r] = time_function(in, in.required(m, "target"), m.at("target"));
    }
}

void read_distance_bounds(const Reader& in, const YAML::Node& node, Scenario* s)
{
    const std::vector<YAML::Node> bounds =
        in.sequence(node, "distance_bounds", 0, tvo_lcm::session_t::MAX_DISTANCE_BOUNDS);
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        const std::string at = item("distance_bounds", i);
        const Map m = in.map(bounds[i], at, {"robots", "min_m", "min_rate_mps", "max_m", "max_rate_mps"});
        DistanceBound d;
        const auto pair = in.robot_pair(in.required(m, "robots"), m.at("robots"), s->robot_count);
        d.robot_a = pair[0];
        d.robot_b = pair[1];
        const YAML::Node* min = m.find("min_m");
        const YAML::Node* max = m.find("max_m");
        d.min_m = min != nullptr ? in.non_negative(*min, m.at("min_m")) : 0.0;
        d.max_m = max != nullptr ? in.non_negative(*max, m.at("max_m")) : 0.0;
        d.min_rate_mps = optional_real(in, m, "min_rate_mps", 0.0);
        d.max_rate_mps = optional_real(in, m, "max_rate_mps", 0.0);
        if (d.min_m <= 0.0 && d.max_m <= 0.0) {
            in.fail(m.mark, at, "give min_m or max_m (> 0; 0 means no such bound)");
        }
        if (d.min_m > 0.0 && d.max_m > 0.0 && d.min_m >= d.max_m) {
            in.fail(*min, m.at("min_m"), "must be below max_m (" + number(d.max_m) + "), got " + min->Scalar());
        }
        s->distances.push_back(d);
    }
}

void read_halfspaces(const Reader& in, const YAML::Node& node, Scenario* s, Marks* marks)
{
    const std::vector<YAML::Node> halfspaces = in.sequence(node, "halfspaces", 0, tvo_lcm::session_t::MAX_HALFSPACES);
    for (std::size_t i = 0; i < halfspaces.size(); ++i) {
        const std::string at = item("halfspaces", i);
        const Map m = in.map(halfspaces[i], at, {"robot", "normal", "normal_rate", "bound_m", "bound_rate_mps"});
        HalfSpace h;
        h.robot = in.robot_index(in.required(m, "robot"), m.at("robot"), s->robot_count);
        h.normal = in.vec2(in.required(m, "normal"), m.at("normal"));
        if (h.normal.isZero(0.0)) {
            in.fail(*m.find("normal"), m.at("normal"), "must not be [0, 0]");
        }
        h.normal_rate = optional_vec2(in, m, "normal_rate", Eigen::Vector2d::Zero());
        h.bound_m = in.real(in.required(m, "bound_m"), m.at("bound_m"));
        h.bound_rate_mps = optional_real(in, m, "bound_rate_mps", 0.0);
        s->halfspaces.push_back(h);
        marks->halfspaces.push_back(m.mark);
    }
}

void read_obstacles(const Reader& in, const YAML::Node& node, Scenario* s, Marks* marks)
{
    const std::vector<YAML::Node> disks = in.sequence(node, "obstacles", 0, tvo_lcm::session_t::MAX_OBSTACLES);
    for (std::size_t i = 0; i < disks.size(); ++i) {
        const std::string at = item("obstacles", i);
        const Map m = in.map(disks[i], at, {"center_m", "radius_m"});
        Disk d;
        d.center_m = in.vec2(in.required(m, "center_m"), m.at("center_m"));
        d.radius_m = in.positive(in.required(m, "radius_m"), m.at("radius_m"));
        s->obstacles.push_back(d);
        marks->obstacles.push_back(m.mark);
    }
}

void read_offsets(const Reader& in, const YAML::Node& node, Scenario* s)
{
    const std::vector<YAML::Node> offsets = in.sequence(node, "offsets", 0, tvo_lcm::session_t::MAX_OFFSETS);
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        const std::string at = item("offsets", i);
        const Map m = in.map(offsets[i], at, {"robots", "offset"});
        OffsetEquality o;
        const auto pair = in.robot_pair(in.required(m, "robots"), m.at("robots"), s->robot_count);
        o.robot_a = pair[0];
        o.robot_b = pair[1];
        o.offset = time_function(in, in.required(m, "offset"), m.at("offset"));
        s->offsets.push_back(o);
    }
}

void read_barrier(const Reader& in, const YAML::Node& node, BarrierOverrides* b)
{
    namespace r = sim_ranges;
    const Map m = in.map(node, "barrier", {"c0", "alpha_c_per_s", "c_max", "delta0", "alpha_s_per_s", "slack_margin",
                                           "relaxation_degree"});
    const auto take = [&](const char* key, const Interval& range, std::optional<double>* field) {
        if (const YAML::Node* value = m.find(key)) {
            *field = in.real_in(*value, m.at(key), range);
        }
    };
    take("c0", r::kBarrierC0, &b->c0);
    take("alpha_c_per_s", r::kBarrierAlphaC, &b->alpha_c_per_s);
    take("c_max", r::kBarrierCMax, &b->c_max);
    take("delta0", r::kBarrierDelta0, &b->delta0);
    take("alpha_s_per_s", r::kBarrierAlphaS, &b->alpha_s_per_s);
    take("slack_margin", r::kBarrierSlackMargin, &b->slack_margin);
    if (const YAML::Node* degree = m.find("relaxation_degree")) {
        b->relaxation_degree = in.whole<int>(*degree, m.at("relaxation_degree"), r::kMinBarrierDegree, r::kMaxBarrierDegree);
    }
}

/// Times (1 ms grid over [0, T]) at which two targets are closer than distance_m: the first and last.
std::optional<TimeWindow> window_closer_than(const TargetPath& a, const TargetPath& b, double distance_m,
                                             double duration_s)
{
    std::optional<TimeWindow> window;
    const auto samples = static_cast<long>(std::llround(duration_s * 1000.0));
    for (long i = 0; i <= samples; ++i) {
        const double t = static_cast<double>(i) * 1e-3;
        if ((a.position(t) - b.position(t)).norm() < distance_m) {
            if (!window) {
                window = TimeWindow{t, t};
            }
            window->end_s = t;
        }
    }
    return window;
}

void read_report(const Reader& in, const YAML::Node& node, Scenario* s)
{
    const Map m = in.map(node, "report", {"settle_time_s", "crossing_closer_than_m"});
    if (const YAML::Node* settle = m.find("settle_time_s")) {
        s->settle_time_s = in.non_negative(*settle, m.at("settle_time_s"));
    }
    if (const YAML::Node* closer = m.find("crossing_closer_than_m")) {
        const double distance_m = in.positive(*closer, m.at("crossing_closer_than_m"));
        const auto pair = s->reported_pair();
        if (!pair) {
            in.fail(*closer, m.at("crossing_closer_than_m"), "needs a robot pair (a distance bound or an offset)");
        }
        s->crossing_window = window_closer_than(s->targets[(*pair)[0]], s->targets[(*pair)[1]], distance_m, s->duration_s);
    }
}

void read_variants(const Reader& in, const YAML::Node& node, const Scenario& s, ScenarioVariants* v)
{
    const Map m = in.map(node, "variants", {"robots", "circle_radius_m"});
    const auto analytic = [&s](std::size_t r) { return s.targets[r].kind() != PathKind::Polynomial; };
    if (const YAML::Node* robots = m.find("robots")) {
        if (in.text(*robots, m.at("robots")) != "turned") {
            in.fail(*robots, m.at("robots"), "the one variant is 'turned' (got '" + robots->Scalar() + "')");
        }
        if (s.robot_count != 1 || !analytic(0)) {
            in.fail(*robots, m.at("robots"), "needs exactly one robot with an ellipse or circle target");
        }
        v->robots_turned = true;
    }
    if (const YAML::Node* radius = m.find("circle_radius_m")) {
        v->circle_radius_m = in.positive(*radius, m.at("circle_radius_m"));
        for (std::size_t r = 0; r < s.robot_count; ++r) {
            if (s.targets[r].kind() != PathKind::Ellipse) {
                in.fail(*radius, m.at("circle_radius_m"), "needs every robot's target to be an ellipse");
            }
        }
    }
}

void read_run_settings(const Reader& in, const Map& top, RunSettings* run)
{
    namespace r = sim_ranges;
    const auto real = [&in](const Map& m, const char* key, const Interval& range, std::optional<double>* field) {
        if (const YAML::Node* value = m.find(key)) {
            *field = in.real_in(*value, m.at(key), range);
        }
    };
    const auto flag = [&in](const Map& m, const char* key, std::optional<bool>* field) {
        if (const YAML::Node* value = m.find(key)) {
            *field = in.boolean(*value, m.at(key));
        }
    };
    /// A pair given as a map of two named numbers, each with its range.
    const auto pair = [&in](const Map& m, const char* key, const char* first, const Interval& first_range,
                            const char* second, const Interval& second_range,
                            std::optional<std::pair<double, double>>* field) {
        if (const YAML::Node* value = m.find(key)) {
            const Map p = in.map(*value, m.at(key), {first, second});
            *field = std::make_pair(in.real_in(in.required(p, first), p.at(first), first_range),
                                    in.real_in(in.required(p, second), p.at(second), second_range));
        }
    };
    if (const YAML::Node* node = top.find("timing")) {
        const Map m = in.map(*node, "timing", {"period_s", "delay_s", "compensation", "zoh_aware"});
        real(m, "period_s", r::kPeriod, &run->period_s);
        real(m, "delay_s", r::kDelay, &run->delay_s);
        flag(m, "compensation", &run->compensation);
        flag(m, "zoh_aware", &run->zoh_aware);
    }
    if (const YAML::Node* node = top.find("sensing")) {
        const Map m = in.map(*node, "sensing", {"sigma", "position_only", "filter_tf_s", "seed"});
        real(m, "sigma", r::kSigma, &run->sigma);
        flag(m, "position_only", &run->position_only);
        real(m, "filter_tf_s", r::kFilterTf, &run->filter_tf_s);
        if (const YAML::Node* seed = m.find("seed")) {
            run->seed = in.whole<std::uint64_t>(*seed, m.at("seed"), 0, std::numeric_limits<std::uint64_t>::max());
        }
    }
    if (const YAML::Node* node = top.find("controller")) {
        const Map m = in.map(*node, "controller", {"gains", "omega_max_radps", "accel_max_mps2", "speed_max_mps",
                                                   "min_speed_mps", "watchdog_periods"});
        pair(m, "gains", "kp", r::kGainKp, "kd", r::kGainKd, &run->gains);
        real(m, "omega_max_radps", r::kOmegaMax, &run->omega_max_radps);
        real(m, "accel_max_mps2", r::kAccelMax, &run->accel_max_mps2);
        real(m, "speed_max_mps", r::kSpeedMax, &run->speed_max_mps);
        real(m, "min_speed_mps", r::kMinSpeed, &run->min_speed_mps);
        if (const YAML::Node* periods = m.find("watchdog_periods")) {
            run->watchdog_periods = in.whole<std::int32_t>(*periods, m.at("watchdog_periods"), r::kMinWatchdogPeriods,
                                                           r::kMaxWatchdogPeriods);
        }
    }
    if (const YAML::Node* node = top.find("faults")) {
        const Map m = in.map(*node, "faults", {"drop_prob", "extra_delay_s", "disturbance", "link_loss"});
        real(m, "drop_prob", r::kDropProb, &run->drop_prob);
        real(m, "extra_delay_s", r::kExtraDelay, &run->extra_delay_s);
        pair(m, "disturbance", "speed_sigma_mps", r::kDisturbanceSpeed, "turn_sigma_radps", r::kDisturbanceTurn,
             &run->disturbance);
        pair(m, "link_loss", "start_s", r::kLinkLossStart, "duration_s", r::kLinkLossDuration, &run->link_loss);
    }
}

// ---- checks between sections -----------------------------------------------------------------

/// No robot starts in contact with an obstacle (the run's collision test: clearance < 0) or beyond one
/// of its half-space walls at t = 0: the run would begin with a collision or a violated wall.
void check_starts(const Reader& in, const Scenario& s, const Marks& marks)
{
    for (std::size_t r = 0; r < s.robot_count; ++r) {
        const std::string at = item("robots", r) + ".start.position_m";
        const Eigen::Vector2d& p = s.starts[r].position_m;
        for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
            const Disk& o = s.obstacles[i];
            const double distance_m = (p - o.center_m).norm();
            if (distance_m - s.robot_radius_m - o.radius_m < 0.0) {
                in.fail(marks.starts[r], at,
                        "robot " + std::to_string(r) + " starts inside " + item("obstacles", i) + " (" +
                            in.where(marks.obstacles[i], "obstacles") + "): " + point(p) + " is " + approx(distance_m) +
                            " m from its centre " + point(o.center_m) + ", less than its radius " +
                            number(o.radius_m) + " m + robot_radius_m " + number(s.robot_radius_m) + " m");
            }
        }
        for (std::size_t k = 0; k < s.halfspaces.size(); ++k) {
            const HalfSpace& h = s.halfspaces[k];
            const double side = h.normal.dot(p);
            if (h.robot == r && side > h.bound_m) {
                in.fail(marks.starts[r], at,
                        "robot " + std::to_string(r) + " starts beyond the wall " + item("halfspaces", k) + " (" +
                            in.where(marks.halfspaces[k], "halfspaces") + "): normal^T " + point(p) + " = " +
                            approx(side) + " > bound_m " + number(h.bound_m) + " at t = 0");
            }
        }
    }
}

/// Disjoint obstacles: each is its own barrier constraint, and overlapping disks are one obstacle
/// written twice (give a disk that covers both).
void check_obstacles(const Reader& in, const Scenario& s, const Marks& marks)
{
    for (std::size_t j = 1; j < s.obstacles.size(); ++j) {
        for (std::size_t i = 0; i < j; ++i) {
            const Disk& a = s.obstacles[i];
            const Disk& b = s.obstacles[j];
            const double apart_m = (a.center_m - b.center_m).norm();
            if (apart_m < a.radius_m + b.radius_m) {
                in.fail(marks.obstacles[j], item("obstacles", j),
                        "overlaps " + item("obstacles", i) + " (" + in.where(marks.obstacles[i], "obstacles") +
                            "): centres " + approx(apart_m) + " m apart, less than the radii's sum " +
                            approx(a.radius_m + b.radius_m) + " m (give one disk that covers both, or move them apart)");
            }
        }
    }
}

// Times are whole microseconds of plant time: a nanosecond of slack keeps a run that ends on the
// waypoint in.
constexpr double kWaypointSlackS = 1e-9;
constexpr const char* kNoHold =
    "a `through` polynomial is not held after its last waypoint but runs on (the firmware evaluates "
    "it on board); end the run by then or add a later waypoint";

const WaypointEnd* first_end_before(const ScenarioFile& file, double duration_s)
{
    for (const WaypointEnd& end : file.waypoint_ends) {
        if (duration_s > end.t_s + kWaypointSlackS) {
            return &end;
        }
    }
    return nullptr;
}

bool has_yaml_extension(const std::string& name)
{
    const std::string ext = std::filesystem::path(name).extension().string();
    return ext == ".yaml" || ext == ".yml";
}


/// The file's text, refused before it is parsed if it is larger than kMaxScenarioFileBytes (also if
/// it grew after its size was read: at most one byte more is ever read).
std::string read_bounded(const Reader& in, const std::string& path)
{
    const auto too_large = [&in](const std::string& size) {
        in.fail(YAML::Mark::null_mark(), "", "the file is " + size + " bytes, over the limit of " +
                                                 std::to_string(kMaxScenarioFileBytes) +
                                                 " bytes for a scenario file (refused before parsing)");
    };
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (!error && size > kMaxScenarioFileBytes) {
        too_large(std::to_string(size));
    }
    std::ifstream stream(path, std::ios::binary);
    if (!stream) {
        throw ScenarioFileError(path + ": cannot read the file");
    }
    std::string text(kMaxScenarioFileBytes + 1, '\0');
    stream.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(stream.gcount()));
    if (text.size() > kMaxScenarioFileBytes) {
        too_large("more than " + std::to_string(kMaxScenarioFileBytes));
    }
    return text;
}

YAML::Node parse_yaml(const Reader& in, const std::string& path)
{
    const std::string text = read_bounded(in, path);
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
        // yaml-cpp's own guard; its message is only "bad file".
        in.fail(e.mark, "", "not valid YAML for a scenario: nested deeper than the parser's limit of " +
                                std::to_string(e.depth()) + " levels (a scenario's deepest key, "
                                "robots[i].target.through[j].velocity_mps.speed_mps, is 7 levels down)");
    } catch (const YAML::ParserException& e) {
        in.fail(e.mark, "", "not valid YAML: " + e.msg);
    }
    if (root.IsNull()) {
        in.fail(YAML::Mark::null_mark(), "", "the file is empty; a scenario is a YAML map (description, robots, ...)");
    }
    return root;
}

Map top_level(const Reader& in, const YAML::Node& root)
{
    return in.map(root, "", {"base", "description", "duration_s", "robots", "streamed", "robot_radius_m", "obstacles",
                             "distance_bounds", "halfspaces", "offsets", "barrier", "report", "variants", "timing",
                             "sensing", "controller", "faults"});
}

}  // namespace

ScenarioFile load_scenario_file(const std::string& path)
{
    Reader in(path);
    Map top = top_level(in, parse_yaml(in, path));
    // base: a scenario file (beside this one) whose top-level keys this file keeps unless it gives them.
    if (const YAML::Node* base = top.find("base")) {
        const std::string base_path =
            (std::filesystem::path(path).parent_path() / in.text(*base, "base")).string();
        if (std::filesystem::is_directory(base_path)) {
            in.fail(*base, "base", base_path + " is a folder, not a scenario file");
        }
        if (!std::filesystem::is_regular_file(base_path)) {
            in.fail(*base, "base", "no file " + base_path);
        }
        const Reader base_in(base_path);
        const Map base_top = top_level(base_in, parse_yaml(base_in, base_path));
        if (const YAML::Node* nested = base_top.find("base")) {
            base_in.fail(*nested, "base", "a base file cannot have a base itself");
        }
        load_scenario_file(base_path);  // the base is a scenario on its own: its own errors name it
        for (const auto& [key, value] : base_top.entries) {
            if (top.find(key) == nullptr) {
                top.entries.emplace_back(key, value);
                in.set_origin(key, base_path);
            }
        }
    }
    ScenarioFile file;
    file.path = path;
    file.description = in.text(in.required(top, "description"), "description");
    Scenario& s = file.scenario;
    Marks marks;
    s.name = std::filesystem::path(path).stem().string();
    const YAML::Node* duration = top.find("duration_s");
    if (duration != nullptr) {
        s.duration_s = in.real_in(*duration, "duration_s", sim_ranges::kDuration);
    }
    read_robots(in, in.required(top, "robots"), &s, &marks);
    if (const YAML::Node* streamed = top.find("streamed")) {
        s.streamed = in.boolean(*streamed, "streamed");
    }
    if (const YAML::Node* radius = top.find("robot_radius_m")) {
        s.robot_radius_m = in.non_negative(*radius, "robot_radius_m");
    }
    if (const YAML::Node* node = top.find("obstacles")) {
        read_obstacles(in, *node, &s, &marks);
    }
    if (const YAML::Node* node = top.find("distance_bounds")) {
        read_distance_bounds(in, *node, &s);
    }
    if (const YAML::Node* node = top.find("halfspaces")) {
        read_halfspaces(in, *node, &s, &marks);
    }
    if (const YAML::Node* node = top.find("offsets")) {
        read_offsets(in, *node, &s);
    }
    if (const YAML::Node* node = top.find("barrier")) {
        read_barrier(in, *node, &s.barrier);
    }
    if (const YAML::Node* node = top.find("report")) {
        read_report(in, *node, &s);
    }
    if (const YAML::Node* node = top.find("variants")) {
        read_variants(in, *node, s, &file.variants);
    }
    read_run_settings(in, top, &file.run);
    // Between sections: each names the node of the field at fault.
    check_obstacles(in, s, marks);
    check_starts(in, s, marks);
    file.waypoint_ends = in.waypoint_ends;
    if (duration != nullptr) {
        if (const WaypointEnd* end = first_end_before(file, s.duration_s)) {
            in.fail(*duration, "duration_s", "must be at most the last waypoint's time, " + end->field + " = " +
                                                 number(end->t_s) + " s (" + end->where + "), got " +
                                                 duration->Scalar() + ": " + kNoHold);
        }
    } else {
        check_run_duration(file, s.duration_s, "the default duration, no duration_s given");
    }
    return file;
}

void check_run_duration(const ScenarioFile& file, double duration_s, const std::string& duration_source)
{
    if (const WaypointEnd* end = first_end_before(file, duration_s)) {
        throw ScenarioFileError(end->where + ": " + end->field + ": the last waypoint, at " + number(end->t_s) +
                                " s, comes before the run's end, " + number(duration_s) + " s (" + duration_source +
                                "): " + kNoHold);
    }
}

std::string scenario_folder()
{
    const char* folder = std::getenv("TVO_SCENARIO_DIR");
    return folder != nullptr && *folder != '\0' ? folder : TVO_SCENARIO_SOURCE_DIR;
}

std::string scenario_path(const std::string& name_or_path)
{
    if (name_or_path.find('/') != std::string::npos || has_yaml_extension(name_or_path)) {
        return name_or_path;
    }
    return (std::filesystem::path(scenario_folder()) / (name_or_path + ".yaml")).string();
}

std::vector<std::string> scenario_folder_files()
{
    std::vector<std::string> files;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(scenario_folder(), error)) {
        if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
            files.push_back(entry.path().string());
        }
    }
    std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
        return std::filesystem::path(a).stem() < std::filesystem::path(b).stem();
    });
    return files;
}

std::vector<std::string> scenario_subfolder_files()
{
    std::vector<std::string> files;
    std::error_code error;
    for (const auto& folder : std::filesystem::directory_iterator(scenario_folder(), error)) {
        if (!folder.is_directory()) {
            continue;
        }
        for (const auto& entry : std::filesystem::directory_iterator(folder.path(), error)) {
            if (entry.is_regular_file() && entry.path().extension() == ".yaml") {
                files.push_back(entry.path().string());
            }
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

Scenario instantiate_scenario(const ScenarioFile& file, std::size_t robots, TargetKind kind)
{
    Scenario s = file.scenario;
    const std::string name = "scenario " + s.name;
    if (kind == TargetKind::Circle) {
        if (!file.variants.circle_radius_m) {
            throw ScenarioFileError(name + " has its own targets (its file has no variants.circle_radius_m)");
        }
        for (std::size_t r = 0; r < s.robot_count; ++r) {
            const EllipseTarget& e = s.targets[r].ellipse_params();
            s.targets[r] = TargetPath::circle(e.center_m, *file.variants.circle_radius_m, e.omega_radps, e.phase_rad);
        }
    }
    if (file.variants.robots_turned) {
        if (robots < 1 || robots > kMaxRobots) {
            throw ScenarioFileError(name + ": 1 .. " + std::to_string(kMaxRobots) + " robots, got " + std::to_string(robots));
        }
        const TargetPath base_target = s.targets[0];
        const UnicycleState base_start = s.starts[0];
        for (std::size_t r = 0; r < robots; ++r) {
            const double turn_rad = 2.0 * kPi * static_cast<double>(r) / static_cast<double>(robots);
            EllipseTarget e = base_target.ellipse_params();
            e.phase_rad += turn_rad;
            s.targets[r] = base_target.kind() == PathKind::Circle
                               ? TargetPath::circle(e.center_m, e.semi_axis_m.x(), e.omega_radps, e.phase_rad)
                               : TargetPath::ellipse(e);
            s.starts[r].position_m = Eigen::Rotation2Dd(turn_rad) * base_start.position_m;
            s.starts[r].heading_rad = base_start.heading_rad + turn_rad;
            s.weights[r] = s.weights[0];
        }
        s.robot_count = robots;
    } else if (robots != 1 && robots != s.robot_count) {
        throw ScenarioFileError(name + " has its own robots (its file has no variants.robots)");
    }
    s.streamed = s.streamed || kind == TargetKind::Streamed;
    return s;
}

bool scenario_exists(const std::string& name_or_path)
{
    std::error_code error;
    return std::filesystem::is_regular_file(scenario_path(name_or_path), error);
}

Scenario make_scenario(const std::string& name_or_path, std::size_t robots, TargetKind kind)
{
    return instantiate_scenario(load_scenario_file(scenario_path(name_or_path)), robots, kind);
}

Scenario make_demo_scenario(std::size_t robot_count, TargetKind kind)
{
    return make_scenario("demo", robot_count, kind);
}

}  // namespace tvo_host
