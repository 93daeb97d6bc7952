#include "lifted.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace study {

Eigen::MatrixXd chain_flow_A(int k, double dt)
{
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(k, k);
    for (int j = 0; j < k; ++j) {
        double factor = 1.0;  // dt^(m-j)/(m-j)!
        for (int m = j; m < k; ++m) {
            A(j, m) = factor;
            factor *= dt / static_cast<double>(m - j + 1);
        }
    }
    return A;
}

Eigen::VectorXd chain_flow_B(int k, double dt)
{
    Eigen::VectorXd B(k);
    for (int j = 0; j < k; ++j) {
        double factor = 1.0;
        for (int m = 1; m <= k - j; ++m) {
            factor *= dt / static_cast<double>(m);
        }
        B(j) = factor;
    }
    return B;
}

Eigen::MatrixXd lifted_matrix(int k, const std::vector<double> &a, double h, double tau, bool compensation,
                              bool zoh_aware)
{
    const double c = (compensation ? tau : 0.0) + (zoh_aware ? 0.5 * h : 0.0);
    const Eigen::MatrixXd Ah = chain_flow_A(k, h), As = chain_flow_A(k, h - tau), Ac = chain_flow_A(k, c);
    const Eigen::VectorXd Bh = chain_flow_B(k, h), Bs = chain_flow_B(k, h - tau), Bc = chain_flow_B(k, c);
    Eigen::RowVectorXd aT(k);
    for (int i = 0; i < k; ++i) {
        aT(i) = a[static_cast<size_t>(i)];
    }
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(k + 1, k + 1);
    M.topLeftCorner(k, k) = Ah;
    M.topRightCorner(k, 1) = Bh;
    M.bottomLeftCorner(1, k) = -aT * Ac * As;
    M(k, k) = -(aT * (Ac * Bs + Bc))(0, 0);
    return M;
}

double spectral_radius(const Eigen::MatrixXd &m)
{
    Eigen::EigenSolver<Eigen::MatrixXd> es(m, false);
    return es.eigenvalues().cwiseAbs().maxCoeff();
}

double exact_stability_edge(int k, const std::vector<double> &a, const LoopTiming &timing, double h_max_s,
                            double scan_step_s, double tol_s)
{
    auto rho = [&](double h) {
        return spectral_radius(lifted_matrix(k, a, h, timing.tau_frac * h, timing.compensation, timing.zoh_aware));
    };
    double lo = 0.0;
    for (double h = scan_step_s; h <= h_max_s + 1e-12; h += scan_step_s) {
        if (rho(h) >= 1.0) {
            double hi = h;
            while (hi - lo > tol_s) {
                const double mid = 0.5 * (lo + hi);
                if (rho(mid) >= 1.0) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return 0.5 * (lo + hi);
        }
        lo = h;
    }
    return h_max_s;
}

}  // namespace study
