// Reduced model files: round trip (every array bit for bit, same online answer); a missing
// file, a non-HDF5 file, a truncated file, a wrong version and a checksum mismatch each give a
// clear error naming the file.
#include <gtest/gtest.h>
#include <hdf5.h>

#include "support/temp_dir.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "contactrb/cases/case_spec.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/file_seal.hpp"
#include "contactrb/io/reduced_model_file.hpp"
#include "contactrb/offline/offline_builder.hpp"
#include "contactrb/online/online_solver.hpp"
#include "contactrb/online/model_check.hpp"
#include "contactrb/online/reconstruction.hpp"
#include "contactrb/offline/snapshot_generation.hpp"

namespace {

using contactrb::model::ReducedModel;

const contactrb::offline::OfflineResult& built() {
  static std::unique_ptr<contactrb::offline::OfflineResult> result;
  if (!result) {
    const auto spec = contactrb::cases::builtin_case_spec("hertz-b");
    const auto request = contactrb::offline::make_snapshot_request(spec, "training", 0, std::nullopt,
                                                                   contactrb::cases::points_1d({0.905, 1.005, 1.105}));
    const auto set = contactrb::offline::generate_snapshots(request);
    contactrb::offline::OfflineSettings s;
    s.eps_pod = 0.0;
    s.eps_du = 0.0;
    s.eps_eim_k = 0.0;
    s.eps_eim_g = 0.0;
    result = std::make_unique<contactrb::offline::OfflineResult>(contactrb::offline::build_reduced_model(set, spec, s));
  }
  return *result;
}

std::vector<char> bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void put(const std::string& path, const std::vector<char>& data) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

// The error message of read_reduced_model_file(path), or "" if it did not throw.
std::string read_error(const std::string& path) {
  try {
    (void)contactrb::io::read_reduced_model_file(path);
  } catch (const contactrb::Error& e) {
    return e.what();
  }
  return "";
}

bool same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

TEST(ReducedModelFile, RoundTripKeepsEveryArrayAndTheOnlineAnswer) {
  contactrb::test::TempDir dir("reduced_model_round_trip");
  const ReducedModel& m = built().model;
  const std::string path = dir.file("model.h5");
  contactrb::io::write_reduced_model_file(m, path);
  const ReducedModel r = contactrb::io::read_reduced_model_file(path);
  EXPECT_NO_THROW(contactrb::online::check_model(r));
  EXPECT_EQ(r.eps_du, m.eps_du);
  EXPECT_EQ(r.eps_du_relative, m.eps_du_relative);
  EXPECT_TRUE(m.eps_pod_relative && m.eps_du_relative && m.eps_eim_k_relative && m.eps_eim_g_relative);  // defaults
  EXPECT_EQ(r.eps_pod_relative, m.eps_pod_relative);
  EXPECT_EQ(r.eps_eim_k_relative, m.eps_eim_k_relative);
  EXPECT_EQ(r.eps_eim_g_relative, m.eps_eim_g_relative);
  // Each mode flag survives the file in both states, independently of the others.
  for (int flipped = 0; flipped < 4; ++flipped) {
    ReducedModel other = m;
    bool* flags[] = {&other.eps_pod_relative, &other.eps_du_relative, &other.eps_eim_k_relative,
                     &other.eps_eim_g_relative};
    *flags[flipped] = !*flags[flipped];
    contactrb::io::write_reduced_model_file(other, dir.file("modes.h5"));
    const ReducedModel back = contactrb::io::read_reduced_model_file(dir.file("modes.h5"));
    EXPECT_EQ(back.eps_pod_relative, other.eps_pod_relative) << flipped;
    EXPECT_EQ(back.eps_du_relative, other.eps_du_relative) << flipped;
    EXPECT_EQ(back.eps_eim_k_relative, other.eps_eim_k_relative) << flipped;
    EXPECT_EQ(back.eps_eim_g_relative, other.eps_eim_g_relative) << flipped;
  }
  EXPECT_EQ(r.case_name, m.case_name);
  EXPECT_EQ(r.case_spec, m.case_spec);
  ASSERT_EQ(r.parameters.size(), m.parameters.size());
  ASSERT_EQ(m.parameters.size(), 1u);
  for (std::size_t k = 0; k < m.parameters.size(); ++k) {
    EXPECT_EQ(r.parameters[k].name, m.parameters[k].name);
    EXPECT_EQ(r.parameters[k].units, m.parameters[k].units);
    EXPECT_EQ(r.parameters[k].kind, m.parameters[k].kind);
    EXPECT_EQ(r.parameters[k].min, m.parameters[k].min);
    EXPECT_EQ(r.parameters[k].max, m.parameters[k].max);
    EXPECT_EQ(r.parameters[k].reference, m.parameters[k].reference);
    EXPECT_EQ(r.parameters[k].body, m.parameters[k].body);
    EXPECT_EQ(r.parameters[k].center, m.parameters[k].center);
  }
  EXPECT_TRUE(same(r.training_mu, m.training_mu));
  ASSERT_EQ(m.training_jacobian.rows(), m.N_max);  // the row cone at N_max <= kMaxJacobianN
  EXPECT_TRUE(same(r.training_jacobian, m.training_jacobian));
  // One parameter: no sensitivities (the start interpolates two training values); a model that
  // holds them keeps them bit for bit.
  EXPECT_EQ(m.training_u_sensitivity.size(), 0);
  ReducedModel with_sensitivity = m;
  with_sensitivity.training_u_sensitivity = Eigen::MatrixXd::Random(m.N_max, m.training_mu.cols());
  contactrb::io::write_reduced_model_file(with_sensitivity, dir.file("sensitivity.h5"));
  EXPECT_TRUE(same(contactrb::io::read_reduced_model_file(dir.file("sensitivity.h5")).training_u_sensitivity,
                   with_sensitivity.training_u_sensitivity));
  EXPECT_EQ(r.thetas.f.size(), m.thetas.f.size());
  // Format 4: each theta monomial with its factors.
  const auto expect_same_thetas = [](const std::vector<contactrb::cases::ThetaMonomial>& x,
                                     const std::vector<contactrb::cases::ThetaMonomial>& y) {
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t j = 0; j < y.size(); ++j) {
      EXPECT_EQ(x[j].coefficient, y[j].coefficient);
      ASSERT_EQ(x[j].factors.size(), y[j].factors.size());
      for (std::size_t i = 0; i < y[j].factors.size(); ++i) {
        EXPECT_EQ(x[j].factors[i].parameter, y[j].factors[i].parameter);
        EXPECT_EQ(x[j].factors[i].scale, y[j].factors[i].scale);
        EXPECT_EQ(x[j].factors[i].power, y[j].factors[i].power);
      }
    }
  };
  expect_same_thetas(r.thetas.a, m.thetas.a);
  expect_same_thetas(r.thetas.f, m.thetas.f);
  expect_same_thetas(r.thetas.lift, m.thetas.lift);
  EXPECT_EQ(r.N_max, m.N_max);
  EXPECT_EQ(r.R_max, m.R_max);
  EXPECT_EQ(r.Mk_max, m.Mk_max);
  EXPECT_EQ(r.Mg_max, m.Mg_max);
  EXPECT_EQ(r.kept_rows, m.kept_rows);
  EXPECT_EQ(r.kappa_row, m.kappa_row);
  EXPECT_EQ(r.kappa_dof, m.kappa_dof);
  EXPECT_EQ(r.gamma_row, m.gamma_row);
  EXPECT_EQ(r.surface.slave, m.surface.slave);
  EXPECT_EQ(r.surface.master, m.surface.master);
  EXPECT_EQ(r.surface.discretization, m.surface.discretization);
  EXPECT_EQ(r.lift_AA, m.lift_AA);
  ASSERT_EQ(r.C_kappa.size(), m.C_kappa.size());
  for (std::size_t j = 0; j < m.C_kappa.size(); ++j) EXPECT_TRUE(same(r.C_kappa[j], m.C_kappa[j]));
  EXPECT_TRUE(same(r.Xi, m.Xi));
  EXPECT_TRUE(same(r.XiQ_gamma, m.XiQ_gamma));
  EXPECT_TRUE(same(r.Theta_c, m.Theta_c));
  EXPECT_TRUE(same(r.A_hat[0], m.A_hat[0]));
  // Format 3: the error estimate's arrays.
  ASSERT_GT(m.estimate.residual_T.size(), 0);
  EXPECT_TRUE(same(r.estimate.residual_T, m.estimate.residual_T));
  EXPECT_TRUE(same(r.estimate.theta_a_reference, m.estimate.theta_a_reference));
  EXPECT_TRUE(same(r.estimate.Q_gamma, m.estimate.Q_gamma));
  ASSERT_EQ(r.estimate.QTheta_kappa.size(), m.estimate.QTheta_kappa.size());
  for (std::size_t j = 0; j < m.estimate.QTheta_kappa.size(); ++j) {
    EXPECT_TRUE(same(r.estimate.QTheta_kappa[j], m.estimate.QTheta_kappa[j]));
  }
  contactrb::online::OnlineSolver a(m), b(r);
  const auto sa = a.solve(1.0), sb = b.solve(1.0);
  ASSERT_TRUE(sa.converged());
  EXPECT_TRUE(same(sa.u_hat, sb.u_hat));
  EXPECT_TRUE(same(sa.lambda_hat, sb.lambda_hat));
  ASSERT_TRUE(sa.estimate.available);
  EXPECT_EQ(sa.estimate.energy, sb.estimate.energy);
}

