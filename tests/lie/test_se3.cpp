#define BOOST_TEST_MODULE se3
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "finite_difference.hpp"
#include "hard_samples.hpp"
#include "rodlab/lie/se3.hpp"

// Property tests of rodlab::lie::SE3 and the se(3) operators over the hard sample set
// (tests/lie/hard_samples.hpp). Every check logs its measured maximum error and, on failure,
// the worst sample.

namespace {

using namespace rodlab::lie;
using namespace rodlab::lie::testing;
using Matrix4L = Eigen::Matrix<long double, 4, 4>;

/// exp of a 4x4 matrix in long double by scaling and squaring: X / 2^s with max-row-sum norm
/// <= 1/4, 30 Taylor terms (truncation < 4^-30 / 30! ~ 1e-50), then s squarings. Independent of
/// every closed form in se3.hpp; its error (~ s eps_long_double ~ 1e-18) is far below the
/// tolerance.
Matrix4L expm_long_double(const Matrix4& X) {
  Matrix4L A = X.cast<long double>();
  int s = 0;
  while (A.cwiseAbs().rowwise().sum().maxCoeff() > 0.25L) {
    A /= 2.0L;
    ++s;
  }
  Matrix4L sum = Matrix4L::Identity(), term = Matrix4L::Identity();
  for (int k = 1; k <= 30; ++k) {
    term = (term * A) / static_cast<long double>(k);
    sum += term;
  }
  for (int i = 0; i < s; ++i) sum = sum * sum;
  return sum;
}

/// Natural scale of a product of operands: rounding errors of M x are bounded by eps |M| |x|.
double scale_of(double a, double b) { return (1.0 + a) * (1.0 + b); }

/// Each twist sample paired with a group sample (all twists and all transforms are visited).
template <class F>
void for_each_transform_and_twist(const F& f) {
  const auto& g = transforms();
  const auto& x = twists();
  for (std::size_t k = 0; k < x.size(); ++k) {
    const auto& gk = g[k % g.size()];
    f(gk.value, x[k].value, gk.label + " on " + x[k].label);
  }
}

}  // namespace

// (1.5), (1.8), (1.10). vee(hat(xi)) = xi exactly; hat(xi) has the block form of (1.5) exactly;
// ad_a b = vee([hat a, hat b]) to kAlgebraTol (1 + |a||b|) (sums of products <= |a||b|);
// ad_apply and coad_apply equal ad(xi) y and ad(xi)^T lambda to kAlgebraTol (1 + |xi||y|).
BOOST_AUTO_TEST_CASE(hat_vee_and_ad) {
  Worst round_trip("se3 vee(hat(xi)) - xi"), block("hat(xi) - [hat(w) nu; 0 0]"),
      bracket("ad_a b - vee([hat a, hat b]) (1.8)"), ad_apply("ad_apply(a, b) - ad(a) b"),
      coad_apply("coad_apply(a, l) - ad(a)^T l");
  const auto& x = twists();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vector6& a = x[i].value;
    const Vector6& b = x[(i + 7) % x.size()].value;
    const std::string label = x[i].label + " with " + x[(i + 7) % x.size()].label;
    const Matrix4 A = se3::hat(a), B = se3::hat(b);
    Matrix4 expected = Matrix4::Zero();
    expected.topLeftCorner<3, 3>() = so3::hat(a.head<3>());
    expected.topRightCorner<3, 1>() = a.tail<3>();
    const double scale = 1.0 + a.norm() * b.norm();
    round_trip.update(max_abs_diff(se3::vee(A), a), x[i].label);
    block.update(max_abs_diff(A, expected), x[i].label);
    bracket.update(max_abs_diff(se3::ad(a) * b, se3::vee(Matrix4(A * B - B * A))) / scale, label);
    ad_apply.update(max_abs_diff(se3::ad_apply(a, b), se3::ad(a) * b) / scale, label);
    coad_apply.update(max_abs_diff(se3::coad_apply(a, b), se3::ad(a).transpose() * b) / scale,
                      label);
  }
  round_trip.check(0.0);
  block.check(0.0);
  bracket.check(kAlgebraTol);
  ad_apply.check(kAlgebraTol);
  coad_apply.check(kAlgebraTol);
}

