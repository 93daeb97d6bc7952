// Analytic target paths; see target_path.hpp.
#include "target_path.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace tvo_host {

namespace {
constexpr double kPi = 3.14159265358979323846;

/// d^order/dt^order of t^j at t: j!/(j-order)! t^(j-order), 0 for j < order.
double monomial_derivative(std::size_t j, int order, double t_s)
{
    if (static_cast<int>(j) < order) {
        return 0.0;
    }
    double factor = 1.0;
    for (int k = 0; k < order; ++k) {
        factor *= static_cast<double>(static_cast<int>(j) - k);
    }
    return factor * std::pow(t_s, static_cast<double>(static_cast<int>(j) - order));
}
}  // namespace

std::array<Eigen::Vector2d, 4> EllipseTarget::derivatives(double t_s) const
{
    // d^j/dt^j (cos phi, sin phi) = omega^j (cos, sin)(phi + j pi/2): one formula for every order.
    const Eigen::Rotation2Dd rotation(rotation_rad);
    const double phi = omega_radps * t_s + phase_rad;
    std::array<Eigen::Vector2d, 4> deriv;
    double omega_pow = 1.0;
    for (std::size_t j = 0; j < deriv.size(); ++j) {
        const double shifted = phi + static_cast<double>(j) * kPi / 2.0;
        const Eigen::Vector2d local(semi_axis_m.x() * omega_pow * std::cos(shifted),
                                    semi_axis_m.y() * omega_pow * std::sin(shifted));
        deriv[j] = rotation * local;
        omega_pow *= omega_radps;
    }
    deriv[0] += center_m;
    return deriv;
}

Eigen::Vector2d EllipseTarget::position(double t_s) const
{
    const double phi = omega_radps * t_s + phase_rad;
    const Eigen::Vector2d local(semi_axis_m.x() * std::cos(phi), semi_axis_m.y() * std::sin(phi));
    return center_m + Eigen::Rotation2Dd(rotation_rad) * local;
}

TargetPath TargetPath::polynomial(const PolyCoeffs& coeff)
{
    TargetPath path;
    path.kind_ = PathKind::Polynomial;
    path.coeff_ = coeff;
    return path;
}

TargetPath TargetPath::through(const std::vector<PathCondition>& conditions)
{
    const std::size_t n = conditions.size();
    if (n == 0 || n > kPolyCoeffs) {
        throw std::invalid_argument("TargetPath::through: 1 .. 8 conditions (degree <= 7)");
    }
    // Both axes share the (confluent Vandermonde) matrix of the conditions.
    Eigen::MatrixXd a(n, n);
    Eigen::MatrixXd b(n, 2);
    for (std::size_t i = 0; i < n; ++i) {
        const PathCondition& c = conditions[i];
        for (std::size_t j = 0; j < n; ++j) {
            a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = monomial_derivative(j, c.order, c.t_s);
        }
        b.row(static_cast<Eigen::Index>(i)) = c.value.transpose();
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
    if (lu.rank() < static_cast<Eigen::Index>(n)) {
        throw std::invalid_argument("TargetPath::through: the conditions do not determine the polynomial");
    }
    const Eigen::MatrixXd x = lu.solve(b);
    PolyCoeffs coeff{};
    for (std::size_t axis = 0; axis < 2; ++axis) {
        for (std::size_t j = 0; j < n; ++j) {
            coeff[axis][j] = x(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(axis));
        }
    }
    return polynomial(coeff);
}

TargetPath TargetPath::circle(const Eigen::Vector2d& center_m, double radius_m, double omega_radps, double phase_rad)
{
    TargetPath path;
    path.kind_ = PathKind::Circle;
    path.ellipse_.center_m = center_m;
    path.ellipse_.semi_axis_m = Eigen::Vector2d(radius_m, radius_m);
    path.ellipse_.omega_radps = omega_radps;
    path.ellipse_.phase_rad = phase_rad;
    path.ellipse_.rotation_rad = 0.0;
    return path;
}

TargetPath TargetPath::ellipse(const EllipseTarget& ellipse)
{
    TargetPath path;
    path.kind_ = PathKind::Ellipse;
    path.ellipse_ = ellipse;
    return path;
}

std::array<Eigen::Vector2d, 4> TargetPath::derivatives(double t_s) const
{
    if (kind_ != PathKind::Polynomial) {
        return ellipse_.derivatives(t_s);
    }
    std::array<Eigen::Vector2d, 4> deriv;
    for (std::size_t order = 0; order < deriv.size(); ++order) {
        deriv[order] = Eigen::Vector2d::Zero();
        for (std::size_t j = order; j < kPolyCoeffs; ++j) {
            const double m = monomial_derivative(j, static_cast<int>(order), t_s);
            deriv[order] += m * Eigen::Vector2d(coeff_[0][j], coeff_[1][j]);
        }
    }
    return deriv;
}

Eigen::Vector2d TargetPath::position(double t_s) const
{
    if (kind_ != PathKind::Polynomial) {
        return ellipse_.position(t_s);
    }
    // Horner per axis.
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    for (std::size_t j = kPolyCoeffs; j-- > 0;) {
        p = p * t_s + Eigen::Vector2d(coeff_[0][j], coeff_[1][j]);
    }
    return p;
}

}  // namespace tvo_host
