// study/study.hpp: the helpers of the report study (subsets of a parameter set, the Table 3-5
// size rows), its settings checks, the per-case tolerances, and the report.md tables built
// from a hand-made result.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/study/study.hpp"

namespace study = contactrb::study;

TEST(Study, EvenlySpacedSubsetKeepsBothEnds) {
  const std::vector<double> v{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(study::evenly_spaced_subset(v, -1), v);
  EXPECT_EQ(study::evenly_spaced_subset(v, 11), v);
  EXPECT_EQ(study::evenly_spaced_subset(v, 20), v);
  EXPECT_EQ(study::evenly_spaced_subset(v, 3), (std::vector<double>{0, 5, 10}));
  EXPECT_EQ(study::evenly_spaced_subset(v, 2), (std::vector<double>{0, 10}));
  EXPECT_EQ(study::evenly_spaced_subset(v, 1), (std::vector<double>{0}));
  EXPECT_TRUE(study::evenly_spaced_subset(v, 0).empty());
  const std::vector<double> s = study::evenly_spaced_subset(v, 4);  // 0, 3.33, 6.67, 10 rounded
  EXPECT_EQ(s, (std::vector<double>{0, 3, 7, 10}));
}

TEST(Study, SizeReachingAndPodSize) {
  const std::vector<double> h{3.4, 0.75, 0.4, 0.09, 0.1, 0.004};
  EXPECT_EQ(study::size_reaching(h, 1e-1), 3);  // the first R at or below eps, not the last
  EXPECT_EQ(study::size_reaching(h, 0.4), 2);
  EXPECT_EQ(study::size_reaching(h, 5e-3), 5);
  EXPECT_EQ(study::size_reaching(h, 1e-3), -1);
  EXPECT_EQ(study::size_reaching({}, 1.0), -1);
  Eigen::VectorXd sigma(5);
  sigma << 35.3, 0.107, 0.0187, 0.00208, 0.0;
  EXPECT_EQ(study::pod_size(sigma, 1e-2), 3);
  EXPECT_EQ(study::pod_size(sigma, 1e-3), 4);
  EXPECT_EQ(study::pod_size(sigma, 0.0), 4);  // a zero singular value is never a mode
  EXPECT_EQ(study::pod_size(sigma, 100.0), 0);
}

TEST(Study, DefaultTolerancesFollowThePaper) {
  const study::StudyTolerances b = study::default_study_tolerances("hertz-b");  // Fig. 13
  EXPECT_DOUBLE_EQ(b.eps_pod, 1e-5);
  EXPECT_DOUBLE_EQ(b.eps_du, 1e-4);
  // Tighter than the paper's 1e-2 / 1e-3, which keep M^g = 1 (docs/cli.md, "`contactrb report`").
  EXPECT_DOUBLE_EQ(b.eps_eim_k, 1e-4);
  EXPECT_DOUBLE_EQ(b.eps_eim_g, 1e-5);
  EXPECT_EQ(b.table_eps_pod, (std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 4e-6}));  // Table 4
  const study::StudyTolerances a = study::default_study_tolerances("hertz-a");  // Section 6.2.3
  EXPECT_DOUBLE_EQ(a.eps_pod, 1e-2);
  EXPECT_DOUBLE_EQ(a.eps_du, 1e-1);
  EXPECT_EQ(a.table_eps_du, (std::vector<double>{1e-1, 1e-2, 5e-3}));  // Table 3
  const study::StudyTolerances c = study::default_study_tolerances("ring-block");
  EXPECT_DOUBLE_EQ(c.eps_eim_g, 1e-5);  // Fig. 21
  const study::StudyTolerances other = study::default_study_tolerances("my-case");
  EXPECT_DOUBLE_EQ(other.eps_du, study::StudyTolerances{}.eps_du);
}

// A user case gets `contactrb offline`'s defaults, not the paper's eps_EIM^k = 1e-2,
// eps_EIM^g = 1e-3 (M^g = 0, e_displ 31-121%).
TEST(Study, UserCasesGetTheOfflineDefaults) {
  const study::StudyTolerances t = study::default_study_tolerances("my-case");
  const contactrb::offline::OfflineSettings offline;
  EXPECT_DOUBLE_EQ(t.eps_pod, offline.eps_pod);
  EXPECT_DOUBLE_EQ(t.eps_du, offline.eps_du);
  EXPECT_DOUBLE_EQ(t.eps_eim_k, offline.eps_eim_k);
  EXPECT_DOUBLE_EQ(t.eps_eim_g, offline.eps_eim_g);
  EXPECT_DOUBLE_EQ(t.eps_eim_k, 1e-5);  // the documented `offline` default (docs/cli.md, "`contactrb offline`")
  EXPECT_DOUBLE_EQ(t.eps_eim_g, 1e-5);
  EXPECT_TRUE(t.relative);  // as `offline`'s defaults
  EXPECT_FALSE(study::default_study_tolerances("hertz-b").relative);  // the paper's, absolute
}

