#include "contactrb/study/study_configurations.hpp"

#include <filesystem>

#include "contactrb/cases/case_problem.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/hf/hf_solver.hpp"
#include "contactrb/io/csv_writer.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::study {

namespace {

// The case's HF settings (those of the snapshots: hf::HFSettings defaults).
hf::HFSolution solve_at(const cases::CaseSpec& spec, const mesh::Mesh& reference, double mu,
                        std::optional<contact::Discretization> constraint) {
  hf::HFSolver solver(cases::make_problem(spec, reference, mu, constraint));
  return solver.solve(hf::HFSettings{});
}

ConstraintProfile profile_of(const cases::CaseSpec& spec, const mesh::Mesh& reference, double mu,
                             contact::Discretization d) {
  hf::HFSolver solver(cases::make_problem(spec, reference, mu, d));
  const hf::HFSolution s = solver.solve(hf::HFSettings{});
  const contact::ContactQuadrature& q = solver.quadrature();
  ConstraintProfile p;
  p.constraint = contact::to_string(d);
  p.converged = s.converged;
  p.status = solve::to_string(s.status);
  p.iterations = s.iterations;
  p.energy = s.energy;
  p.contact_force = s.contact_force;
  require(s.lambda.size() == q.weight.size() && q.center_node.size() == static_cast<std::size_t>(q.weight.size()),
          "report: the HF multipliers at mu = " + number_text(mu) + " do not match the contact quadrature");
  for (Eigen::Index r = 0; r < s.lambda.size(); ++r) {
    p.abscissa.push_back(reference.nodes[static_cast<std::size_t>(q.center_node[static_cast<std::size_t>(r)])].x());
    p.pressure.push_back(s.lambda(r));
    p.weight.push_back(q.weight(r));
  }
  return p;
}

}  // namespace

std::vector<DeformedConfiguration> deformed_configurations(const cases::CaseSpec& spec, const mesh::Mesh& reference,
                                                           const std::vector<double>& mus) {
  std::vector<DeformedConfiguration> out;
  for (double mu : mus) {
    DeformedConfiguration c;
    c.mu = mu;
    c.mesh = cases::mapped_mesh(spec, reference, mu);
    const hf::HFSolution s = solve_at(spec, reference, mu, std::nullopt);
    c.u = s.u;
    c.converged = s.converged;
    c.status = solve::to_string(s.status);
    require(c.u.size() == c.mesh.num_dofs(), "report: the HF displacement at mu = " + number_text(mu) +
                                                 " does not match the mesh");
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<ConstraintComparison> compare_constraints(const cases::CaseSpec& spec, const mesh::Mesh& reference,
                                                      const std::vector<double>& mus) {
  std::vector<ConstraintComparison> out;
  for (double mu : mus) {
    ConstraintComparison c;
    c.mu = mu;
    c.lac = profile_of(spec, reference, mu, contact::Discretization::LAC);
    c.collocation = profile_of(spec, reference, mu, contact::Discretization::Collocation);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<std::string> write_configuration_files(const std::vector<DeformedConfiguration>& configurations,
                                                   const std::vector<ConstraintComparison>& comparisons,
                                                   const std::string& dir) {
  namespace fs = std::filesystem;
  const auto path = [&](const std::string& name) { return (fs::path(dir) / name).string(); };
  std::vector<std::string> files;
  if (!configurations.empty()) {
    io::CsvWriter nodes({"mu", "node", "body", "x", "y", "ux", "uy"});
    for (const DeformedConfiguration& c : configurations) {
      // A node's body: that of any triangle holding it (the bodies share no node).
      std::vector<long long> body(c.mesh.nodes.size(), -1);
      for (std::size_t t = 0; t < c.mesh.triangles.size(); ++t) {
        for (int n : c.mesh.triangles[t]) body[static_cast<std::size_t>(n)] = c.mesh.body[t];
      }
      for (std::size_t n = 0; n < c.mesh.nodes.size(); ++n) {
        const Eigen::Index i = static_cast<Eigen::Index>(2 * n);
        nodes.add_row({c.mu, static_cast<long long>(n), body[n], c.mesh.nodes[n].x(), c.mesh.nodes[n].y(), c.u(i),
                       c.u(i + 1)});
      }
    }
    nodes.write(path("deformed_nodes.csv"));
    files.push_back("deformed_nodes.csv");
    io::CsvWriter triangles({"triangle", "n0", "n1", "n2", "body"});
    const mesh::Mesh& m = configurations.front().mesh;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      triangles.add_row({static_cast<long long>(t), static_cast<long long>(m.triangles[t][0]),
                         static_cast<long long>(m.triangles[t][1]), static_cast<long long>(m.triangles[t][2]),
                         static_cast<long long>(m.body[t])});
    }
    triangles.write(path("deformed_triangles.csv"));
    files.push_back("deformed_triangles.csv");
  }
  if (!comparisons.empty()) {
    io::CsvWriter w({"mu", "constraint", "abscissa", "pressure", "weight"});
    for (const ConstraintComparison& c : comparisons) {
      for (const ConstraintProfile* p : {&c.lac, &c.collocation}) {
        for (std::size_t r = 0; r < p->abscissa.size(); ++r) {
          w.add_row({c.mu, p->constraint, p->abscissa[r], p->pressure[r], p->weight[r]});
        }
      }
    }
    w.write(path("constraint_comparison.csv"));
    files.push_back("constraint_comparison.csv");
  }
  return files;
}

}  // namespace contactrb::study
