// The controller step against Ipopt on the same closed loop: obstacles4 from the bench
// (firmware/apps/bench/bench_problems.c) runs with the step in the loop, and at every period Ipopt
// solves the frozen problem the law tracks,
//     min_y 1/2 (y - y_d(t))^T W (y - y_d(t))   s.t.   |y - c_i| >= r + r_i  (every obstacle i),
// warm-started from the previous period's solution (primal and multipliers).
//
//   tvo_ipopt_bench [--repetitions N] [--measure step|ipopt|none] [--no-check]
//
// The bench's BENCH_STEPS periods are measured, in every repetition. --measure turns callgrind's
// instrumentation on around only the chosen calls (run under valgrind --tool=callgrind
// --instr-atstart=no; outside valgrind the requests do nothing).
// Prints "HOST_BENCH <key> <value>" lines: the calls, median ns of each (machine-dependent:
// informational), Ipopt's iterations, and how far Ipopt's minimiser is from the robot the law
// drives onto the tracked minimiser. Exits 1 when an Ipopt solve fails or the two disagree.
#include <IpIpoptApplication.hpp>
#include <IpIpoptData.hpp>
#include <IpTNLP.hpp>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench_problems.h"
#include "tvo/tracking.h"

namespace {

using Ipopt::Index;
using Ipopt::Number;

// The sanity check: after the bench's periods the loop runs on, unmeasured, to kCheckEndS; the
// robot, whose law tracks the minimiser, must then sit on Ipopt's minimiser (within kAgreementToleranceM)
// from kSettledAfterS on, once the start transient and both obstacle encounters are over. Before
// that the two legitimately differ: the robot lags while it slides round an obstacle, and behind
// obstacle 1 the law's local free space holds a KKT point that is a saddle of the disk problem
// (the target has crossed the disk's centre), which Ipopt leaves for the far side.
constexpr double kSettledAfterS = 11.0;
constexpr double kCheckEndS = 15.0;
constexpr double kAgreementToleranceM = 0.01;

// The frozen problem of one robot among disks, for Ipopt.
class FrozenObstacles : public Ipopt::TNLP {
public:
    explicit FrozenObstacles(const tvo_problem_desc_t& desc)
    {
        weight_ = {desc.tracking_weight[0][0], desc.tracking_weight[0][1]};
        for (uint8_t i = 0; i < desc.obstacle_count; ++i) {
            center_.push_back({desc.obstacle[i].center_m[0], desc.obstacle[i].center_m[1]});
            const double reach = double(desc.robot_radius_m) + double(desc.obstacle[i].radius_m);
            reach_sq_.push_back(reach * reach);
        }
        lambda_.assign(center_.size(), 0.0);
    }

    void freeze(const std::array<double, 2>& target) { target_ = target; }
    void start_at(const std::array<double, 2>& y) { x_ = y; }
    const std::array<double, 2>& solution() const { return x_; }
    bool solved() const { return solved_; }
    Index iterations() const { return iterations_; }

    bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override
    {
        n = 2;
        m = Index(center_.size());
        nnz_jac_g = 2 * m;
        nnz_h_lag = 2; // diagonal: W and 2 lambda_i I
        style = C_STYLE;
        return true;
    }

    bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override
    {
        for (Index k = 0; k < n; ++k) {
            x_l[k] = -kInfinity;
            x_u[k] = kInfinity;
        }
        for (Index i = 0; i < m; ++i) {
            g_l[i] = reach_sq_[std::size_t(i)];
            g_u[i] = kInfinity;
        }
        return true;
    }

    bool get_starting_point(Index, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index,
                            bool init_lambda, Number* lambda) override
    {
        if (init_x) {
            x[0] = x_[0];
            x[1] = x_[1];
        }
        if (init_z) { // no variable bounds: Ipopt asks for none, but answer if it does
            z_l[0] = z_l[1] = z_u[0] = z_u[1] = 0.0;
        }
        if (init_lambda) {
            std::copy(lambda_.begin(), lambda_.end(), lambda);
        }
        return true;
    }

