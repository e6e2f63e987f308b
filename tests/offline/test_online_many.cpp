// online/online_many.hpp: solve_many on 1 and 3 threads answers every point as one solver
// answering them in order does, bit for bit (the claim the threaded `online --batch` and
// `sample` rest on: an answer does not depend on the queries before it), in the order of the
// points, with the error of a point outside the domain in its slot; an exception of the
// callback of for_each_query reaches the caller.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_many.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace online = contactrb::online;
namespace offline = contactrb::offline;
namespace cases = contactrb::cases;

namespace {

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

const contactrb::model::ReducedModel& hertz_b_model() {
  static const contactrb::model::ReducedModel model = [] {
    const cases::CaseSpec spec = cases::builtin_case_spec("hertz-b");
    const offline::SnapshotRequest request = offline::make_snapshot_request(spec, "training");
    offline::SnapshotRunOptions run;
    run.jobs = 2;
    return offline::build_reduced_model(offline::generate_snapshots(request, run), spec, offline::OfflineSettings{})
        .model;
  }();
  return model;
}

}  // namespace

TEST(OnlineMany, ThreadsAnswerAsOneSolverInOrder) {
  const contactrb::model::ReducedModel& model = hertz_b_model();
  std::vector<cases::Mu> points;
  for (int i = 0; i < 150; ++i) points.push_back(cases::Mu::Constant(1, 0.9 + 0.22 * ((i * 37) % 150) / 149.0));
  points[40] = cases::Mu::Constant(1, 1.5);  // outside [0.9, 1.12]
  online::OnlineSolver serial(model);
  for (int jobs : {1, 3}) {
    const std::vector<online::QueryAnswer> answers = online::solve_many(model, {}, {}, points, jobs);
    ASSERT_EQ(answers.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      SCOPED_TRACE("point " + std::to_string(i) + ", jobs " + std::to_string(jobs));
      if (i == 40) {
        EXPECT_FALSE(answers[i].answered);
        EXPECT_NE(answers[i].error.find("outside"), std::string::npos) << answers[i].error;
        EXPECT_THROW(serial.solve(points[i]), contactrb::Error);
        continue;
      }
      const online::OnlineSolution s = serial.solve(points[i]);
      const online::OnlineSolution& t = answers[i].solution;
      ASSERT_TRUE(answers[i].answered) << answers[i].error;
      EXPECT_TRUE(s.converged());
      EXPECT_EQ(t.status, s.status);
      EXPECT_EQ(t.iterations, s.iterations);
      EXPECT_TRUE(same_bits(t.u_hat, s.u_hat));
      EXPECT_TRUE(same_bits(t.lambda_hat, s.lambda_hat));
      EXPECT_TRUE(same_bits(t.energy, s.energy));
      EXPECT_TRUE(same_bits(t.contact_force, s.contact_force));
      EXPECT_TRUE(same_bits(t.estimate.energy, s.estimate.energy));
    }
  }
}

TEST(OnlineMany, CallbackExceptionReachesTheCaller) {
  const contactrb::model::ReducedModel& model = hertz_b_model();
  std::vector<char> seen(500, 0);
  EXPECT_THROW(online::for_each_query(
                   model, {}, seen.size(), 2,
                   [&](online::OnlineSolver&, std::size_t i) {
                     seen[i] = 1;
                     if (i == 57) throw std::runtime_error("stop");
                   },
                   4),
               std::runtime_error);
  EXPECT_EQ(seen[57], 1);
  EXPECT_THROW(online::for_each_query(model, {}, 10, 0, [](online::OnlineSolver&, std::size_t) {}), contactrb::Error);
  int calls = 0;
  online::for_each_query(model, {}, 0, 2, [&](online::OnlineSolver&, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}
