#pragma once
// The registered dual cone offline (model/registration.hpp; docs/offline-online.md, "The
// registered cone"): each training pressure's support [s_left, s_right] along the slave chain,
// the pressures resampled in the registered coordinate xi = (s - s_left) / (s_right - s_left),
// and a CPG cone (Algorithm 2) of those registered profiles.
#include <Eigen/Core>
#include <vector>

#include "contactrb/cases/parameter.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/offline/dual_cone.hpp"

namespace contactrb::offline {

// Grid of the registered profiles: xi in [-kRegistrationMargin, 1 + kRegistrationMargin], so that
// a support predicted a little narrower than the true one still carries the pressure's ends.
inline constexpr int kRegistrationGridPoints = 441;
inline constexpr double kRegistrationMargin = 0.05;

struct RegistrationResult {
  model::Registration registration;
  DualConeResult cone;  // the CPG of the registered profiles (errors in the grid's L2 norm)
};

// `Lambda` (R_kept x P, >= 0): the training pressures on the kept rows `kept`; `training_mu`
// (p x P); `settings`: the CPG's tolerance and size. Throws contactrb::Error when a training
// pressure vanishes (no support to register).
RegistrationResult build_registration(const model::ContactSurface& surface, const std::vector<int>& kept,
                                      const Eigen::MatrixXd& Lambda, const Eigen::MatrixXd& training_mu,
                                      const std::vector<cases::ParameterSpec>& parameters,
                                      const DualConeSettings& settings);

}  // namespace contactrb::offline