TEST(ReducedModelFile, DamagedOrForeignFilesGiveClearErrors) {
  contactrb::test::TempDir dir("reduced_model_damaged");
  const ReducedModel& m = built().model;
  const std::string good = dir.file("model.h5");
  contactrb::io::write_reduced_model_file(m, good);
  const std::vector<char> data = bytes(good);

  const std::string missing = dir.file("missing.h5");
  EXPECT_NE(read_error(missing).find("no such file"), std::string::npos) << read_error(missing);

  const std::string text = dir.file("text.h5");
  put(text, std::vector<char>{'h', 'e', 'l', 'l', 'o'});
  EXPECT_NE(read_error(text).find("not an HDF5 file"), std::string::npos) << read_error(text);

  const std::string truncated = dir.file("truncated.h5");
  put(truncated, std::vector<char>(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(data.size() / 2)));
  const std::string t = read_error(truncated);
  EXPECT_FALSE(t.empty());
  EXPECT_NE(t.find(truncated), std::string::npos) << t;

  ReducedModel future = m;
  future.format_version = contactrb::model::kReducedModelFormatVersion + 1;
  const std::string newer = dir.file("newer.h5");
  contactrb::io::write_reduced_model_file(future, newer);
  EXPECT_NE(read_error(newer).find("model format " + std::to_string(future.format_version) +
                                   " is newer than this build reads"),
            std::string::npos)
      << read_error(newer);

  // Change one stored double (the first entry of Theta_c that is not 0) in the file's bytes.
  double target = 0.0;
  for (Eigen::Index i = 0; i < m.Theta_c.size() && target == 0.0; ++i) target = m.Theta_c.data()[i];
  ASSERT_NE(target, 0.0);
  std::vector<char> damaged = data;
  char pattern[sizeof(double)];
  std::memcpy(pattern, &target, sizeof target);
  auto it = std::search(damaged.begin(), damaged.end(), pattern, pattern + sizeof pattern);
  ASSERT_NE(it, damaged.end());
  const double changed = target * (1.0 + 1e-12);
  std::memcpy(&*it, &changed, sizeof changed);
  const std::string flipped = dir.file("flipped.h5");
  put(flipped, damaged);
  EXPECT_NE(read_error(flipped).find("checksum mismatch"), std::string::npos) << read_error(flipped);
  for (const std::string& f : {missing, text, truncated, newer, flipped}) std::printf("  %s\n", read_error(f).c_str());
}

}  // namespace

