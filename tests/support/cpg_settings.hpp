#pragma once
// Offline settings of the paper's method: the CPG dual cone, its EIM contact operators and their
// estimate, at the POD tolerance eps_pod 3e-5 (relative) the figures of the tests that use it were
// measured at. The library's default is the row cone at eps_pod 1e-6 (offline_builder.hpp).
#include "contactrb/offline/dual_cone.hpp"
#include "contactrb/offline/offline_builder.hpp"

namespace test_support {

inline contactrb::offline::OfflineSettings cpg_settings() {
  contactrb::offline::OfflineSettings s;
  s.dual_method = contactrb::offline::DualConeMethod::CPG;
  s.eps_pod = 3e-5;
  return s;
}

}  // namespace test_support
