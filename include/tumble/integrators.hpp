#pragma once
/// The fixed-step integrators over a body's whole state, and the two representations of
/// orientation. Names are the ones a scene file and the command line use.

#include <array>
#include <optional>
#include <string_view>

namespace tumble {

/// Order of accuracy: euler 1, symplectic-euler 1, midpoint 2 (the seed's "Euler step, then
/// midpoint evaluation"), rk4 4 (classical Runge-Kutta). adaptive: Dormand–Prince 5(4) with a
/// PI step-size controller and a local error tolerance; dt is then its largest step.
enum class Integrator { Euler, SymplecticEuler, Midpoint, Rk4, Adaptive };

/// How orientation is carried: a unit quaternion (renormalised after each step) or the seed's
/// rotation matrix R (re-orthonormalised after each step).
enum class RotationRep { Quaternion, Matrix };

inline constexpr std::array<std::string_view, 5> kIntegratorNames = {"euler", "symplectic-euler",
                                                                     "midpoint", "rk4", "adaptive"};
/// The fixed-step integrators (every one but adaptive), in the order a study lists them.
inline constexpr std::array<Integrator, 4> kFixedStepIntegrators = {
    Integrator::Euler, Integrator::SymplecticEuler, Integrator::Midpoint, Integrator::Rk4};
inline constexpr std::array<std::string_view, 2> kRotationNames = {"quaternion", "matrix"};

constexpr std::string_view to_string(Integrator i) {
  return kIntegratorNames[static_cast<int>(i)];
}
constexpr std::string_view to_string(RotationRep r) {
  return kRotationNames[static_cast<int>(r)];
}

constexpr std::optional<Integrator> parse_integrator(std::string_view name) {
  for (std::size_t i = 0; i < kIntegratorNames.size(); ++i)
    if (kIntegratorNames[i] == name) return static_cast<Integrator>(i);
  return std::nullopt;
}
constexpr std::optional<RotationRep> parse_rotation(std::string_view name) {
  for (std::size_t i = 0; i < kRotationNames.size(); ++i)
    if (kRotationNames[i] == name) return static_cast<RotationRep>(i);
  return std::nullopt;
}

/// The adaptive step-size controller's memory, carried from one stretch to the next (per body).
struct AdaptiveController {
  double h_next_s = 0.0;   ///< proposed next substep; 0 = none yet (start from the stretch)
  double err_prev = 1e-4;  ///< the last accepted step's scaled error (PI memory)
};

/// Formal order of accuracy of an integrator (global error ~ dt^order).
constexpr int order_of(Integrator i) {
  switch (i) {
    case Integrator::Euler:
      return 1;
    case Integrator::SymplecticEuler:
      return 1;
    case Integrator::Midpoint:
      return 2;
    case Integrator::Rk4:
      return 4;
    case Integrator::Adaptive:
      return 5;
  }
  return 0;
}

}  // namespace tumble
