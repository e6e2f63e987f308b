#pragma once
// The consistency check of a reduced model (model/reduced_model.hpp), run after building and
// after reading a file, before any online solve.
#include "contactrb/model/reduced_model.hpp"

namespace contactrb::online {

// Throws contactrb::Error naming the first inconsistent array (sizes against the maxima, the
// affine term counts, the contact surface, the estimate data). Used after building and after
// reading a file.
void check_model(const contactrb::model::ReducedModel& model);

}  // namespace contactrb::online