TEST(Study, LargeVerificationErrorsAreWarnedInTheReport) {
  study::StudyResult r;
  r.case_name = "my-case";
  r.parameter_name = "p";
  r.constraint = "collocation";
  r.training_mus = {0.1, 0.2};
  r.verification_mus = {0.15};
  r.dual.R_max = 1;
  const auto model = [](const char* key, const char* label, double train, std::optional<double> verif) {
    study::StudyModel m;
    m.key = key;
    m.label = label;
    m.N = m.R = m.Mk = 1;
    m.training.summary.max_e_displ = train;
    if (verif) {
      m.verification = m.training;
      m.verification->summary.max_e_displ = *verif;
    }
    return m;
  };
  r.models.push_back(model("cpg", "CPG", 1e-4, 2e-3));    // fine
  r.models.push_back(model("angle", "angle-greedy", 1e-4, 0.31));  // bad on the verification set only
  r.models.push_back(model("nmf", "NMF", 1e-4, std::nan("")));  // no converged pair: not fine either
  const std::vector<std::string> w = study::study_warnings(r);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("angle-greedy"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("verification set is 0.31"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("NMF"), std::string::npos) << w[1];
  EXPECT_NE(w[1].find("nan"), std::string::npos) << w[1];
  const std::string md = study::study_markdown(r, {});
  EXPECT_NE(md.find("## Warnings"), std::string::npos) << md;
  EXPECT_NE(md.find("- **Warning**: model angle-greedy"), std::string::npos) << md;
  EXPECT_EQ(md.find("model CPG"), std::string::npos) << md;
  r.models.resize(1);
  EXPECT_TRUE(study::study_warnings(r).empty());
  // Without a verification set the training errors are read.
  r.verification_mus.clear();
  r.models[0].verification.reset();
  r.models[0].training.summary.max_e_displ = 0.05;
  ASSERT_EQ(study::study_warnings(r).size(), 1u);
  EXPECT_NE(study::study_warnings(r)[0].find("training set is 0.05"), std::string::npos);
  r.models[0].training.summary.max_e_displ = 1e-4;
  EXPECT_EQ(study::study_markdown(r, {}).find("Warning"), std::string::npos);
}

TEST(Study, SettingsAreChecked) {
  study::StudySettings s;
  EXPECT_NO_THROW(study::check_settings(s));
  s.max_training = 1;
  EXPECT_THROW(study::check_settings(s), contactrb::Error);
  s = {};
  s.tolerances.eps_du = -1.0;
  EXPECT_THROW(study::check_settings(s), contactrb::Error);
  s = {};
  s.jobs = 0;
  EXPECT_THROW(study::check_settings(s), contactrb::Error);
  s = {};
  s.online_repeats = 0;
  EXPECT_THROW(study::check_settings(s), contactrb::Error);
  s = {};
  s.training_values = std::vector<double>{0.2};
  EXPECT_THROW(study::check_settings(s), contactrb::Error);
}

TEST(Study, MarkdownTablesFromAResult) {
  study::StudyResult r;
  r.case_name = "hertz-b";
  r.parameter_name = "lower radius R2";
  r.constraint = "collocation";
  r.training_mus = {0.905, 1.115};
  r.verification_mus = {1.0};
  r.tolerances = study::default_study_tolerances("hertz-b");
  r.singular_values = Eigen::VectorXd(3);
  r.singular_values << 35.3, 0.107, 5e-6;
  r.dual.R_max = 2;
  r.dual.cpg = {3.0, 0.18, 0.0};
  r.dual.angle_cone = {3.0, 0.18, 0.05};
  r.dual.nmf = {3.0, 0.11, 0.06};
  for (const char* key : {"cpg", "nmf"}) {
    study::StudyModel m;
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
  const std::string md = study::study_markdown(r, {"dual_cone_error.png"});
  for (const char* s : {"# contactrb report: hertz-b", "| CPG | 2 | 2 |", "0.00015", "1234",
                        "| eps_DU | 0.05 | 0.01 | 0.005 | 0.001 |", "| NMF R | > 2 | > 2 | > 2 | > 2 |",
                        "| CPG R | 2 | 2 | 2 | 2 |", "| N | 2 | 2 | 2 | 2 | 3 |",
                        "![dual_cone_error.png](dual_cone_error.png)", "verification set"}) {
    EXPECT_NE(md.find(s), std::string::npos) << "missing: " << s << "\n" << md;
  }
  EXPECT_THROW((void)r.model("angle"), contactrb::Error);
}
