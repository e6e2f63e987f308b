// rb/study.hpp: the helpers of the report study (subsets of a parameter set, the Table 3-5
// size rows), its settings checks, the per-case tolerances, and the report.md tables built
// from a hand-made result.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/rb/study.hpp"

namespace rb = contactrb::rb;

TEST(Study, EvenlySpacedSubsetKeepsBothEnds) {
  const std::vector<double> v{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(rb::evenly_spaced_subset(v, -1), v);
  EXPECT_EQ(rb::evenly_spaced_subset(v, 11), v);
  EXPECT_EQ(rb::evenly_spaced_subset(v, 20), v);
  EXPECT_EQ(rb::evenly_spaced_subset(v, 3), (std::vector<double>{0, 5, 10}));
  EXPECT_EQ(rb::evenly_spaced_subset(v, 2), (std::vector<double>{0, 10}));
  EXPECT_EQ(rb::evenly_spaced_subset(v, 1), (std::vector<double>{0}));
  EXPECT_TRUE(rb::evenly_spaced_subset(v, 0).empty());
  const std::vector<double> s = rb::evenly_spaced_subset(v, 4);  // 0, 3.33, 6.67, 10 rounded
  EXPECT_EQ(s, (std::vector<double>{0, 3, 7, 10}));
}

TEST(Study, SizeReachingAndPodSize) {
  const std::vector<double> h{3.4, 0.75, 0.4, 0.09, 0.1, 0.004};
  EXPECT_EQ(rb::size_reaching(h, 1e-1), 3);  // the first R at or below eps, not the last
  EXPECT_EQ(rb::size_reaching(h, 0.4), 2);
  EXPECT_EQ(rb::size_reaching(h, 5e-3), 5);
  EXPECT_EQ(rb::size_reaching(h, 1e-3), -1);
  EXPECT_EQ(rb::size_reaching({}, 1.0), -1);
  Eigen::VectorXd sigma(5);
  sigma << 35.3, 0.107, 0.0187, 0.00208, 0.0;
  EXPECT_EQ(rb::pod_size(sigma, 1e-2), 3);
  EXPECT_EQ(rb::pod_size(sigma, 1e-3), 4);
  EXPECT_EQ(rb::pod_size(sigma, 0.0), 4);  // a zero singular value is never a mode
  EXPECT_EQ(rb::pod_size(sigma, 100.0), 0);
}

TEST(Study, DefaultTolerancesFollowThePaper) {
  const rb::StudyTolerances b = rb::default_study_tolerances("hertz-b");  // Fig. 13
  EXPECT_DOUBLE_EQ(b.eps_pod, 1e-5);
  EXPECT_DOUBLE_EQ(b.eps_du, 1e-4);
  // Tighter than the paper's 1e-2 / 1e-3, which keep M^g = 1 (docs/user-guide.md, "report").
  EXPECT_DOUBLE_EQ(b.eps_eim_k, 1e-4);
  EXPECT_DOUBLE_EQ(b.eps_eim_g, 1e-5);
  EXPECT_EQ(b.table_eps_pod, (std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 4e-6}));  // Table 4
  const rb::StudyTolerances a = rb::default_study_tolerances("hertz-a");  // Section 6.2.3
  EXPECT_DOUBLE_EQ(a.eps_pod, 1e-2);
  EXPECT_DOUBLE_EQ(a.eps_du, 1e-1);
  EXPECT_EQ(a.table_eps_du, (std::vector<double>{1e-1, 1e-2, 5e-3}));  // Table 3
  const rb::StudyTolerances c = rb::default_study_tolerances("ring-block");
  EXPECT_DOUBLE_EQ(c.eps_eim_g, 1e-5);  // Fig. 21
  const rb::StudyTolerances other = rb::default_study_tolerances("my-case");
  EXPECT_DOUBLE_EQ(other.eps_du, rb::StudyTolerances{}.eps_du);
}

TEST(Study, SettingsAreChecked) {
  rb::StudySettings s;
  EXPECT_NO_THROW(rb::check_settings(s));
  s.max_training = 1;
  EXPECT_THROW(rb::check_settings(s), contactrb::Error);
  s = {};
  s.tolerances.eps_du = -1.0;
  EXPECT_THROW(rb::check_settings(s), contactrb::Error);
  s = {};
  s.jobs = 0;
  EXPECT_THROW(rb::check_settings(s), contactrb::Error);
  s = {};
  s.online_repeats = 0;
  EXPECT_THROW(rb::check_settings(s), contactrb::Error);
  s = {};
  s.training_values = std::vector<double>{0.2};
  EXPECT_THROW(rb::check_settings(s), contactrb::Error);
}

TEST(Study, MarkdownTablesFromAResult) {
  rb::StudyResult r;
  r.case_name = "hertz-b";
  r.parameter_name = "lower radius R2";
  r.constraint = "collocation";
  r.training_mus = {0.905, 1.115};
  r.verification_mus = {1.0};
  r.tolerances = rb::default_study_tolerances("hertz-b");
  r.singular_values = Eigen::VectorXd(3);
  r.singular_values << 35.3, 0.107, 5e-6;
  r.dual.R_max = 2;
  r.dual.cpg = {3.0, 0.18, 0.0};
  r.dual.angle_cone = {3.0, 0.18, 0.05};
  r.dual.nmf = {3.0, 0.11, 0.06};
  for (const char* key : {"cpg", "nmf"}) {
    rb::StudyModel m;
    m.key = key;
    m.label = key == std::string("cpg") ? "CPG" : "NMF";
    m.N = 2;
    m.R = 2;
    m.training.N = 2;
    m.training.R = 2;
    m.training.summary.max_e_displ = 1.5e-4;
    m.training.summary.median_speedup = 1234.0;
    m.verification = m.training;
    r.models.push_back(m);
  }
  const std::string md = rb::study_markdown(r, {"dual_cone_error.png"});
  for (const char* s : {"# contactrb report: hertz-b", "| CPG | 2 | 2 |", "0.00015", "1234",
                        "| eps_DU | 0.05 | 0.01 | 0.005 | 0.001 |", "| NMF R | > 2 | > 2 | > 2 | > 2 |",
                        "| CPG R | 2 | 2 | 2 | 2 |", "| N | 2 | 2 | 2 | 2 | 3 |",
                        "![dual_cone_error.png](dual_cone_error.png)", "verification set"}) {
    EXPECT_NE(md.find(s), std::string::npos) << "missing: " << s << "\n" << md;
  }
  EXPECT_THROW((void)r.model("angle"), contactrb::Error);
}
