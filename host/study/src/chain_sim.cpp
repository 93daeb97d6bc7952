#include "chain_sim.hpp"

#include <cmath>
#include <complex>
#include <cstring>
#include <random>
#include <stdexcept>

extern "C" {
#include "tvo/chain_controller.h"
#include "tvo/objective.h"
#include "tvo/status.h"
#include "tvo/target.h"
#include "tvo/tracking.h"
}

namespace study {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kDim = 2;
constexpr uint32_t kEpochTick = 1000000u;  // leaves room for the first stamp, epoch - tau

// y_d^(j)(t) of the unit circle, per axis.
void target_derivs(double omega, double t, int order, double out[4][2])
{
    const double phi = omega * t;
    const double c = std::cos(phi), s = std::sin(phi);
    const double dc[4] = {c, -s, -c, s};
    const double ds[4] = {s, c, -s, -c};
    double wp = 1.0;
    for (int j = 0; j <= order; ++j) {
        out[j][0] = dc[j & 3] * wp;
        out[j][1] = ds[j & 3] * wp;
        wp *= omega;
    }
}

// The chain's exact flow with u held: x[j] <- sum_{m>=j} x[m] dt^(m-j)/(m-j)! + u dt^(k-j)/(k-j)!.
void flow(int k, const double x[3], double u, double dt, double out[3])
{
    double tmp[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < k; ++j) {
        double sum = 0.0, factor = 1.0;
        for (int m = j; m <= k; ++m) {
            sum += ((m < k) ? x[m] : u) * factor;
            factor *= dt / static_cast<double>(m - j + 1);
        }
        tmp[j] = sum;
    }
    for (int j = 0; j < k; ++j) {
        out[j] = tmp[j];
    }
}

double position_error(double omega, double t, const double y0, const double y1)
{
    double yd[4][2];
    target_derivs(omega, t, 0, yd);
    return std::hypot(y0 - yd[0][0], y1 - yd[0][1]);
}

}  // namespace

double paper_omega()
{
    return 2.0 * kPi / 10.0;
}

std::vector<double> chain_gains(int k, double pole)
{
    // coefficients of (s + p)^k: a_i = C(k, i) p^(k - i)
    std::vector<double> a(static_cast<size_t>(k));
    for (int i = 0; i < k; ++i) {
        double binom = 1.0;
        for (int j = 1; j <= i; ++j) {
            binom = binom * static_cast<double>(k - i + j) / static_cast<double>(j);
        }
        a[static_cast<size_t>(i)] = binom * std::pow(pole, k - i);
    }
    return a;
}