namespace {

// Sets the `complete` mark (an attribute of `object`: "/" or "reconstruction") to `value` through
// the HDF5 C API.
void set_complete(const std::string& path, const std::string& object, int value) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t obj = H5Oopen(file, object.c_str(), H5P_DEFAULT);
  const hid_t attr = obj >= 0 ? H5Aopen(obj, "complete", H5P_DEFAULT) : -1;
  const herr_t written = attr >= 0 ? H5Awrite(attr, H5T_NATIVE_INT, &value) : -1;
  if (attr >= 0) H5Aclose(attr);
  if (obj >= 0) H5Oclose(obj);
  H5Fclose(file);
  ASSERT_GE(written, 0);
  contactrb::seal_file(path);  // a crafted file: the reader's checks behind the seal
}

// `complete = 0` is refused, not only a missing `complete`.
TEST(ReducedModelFile, CompleteOtherThanOneIsRefused) {
  contactrb::test::TempDir dir("reduced_model_complete");
  const std::string path = dir.file("model.h5");
  contactrb::io::write_reduced_model_file(built().model, built().reconstruction, path);
  ASSERT_EQ(read_error(path), "");
  ASSERT_NO_THROW((void)contactrb::io::read_reconstruction(path));
  set_complete(path, "/", 0);
  EXPECT_NE(read_error(path).find("incomplete file"), std::string::npos) << read_error(path);
  set_complete(path, "/", 1);
  EXPECT_EQ(read_error(path), "");
  set_complete(path, "reconstruction", 0);
  try {
    (void)contactrb::io::read_reconstruction(path);
    ADD_FAILURE() << "an incomplete reconstruction was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("incomplete reconstruction"), std::string::npos) << e.what();
  }
}