// Group axioms on (g_i, g_i+1, g_i+2) over all transform samples (|p| up to 10), as 4x4 matrices;
// errors relative to 1 + max|reference| (the translations set the scale), tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(group_axioms) {
  Worst assoc("(ab)c - a(bc)"), ident("aI - a, Ia - a"), inv("a a^-1 - I, a^-1 a - I"),
      product("matrix(ab) - matrix(a) matrix(b)"), action("a * x - (matrix(a) [x; 1]).head(3)"),
      inverse_matrix("matrix(a^-1) - matrix(a)^-1"),
      inverse_times("matrix(a.inverse_times(b)) - matrix(a)^-1 matrix(b)");
  const auto& g = transforms();
  const Matrix4 I = Matrix4::Identity();
  for (std::size_t i = 0; i < g.size(); ++i) {
    const SE3& a = g[i].value;
    const SE3& b = g[(i + 1) % g.size()].value;
    const SE3& c = g[(i + 2) % g.size()].value;
    const std::string& label = g[i].label;
    const Matrix4 Ma = a.matrix(), Mb = b.matrix();
    const Matrix4 abc = (a * (b * c)).matrix();
    assoc.update(scaled_error(((a * b) * c).matrix(), abc), label);
    ident.update(std::max(scaled_error((a * SE3::identity()).matrix(), Ma),
                          scaled_error((SE3::identity() * a).matrix(), Ma)),
                 label);
    // a a^-1 = I up to rounding of the translation p + R(-R^T p): absolute error ~ eps |p|.
    inv.update(std::max(max_abs_diff((a * a.inverse()).matrix(), I),
                        max_abs_diff((a.inverse() * a).matrix(), I)) /
                   (1.0 + a.translation().norm()),
               label);
    product.update(scaled_error((a * b).matrix(), Matrix4(Ma * Mb)), label);
    const Vector3 x = b.translation() + Vector3(0.5, -1.0, 2.0);
    const Eigen::Vector4d xh(x.x(), x.y(), x.z(), 1.0);
    action.update(scaled_error(a * x, Vector3((Ma * xh).head<3>())), label);
    inverse_matrix.update(scaled_error(a.inverse().matrix(), Matrix4(Ma.inverse())), label);
    inverse_times.update(scaled_error(a.inverse_times(b).matrix(), Matrix4(Ma.inverse() * Mb)),
                         label);
  }
  for (Worst* w : {&assoc, &ident, &inv, &product, &action, &inverse_matrix, &inverse_times})
    w->check(kAlgebraTol);
}

// SE3::exp(xi) against the 4x4 matrix exponential of hat(xi) (long double scaling and squaring),
// for every twist sample including |omega| = 20, 30 rad and |nu| up to 10. Error relative to
// 1 + max|reference|, tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(exp_matches_matrix_exponential) {
  Worst w("SE3::exp(xi) - expm(hat(xi)) [long double]");
  for (const auto& [label, xi] : twists()) {
    const Matrix4L reference = expm_long_double(se3::hat(xi));
    w.update(
        static_cast<double>(max_abs_diff(SE3::exp(xi).matrix().cast<long double>(), reference) /
                            (1.0L + max_abs(reference))),
        label);
  }
  w.check(kAlgebraTol);
}

