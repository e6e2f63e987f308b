// `online --out DIR` (cmd_online.cpp): the reconstructed solution on the HF mesh Omega(mu), from
// the model file's reconstruction data (study/solution_fields.hpp). It needs the case's mesh
// (mesh generation, FE), so it is part of contactrb-full only; the light `contactrb` hands every
// `online --out` to contactrb-full (front_main.cpp).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "contactrb/cases/case_record.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "contactrb/study/solution_fields.hpp"

namespace contactrb::app {

namespace {

class FieldOutput final : public OnlineFields {
 public:
  FieldOutput(contactrb::model::ReducedReconstruction rec, cases::CaseSpec spec, mesh::Mesh reference)
      : reconstruction_(std::move(rec)), spec_(std::move(spec)), reference_(std::move(reference)) {}

  nlohmann::json write(const contactrb::model::ReducedModel& model, const cases::Mu& mu,
                       const online::OnlineSolution& s, const std::string& dir) const override {
    const study::SolutionFiles files =
        study::write_solution_fields(spec_, reference_, mu, model.surface.discretization,
                                     online::reconstruct_displacement(reconstruction_, mu, s.u_hat),
                                     online::reconstruct_multipliers(reconstruction_, mu, s.lambda_hat), dir);
    return {{"vtu", files.vtu},
            {"deformed_vtu", files.deformed_vtu},
            {"contact_vtu", files.contact_vtu},
            {"multipliers", files.multipliers}};
  }

 private:
  contactrb::model::ReducedReconstruction reconstruction_;
  cases::CaseSpec spec_;
  mesh::Mesh reference_;
};

std::unique_ptr<OnlineFields> read_field_output(const contactrb::model::ReducedModel& model,
                                                const std::string& model_path) {
  contactrb::model::ReducedReconstruction rec = io::read_reconstruction(model_path);
  // The mesh stored in the model file (format 5) is used: the case's .msh file may be gone.
  cases::CaseSpec spec = cases::case_from_record(
      model.case_kind, model.case_spec, model_path,
      rec.mesh.nodes.empty() ? cases::MeshFile::Required : cases::MeshFile::Optional);
  // The case against the file first (its message names the level or mesh that disagrees), then
  // the reconstruction data against the mesh.
  mesh::Mesh reference = study::model_reference_mesh(spec, model, rec, model_path);
  online::check_reconstruction(model, rec);
  return std::make_unique<FieldOutput>(std::move(rec), std::move(spec), std::move(reference));
}

std::vector<FileRole> field_roles(const std::string& dir, const std::string& where) {
  const study::SolutionFiles f = study::solution_file_names(dir);
  return {{"solution.vtu in " + where, f.vtu},
          {"solution_deformed.vtu in " + where, f.deformed_vtu},
          {"contact.vtu in " + where, f.contact_vtu},
          {"multipliers.csv in " + where, f.multipliers}};
}

}  // namespace

const OnlineFieldHooks* online_field_hooks() {
  static const OnlineFieldHooks hooks{&field_roles, &read_field_output};
  return &hooks;
}

}  // namespace contactrb::app