// A snapshot file given as a model is named as such (not "missing dataset 'format'").
TEST(ReducedModelFile, ASnapshotFileIsNamedAsSuch) {
  contactrb::test::TempDir dir("reduced_model_snapshots");
  const std::string path = dir.file("snapshots.h5");
  const auto request = contactrb::offline::make_snapshot_request(
      contactrb::cases::builtin_case_spec("hertz-a"), "training", 0, std::nullopt, contactrb::cases::points_1d({0.3}));
  contactrb::io::write_snapshot_file(contactrb::offline::generate_snapshots(request), path);
  const std::string e = read_error(path);
  EXPECT_NE(e.find("'" + path + "': a contactrb snapshot file, not a reduced model"), std::string::npos) << e;
}

}  // namespace

namespace {

// A file of the flat layout of model formats <= 4 (every field a root dataset, the format name
// as bytes, the version a one-element int dataset) gets the rebuild message, not "no format".
TEST(ReducedModelFile, TheFlatLayoutOfVersionFourAsksForARebuild) {
  contactrb::test::TempDir dir("reduced_model_flat");
  const std::string path = dir.file("old.h5");
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const std::string format = contactrb::io::kReducedModelFormatName;
  const hsize_t n[1] = {format.size()}, one[1] = {1};
  const int version = 4;
  const hid_t s1 = H5Screate_simple(1, n, nullptr), s2 = H5Screate_simple(1, one, nullptr);
  const hid_t d1 = H5Dcreate2(file, "format", H5T_STD_U8LE, s1, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t d2 = H5Dcreate2(file, "format_version", H5T_STD_I32LE, s2, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(H5Dwrite(d1, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, format.data()), 0);
  EXPECT_GE(H5Dwrite(d2, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, &version), 0);
  H5Dclose(d1);
  H5Dclose(d2);
  H5Sclose(s1);
  H5Sclose(s2);
  H5Fclose(file);
  const std::string e = read_error(path);
  EXPECT_NE(e.find("model format 4 is no longer read (this build reads format " +
                   std::to_string(contactrb::model::kReducedModelFormatVersion) +
                   "): rebuild it with `contactrb offline`"),
            std::string::npos)
      << e;
  std::string r;
  try {
    (void)contactrb::io::read_reconstruction(path);
  } catch (const contactrb::Error& x) {
    r = x.what();
  }
  EXPECT_NE(r.find("rebuild it with `contactrb offline`"), std::string::npos) << r;
}

}  // namespace

// A negated pressure basis (a crafted file with a valid seal) is not a model of this method: the
// dual cone's generators are pressures.
TEST(ReducedModelFile, ANegativePressureBasisIsRefused) {
  ReducedModel m = built().model;
  ASSERT_NO_THROW(contactrb::online::check_model(m));
  m.Xi = -m.Xi;
  try {
    contactrb::online::check_model(m);
    ADD_FAILURE() << "a negated Xi was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("the pressure basis Xi has a negative entry"), std::string::npos) << e.what();
  }
}

// A stored mesh scaled by 2 (a crafted file with a valid seal) would give fields on the doubled
// mesh: the model's contact nodes are nodes of the mesh it was built on, bit for bit.
TEST(ReducedModelFile, AStoredMeshOtherThanTheModelsIsRefused) {
  contactrb::model::ReducedReconstruction rec = built().reconstruction;
  ASSERT_FALSE(rec.mesh.nodes.empty());
  ASSERT_NO_THROW(contactrb::online::check_reconstruction(built().model, rec));
  for (Eigen::Vector2d& x : rec.mesh.nodes) x *= 2.0;
  try {
    contactrb::online::check_reconstruction(built().model, rec);
    ADD_FAILURE() << "a scaled mesh was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a node of the stored mesh"), std::string::npos) << e.what();
  }
  rec = built().reconstruction;
  rec.mesh.nodes.pop_back();
  EXPECT_THROW(contactrb::online::check_reconstruction(built().model, rec), contactrb::Error);
}

// A level above the finest built-in one (a crafted file: level 40 over a level-0 mesh) is refused.
TEST(ReducedModelFile, ALevelAboveTheFinestIsRefused) {
  ReducedModel m = built().model;
  m.level = 40;
  try {
    contactrb::online::check_model(m);
    ADD_FAILURE() << "level 40 was accepted";
  } catch (const contactrb::Error& e) {
    EXPECT_NE(std::string(e.what()).find("reduced model: level 40 (expected 0 to 16"), std::string::npos) << e.what();
  }
}
