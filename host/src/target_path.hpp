// Time functions of the plane with analytic derivatives: the robots' targets y_d(t) and the
// formation offsets d(t). They use the firmware's own parametrisations (polynomial sum A_j t^j of
// degree <= 7, circle, ellipse), so the session message carries them as they are and the plant
// side evaluates exactly what the controller was told.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace tvo_host {

/// Coefficients A_0 .. A_7 per axis (TVO_POLY_MAX_DEGREE = 7 on board).
constexpr std::size_t kPolyCoeffs = 8;
using PolyCoeffs = std::array<std::array<double, kPolyCoeffs>, 2>;

/// y_d(t) = c + R(rotation) (a cos(phi), b sin(phi)), phi = omega t + phase. a = b: a circle.
struct EllipseTarget {
    Eigen::Vector2d center_m{Eigen::Vector2d::Zero()};
    Eigen::Vector2d semi_axis_m{Eigen::Vector2d::Ones()};
    double omega_radps{0.0};
    double phase_rad{0.0};
    double rotation_rad{0.0};

    /// deriv[j] = j-th time derivative of y_d at t_s, j = 0..3 (position .. jerk).
    std::array<Eigen::Vector2d, 4> derivatives(double t_s) const;
    Eigen::Vector2d position(double t_s) const;
};

/// One interpolation condition of a polynomial path: its `order`-th derivative at t_s is value.
struct PathCondition {
    double t_s{0.0};
    int order{0};
    Eigen::Vector2d value{Eigen::Vector2d::Zero()};
};

enum class PathKind { Polynomial, Circle, Ellipse };

class TargetPath {
public:
    /// The zero polynomial (a point at the origin).
    TargetPath() = default;

    static TargetPath polynomial(const PolyCoeffs& coeff);
    /// The polynomial of degree conditions.size() - 1 (at most 7) meeting every condition
    /// (std::invalid_argument if there are too many or they do not determine it).
    static TargetPath through(const std::vector<PathCondition>& conditions);
    static TargetPath circle(const Eigen::Vector2d& center_m, double radius_m, double omega_radps, double phase_rad);
    static TargetPath ellipse(const EllipseTarget& ellipse);

    PathKind kind() const { return kind_; }
    const PolyCoeffs& coefficients() const { return coeff_; }
    const EllipseTarget& ellipse_params() const { return ellipse_; }

    /// deriv[j] = j-th time derivative at t_s, j = 0..3 (position .. jerk).
    std::array<Eigen::Vector2d, 4> derivatives(double t_s) const;
    Eigen::Vector2d position(double t_s) const;

private:
    PathKind kind_{PathKind::Polynomial};
    PolyCoeffs coeff_{};
    EllipseTarget ellipse_{};
};

}  // namespace tvo_host