    bool eval_f(Index, const Number* x, bool, Number& f) override
    {
        f = 0.0;
        for (int k = 0; k < 2; ++k) {
            f += 0.5 * weight_[std::size_t(k)] * (x[k] - target_[std::size_t(k)]) * (x[k] - target_[std::size_t(k)]);
        }
        return true;
    }

    bool eval_grad_f(Index, const Number* x, bool, Number* grad) override
    {
        for (int k = 0; k < 2; ++k) {
            grad[k] = weight_[std::size_t(k)] * (x[k] - target_[std::size_t(k)]);
        }
        return true;
    }

    bool eval_g(Index, const Number* x, bool, Index m, Number* g) override
    {
        for (Index i = 0; i < m; ++i) {
            const auto& c = center_[std::size_t(i)];
            g[i] = (x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]);
        }
        return true;
    }

    bool eval_jac_g(Index, const Number* x, bool, Index m, Index, Index* rows, Index* cols, Number* values) override
    {
        for (Index i = 0; i < m; ++i) {
            for (Index k = 0; k < 2; ++k) {
                if (values == nullptr) {
                    rows[2 * i + k] = i;
                    cols[2 * i + k] = k;
                } else {
                    values[2 * i + k] = 2.0 * (x[k] - center_[std::size_t(i)][std::size_t(k)]);
                }
            }
        }
        return true;
    }

    bool eval_h(Index, const Number*, bool, Number obj_factor, Index m, const Number* lambda, bool, Index,
                Index* rows, Index* cols, Number* values) override
    {
        if (values == nullptr) {
            rows[0] = cols[0] = 0;
            rows[1] = cols[1] = 1;
            return true;
        }
        double constraint_curvature = 0.0;
        for (Index i = 0; i < m; ++i) {
            constraint_curvature += 2.0 * lambda[i];
        }
        values[0] = obj_factor * weight_[0] + constraint_curvature;
        values[1] = obj_factor * weight_[1] + constraint_curvature;
        return true;
    }

    void finalize_solution(Ipopt::SolverReturn status, Index, const Number* x, const Number*, const Number*,
                           Index m, const Number*, const Number* lambda, Number, const Ipopt::IpoptData* data,
                           Ipopt::IpoptCalculatedQuantities*) override
    {
        solved_ = (status == Ipopt::SUCCESS);
        iterations_ = (data != nullptr) ? data->iter_count() : 0;
        if (solved_) { // the next period's warm start
            x_ = {x[0], x[1]};
            std::copy(lambda, lambda + m, lambda_.begin());
        }
    }

private:
    static constexpr Number kInfinity = 2e19; // Ipopt's default nlp_upper_bound_inf is 1e19
    std::array<double, 2> weight_{};
    std::array<double, 2> target_{};
    std::array<double, 2> x_{};
    std::vector<std::array<double, 2>> center_;
    std::vector<double> reach_sq_;
    std::vector<double> lambda_;
    bool solved_ = false;
    Index iterations_ = 0;
};

// The instant ticks after the objective's epoch as a time jet along the trajectory, each field as
// tvo/objective.h defines it (whole seconds and the tick fraction apart; no shared values).
tvo_time_jet_t time_jet_at(uint64_t ticks, uint32_t tick_hz)
{
    tvo_time_jet_t t{};
    t.ticks = ticks;
    t.tick_hz = tick_hz;
    t.whole_s = uint32_t(ticks / tick_hz);
    t.frac_ticks = uint32_t(ticks % tick_hz);
    t.frac_s = tvo_real_t(t.frac_ticks) / tvo_real_t(tick_hz);
    t.t_s = tvo_real_t(t.whole_s) + t.frac_s;
    t.rate = TVO_R(1.0);
    t.shared = nullptr;
    return t;
}

