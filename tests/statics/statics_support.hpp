#pragma once
// Shared helpers of the statics tests (tests/statics): the Table 2.1 rod and its test problems,
// a solve wrapper, tip-error measures, structure checks, a least-squares order fit, and an
// independent matrix exponential for closed-form references.
//
// The section constants (A, I, J) are computed here from Table 2.1 directly, not read back from
// RodModel, so the closed-form references do not depend on the code under test; the first test
// of test_constant_strain.cpp checks that the model's K agrees with them.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"
#include "rodlab/loads/gravity.hpp"
#include "rodlab/loads/point_wrench.hpp"
#include "rodlab/result/static_result.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

#include "reference/reference_rods.hpp"
#include "schemes_under_test.hpp"

namespace rodlab::testing::statics {

using lie::Matrix3;
using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;
using result::StaticResult;
using solvers::statics::StaticProblem;

// ------------------------------------------------------------------------------------------
// Table 2.1 (thesis section 2.7), defined once for validation, tests and benchmarks
// (validation/reference/reference_rods.hpp).
using validation::reference::Table21;
using validation::reference::table21_model;

inline const char* kind_name(rod::ModelKind kind) {
  return kind == rod::ModelKind::kirchhoff ? "kirchhoff" : "cosserat";
}

inline StaticProblem table21_problem(rod::ModelKind kind = rod::ModelKind::cosserat) {
  StaticProblem p(table21_model(kind), SE3::identity());
  p.set_name(std::string("table2.1-") + kind_name(kind));  // shows in describe(result)
  return p;
}

/// Free tip with a point wrench [moment; force].
inline StaticProblem tip_wrench_problem(rod::ModelKind kind, const Vector6& wrench,
                                        loads::WrenchFrame frame) {
  StaticProblem p = table21_problem(kind);
  p.set_tip_wrench(loads::PointWrench{wrench, frame});
  return p;
}

/// Thesis 2.7.1: cantilever along +z, gravity along x (default [-9.81, 0, 0]).
inline StaticProblem gravity_cantilever(rod::ModelKind kind,
                                        const Vector3& g = Vector3(-9.81, 0.0, 0.0)) {
  StaticProblem p = table21_problem(kind);
  p.set_gravity(loads::Gravity(p.model(), g));
  return p;
}

/// Thesis 2.7.2 (2.113)-(2.115): no loads, tip clamped at identity rotation and position
/// [dx, 0, L] (the thesis: dx = 0.1 L).
inline StaticProblem fixed_ends(rod::ModelKind kind, double dx = 0.1 * Table21::L) {
  StaticProblem p = table21_problem(kind);
  p.set_tip_clamped(SE3::translation(Vector3(dx, 0.0, Table21::L)));
  return p;
}

/// Wrench helpers.
/// Closed form of pure bending about x with curvature kappa (constant xi = [kappa 0 0 0 0 1]):
/// R(s) = rotation about x by kappa s, p(s) = (0, (cos(kappa s) - 1)/kappa, sin(kappa s)/kappa).
inline SE3 bent_arc_pose(double kappa, double s) {
  Eigen::Matrix4d g = Eigen::Matrix4d::Identity();
  const double a = kappa * s;
  g.block<3, 3>(0, 0) << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  g.block<3, 1>(0, 3) << 0.0, (std::cos(a) - 1.0) / kappa, std::sin(a) / kappa;
  return SE3::from_matrix(g);
}

inline Vector6 wrench(const Vector3& moment, const Vector3& force) {
  return lie::se3::join(moment, force);
}

// ------------------------------------------------------------------------------------------
// Solving.
inline constexpr double kTol = 1e-12;  // Newton tolerance on the scaled tip residual

inline StaticResult solve(const StaticProblem& problem, const std::string& scheme, int nodes,
                          double tol = kTol, int max_iterations = 50) {
  solvers::statics::StaticSolveOptions o;
  o.scheme = scheme;
  o.nodes = nodes;
  o.tol = tol;
  o.max_iterations = max_iterations;
  return solvers::statics::solve_static(problem, o);
}

inline std::string describe(const StaticResult& r) {
  std::ostringstream os;
  if (!r.scene.empty()) os << "[" << r.scene << "] ";
  os << r.scheme << " N=" << r.nodes << (r.converged ? " converged" : " NOT converged")
     << " it=" << r.iterations << " res=" << r.residual_norm;
  if (!r.reason.empty()) os << " (" << r.reason << ")";
  return os.str();
}

// ------------------------------------------------------------------------------------------
// Structure (case 8): det R = 1 and R^T R = I at every node, to 1e-13, in every result.
inline constexpr double kStructureTol = 1e-13;

/// Largest det / orthogonality deviations seen by check_structure in this process (reported).
struct StructureRecord {
  double det = 0.0, orth = 0.0;
  int results = 0;
};
inline StructureRecord& structure_record() {
  static StructureRecord r;
  return r;
}

inline void check_structure(const StaticResult& r) {
  BOOST_TEST(r.max_det_deviation <= kStructureTol, describe(r) << ": max |det R - 1| = " << r.max_det_deviation);
  BOOST_TEST(r.max_orthogonality_error <= kStructureTol,
             describe(r) << ": max |R^T R - I| = " << r.max_orthogonality_error);
  // Recompute from the centreline, independently of the result builder.
  double det = 0.0, orth = 0.0;
  for (const auto& c : r.centerline) {
    const Matrix3 R = c.pose.rotation_matrix();
    det = std::max(det, std::abs(R.determinant() - 1.0));
    orth = std::max(orth, (R.transpose() * R - Matrix3::Identity()).norm());
  }
  BOOST_TEST(det <= kStructureTol);
  BOOST_TEST(orth <= kStructureTol);
  BOOST_TEST(std::abs(det - r.max_det_deviation) <= 1e-15,
             "reported det deviation " << r.max_det_deviation << ", recomputed " << det);
  auto& rec = structure_record();
  rec.det = std::max(rec.det, det);
  rec.orth = std::max(rec.orth, orth);
  ++rec.results;
}

/// Reports the worst structure deviations of the whole test module at its end (case 8).
struct StructureReport {
  void setup() {}
  void teardown() {
    const auto& rec = structure_record();
    BOOST_TEST_MESSAGE("structure over " << rec.results << " results: max |det R - 1| = " << rec.det
                                         << ", max |R^T R - I|_F = " << rec.orth);
  }
};
BOOST_TEST_GLOBAL_FIXTURE(StructureReport);

/// Converged, with the centreline of N nodes from s = 0 to s = L, and structure preserved.
/// Non-fatal (so that one failing (scheme, N) does not hide the others); returns whether the
/// result can be checked further.
[[nodiscard]] inline bool check_result(const StaticResult& r, int nodes, double L = Table21::L) {
  BOOST_TEST(r.converged, describe(r));
  const bool sized = static_cast<int>(r.centerline.size()) == nodes;
  BOOST_TEST(sized, describe(r) << ": " << r.centerline.size() << " centreline samples");
  if (!sized) return false;
  BOOST_TEST(r.centerline.front().s == 0.0);
  BOOST_TEST(std::abs(r.centerline.back().s - L) <= 1e-15 * L);
  check_structure(r);
  return r.converged;
}

// ------------------------------------------------------------------------------------------
// Errors.

/// Rotation distance ||Ra - Rb||_F / sqrt 2 (= 2 sin(angle/2) = angle to O(angle^3)); uses no
/// log of the code under test.
inline double rotation_distance(const Matrix3& Ra, const Matrix3& Rb) {
  return (Ra - Rb).norm() / std::sqrt(2.0);
}

struct PoseError {
  double position = 0.0;  ///< |pa - pb| / L
  double rotation = 0.0;  ///< rotation_distance
  double max() const { return std::max(position, rotation); }
};

inline PoseError pose_error(const SE3& a, const SE3& b, double L = Table21::L) {
  return {(a.translation() - b.translation()).norm() / L,
          rotation_distance(a.rotation_matrix(), b.rotation_matrix())};
}

/// Tip error of a result against a reference result (or pose): max(|dp|/L, rotation distance).
inline double tip_error(const StaticResult& r, const SE3& reference, double L = Table21::L) {
  return pose_error(r.centerline.back().pose, reference, L).max();
}
inline double tip_error(const StaticResult& r, const StaticResult& reference, double L = Table21::L) {
  return tip_error(r, reference.centerline.back().pose, L);
}

// ------------------------------------------------------------------------------------------
// Least-squares slope of log(err) against log(h): the observed order.
inline double fitted_order(const std::vector<double>& h, const std::vector<double>& err) {
  const std::size_t n = h.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// The a-priori error bound the tests hold a scheme to at N nodes: max(floor, C (h/L)^p) with
/// h/L = 1/(N-1) and p the design order (the lower bound for ">= p"); spectral schemes:
/// max(floor, C 2^-N), i.e. geometric convergence at a rate of at least 2 per node (measured
/// for chebyshev on the fixed ends: ~5 per node). `floor` covers the reference's own error and
/// the Newton tolerance.
inline double error_bound(const SchemeUnderTest& s, int N, double C, double floor) {
  if (s.spectral) return std::max(floor, C * std::pow(2.0, -N));
  return std::max(floor, C * std::pow(1.0 / (N - 1), s.design_order));
}

/// The observed-order assertion shared by the convergence tests. err[i] is the error at step
/// h[i]; errors at or below `floor` (the reference's own error or rounding) are left out of the
/// fit. Design order p: |fit - p| <= tol. Order ">= p": fit >= p - tol (or every error at the
/// floor). Spectral: the finest error must be <= spectral_max. Returns the fitted order (NaN if
/// none was fitted).
template <class Scheme>
double check_observed_order(const Scheme& s, const std::vector<double>& h, const std::vector<double>& err,
                            double floor, const std::string& what, double tol = 0.15,
                            double spectral_max = 1e-9) {
  std::vector<double> hh, ee;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (err[i] > floor) {
      hh.push_back(h[i]);
      ee.push_back(err[i]);
    }
  if (s.spectral) {
    BOOST_TEST(err.back() <= spectral_max, what << " " << s.name << ": finest error " << err.back()
                                                << " above the spectral threshold " << spectral_max);
    return hh.size() >= 2 ? fitted_order(hh, ee) : std::nan("");
  }
  if (hh.size() < 2) {
    BOOST_TEST(s.at_least, what << " " << s.name << ": errors at the floor " << floor
                                << ", no order can be fitted (use coarser grids)");
    return std::nan("");
  }
  const double p = fitted_order(hh, ee);
  if (s.at_least)
    BOOST_TEST(p >= s.design_order - tol, what << " " << s.name << ": observed order " << p << " < " << s.order);
  else
    BOOST_TEST(std::abs(p - s.design_order) <= tol,
               what << " " << s.name << ": observed order " << p << ", design " << s.design_order);
  return p;
}

// ------------------------------------------------------------------------------------------
// Independent references.

/// (1.10) written out: ad_xi = [hat w, 0; hat v, hat w], as a matrix (the tests use its
/// transpose for the coadjoint instead of lie::se3::coad_apply).
inline Eigen::Matrix<double, 6, 6> ad_matrix(const Vector6& xi) {
  auto skew = [](const Vector3& a) {
    Matrix3 S;
    S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return S;
  };
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  M.topLeftCorner<3, 3>() = skew(xi.head<3>());
  M.bottomRightCorner<3, 3>() = skew(xi.head<3>());
  M.bottomLeftCorner<3, 3>() = skew(xi.tail<3>());
  return M;
}

/// The Table 2.1 Cosserat rod's internal wrench at the constant twist xi: K (xi - xi*) (2.28).
inline Vector6 constant_twist_wrench(const Vector6& xi) {
  const Vector6 K = (Vector6() << Table21::EI, Table21::EI, Table21::GJ, Table21::GA, Table21::GA,
                     Table21::EA).finished();
  const Vector6 xi_star = (Vector6() << 0, 0, 0, 0, 0, 1).finished();
  return K.cwiseProduct(xi - xi_star);
}

/// The constant-twist load (2.68)-(2.69) on the Table 2.1 rod: the body tip wrench Lambda and
/// the body distributed wrench ad_xi^T Lambda, which hold it at g(s) = exp(s xi) when Lambda is
/// its internal wrench at xi.
inline StaticProblem constant_twist_problem(rod::ModelKind kind, const Vector6& xi,
                                            const Vector6& Lambda) {
  StaticProblem problem = tip_wrench_problem(kind, Lambda, loads::WrenchFrame::body);  // (2.69)
  problem.set_distributed(
      loads::DistributedWrench{ad_matrix(xi).transpose() * Lambda, loads::WrenchFrame::body});
  return problem;  // (2.68)
}

/// exp of hat(xi) as a 4x4 matrix, in long double by scaling and squaring (30 Taylor terms of
/// X / 2^s with norm <= 1/4): independent of every closed form in rodlab::lie; error ~1e-18.
inline Eigen::Matrix4d expm_reference(const Vector6& xi) {
  using M4 = Eigen::Matrix<long double, 4, 4>;
  M4 A = M4::Zero();
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  A(0, 1) = -w.z(); A(0, 2) = w.y();
  A(1, 0) = w.z();  A(1, 2) = -w.x();
  A(2, 0) = -w.y(); A(2, 1) = w.x();
  A(0, 3) = v.x(); A(1, 3) = v.y(); A(2, 3) = v.z();
  int s = 0;
  while (A.cwiseAbs().rowwise().sum().maxCoeff() > 0.25L) {
    A /= 2.0L;
    ++s;
  }
  M4 sum = M4::Identity(), term = M4::Identity();
  for (int k = 1; k <= 30; ++k) {
    term = (term * A) / static_cast<long double>(k);
    sum += term;
  }
  for (int i = 0; i < s; ++i) sum = sum * sum;
  return sum.cast<double>();
}

/// Pose error against a 4x4 reference matrix.
inline PoseError pose_error(const SE3& a, const Eigen::Matrix4d& ref, double L = Table21::L) {
  return {(a.translation() - ref.topRightCorner<3, 1>()).norm() / L,
          rotation_distance(a.rotation_matrix(), ref.topLeftCorner<3, 3>())};
}

}  // namespace rodlab::testing::statics
