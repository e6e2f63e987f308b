// --n, --r, --mk, --mg of `online` and `evaluate`: checked before the model is read (signs),
// then against the maxima the model stores (the online stage uses leading sub-blocks); their
// --iteration.
#include <string>

#include "commands.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::app {

online::OnlineSizes checked_size_flags(const SizeFlags& f) {
  // Every negative value given is refused (-1 as well as -3); leaving the flag out is the way
  // to ask for the maximum.
  const auto size = [](const char* flag, const std::optional<int>& v, int min) {
    if (!v) return -1;
    require(*v >= min, std::string(flag) + " must be >= " + std::to_string(min) + " (got " + std::to_string(*v) +
                           "; leave it out for the model's maximum)");
    return *v;
  };
  return online::OnlineSizes{size("--n", f.n, 1), size("--r", f.r, 0), size("--mk", f.mk, 0), size("--mg", f.mg, 0)};
}

void check_sizes_against(const online::OnlineSizes& s, const contactrb::model::ReducedModel& model,
                         const std::string& path) {
  const auto above = [&path](const char* flag, int value, int max) {
    require(value <= max, std::string(flag) + " = " + std::to_string(value) + " is above the maximum " +
                              std::to_string(max) + " stored in '" + path + "'");
  };
  above("--n", s.N, model.N_max);
  above("--r", s.R, model.online_R_max());
  above("--mk", s.Mk, model.Mk_max);
  above("--mg", s.Mg, model.Mg_max);
}

online::OnlineIteration checked_iteration_flag(const std::string& value, const contactrb::model::ReducedModel& model) {
  const online::OnlineIteration iteration = option_enum("--iteration", value, online::online_iteration_from_string);
  require(iteration != online::OnlineIteration::Newton || model.dual_method == contactrb::model::kRowCone,
          "--iteration newton needs a model built with `contactrb offline --dual rows` (its dual cone is '" +
              model.dual_method + "')");
  return iteration;
}

}  // namespace contactrb::app
