// Checks of the plant library: the exact arcs, the analytic target derivatives, the metrics and
// the reproducibility of the random streams. Plain asserts (no framework): exit code 0 = pass.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "constraint_metrics.hpp"
#include "faults.hpp"
#include "metrics.hpp"
#include "noise.hpp"
#include "plant.hpp"
#include "scenario.hpp"
#include "summary.hpp"

namespace {

int g_failures = 0;

void check(bool ok, const char* what, double got, double limit)
{
    std::printf("%s %-58s %.3e (limit %.1e)\n", ok ? "ok  " : "FAIL", what, got, limit);
    g_failures += ok ? 0 : 1;
}

using tvo_host::UnicycleInput;
using tvo_host::UnicycleState;

UnicycleState rk4(UnicycleState s, const UnicycleInput& u, double dt_s, int steps)
{
    // Reference by brute force: the arc must agree with a fine classical Runge-Kutta integration.
    const double h = dt_s / steps;
    auto f = [&u](double th) { return Eigen::Vector3d(u.speed_mps * std::cos(th), u.speed_mps * std::sin(th),
                                                      u.turn_rate_radps); };
    Eigen::Vector3d x(s.position_m.x(), s.position_m.y(), s.heading_rad);
    for (int i = 0; i < steps; ++i) {
        const Eigen::Vector3d k1 = f(x.z());
        const Eigen::Vector3d k2 = f(x.z() + 0.5 * h * k1.z());
        const Eigen::Vector3d k3 = f(x.z() + 0.5 * h * k2.z());
        const Eigen::Vector3d k4 = f(x.z() + h * k3.z());
        x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    s.position_m = x.head<2>();
    s.heading_rad = x.z();
    return s;
}

double distance(const UnicycleState& a, const UnicycleState& b)
{
    return (a.position_m - b.position_m).norm() + std::abs(a.heading_rad - b.heading_rad);
}

void test_arcs()
{
    UnicycleState start;
    start.position_m = Eigen::Vector2d(-1.0, 2.0);
    start.heading_rad = 0.7;
    const UnicycleInput turning{1.3, 2.1};
    const double arc_err = distance(tvo_host::exact_arc(start, turning, 0.37), rk4(start, turning, 0.37, 20000));
    check(arc_err < 1e-11, "arc matches RK4 (v = 1.3, omega = 2.1, 0.37 s)", arc_err, 1e-11);
    // Tiny turn: the series branch, against RK4 (whose error is pure round-off here).
    const UnicycleInput slight{2.0, 3e-5};
    const double slight_err = distance(tvo_host::exact_arc(start, slight, 1.5), rk4(start, slight, 1.5, 1000));
    check(slight_err < 1e-12, "series branch matches RK4 (omega = 3e-5, 1.5 s)", slight_err, 1e-12);
    const UnicycleInput straight{2.0, 0.0};
    const UnicycleState line = tvo_host::exact_arc(start, straight, 1.5);
    const Eigen::Vector2d expect = start.position_m + 3.0 * Eigen::Vector2d(std::cos(0.7), std::sin(0.7));
    check((line.position_m - expect).norm() < 1e-12, "zero turn is a straight line",
          (line.position_m - expect).norm(), 1e-12);
    const double pi = 3.14159265358979323846;
    const UnicycleState loop = tvo_host::exact_arc(start, UnicycleInput{1.0, 2.0 * pi}, 1.0);
    check((loop.position_m - start.position_m).norm() < 1e-14, "a full turn closes the circle",
          (loop.position_m - start.position_m).norm(), 1e-14);
    const UnicycleState two = tvo_host::exact_arc(tvo_host::exact_arc(start, turning, 0.011), turning, 0.029);
    const UnicycleState one = tvo_host::exact_arc(start, turning, 0.04);
    check(distance(two, one) < 1e-14, "arcs compose (split at a sample instant changes nothing)",
          distance(two, one), 1e-14);
}

void test_target_derivatives()
{
    const tvo_host::Scenario demo = tvo_host::make_demo_scenario(1, tvo_host::TargetKind::Ellipse);
    tvo_host::EllipseTarget target = demo.targets[0].ellipse_params();
    target.rotation_rad = 0.4;
    target.center_m = Eigen::Vector2d(0.5, -0.25);
    const double t = 1.234;
    const double h = 1e-4;
    const auto d = target.derivatives(t);
    double worst = (d[0] - target.position(t)).norm();
    for (std::size_t j = 1; j < d.size(); ++j) {
        // Central difference of the (j-1)-th derivative approximates the j-th to O(h^2).
        const Eigen::Vector2d fd = (target.derivatives(t + h)[j - 1] - target.derivatives(t - h)[j - 1]) / (2.0 * h);
        worst = std::max(worst, (fd - d[j]).norm());
    }
    check(worst < 1e-7, "ellipse derivatives match central differences", worst, 1e-7);
}

void test_polynomial_paths()
{
    // Through seven conditions: each one met, and the derivatives agree with differences of the path.
    const std::vector<tvo_host::PathCondition> conditions = {
        {0.0, 0, {-5.0, -3.0}}, {0.0, 1, {1.0, 0.5}}, {0.0, 2, {0.0, 0.0}}, {5.0, 0, {0.5, -3.4}},
        {5.0, 1, {1.0, -0.4}},  {10.0, 0, {4.0, -5.2}}, {10.0, 1, {0.6, -0.2}}};
    const tvo_host::TargetPath path = tvo_host::TargetPath::through(conditions);
    double worst = 0.0;
    for (const auto& c : conditions) {
        worst = std::max(worst, (path.derivatives(c.t_s)[static_cast<std::size_t>(c.order)] - c.value).norm());
    }
    check(worst < 1e-9, "polynomial meets its interpolation conditions", worst, 1e-9);
    const double t = 3.21;
    const double h = 1e-4;
    const auto d = path.derivatives(t);
    double fd_worst = (d[0] - path.position(t)).norm();
    for (std::size_t j = 1; j < d.size(); ++j) {
        const Eigen::Vector2d fd = (path.derivatives(t + h)[j - 1] - path.derivatives(t - h)[j - 1]) / (2.0 * h);
        fd_worst = std::max(fd_worst, (fd - d[j]).norm());
    }
    check(fd_worst < 1e-6, "polynomial derivatives match central differences", fd_worst, 1e-6);
}

void test_equality_reference()
{
    // Both robots track m_d with y1 - y2 = d(t): the constrained minimiser is m_d +- d/2.
    const tvo_host::Scenario s = tvo_host::make_scenario("formation-equality", 1, tvo_host::TargetKind::Ellipse);
    const double t = 7.3;
    const auto ref = s.references(t);
    const Eigen::Vector2d m = s.targets[0].position(t);
    const Eigen::Vector2d d = s.offsets[0].offset.position(t);
    const double err = std::max((ref[0] - (m + d / 2.0)).norm(), (ref[1] - (m - d / 2.0)).norm());
    check(err < 1e-12 && std::abs(d.norm() - 1.0) < 1e-12, "equality reference is m_d +- d/2, |d| = 1", err, 1e-12);
}

/// Smallest clearance of the scenario's robot disk, placed on its target, from every obstacle.
double target_clearance(const tvo_host::Scenario& s, double t0, double t1, double* at_end)
{
    double worst = 1e9;
    for (int i = 0; i <= 20000; ++i) {
        const double t = t0 + (t1 - t0) * i / 20000.0;
        for (const auto& o : s.obstacles) {
            const double c = (s.targets[0].position(t) - o.center_m).norm() - o.radius_m - s.robot_radius_m;
            worst = std::min(worst, c);
            if (i == 20000) {
                *at_end = std::min(*at_end, c);
            }
        }
    }
    return worst;
}

void test_scenario_data()
{
    // The scenarios' own promises (README.md): what the issue asks of the targets.
    using tvo_host::TargetKind;
    const auto formation = tvo_host::make_scenario("formation-max", 1, TargetKind::Ellipse);
    double min_d = 1e9;
    for (int i = 0; i <= 10000; ++i) {
        const double t = i * 1e-3;
        min_d = std::min(min_d, (formation.targets[0].position(t) - formation.targets[1].position(t)).norm());
    }
    const double end_d = (formation.targets[0].position(10.0) - formation.targets[1].position(10.0)).norm();
    check(min_d < 0.1, "formation targets cross (closest approach)", min_d, 0.1);
    check(std::abs(end_d - 4.4) < 0.1, "formation targets end about 4.4 m apart", end_d, 4.4);
    check(formation.crossing_window.has_value() && formation.crossing_window->start_s > 3.0 &&
              formation.crossing_window->end_s < 7.0,
          "crossing window lies mid-run", formation.crossing_window ? formation.crossing_window->start_s : -1.0, 3.0);

    double end_clear = 1e9;
    const auto feasible = tvo_host::make_scenario("obstacles", 1, TargetKind::Ellipse);
    const double clear = target_clearance(feasible, 0.0, feasible.duration_s, &end_clear);
    check(clear >= 0.3, "feasible target keeps >= 0.3 m + r from every obstacle", clear, 0.3);
    end_clear = 1e9;
    const auto infeasible = tvo_host::make_scenario("obstacles-infeasible-target", 1, TargetKind::Ellipse);
    const double crossing = target_clearance(infeasible, 0.0, infeasible.duration_s, &end_clear);
    check(crossing < -0.5, "infeasible target runs through an obstacle", crossing, -0.5);
    check(end_clear > 0.5, "infeasible target ends in open space", end_clear, 0.5);
}

void test_constraint_monitor()
{
    // One robot of radius 0.2 passing through a unit disk at the origin twice: two entries, not one
    // per sample inside; clearance, violation and time to feasibility follow.
    tvo_host::Scenario s;
    s.name = "monitor-check";
    s.robot_count = 1;
    s.robot_radius_m = 0.2;
    s.obstacles = {{{0.0, 0.0}, 1.0}};
    tvo_host::ConstraintMonitor monitor(s);
    tvo_host::Positions p{};
    const double xs[] = {3.0, 1.1, 0.9, 0.5, 2.0, 1.0, 3.0, 2.0};
    for (std::size_t i = 0; i < sizeof(xs) / sizeof(xs[0]); ++i) {
        p[0] = Eigen::Vector2d(xs[i], 0.0);
        monitor.observe(static_cast<double>(i), p);
    }
    check(monitor.collisions() == 2, "collision events counted on entry", static_cast<double>(monitor.collisions()),
          2.0);
    check(std::abs(monitor.min_clearance_m() - (0.5 - 1.2)) < 1e-12, "min clearance is the deepest overlap",
          monitor.min_clearance_m(), -0.7);
    check(std::abs(monitor.max_violation_frac() - 0.7 / 1.2) < 1e-12, "violation relative to r + r_i",
          monitor.max_violation_frac(), 0.7 / 1.2);
    check(monitor.time_to_feasible_s() == 6.0, "feasible for good from the last exit",
          monitor.time_to_feasible_s(), 6.0);

    // Infeasible start with a maximum distance: violation counted from the first feasible instant.
    tvo_host::Scenario pair;
    pair.robot_count = 2;
    tvo_host::DistanceBound bound;
    bound.max_m = 3.0;
    pair.distances.push_back(bound);
    tvo_host::ConstraintMonitor m2(pair);
    const double gaps[] = {4.5, 3.5, 2.9, 3.03, 2.95, 2.9};
    for (std::size_t i = 0; i < sizeof(gaps) / sizeof(gaps[0]); ++i) {
        p[0] = Eigen::Vector2d(0.0, 0.0);
        p[1] = Eigen::Vector2d(gaps[i], 0.0);
        m2.observe(0.5 * static_cast<double>(i), p);
    }
    check(std::abs(m2.initial_violation_frac() - 0.5) < 1e-12, "initial violation (4.5 - 3) / 3",
          m2.initial_violation_frac(), 0.5);
    check(std::abs(m2.max_violation_frac() - 0.01) < 1e-12, "re-violation after entry, 1 %", m2.max_violation_frac(),
          0.01);
    check(m2.time_to_feasible_s() == 2.0 && m2.final_distance_m() == 2.9 && m2.min_distance_m() == 2.9,
          "time to feasibility, final and min distance", m2.time_to_feasible_s(), 2.0);
}

void test_metrics()
{
    tvo_host::TrackingMetrics metrics(20.0, 5.0);
    for (int n = 0; n <= 2000; ++n) {
        const double t = n * 0.01;
        metrics.add_error_sample(t, t >= 15.0 - 1e-12 ? 2.0 : 100.0);
    }
    check(std::abs(metrics.rms_error_window_m() - 2.0) < 1e-15, "RMS covers exactly the last 5 s",
          std::abs(metrics.rms_error_window_m() - 2.0), 1e-15);
    check(!metrics.rms_whole_run(), "a 20 s run's RMS is over its last 5 s, not the whole run", 20.0,
          tvo_host::kRmsWindowS);
    // A run of at most the window: every sample counts, and the summary says "whole run".
    for (const double duration_s : {3.0, tvo_host::kRmsWindowS}) {
        tvo_host::TrackingMetrics short_run(duration_s, tvo_host::kRmsWindowS);
        short_run.add_error_sample(0.0, 3.0);
        short_run.add_error_sample(duration_s, 4.0);
        tvo_host::RunSummary summary;
        summary.rms_error_last5s_m = short_run.rms_error_window_m();
        summary.rms_whole_run = short_run.rms_whole_run();
        std::ostringstream table;
        tvo_host::print_summary_table(table, summary, tvo_host::SimOptions{});
        const bool labelled = table.str().find("RMS tracking error, whole run") != std::string::npos &&
                              table.str().find("last 5 s") == std::string::npos;
        check(short_run.rms_whole_run() && labelled && std::abs(summary.rms_error_last5s_m - std::sqrt(12.5)) < 1e-15,
              "a run <= 5 s: RMS over the whole run, labelled so", duration_s, tvo_host::kRmsWindowS);
    }
    tvo_host::RunSummary long_summary;
    std::ostringstream long_table;
    tvo_host::print_summary_table(long_table, long_summary, tvo_host::SimOptions{});
    check(long_table.str().find("RMS tracking error, last 5 s") != std::string::npos, "a longer run's label: last 5 s",
          0.0, 0.0);
    const double omegas[2] = {0.5, -3.0};
    metrics.add_command(omegas, 2, true);
    check(metrics.max_abs_omega_radps() == 3.0 && metrics.faults() == 1, "max |omega| and faults counted",
          metrics.max_abs_omega_radps(), 3.0);
}

void test_reproducible_streams()
{
    tvo_host::MeasurementNoise a({1e-3, 1e-3, 1e-3}, 42);
    tvo_host::MeasurementNoise b({1e-3, 1e-3, 1e-3}, 42);
    tvo_host::FaultInjector drops({0.5, 0}, 42);
    UnicycleState s;
    double diff = 0.0;
    for (int i = 0; i < 100; ++i) {
        drops.drop_measurement();  // another stream: must not disturb the noise sequence
        diff += (a.measure(s, {}).position_m - b.measure(s, {}).position_m).norm();
    }
    check(diff == 0.0, "same seed, same noise (drops draw from their own stream)", diff, 0.0);
}

}  // namespace

int main()
{
    test_arcs();
    test_target_derivatives();
    test_polynomial_paths();
    test_equality_reference();
    test_scenario_data();
    test_constraint_monitor();
    test_metrics();
    test_reproducible_streams();
    std::printf("%s\n", g_failures == 0 ? "all passed" : "FAILED");
    return g_failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
