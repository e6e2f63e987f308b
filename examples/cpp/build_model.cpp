// The offline stage of hertz-b from C++: the HF snapshots of the case's training set, then a
// reduced model with the default offline settings, written to a model file that
// `contactrb online --model FILE` and examples/cpp/online_query.cpp read (docs/cpp-api.md).
//
// Build (in the contactrb build tree, tests on):
//   cmake --build build --target example_build_model
// Run:
//   ./build/examples/cpp/example_build_model out/hertz-b-model.h5
//   (or: ctest --test-dir build -R example_   which then runs example_online_query on it)
// Exits 1 when a snapshot solve fails or the library throws (an unwritable path, ...).
#include <cstdio>
#include <exception>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: example_build_model MODEL.h5\n");
    return 1;
  }
  try {
    const contactrb::cases::CaseSpec spec = contactrb::cases::builtin_case_spec("hertz-b");
    // The 22 training values of the lower radius R2; the reference mesh is generated once here.
    const contactrb::offline::SnapshotRequest request = contactrb::offline::make_snapshot_request(spec, "training");
    contactrb::offline::SnapshotRunOptions run;
    run.jobs = 2;  // the snapshots do not depend on the thread count
    const contactrb::io::SnapshotSet snapshots = contactrb::offline::generate_snapshots(request, run);
    const contactrb::offline::SnapshotSummary summary = contactrb::offline::summarize(snapshots);
    if (summary.failures > 0) {  // a failed solve is recorded in the set, never dropped
      std::fprintf(stderr, "example_build_model: %d snapshot solves failed\n", summary.failures);
      return 1;
    }
    // POD, supremizers, compression, dual cone (CPG), EIM of kappa and gamma, estimate data.
    const contactrb::offline::OfflineResult result = contactrb::offline::build_reduced_model(snapshots, spec);
    contactrb::io::write_reduced_model_file(result.model, result.reconstruction, argv[1]);
    std::printf("hertz-b: %d snapshots -> N %d, R %d, Mk %d, Mg %d\n", summary.solves, result.report.N,
                result.report.R, result.report.Mk, result.report.Mg);
    std::printf("wrote %s\n", argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "example_build_model: %s\n", e.what());
    return 1;
  }
  return 0;
}
