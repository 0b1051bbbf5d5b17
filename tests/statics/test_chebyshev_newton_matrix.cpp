#define BOOST_TEST_MODULE chebyshev_newton_matrix
#include <boost/test/unit_test.hpp>

// The condensed factorisation of the chebyshev Newton matrix
// (solvers/include/rodlab/solvers/statics/chebyshev_newton_matrix.hpp) is exact algebra: its
// solve must equal a dense LU solve of the assembled 12N (+ q) matrix up to rounding.
// Reference: Eigen's PartialPivLU of assemble(). The node blocks are random with the structure
// the condensation relies on (theta_0 = 0 rows, phi rows free of rho, Lambda rows free of rho
// except at the tip, chart blocks on phi except the tip rows), and with what actuators add:
// phi rows coupled to the force n (the tendon law), continuity rows with an entry jump
// (I + a Lambda block), and a border of extra unknowns (length control, muscles).

#include <random>
#include <vector>

#include <Eigen/Dense>

#include "rodlab/solvers/common/chebyshev_operators.hpp"
#include "rodlab/solvers/statics/chebyshev_newton_matrix.hpp"

using rodlab::solvers::chebyshev_differentiation_matrix;
using rodlab::solvers::statics::ChebyshevNewtonMatrix;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr int kPhi = 0, kRho = 3, kM = 6, kLambda = 6;

struct Fixture {
  std::mt19937 rng{12345};
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  std::vector<MatrixXd> D;

  MatrixXd random(int r, int c) {
    MatrixXd m(r, c);
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < c; ++j) m(i, j) = u(rng);
    return m;
  }

  /// Fills a matrix for elements of `sizes` nodes; `coupled`: phi rows depend on n; `jumps`:
  /// continuity rows with an entry-jump block; `extra`: border size.
  ChebyshevNewtonMatrix make(const std::vector<int>& sizes, bool coupled, bool jumps, int extra) {
    D.clear();
    for (int n : sizes) D.push_back(chebyshev_differentiation_matrix(n));
    std::vector<ChebyshevNewtonMatrix::Element> elements;
    int first = 0;
    for (std::size_t e = 0; e < sizes.size(); ++e) {
      elements.push_back({sizes[e], first, &D[e]});
      first += sizes[e];
    }
    const int nodes = first, E = static_cast<int>(sizes.size());
    ChebyshevNewtonMatrix M(elements, extra);
    for (int e = 0; e < E; ++e) {
      const auto& el = elements[e];
      for (int i = 0; i < el.n; ++i) {
        auto& G = M.node_block(el.first + i);
        G.setZero();
        const bool tip = e + 1 == E && i + 1 == el.n;
        if (i == 0) {
          G.topLeftCorner<6, 6>().setIdentity();
        } else {
          G.block<3, 3>(kPhi, kPhi) = random(3, 3);
          G.block<3, 3>(kPhi, kM) = random(3, 3) + 4.0 * Eigen::Matrix3d::Identity();
          if (coupled) G.block<3, 3>(kPhi, kM + 3) = random(3, 3);
          G.block<3, 12>(kRho, 0) = random(3, 12);
        }
        if (tip) {
          G.bottomRows<6>() = random(6, 12);
        } else if (i + 1 == el.n) {  // continuity (with an entry jump)
          G.bottomRightCorner<6, 6>().setIdentity();
          if (jumps) G.bottomRightCorner<6, 6>() += 0.3 * random(6, 6);
        } else {
          G.block<6, 3>(kLambda, kPhi) = random(6, 3);
          G.block<6, 6>(kLambda, kLambda) = random(6, 6);
        }
      }
      if (e + 1 < E) {  // chart block: Lambda rows of later nodes on phi; the tip rows on phi, rho
        MatrixXd& C = M.chart_block(e);
        C.setZero();
        const int later = nodes - elements[e + 1].first;
        for (int f = e + 1; f < E; ++f)
          for (int j = 0; j < elements[f].n; ++j) {
            const int at = 12 * (elements[f].first + j - elements[e + 1].first);
            if (j + 1 < elements[f].n) C.block<6, 3>(at + kLambda, kPhi) = random(6, 3);
            else if (f + 1 == E) C.block<6, 6>(at + kLambda, 0) = random(6, 6);
          }
        BOOST_REQUIRE(C.rows() == 12 * later);
      }
    }
    if (extra > 0) {
      M.border_columns() = random(12 * nodes, extra);
      M.border_rows() = random(extra, 12 * nodes);
      M.border_corner() = random(extra, extra) + 3.0 * MatrixXd::Identity(extra, extra);
    }
    return M;
  }

  /// max |x_condensed - x_dense| / max |x_dense| for a random right-hand side.
  double mismatch(ChebyshevNewtonMatrix& M) {
    BOOST_REQUIRE(M.factorize(1e-14));
    MatrixXd J;
    M.assemble(J);
    const VectorXd b = random(M.size(), 1);
    const VectorXd dense = J.partialPivLu().solve(b);
    VectorXd x;
    M.solve(b, x);
    BOOST_TEST_MESSAGE("size " << M.size() << ": dense residual " << (J * dense - b).lpNorm<Eigen::Infinity>()
                               << ", condensed residual " << (J * x - b).lpNorm<Eigen::Infinity>());
    return (x - dense).lpNorm<Eigen::Infinity>() / dense.lpNorm<Eigen::Infinity>();
  }
};

}  // namespace

// Without actuators: the structure the scheme had before (one and three elements).
BOOST_AUTO_TEST_CASE(plain_structure_matches_dense_lu) {
  Fixture f;
  auto one = f.make({9}, false, false, 0);
  BOOST_TEST(f.mismatch(one) < 1e-10);
  auto three = f.make({6, 5, 7}, false, false, 0);
  BOOST_TEST(f.mismatch(three) < 1e-10);
}

// With actuators: omega coupled to the force (N_k = H_k G_phi,n in (C2)), entry jumps in the
// continuity rows, elements of 2 and 3 nodes (short stretches between breakpoints).
BOOST_AUTO_TEST_CASE(force_coupling_and_entry_jumps_match_dense_lu) {
  Fixture f;
  auto M = f.make({7, 3, 2, 6}, true, true, 0);
  BOOST_TEST(f.mismatch(M) < 1e-10);
}

// The border of extra unknowns, solved through the Schur complement.
BOOST_AUTO_TEST_CASE(border_matches_dense_lu) {
  Fixture f;
  auto one = f.make({8}, true, false, 1);
  BOOST_TEST(f.mismatch(one) < 1e-10);
  auto M = f.make({5, 4, 6}, true, true, 2);
  BOOST_TEST(f.mismatch(M) < 1e-10);
}

// The test can fail: a wrong block in the assembled matrix is seen.
BOOST_AUTO_TEST_CASE(a_perturbed_matrix_does_not_match) {
  Fixture f;
  auto M = f.make({5, 4, 6}, true, true, 2);
  BOOST_REQUIRE(M.factorize(1e-14));
  MatrixXd J;
  M.assemble(J);
  J(20, 30) += 0.5;  // a change the factorisation does not know of
  const VectorXd b = f.random(M.size(), 1);
  VectorXd x;
  M.solve(b, x);
  const VectorXd dense = J.partialPivLu().solve(b);
  BOOST_TEST((x - dense).lpNorm<Eigen::Infinity>() / dense.lpNorm<Eigen::Infinity>() > 1e-6);
}