// y_d(t) of the target, through the public tracking term: with W = I its gradient at y = 0 is
// W (0 - y_d(t)) = -y_d(t), exactly (the firmware's own target evaluation, no copy of it here).
bool target_position(const tvo_target_t* target, const tvo_time_jet_t& t, std::array<double, 2>* y_d)
{
    const tvo_real_t unit_weight[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_tracking_term_t term;
    if (tvo_tracking_init(&term, target, unit_weight, 0u) != TVO_OK) {
        return false;
    }
    const tvo_jet_t y[2] = {};
    tvo_jet_t gradient[2] = {};
    if (tvo_tracking_gradient_jet(&term, y, 2u, &t, 0u, gradient) != TVO_OK) {
        return false;
    }
    *y_d = {-double(gradient[0].c[0]), -double(gradient[1].c[0])};
    return true;
}

double median(std::vector<double> values)
{
    if (values.empty()) {
        return 0.0;
    }
    const auto mid = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

struct Options {
    int repetitions = 1;
    std::string measure = "none";
    bool check = true;
};

bool parse(int argc, char** argv, Options& options)
{
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--repetitions" && i + 1 < argc) {
            options.repetitions = std::atoi(argv[++i]);
        } else if (arg == "--measure" && i + 1 < argc) {
            options.measure = argv[++i];
        } else if (arg == "--no-check") {
            options.check = false;
        } else {
            return false;
        }
    }
    return options.repetitions >= 1 &&
           (options.measure == "step" || options.measure == "ipopt" || options.measure == "none");
}

// Runs fn, timed, and instrumented by callgrind when `collect`.
template <typename Fn>
double timed_ns(bool collect, Fn&& fn)
{
    const auto start = std::chrono::steady_clock::now();
    if (collect) {
        CALLGRIND_START_INSTRUMENTATION;
    }
    fn();
    if (collect) {
        CALLGRIND_STOP_INSTRUMENTATION;
    }
    const auto end = std::chrono::steady_clock::now();
    return double(std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count());
}

} // namespace