// exp(log g) = g for every transform (near pi, beyond pi, large tangents, half turns); log(exp xi)
// = xi inside the injectivity radius |omega| < pi (errors relative to 1 + |xi|); at |omega| = pi,
// log returns +/- omega. |log(g).head(3)| <= pi (1 + 2 eps). Tolerances kAlgebraTol.
BOOST_AUTO_TEST_CASE(exp_log_round_trips) {
  Worst exp_log("exp(log g) - g"), angle("|log(g).head(3)| / pi - 1 (when > 0)"),
      log_exp("log(exp xi) - xi, |omega| < pi"),
      at_pi("log(exp xi) at |omega| = pi: rotation part -/+ omega");
  for (const auto& [label, g] : transforms()) {
    const Vector6 l = g.log();
    exp_log.update(scaled_error(SE3::exp(l).matrix(), g.matrix()), label);
    angle.update(std::max(0.0, l.head<3>().norm() / kPi - 1.0), label);
  }
  for (const auto& [label, xi] : twists()) {
    const Vector3 w = xi.head<3>();
    const double t = w.norm();
    const Vector6 l = SE3::exp(xi).log();
    if (std::abs(t - kPi) < 1e-13) {
      at_pi.update(std::min(max_abs_diff(l.head<3>(), w), max_abs_diff(l.head<3>(), Vector3(-w))),
                   label);
    } else if (t < kPi) {
      log_exp.update(max_abs_diff(l, xi) / (1.0 + xi.norm()), label);
    }
  }
  exp_log.check(kAlgebraTol);
  angle.check(2.0 * kEps);
  log_exp.check(kAlgebraTol);
  at_pi.check(kAlgebraTol);
}

// (1.11)-(1.19). Ad_g x = vee(g hat(x) g^-1); Ad_apply = Ad() x; coAd_apply = Ad()^T W;
// Ad_{gh} = Ad_g Ad_h; Ad_{g^-1} = Ad_g^-1; Ad_g ad_x Ad_g^-1 = ad_{Ad_g x}; power is frame
// invariant: <Ad_g eta, W> = <eta, Ad_g^T W> (1.18), (1.19). Errors relative to the natural
// scale of the operands ((1 + |Ad_g|)(1 + |x|) for Ad_g x, etc.), tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(adjoint_identities) {
  Worst conjugation("Ad_g x - vee(g hat(x) g^-1) (1.11)"), apply("Ad_apply(x) - Ad() x"),
      co_apply("coAd_apply(W) - Ad()^T W"), product("Ad_{gh} - Ad_g Ad_h"),
      inverse("Ad_{g^-1} - Ad_g^-1"), ad_conj("Ad_g ad_x Ad_g^-1 - ad_{Ad_g x}"),
      power("<Ad_g eta, W> - <eta, Ad_g^T W> (1.18)"),
      matrix_maps("SE3Adjoints (R^T as a matrix) - Ad_{g^-1} x, Ad_g^T W");
  const auto& all = transforms();
  std::size_t k = 0;
  for_each_transform_and_twist([&](const SE3& g, const Vector6& x, const std::string& label) {
    const SE3& h = all[(k++ * 5 + 1) % all.size()].value;
    const Matrix6 Ad = g.Ad(), Ad_inv = g.inverse().Ad();
    const double nAd = max_abs(Ad), nx = max_abs(x);
    const Vector6 W =
        twists()[(k * 11) % twists().size()].value;  // any 6-vector serves as a wrench
    conjugation.update(max_abs_diff(Vector6(Ad * x), se3::vee(Matrix4(g.matrix() * se3::hat(x) *
                                                                      g.inverse().matrix()))) /
                           scale_of(nAd * nAd, nx),
                       label);
    apply.update(max_abs_diff(g.Ad_apply(x), Vector6(Ad * x)) / scale_of(nAd, nx), label);
    co_apply.update(
        max_abs_diff(g.coAd_apply(W), Vector6(Ad.transpose() * W)) / scale_of(nAd, max_abs(W)),
        label);
    product.update(
        max_abs_diff((g * h).Ad(), Matrix6(Ad * h.Ad())) / scale_of(nAd, max_abs(h.Ad())), label);
    inverse.update(std::max(max_abs_diff(Ad_inv, Matrix6(Ad.inverse())),
                            max_abs_diff(Matrix6(Ad_inv * Ad), Matrix6::Identity())) /
                       scale_of(nAd, nAd),
                   label);
    ad_conj.update(max_abs_diff(Matrix6(Ad * se3::ad(x) * Ad_inv), se3::ad(g.Ad_apply(x))) /
                       scale_of(nAd * nAd, nx),
                   label);
    power.update(
        std::abs(g.Ad_apply(x).dot(W) - x.dot(g.coAd_apply(W))) / scale_of(nAd * nx, max_abs(W)),
        label);
    const SE3Adjoints maps(g);
    matrix_maps.update(std::max(max_abs_diff(maps.inverse_Ad_apply(x), Vector6(Ad_inv * x)) /
                                    scale_of(nAd, nx),
                                max_abs_diff(maps.coAd_apply(W), g.coAd_apply(W)) /
                                    scale_of(nAd, max_abs(W))),
                       label);
  });
  for (Worst* w : {&conjugation, &apply, &co_apply, &product, &inverse, &ad_conj, &power,
                   &matrix_maps})
    w->check(kAlgebraTol);
}

