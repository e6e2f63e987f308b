// --n, --r, --mk, --mg of `online` and `evaluate`: checked before the model is read (signs),
// then against the maxima the model stores (the online stage uses leading sub-blocks).
#include <string>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/rb/online_solver.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::app {

void check_size_flags(const rb::OnlineSizes& s) {
  require(s.N == -1 || s.N >= 1, "--n must be >= 1 (got " + std::to_string(s.N) + ")");
  require(s.R == -1 || s.R >= 0, "--r must be >= 0 (got " + std::to_string(s.R) + ")");
  require(s.Mk == -1 || s.Mk >= 0, "--mk must be >= 0 (got " + std::to_string(s.Mk) + ")");
  require(s.Mg == -1 || s.Mg >= 0, "--mg must be >= 0 (got " + std::to_string(s.Mg) + ")");
}

void check_sizes_against(const rb::OnlineSizes& s, const rb::ReducedModel& model, const std::string& path) {
  const auto above = [&path](const char* flag, int value, int max) {
    require(value <= max, std::string(flag) + " = " + std::to_string(value) + " is above the maximum " +
                              std::to_string(max) + " stored in '" + path + "'");
  };
  above("--n", s.N, model.N_max);
  above("--r", s.R, model.R_max);
  above("--mk", s.Mk, model.Mk_max);
  above("--mg", s.Mg, model.Mg_max);
}

}  // namespace contactrb::app