SimResult run_chain(const SimConfig &cfg, std::vector<TraceRow> *trace)
{
    if (cfg.k < 1 || cfg.k > TVO_MAX_RELATIVE_DEGREE) {
        throw std::runtime_error("relative degree out of range");
    }
    const int k = cfg.k;
    const double omega = (cfg.omega_radps > 0.0) ? cfg.omega_radps : paper_omega();

    // --- objective and controller (firmware code, tvo_real_t) ---
    // The unit circle, built as the node builds a session's circle (tvo_session_decode_path): the
    // phase rate keeps omega's double precision, so in-process and over-LCM runs agree bit for bit.
    tvo_target_t target;
    tvo_target_ellipse_t circle{};
    circle.semi_axis_m[0] = static_cast<tvo_real_t>(1.0);
    circle.semi_axis_m[1] = static_cast<tvo_real_t>(1.0);
    circle.omega_radps = static_cast<tvo_real_t>(omega);
    circle.rate_turns_q64 = tvo_target_turns_q64(omega);
    if (tvo_target_init_ellipse(&target, &circle) != TVO_OK) {
        throw std::runtime_error("target init failed");
    }
    target.kind = TVO_TARGET_CIRCLE;
    tvo_tracking_term_t term;
    const tvo_real_t weight[2] = {static_cast<tvo_real_t>(1.0), static_cast<tvo_real_t>(1.0)};
    const tvo_term_t tracking = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, nullptr, &term, TVO_TERM_TRACKING};
    tvo_objective_t objective;
    if (tvo_tracking_init(&term, &target, weight, 0u) != TVO_OK || tvo_objective_init(&objective, kDim) != TVO_OK ||
        tvo_objective_add(&objective, &tracking) != TVO_OK) {
        throw std::runtime_error("objective init failed");
    }
    tvo_chain_config_t cc;
    tvo_chain_config_default(&cc);
    cc.tick_hz = cfg.tick_hz;
    cc.period_ticks = cfg.period_ticks;
    cc.delay_ticks = cfg.delay_ticks;
    cc.relative_degree = static_cast<uint8_t>(k);
    cc.delay_compensation = cfg.compensation ? 1u : 0u;
    cc.zoh_aware = cfg.zoh_aware ? 1u : 0u;
    cc.filtered_derivatives = cfg.filtered ? 1u : 0u;
    cc.filter_tf_s = static_cast<tvo_real_t>(cfg.filter_tf_s);
    const std::vector<double> a = chain_gains(k, cfg.pole);
    for (int i = 0; i < k; ++i) {
        cc.gain[i] = static_cast<tvo_real_t>(a[static_cast<size_t>(i)]);
    }
    cc.input_max = static_cast<tvo_real_t>(1e30);  // the study measures the unsaturated loop
    cc.watchdog_periods = 10u;
    tvo_chain_controller_t ctl;
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_NONE;
    if (tvo_chain_controller_init(&ctl, &cc, &objective, kEpochTick, &bad) != TVO_OK) {
        throw std::runtime_error(std::string("chain controller init rejected parameter ") + tvo_chain_param_str(bad));
    }

    // --- plant (double) ---
    double x[kDim][3] = {{2.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    double u[kDim] = {0.0, 0.0};
    const double hz = static_cast<double>(cfg.tick_hz);
    const double h = static_cast<double>(cfg.period_ticks) / hz;
    const double tau = static_cast<double>(cfg.delay_ticks) / hz;
    const double e0 = position_error(omega, 0.0, x[0][0], x[1][0]);
    const double limit = cfg.diverge_factor * e0;
    const double w_start = cfg.duration_s - cfg.window_s;
    const uint64_t n_intervals = static_cast<uint64_t>(std::ceil(cfg.duration_s / h - 1e-9));

    std::mt19937_64 rng(cfg.seed);
    std::normal_distribution<double> gauss(0.0, 1.0);

    SimResult res;
    double sum_sq = 0.0, u_sq = 0.0;
    uint64_t count = 0, u_count = 0;
    // x holds the plant at t_{n-1} (for n = 0: at rest at y(0), which the flow with u = 0 keeps).
    for (uint64_t n = 0; n < n_intervals; ++n) {
        const bool first = (n == 0);
        // The sample at t_n - tau, under the previous command.
        double xs[kDim][3];
        for (int i = 0; i < kDim; ++i) {
            flow(k, x[i], u[i], first ? 0.0 : h - tau, xs[i]);
        }
        const uint32_t apply_tick = kEpochTick + static_cast<uint32_t>(n * cfg.period_ticks);
        tvo_chain_measurement_t meas;
        std::memset(&meas, 0, sizeof(meas));
        meas.stamp_tick = apply_tick - cfg.delay_ticks;
        double measured[2];
        for (int i = 0; i < kDim; ++i) {
            measured[i] = xs[i][0] + ((cfg.sigma_m > 0.0) ? cfg.sigma_m * gauss(rng) : 0.0);
            meas.y.d[0][i] = static_cast<tvo_real_t>(measured[i]);
            for (int j = 1; j < k; ++j) {
                meas.y.d[j][i] = static_cast<tvo_real_t>(xs[i][j]);  // read only when not filtered
            }
        }
        tvo_chain_command_t cmd;
        // 0 when the step applied a new command; else its call error, or 100 + why it held or stopped.
        const tvo_status_t call = tvo_chain_controller_step(&ctl, &meas, apply_tick, &cmd);
        const int st = (call != TVO_OK) ? static_cast<int>(call)
                       : (cmd.outcome == TVO_OUTCOME_APPLIED) ? 0
                                                              : 100 + static_cast<int>(cmd.reason);
        res.steps++;
        if (st != 0) {
            if (res.not_ok == 0) {
                res.first_bad_status = st;
            }
            res.not_ok++;
        }
        if (trace != nullptr) {
            TraceRow row{n,
                         apply_tick,
                         meas.stamp_tick,
                         {measured[0], measured[1]},
                         {k > 1 ? xs[0][1] : 0.0, k > 1 ? xs[1][1] : 0.0},
                         {k > 2 ? xs[0][2] : 0.0, k > 2 ? xs[1][2] : 0.0},
                         {static_cast<float>(cmd.u[0]), static_cast<float>(cmd.u[1])},
                         static_cast<int>(st),
                         cmd.flags};
            trace->push_back(row);
        }
        // The plant at t_n, where the new command takes over.
        for (int i = 0; i < kDim; ++i) {
            if (!first) {
                flow(k, x[i], u[i], h, x[i]);
            }
            u[i] = static_cast<double>(cmd.u[i]);
        }
        // Error over [t_n, t_{n+1}): divergence at the interval start, dense inside the window.
        const double tn = static_cast<double>(n) * h;
        const double en = position_error(omega, tn, x[0][0], x[1][0]);
        res.peak_ratio = std::isfinite(en) ? std::max(res.peak_ratio, en / e0) : HUGE_VAL;
        if (!std::isfinite(en) || en > limit || !std::isfinite(u[0]) || !std::isfinite(u[1])) {
            res.diverged = true;
            res.diverged_at_s = tn;
            break;
        }
        if (tn >= w_start - 1e-12 && tn <= cfg.duration_s + 1e-12) {
            double yd[4][2];
            target_derivs(omega, tn, k, yd);
            u_sq += (u[0] - yd[k][0]) * (u[0] - yd[k][0]) + (u[1] - yd[k][1]) * (u[1] - yd[k][1]);
            u_count++;
        }
        if (tn + h >= w_start) {
            for (int j = 0; j < cfg.subsamples; ++j) {
                const double dt = h * static_cast<double>(j) / static_cast<double>(cfg.subsamples);
                const double t = tn + dt;
                if (t < w_start - 1e-12 || t > cfg.duration_s + 1e-12) {
                    continue;
                }
                double p[kDim][3];
                for (int i = 0; i < kDim; ++i) {
                    flow(k, x[i], u[i], dt, p[i]);
                }
                const double e = position_error(omega, t, p[0][0], p[1][0]);
                res.peak_ratio = std::isfinite(e) ? std::max(res.peak_ratio, e / e0) : HUGE_VAL;
                if (!std::isfinite(e) || e > limit) {
                    res.diverged = true;
                    res.diverged_at_s = t;
                    break;
                }
                res.max_err_m = std::max(res.max_err_m, e);
                sum_sq += e * e;
                count++;
            }
            if (res.diverged) {
                break;
            }
        }
    }
    res.rms_err_m = (count > 0) ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
    res.u_dev_rms = (u_count > 0) ? std::sqrt(u_sq / static_cast<double>(u_count)) : 0.0;
    return res;
}

double continuous_baseline(int k, double pole, double omega_radps, double duration_s, double window_s, double dt_s)
{
    const double omega = (omega_radps > 0.0) ? omega_radps : paper_omega();
    const std::vector<double> a = chain_gains(k, pole);
    // state per axis: y, y', .., y^(k-1)
    auto deriv = [&](double t, const double s[2][3], double ds[2][3]) {
        double yd[4][2];
        target_derivs(omega, t, k, yd);
        for (int i = 0; i < 2; ++i) {
            double u = yd[k][i];
            for (int j = 0; j < k; ++j) {
                u -= a[static_cast<size_t>(j)] * (s[i][j] - yd[j][i]);
            }
            for (int j = 0; j + 1 < k; ++j) {
                ds[i][j] = s[i][j + 1];
            }
            ds[i][k - 1] = u;
        }
    };
    double s[2][3] = {{2.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    const uint64_t steps = static_cast<uint64_t>(std::llround(duration_s / dt_s));
    double worst = 0.0;
    const double w_start = duration_s - window_s;
    for (uint64_t n = 0; n <= steps; ++n) {
        const double t = static_cast<double>(n) * dt_s;
        if (t >= w_start - 1e-12) {
            worst = std::max(worst, position_error(omega, t, s[0][0], s[1][0]));
        }
        if (n == steps) {
            break;
        }
        double k1[2][3], k2[2][3], k3[2][3], k4[2][3], tmp[2][3];
        deriv(t, s, k1);
        for (int i = 0; i < 2; ++i) for (int j = 0; j < k; ++j) tmp[i][j] = s[i][j] + 0.5 * dt_s * k1[i][j];
        deriv(t + 0.5 * dt_s, tmp, k2);
        for (int i = 0; i < 2; ++i) for (int j = 0; j < k; ++j) tmp[i][j] = s[i][j] + 0.5 * dt_s * k2[i][j];
        deriv(t + 0.5 * dt_s, tmp, k3);
        for (int i = 0; i < 2; ++i) for (int j = 0; j < k; ++j) tmp[i][j] = s[i][j] + dt_s * k3[i][j];
        deriv(t + dt_s, tmp, k4);
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < k; ++j) {
                s[i][j] += dt_s / 6.0 * (k1[i][j] + 2.0 * k2[i][j] + 2.0 * k3[i][j] + k4[i][j]);
            }
        }
    }
    return worst;
}

double predicted_bias_floor(int k, double pole, double omega_radps, double tf_s)
{
    const double omega = (omega_radps > 0.0) ? omega_radps : paper_omega();
    const std::vector<double> a = chain_gains(k, pole);
    const std::complex<double> s(0.0, omega);
    const std::complex<double> d = (tf_s > 0.0) ? s / (tf_s * s + 1.0) : s;
    std::complex<double> num(0.0, 0.0), den = std::pow(s, k);
    for (int i = 0; i < k; ++i) {
        const std::complex<double> di = std::pow(d, i), si = std::pow(s, i);
        num += a[static_cast<size_t>(i)] * (si - di);
        den += a[static_cast<size_t>(i)] * di;
    }
    return std::abs(num) / std::abs(den);
}

}  // namespace study
