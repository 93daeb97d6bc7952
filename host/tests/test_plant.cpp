// Checks of the plant library: the exact arcs, the analytic target derivatives, the metrics and
// the reproducibility of the random streams. Plain asserts (no framework): exit code 0 = pass.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "faults.hpp"
#include "metrics.hpp"
#include "noise.hpp"
#include "plant.hpp"
#include "scenario.hpp"

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
    tvo_host::EllipseTarget target = demo.targets[0];
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

void test_metrics()
{
    tvo_host::TrackingMetrics metrics(20.0, 5.0);
    for (int n = 0; n <= 2000; ++n) {
        const double t = n * 0.01;
        metrics.add_error_sample(t, t >= 15.0 - 1e-12 ? 2.0 : 100.0);
    }
    check(std::abs(metrics.rms_error_window_m() - 2.0) < 1e-15, "RMS covers exactly the last 5 s",
          std::abs(metrics.rms_error_window_m() - 2.0), 1e-15);
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
    test_metrics();
    test_reproducible_streams();
    std::printf("%s\n", g_failures == 0 ? "all passed" : "FAILED");
    return g_failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
