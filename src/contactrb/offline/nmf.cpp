#include "contactrb/offline/nmf.hpp"

#include <Eigen/SVD>
#include <chrono>
#include <cmath>
#include <string>

#include "contactrb/common/enum_names.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/offline/cone_projection.hpp"
#include "contactrb/common/number_text.hpp"

namespace contactrb::offline {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// NNDSVDa initialization (see nmf.hpp).
void nndsvda(const Eigen::MatrixXd& T, int R, Eigen::MatrixXd& W, Eigen::MatrixXd& H) {
  const Eigen::Index m = T.rows(), P = T.cols();
  const double mean = T.size() ? T.mean() : 0.0;
  W = Eigen::MatrixXd::Constant(m, R, mean);
  H = Eigen::MatrixXd::Constant(R, P, mean);
  if (T.size() == 0 || T.cwiseAbs().maxCoeff() == 0.0) return;
  Eigen::BDCSVD<Eigen::MatrixXd> svd(T, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Index k = std::min<Eigen::Index>(R, svd.singularValues().size());
  for (Eigen::Index j = 0; j < k; ++j) {
    const double s = svd.singularValues()(j);
    const Eigen::VectorXd x = svd.matrixU().col(j);
    const Eigen::VectorXd y = svd.matrixV().col(j);
    Eigen::VectorXd u, v;
    double sigma = 0.0;
    if (j == 0) {
      u = x.cwiseAbs();
      v = y.cwiseAbs();
      sigma = 1.0;
    } else {
      const Eigen::VectorXd xp = x.cwiseMax(0.0), xn = (-x).cwiseMax(0.0);
      const Eigen::VectorXd yp = y.cwiseMax(0.0), yn = (-y).cwiseMax(0.0);
      const double mp = xp.norm() * yp.norm(), mn = xn.norm() * yn.norm();
      if (mp >= mn && mp > 0.0) {
        u = xp / xp.norm();
        v = yp / yp.norm();
        sigma = mp;
      } else if (mn > 0.0) {
        u = xn / xn.norm();
        v = yn / yn.norm();
        sigma = mn;
      } else {
        continue;  // keep the mean fill
      }
    }
    const double scale = std::sqrt(s * sigma);
    W.col(j) = scale * u;
    H.row(j) = scale * v.transpose();
  }
  // "a": zeros replaced by the mean of T.
  W = (W.array() == 0.0).select(mean, W);
  H = (H.array() == 0.0).select(mean, H);
}

}  // namespace

const char* to_string(NMFStatus status) {
  switch (status) {
    case NMFStatus::Converged: return "converged";
    case NMFStatus::MaxIterations: return "maximum iterations reached";
  }
  return "unknown";
}

NMFStatus nmf_status_from_string(const std::string& name) {
  return enum_from_string(name, "NMF status", std::array{NMFStatus::Converged, NMFStatus::MaxIterations});
}

void check_settings(const NMFSettings& s) {
  require(s.max_iterations >= 1, "nmf: max_iterations must be >= 1, got " + std::to_string(s.max_iterations));
  require(std::isfinite(s.tolerance) && s.tolerance >= 0.0,
          "nmf: tolerance must be finite and >= 0, got " + number_text(s.tolerance));
  require(std::isfinite(s.epsilon) && s.epsilon > 0.0,
          "nmf: epsilon must be finite and > 0, got " + number_text(s.epsilon));
}

NMFResult nmf(const Eigen::MatrixXd& T, int R, const NMFSettings& settings) {
  check_settings(settings);
  require(R >= 1, "nmf: the rank R must be >= 1, got " + std::to_string(R));
  require(T.allFinite() && (T.size() == 0 || T.minCoeff() >= 0.0),
          "nmf: T (" + std::to_string(T.rows()) + "x" + std::to_string(T.cols()) +
              ") must be finite with entries >= 0");
  const auto t0 = Clock::now();
  NMFResult out;
  nndsvda(T, R, out.W, out.H);
  Eigen::MatrixXd& W = out.W;
  Eigen::MatrixXd& H = out.H;
  const double eps = settings.epsilon;
  const double floor = std::pow(settings.tolerance * T.norm(), 2);
  double f = (T - W * H).squaredNorm();
  out.objective.push_back(f);
  out.status = NMFStatus::MaxIterations;
  if (f <= floor) out.status = NMFStatus::Converged;
  Eigen::MatrixXd num, den;
  for (int it = 0; it < settings.max_iterations && out.status != NMFStatus::Converged; ++it) {
    // (70), with eps in numerator and denominator (see NMFSettings::epsilon).
    num.noalias() = W.transpose() * T;
    den.noalias() = (W.transpose() * W) * H;
    H.array() *= (num.array() + eps) / (den.array() + eps);
    num.noalias() = T * H.transpose();
    den.noalias() = W * (H * H.transpose());
    W.array() *= (num.array() + eps) / (den.array() + eps);
    const double f_new = (T - W * H).squaredNorm();
    out.objective.push_back(f_new);
    out.iterations = it + 1;
    const bool small_decrease = f - f_new <= settings.tolerance * f;
    f = f_new;
    if (f <= floor || small_decrease) out.status = NMFStatus::Converged;
  }
  // Unit columns of W (the cone span+{W} is unchanged), H rescaled so that W H is unchanged.
  for (Eigen::Index j = 0; j < W.cols(); ++j) {
    const double n = W.col(j).norm();
    if (n > 0.0) {
      W.col(j) /= n;
      H.row(j) *= n;
    }
  }
  out.seconds = since(t0);
  return out;
}

DualConeResult build_nmf_cone(const Eigen::MatrixXd& snapshots, const DualConeSettings& settings,
                              const NMFSettings& nmf_settings) {
  check_settings(settings.greedy);
  check_settings(nmf_settings);
  check_dual_snapshots("build_nmf_cone", snapshots, settings.weights);
  DualConeResult out;
  out.method = DualConeMethod::NMF;
  const Eigen::Index P = snapshots.cols();
  Eigen::VectorXd norms(P);
  for (Eigen::Index p = 0; p < P; ++p) norms(p) = weighted_norm(snapshots.col(p), settings.weights);
  const int limit = settings.greedy.max_size >= 0
                        ? settings.greedy.max_size
                        : static_cast<int>(std::min(snapshots.rows(), snapshots.cols()));
  auto record = [&](const Eigen::VectorXd& e) {
    double rel = 0.0;
    for (Eigen::Index p = 0; p < P; ++p)
      if (norms(p) > 0.0) rel = std::max(rel, e(p) / norms(p));
    out.errors.push_back(P ? e.maxCoeff() : 0.0);
    out.relative_errors.push_back(rel);
    return settings.greedy.relative ? rel : out.errors.back();
  };
  out.generators = Eigen::MatrixXd(snapshots.rows(), 0);
  double criterion = record(norms);
  const double initial = out.errors.front();
  // The factorizations of different ranks are separate runs: a larger rank may fit worse (the
  // multiplicative updates stop at a local minimum). The best one seen is kept for Exhausted.
  Eigen::MatrixXd best = out.generators;
  double best_criterion = criterion;
  for (int R = 0;; ++R) {
    if (criterion <= settings.greedy.tolerance) {
      out.status = GreedyStatus::ToleranceReached;
      break;
    }
    if (settings.greedy.max_size >= 0 && R >= settings.greedy.max_size) {
      out.status = GreedyStatus::MaxSize;  // the requested rank, even if a smaller one fit better
      break;
    }
    if (R >= limit || out.errors.back() <= settings.greedy.exhaustion_tolerance * initial) {
      out.status = GreedyStatus::Exhausted;
      out.generators = std::move(best);
      break;
    }
    auto t0 = Clock::now();
    NMFResult f = nmf(snapshots, R + 1, nmf_settings);
    out.seconds += since(t0);
    t0 = Clock::now();
    int failures = 0;
    criterion = record(cone_projection_errors(snapshots, f.W, settings.weights, settings.qp, &failures));
    out.history_seconds += since(t0);
    out.qp_failures += failures;
    out.generators = std::move(f.W);
    if (criterion < best_criterion) {
      best_criterion = criterion;
      best = out.generators;
    }
  }
  return out;
}

}  // namespace contactrb::offline