// Jacobians against central differences on the group (right perturbations g exp(h e_j), outputs
// compared by right_minus; step kFdStep = 1e-6, see finite_difference.hpp):
//   c = a b:        J_c_a = Ad_{b^-1}, J_c_b = I           (SE3::compose)
//   g^-1:           J = -Ad_g                              (SE3::inverse(Matrix6*))
//   y = g x:        J = [-R hat(x)  R]  (y(g exp(d)) = R (x + d_w x x + d_v) + p)
// FD error ~ h^2 |f'''| + eps |g| / h ~ 1e-9 for |p| <= 10; tolerance 1e-7 relative to
// 1 + max|J|.
BOOST_AUTO_TEST_CASE(jacobians_against_finite_differences) {
  Worst compose_a("J_c_a - FD"), compose_b("J_c_b - FD"), inverse("J_inv - FD"),
      action("d(g x)/dg - FD"), compose_value("compose(b) - a * b");
  const auto& g = transforms();
  for (std::size_t i = 0; i < g.size(); ++i) {
    const SE3& a = g[i].value;
    const SE3& b = g[(i + 3) % g.size()].value;
    const std::string& label = g[i].label;
    Matrix6 J_c_a, J_c_b, J_inv;
    const SE3 c = a.compose(b, &J_c_a, &J_c_b);
    compose_value.update(scaled_error(c.matrix(), (a * b).matrix()), label);
    const Matrix6 fd_a = central_jacobian<6, 6>(
        [&](const Vector6& d) { return right_minus(SE3(a * SE3::exp(d)) * b, c); });
    const Matrix6 fd_b = central_jacobian<6, 6>(
        [&](const Vector6& d) { return right_minus(a * SE3(b * SE3::exp(d)), c); });
    compose_a.update(scaled_error(J_c_a, fd_a), label);
    compose_b.update(scaled_error(J_c_b, fd_b), label);

    const SE3 a_inv = a.inverse(&J_inv);
    const Matrix6 fd_inv = central_jacobian<6, 6>(
        [&](const Vector6& d) { return right_minus(SE3(a * SE3::exp(d)).inverse(), a_inv); });
    inverse.update(scaled_error(J_inv, fd_inv), label);

    const Vector3 x = b.translation() + Vector3(0.5, -1.0, 2.0);
    const Matrix3 R = a.rotation_matrix();
    Eigen::Matrix<double, 3, 6> J_action;
    J_action << -R * so3::hat(x), R;
    const Eigen::Matrix<double, 3, 6> fd_action =
        central_jacobian<3, 6>([&](const Vector6& d) { return Vector3(SE3(a * SE3::exp(d)) * x); });
    action.update(max_abs_diff(J_action, fd_action) / (1.0 + max_abs(J_action)), label);
  }
  compose_value.check(0.0);
  for (Worst* w : {&compose_a, &compose_b, &inverse, &action}) w->check(1e-7);
}
