// The lifted sampled-data closed loop of the chain testbed, per axis, from the controller's linear law.
//
// For f0 = 1/2 |y - y_d|^2 the law is u = y_d^(k) - sum a_i (y^(i) - y_d^(i)), so stability is
// decided by the homogeneous error dynamics (y_d = 0). State z_n = [x(t_n); u_n] (chain state at
// t_n, the command held over [t_n, t_{n+1})). With A(dt), B(dt) the chain's exact flow with u held:
//   sample:   x(s) = A(h - tau) x_n + B(h - tau) u_n                       (s = t_{n+1} - tau)
//   carry:    x_c  = A(c) x(s) + B(c) u_n,  c = (compensated ? tau : 0) + (ZOH-aware ? h/2 : 0)
//   law:      u_{n+1} = -a^T x_c
//   plant:    x_{n+1} = A(h) x_n + B(h) u_n
// so z_{n+1} = M z_n, M = [[A(h), B(h)], [-a^T A(c) A(h-tau), -a^T (A(c) B(h-tau) + B(c))]].
// (The held command is the only memory the delay needs: tau <= h.)
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace study {

struct LoopTiming {
    double tau_frac = 0.0;     // tau / h
    bool compensation = false;
    bool zoh_aware = false;
};

Eigen::MatrixXd chain_flow_A(int k, double dt);
Eigen::VectorXd chain_flow_B(int k, double dt);
Eigen::MatrixXd lifted_matrix(int k, const std::vector<double> &a, double h, double tau, bool compensation,
                              bool zoh_aware);
double spectral_radius(const Eigen::MatrixXd &m);

// Smallest h with spectral radius >= 1: a scan in steps of `scan_step_s` from scan_step_s up to
// h_max_s, then bisection to `tol_s`. Returns h_max_s if no crossing was found.
double exact_stability_edge(int k, const std::vector<double> &a, const LoopTiming &timing, double h_max_s = 3.0,
                            double scan_step_s = 1e-3, double tol_s = 1e-9);

}  // namespace study