int main(int argc, char** argv)
{
    Options options;
    if (!parse(argc, argv, options)) {
        std::fprintf(stderr, "usage: %s [--repetitions N>=1] [--measure step|ipopt|none] [--no-check]\n", argv[0]);
        return 2;
    }
    tvo_problem_desc_t desc;
    std::array<tvo_pose_t, TVO_MAX_ROBOTS> start{};
    uint8_t robots = 0;
    if (bench_problem_desc(BENCH_OBSTACLES4, &desc, start.data(), &robots) != TVO_OK) {
        std::fprintf(stderr, "ipopt_bench: obstacles4 description failed\n");
        return 1;
    }
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetIntegerValue("print_level", 0);
    app->Options()->SetStringValue("sb", "yes"); // no banner
    app->Options()->SetStringValue("warm_start_init_point", "yes");
    if (app->Initialize() != Ipopt::Solve_Succeeded) {
        std::fprintf(stderr, "ipopt_bench: Ipopt did not initialise\n");
        return 1;
    }

    const bool collect_step = options.measure == "step";
    const bool collect_ipopt = options.measure == "ipopt";
    const bool solve = !collect_step; // the loop does not depend on Ipopt: measuring the step needs none
    options.check = options.check && solve;
    std::vector<double> step_ns;
    std::vector<double> ipopt_ns;
    long steps = 0;
    long solves = 0;
    long failures = 0;
    long step_errors = 0;
    long iterations = 0;
    double worst_distance_m = 0.0;
    double final_distance_m = 0.0;
    auto loop = std::make_unique<bench_loop_t>();
    for (int rep = 0; rep < options.repetitions; ++rep) {
        if (bench_loop_init(loop.get(), BENCH_OBSTACLES4) != TVO_OK) {
            std::fprintf(stderr, "ipopt_bench: obstacles4 did not initialise\n");
            return 1;
        }
        Ipopt::SmartPtr<FrozenObstacles> frozen = new FrozenObstacles(desc);
        frozen->start_at({double(loop->pose[0].position_m[0]), double(loop->pose[0].position_m[1])});
        // The check's continuation runs once, after the first repetition's measured periods.
        const uint32_t periods = (rep == 0 && options.check)
                                     ? uint32_t(std::lround(kCheckEndS / double(loop->half_period_s * TVO_R(2.0))))
                                     : BENCH_STEPS;
        for (uint32_t n = 0; n < periods; ++n) {
            const bool measured = n < BENCH_STEPS;
            if (bench_loop_advance(loop.get()) != TVO_OK) {
                std::fprintf(stderr, "ipopt_bench: the plant failed at period %u\n", unsigned(n));
                return 1;
            }
            tvo_status_t status = TVO_OK;
            const double step_time_ns = timed_ns(collect_step && measured, [&] {
                status = tvo_controller_step(&loop->controller, &loop->meas, loop->apply_tick, &loop->cmd);
            });
            if (measured) {
                step_ns.push_back(step_time_ns);
                ++steps;
            }
            step_errors += (status != TVO_OK || loop->cmd.outcome != TVO_OUTCOME_APPLIED) ? 1 : 0;
            if (!solve) {
                continue;
            }

            // The problem frozen at the apply instant, where the plant now is.
            const tvo_time_jet_t at = time_jet_at(loop->apply_tick, loop->cfg.tick_hz);
            std::array<double, 2> y_d{};
            if (!target_position(tvo_problem_target(&loop->problem, 0u), at, &y_d)) {
                std::fprintf(stderr, "ipopt_bench: the target failed at period %u\n", unsigned(n));
                return 1;
            }
            frozen->freeze(y_d);
            const bool first = (n == 0u);
            const double solve_ns = timed_ns(collect_ipopt && measured, [&] {
                if (first) {
                    (void)app->OptimizeTNLP(frozen);
                } else {
                    (void)app->ReOptimizeTNLP(frozen);
                }
            });
            failures += frozen->solved() ? 0 : 1;
            if (measured) {
                ipopt_ns.push_back(solve_ns);
                ++solves;
                iterations += frozen->iterations();
            }

            const double t_s = double(at.t_s);
            const double distance_m = std::hypot(frozen->solution()[0] - double(loop->pose[0].position_m[0]),
                                                 frozen->solution()[1] - double(loop->pose[0].position_m[1]));
            if (t_s >= kSettledAfterS) {
                worst_distance_m = std::max(worst_distance_m, distance_m);
                final_distance_m = distance_m;
            }
        }
    }
    const bool agree = !options.check || worst_distance_m <= kAgreementToleranceM;
    std::printf("HOST_BENCH problem obstacles4\n");
    std::printf("HOST_BENCH steps %ld\n", steps);
    std::printf("HOST_BENCH step_errors %ld\n", step_errors);
    std::printf("HOST_BENCH solves %ld\n", solves);
    std::printf("HOST_BENCH ipopt_failures %ld\n", failures);
    std::printf("HOST_BENCH ipopt_mean_iterations %.2f\n", double(iterations) / double(std::max(solves, 1L)));
    std::printf("HOST_BENCH step_median_ns %.0f\n", median(step_ns));
    std::printf("HOST_BENCH ipopt_median_ns %.0f\n", median(ipopt_ns));
    if (options.check) {
        std::printf("HOST_BENCH check_from_s %.1f\n", kSettledAfterS);
        std::printf("HOST_BENCH check_to_s %.1f\n", kCheckEndS);
        std::printf("HOST_BENCH max_distance_m %.6f\n", worst_distance_m);
        std::printf("HOST_BENCH final_distance_m %.6f\n", final_distance_m);
        std::printf("HOST_BENCH tolerance_m %.3f\n", kAgreementToleranceM);
        std::printf("HOST_BENCH agree %d\n", agree ? 1 : 0);
    }
    return (failures == 0 && step_errors == 0 && agree) ? 0 : 1;
}
