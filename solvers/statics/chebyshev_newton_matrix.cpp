#include "rodlab/solvers/statics/chebyshev_newton_matrix.hpp"

#include <algorithm>

namespace rodlab::solvers::statics {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using Matrix3 = Eigen::Matrix3d;
using Vector3 = Eigen::Vector3d;

// Field offsets inside a node's 12 unknowns and rows.
constexpr int kPhi = 0, kRho = 3, kM = 6, kN = 9, kLambda = 6;

/// The smallest pivot above `ratio` times the largest, everything finite.
template <class LU>
bool regular_pivots(const LU& lu, double ratio) {
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  return pivots.allFinite() && pivots.minCoeff() > ratio * pivots.maxCoeff();
}

}  // namespace

ChebyshevNewtonMatrix::ChebyshevNewtonMatrix(std::vector<Element> elements, int extra)
    : elements_(std::move(elements)), extra_(extra) {
  int max_n = 0;
  for (const auto& el : elements_) {
    layout_.push_back({reduced_size_, rho_size_});
    reduced_size_ += 6 * el.n;
    rho_size_ += 3 * (el.n - 1);
    nodes_ = el.first + el.n;
    max_n = std::max(max_n, el.n);
  }
  const int E = static_cast<int>(elements_.size());
  blocks_.assign(nodes_, Matrix12::Zero());
  for (int e = 0; e + 1 < E; ++e) chart_.push_back(MatrixXd::Zero(12 * (nodes_ - elements_[e + 1].first), 6));
  H_.assign(nodes_, Matrix3::Zero());
  N_.assign(nodes_, Matrix3::Zero());
  coupled_.assign(nodes_, 0);
  for (const auto& el : elements_) {
    Y_.emplace_back(3 * (el.n - 1), 3 * (el.n - 1));
    rho_lu_.emplace_back(3 * (el.n - 1));
  }
  Z_.resize(6, rho_size_);
  S_.resize(reduced_size_, reduced_size_);
  b_reduced_.resize(reduced_size_);
  z_.resize(reduced_size_);
  b_rho_.resize(rho_size_);
  y_.resize(rho_size_);
  dm_.resize(3 * (max_n - 1));
  drho_.resize(3 * (max_n - 1));
  if (extra_ > 0) {
    const int n = 12 * nodes_;
    border_columns_.setZero(n, extra_);
    border_rows_.setZero(extra_, n);
    border_corner_.setZero(extra_, extra_);
    V_.resize(n, extra_);
    column_.resize(n);
    solved_.resize(n);
    c_.resize(extra_);
    dz_.resize(extra_);
  }
}

template <int R>
void ChebyshevNewtonMatrix::substitute_moment(const int (&rows)[R], const Eigen::Matrix<double, R, 3>& coeff,
                                              int e, int k) {
  const int n = elements_[e].n, col = phi_col(e, 1, 0);
  for (int a = 0; a < 3; ++a) {
    const auto y = Y_[e].row(a * (n - 1) + k - 1);
    for (int r = 0; r < R; ++r) S_.row(rows[r]).segment(col, 3 * (n - 1)) -= coeff(r, a) * y;
  }
  substitute_force<R>(rows, coeff, e, k);
}

template <int R>
void ChebyshevNewtonMatrix::substitute_force(const int (&rows)[R], const Eigen::Matrix<double, R, 3>& coeff,
                                             int e, int k) {
  const int node = elements_[e].first + k;
  if (!coupled_[node]) return;
  const Eigen::Matrix<double, R, 3> on_n = coeff * N_[node];
  for (int r = 0; r < R; ++r)
    for (int b = 0; b < 3; ++b) S_(rows[r], n_col(e, k, b)) -= on_n(r, b);
}

void ChebyshevNewtonMatrix::build_element_systems(bool& regular, double singular_pivot) {
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    check_deadline();
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1;
    const MatrixXd& D = *el.D;
    // (C2): H_k and Y_kl = H_k (D_kl I + delta_kl G_phi,phi(k)), k, l >= 1.
    RowMajorMatrix& Y = Y_[e];
    for (int k = 1; k < n; ++k) {
      const Matrix12& G = blocks_[el.first + k];
      const Matrix3 H = G.block<3, 3>(kPhi, kM).inverse();
      if (!H.allFinite()) regular = false;
      H_[el.first + k] = H;
      coupled_[el.first + k] = !G.block<3, 3>(kPhi, kN).isZero(0.0);
      if (coupled_[el.first + k]) N_[el.first + k] = H * G.block<3, 3>(kPhi, kN);
      const Matrix3 HG = H * G.block<3, 3>(kPhi, kPhi);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          Y.row(a * m + k - 1).segment(b * m, m) = H(a, b) * D.row(k).tail(m);
          Y(a * m + k - 1, b * m + k - 1) += HG(a, b);
        }
    }
    // (1): A_e = D (x) I_3 plus the node blocks G_rho,rho, rows and columns 1..n-1.
    MatrixXd A = MatrixXd::Zero(3 * m, 3 * m);
    for (int i = 1; i < n; ++i) {
      const Matrix12& G = blocks_[el.first + i];
      for (int a = 0; a < 3; ++a) {
        A.row(a * m + i - 1).segment(a * m, m) = D.row(i).tail(m);
        for (int b = 0; b < 3; ++b) A(a * m + i - 1, b * m + i - 1) += G(kRho + a, kRho + b);
      }
    }
    rho_lu_[e].compute(A);
    if (!regular_pivots(rho_lu_[e], singular_pivot)) regular = false;
  }
}

void ChebyshevNewtonMatrix::build_tip_rho_coupling() {
  // T_rho: the tip rows' dependence on rho, at the tip node and through the charts (columns of
  // last nodes only, never of a first node).
  const int E = static_cast<int>(elements_.size());
  MatrixXd T = MatrixXd::Zero(6, rho_size_);
  const Matrix12& G = blocks_[nodes_ - 1];
  for (int c = 0; c < 6; ++c)
    for (int b = 0; b < 3; ++b) T(c, rho_col(E - 1, elements_[E - 1].n - 1, b)) = G(kLambda + c, kRho + b);
  for (int e = 0; e + 1 < E; ++e) {
    const int tip = nodes_ - 1 - elements_[e + 1].first;
    for (int c = 0; c < 6; ++c)
      for (int b = 0; b < 3; ++b)
        T(c, rho_col(e, elements_[e].n - 1, b)) += chart_[e](12 * tip + kLambda + c, kRho + b);
  }
  // (C1): Z = T_rho A^-1, element by element.
  for (int e = 0; e < E; ++e) {
    auto Ze = Z_.middleCols(layout_[e].rho, 3 * (elements_[e].n - 1));
    const auto Te = T.middleCols(layout_[e].rho, Ze.cols());
    if (Te.isZero(0.0)) Ze.setZero();
    else Ze.transpose() = rho_lu_[e].transpose().solve(MatrixXd(Te.transpose()));
  }
}

void ChebyshevNewtonMatrix::build_reduced() {
  S_.setZero();
  const int E = static_cast<int>(elements_.size());
  for (int e = 0; e < E; ++e) {
    check_deadline();
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1, l = n - 1;
    const MatrixXd& D = *el.D;
    // The m rows' D part on m_k, k >= 1, substituted by (C2): -(D (x) I_3) Y, per component.
    for (int a = 0; a < 3; ++a)
      S_.block(m_row(e, 0, a), phi_col(e, 1, 0), m, 3 * m).noalias() -=
          D.block(0, 1, m, m) * Y_[e].middleRows(a * m, m);
    // ... and on n_k through N_k (actuators only).
    for (int k = 1; k < n; ++k) {
      if (!coupled_[el.first + k]) continue;
      for (int j = 0; j < l; ++j) {
        const int rows[3] = {m_row(e, j, 0), m_row(e, j, 1), m_row(e, j, 2)};
        substitute_force<3>(rows, Matrix3(D(j, k) * Matrix3::Identity()), e, k);
      }
    }
    // The m and n rows 0..n-2: the D part on m_0 and on n, the node blocks on their own phi, n,
    // and on m_0 (row 0).
    for (int j = 0; j < l; ++j) {
      const Matrix12& G = blocks_[el.first + j];
      for (int a = 0; a < 3; ++a) {
        S_(m_row(e, j, a), m0_col(e, a)) += D(j, 0);
        for (int k = 0; k < n; ++k) S_(n_row(e, j, a), n_col(e, k, a)) += D(j, k);
        for (int b = 0; b < 3; ++b) {
          S_(m_row(e, j, a), n_col(e, j, b)) += G(kM + a, kN + b);
          S_(n_row(e, j, a), n_col(e, j, b)) += G(kN + a, kN + b);
          if (j == 0) {
            S_(m_row(e, 0, a), m0_col(e, b)) += G(kM + a, kM + b);
            S_(n_row(e, 0, a), m0_col(e, b)) += G(kN + a, kM + b);
          } else {
            S_(m_row(e, j, a), phi_col(e, j, b)) += G(kM + a, kPhi + b);
            S_(n_row(e, j, a), phi_col(e, j, b)) += G(kN + a, kPhi + b);
          }
        }
      }
    }
    // Their m_j coefficients G_m,m(j), G_n,m(j), j >= 1, substituted by (C2): row (j, a) gets
    // -sum_c G(a, c) Y_(j,c), as diagonal scalings of Y's component blocks.
    if (n > 2) {
      VectorXd g(n - 2);
      for (int field : {kM, kN})
        for (int a = 0; a < 3; ++a) {
          auto rows = S_.block(field == kM ? m_row(e, 1, a) : n_row(e, 1, a), phi_col(e, 1, 0), n - 2, 3 * m);
          for (int c = 0; c < 3; ++c) {
            for (int j = 1; j < l; ++j) g[j - 1] = blocks_[el.first + j](field + a, kM + c);
            rows.noalias() -= g.asDiagonal() * Y_[e].middleRows(c * m, n - 2);
          }
        }
      for (int j = 1; j < l; ++j) {  // ... and on n_j through N_j (actuators only)
        const Matrix12& G = blocks_[el.first + j];
        const int m_rows[3] = {m_row(e, j, 0), m_row(e, j, 1), m_row(e, j, 2)};
        const int n_rows[3] = {n_row(e, j, 0), n_row(e, j, 1), n_row(e, j, 2)};
        substitute_force<3>(m_rows, Matrix3(G.block<3, 3>(kM, kM)), e, j);
        substitute_force<3>(n_rows, Matrix3(G.block<3, 3>(kN, kM)), e, j);
      }
    }
    // The last node's six rows (tip conditions or continuity).
    const Matrix12& Gl = blocks_[el.first + l];
    int last_rows[6];
    for (int c = 0; c < 6; ++c) {
      last_rows[c] = last_row(e, c);
      for (int b = 0; b < 3; ++b) {
        S_(last_rows[c], phi_col(e, l, b)) += Gl(kLambda + c, kPhi + b);
        S_(last_rows[c], n_col(e, l, b)) += Gl(kLambda + c, kN + b);
      }
    }
    substitute_moment<6>(last_rows, Gl.block<6, 3>(kLambda, kM), e, l);
    if (e + 1 < E)
      for (int a = 0; a < 3; ++a) {
        S_(last_row(e, a), m0_col(e + 1, a)) -= 1.0;
        S_(last_row(e, 3 + a), n_col(e + 1, 0, a)) -= 1.0;
      }
  }
  // Chart blocks: phi of element e's last node in the m and n rows and the tip rows after it
  // (their rho part is in Z).
  for (int e = 0; e + 1 < E; ++e) {
    const int col = elements_[e].n - 1;
    for (int f = e + 1; f < E; ++f) {
      const Element& el = elements_[f];
      for (int j = 0; j < el.n; ++j) {
        const int at = 12 * (el.first + j - elements_[e + 1].first);
        for (int b = 0; b < 3; ++b) {
          if (j + 1 < el.n) {
            for (int a = 0; a < 3; ++a) {
              S_(m_row(f, j, a), phi_col(e, col, b)) += chart_[e](at + kM + a, kPhi + b);
              S_(n_row(f, j, a), phi_col(e, col, b)) += chart_[e](at + kN + a, kPhi + b);
            }
          } else if (f + 1 == E) {
            for (int c = 0; c < 6; ++c)
              S_(last_row(f, c), phi_col(e, col, b)) += chart_[e](at + kLambda + c, kPhi + b);
          }
        }
      }
    }
  }
  // (C1) on the tip rows: -Z G_rho,x for every node i >= 1, its m part substituted by (C2).
  int tip_rows[6];
  for (int c = 0; c < 6; ++c) tip_rows[c] = last_row(E - 1, c);
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    for (int i = 1; i < el.n; ++i) {
      Eigen::Matrix<double, 6, 3> W;
      for (int a = 0; a < 3; ++a) W.col(a) = Z_.col(rho_col(e, i, a));
      if (W.isZero(0.0)) continue;
      const Matrix12& G = blocks_[el.first + i];
      const Eigen::Matrix<double, 6, 3> on_phi = W * G.block<3, 3>(kRho, kPhi);
      const Eigen::Matrix<double, 6, 3> on_n = W * G.block<3, 3>(kRho, kN);
      for (int c = 0; c < 6; ++c)
        for (int b = 0; b < 3; ++b) {
          S_(tip_rows[c], phi_col(e, i, b)) -= on_phi(c, b);
          S_(tip_rows[c], n_col(e, i, b)) -= on_n(c, b);
        }
      substitute_moment<6>(tip_rows, Eigen::Matrix<double, 6, 3>(-W * G.block<3, 3>(kRho, kM)), e, i);
    }
  }
}

bool ChebyshevNewtonMatrix::factorize(double singular_pivot) {
  // The run's wall-time guard per element of the two builds, after the element systems and per
  // block of S's LU: at N = 1000 one factorisation takes seconds (deadline_lu.hpp).
  bool regular = true;
  build_element_systems(regular, singular_pivot);
  if (!regular) return false;
  check_deadline();
  build_tip_rho_coupling();
  build_reduced();
  S_lu_.compute(S_);
  if (!regular_pivots(S_lu_, singular_pivot)) return false;
  if (extra_ == 0) return true;
  // (3): V = A^-1 B, and the Schur complement E - C V.
  for (int j = 0; j < extra_; ++j) {
    column_ = border_columns_.col(j);
    solve_nodes(column_, solved_);
    V_.col(j) = solved_;
  }
  schur_lu_.compute(border_corner_ - border_rows_ * V_);
  return regular_pivots(schur_lu_, singular_pivot);
}

void ChebyshevNewtonMatrix::solve(const VectorXd& b, VectorXd& x) {
  x.resize(size());
  solve_nodes(b, x);
  if (extra_ == 0) return;
  // (3): dz = (E - C V)^-1 (c - C A^-1 b), dx = A^-1 b - V dz.
  const int n = 12 * nodes_;
  c_ = b.tail(extra_);
  c_.noalias() -= border_rows_ * x.head(n);
  dz_ = schur_lu_.solve(c_);
  x.head(n).noalias() -= V_ * dz_;
  x.tail(extra_) = dz_;
}

void ChebyshevNewtonMatrix::solve_nodes(const VectorXd& b, VectorXd& x) {
  const int E = static_cast<int>(elements_.size());
  // dtheta_0 = b_theta,0; y_k = H_k (b_phi,k - D_k0 b_phi,0) (C2); b_rho,i - D_i0 b_rho,0 (1).
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1, o = layout_[e].rho;
    const MatrixXd& D = *el.D;
    const int first = 12 * el.first;
    x.segment<6>(first) = b.segment<6>(first);
    const Vector3 phi0 = b.segment<3>(first + kPhi), rho0 = b.segment<3>(first + kRho);
    for (int i = 1; i < n; ++i) {
      const int node = first + 12 * i;
      const Vector3 y = H_[el.first + i] * (b.segment<3>(node + kPhi) - D(i, 0) * phi0);
      const Vector3 r = b.segment<3>(node + kRho) - D(i, 0) * rho0;
      for (int a = 0; a < 3; ++a) {
        y_[o + a * m + i - 1] = y[a];
        b_rho_[o + a * m + i - 1] = r[a];
      }
    }
  }
  // b_S.
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1, l = n - 1, o = layout_[e].rho;
    const MatrixXd& D = *el.D;
    auto y_at = [&](int k) { return Vector3(y_[o + k - 1], y_[o + m + k - 1], y_[o + 2 * m + k - 1]); };
    const int first = 12 * el.first;
    const Vector3 phi0 = b.segment<3>(first + kPhi);
    for (int j = 0; j < l; ++j) {
      const Matrix12& G = blocks_[el.first + j];
      Vector3 rm = b.segment<3>(first + 12 * j + kM), rn = b.segment<3>(first + 12 * j + kN);
      if (j == 0) {  // node 0's own phi is known
        rm -= G.block<3, 3>(kM, kPhi) * phi0;
        rn -= G.block<3, 3>(kN, kPhi) * phi0;
      } else {
        const Vector3 y = y_at(j);
        rm -= G.block<3, 3>(kM, kM) * y;
        rn -= G.block<3, 3>(kN, kM) * y;
      }
      for (int a = 0; a < 3; ++a) {
        b_reduced_[m_row(e, j, a)] = rm[a];
        b_reduced_[n_row(e, j, a)] = rn[a];
      }
    }
    for (int a = 0; a < 3; ++a)
      b_reduced_.segment(m_row(e, 0, a), m).noalias() -= D.block(0, 1, m, m) * y_.segment(o + a * m, m);
    const Eigen::Matrix<double, 6, 1> last =
        b.segment<6>(first + 12 * l + kLambda) - blocks_[el.first + l].block<6, 3>(kLambda, kM) * y_at(l);
    for (int c = 0; c < 6; ++c) b_reduced_[last_row(e, c)] = last[c];
  }
  // (C1) on the tip rows: -Z b_rho, and +Z G_rho,m y (the m part substituted by (C2)).
  Eigen::Matrix<double, 6, 1> tip = -Z_ * b_rho_;
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1, o = layout_[e].rho;
    for (int i = 1; i < n; ++i) {
      Eigen::Matrix<double, 6, 3> W;
      for (int a = 0; a < 3; ++a) W.col(a) = Z_.col(rho_col(e, i, a));
      if (W.isZero(0.0)) continue;
      const Vector3 y(y_[o + i - 1], y_[o + m + i - 1], y_[o + 2 * m + i - 1]);
      tip += W * (blocks_[el.first + i].block<3, 3>(kRho, kM) * y);
    }
  }
  for (int c = 0; c < 6; ++c) b_reduced_[last_row(E - 1, c)] += tip[c];

  S_lu_.solve(b_reduced_, z_);

  // Back substitution: dm by (C2), drho by (1).
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    const int n = el.n, m = n - 1, o = layout_[e].rho;
    auto dm = dm_.head(3 * m);
    dm.noalias() = y_.segment(o, 3 * m) - Y_[e] * z_.segment(phi_col(e, 1, 0), 3 * m);
    for (int k = 1; k < n; ++k) {  // - N_k dn_k (C2)
      if (!coupled_[el.first + k]) continue;
      const Vector3 dn(z_[n_col(e, k, 0)], z_[n_col(e, k, 1)], z_[n_col(e, k, 2)]);
      const Vector3 shift = N_[el.first + k] * dn;
      for (int a = 0; a < 3; ++a) dm[a * m + k - 1] -= shift[a];
    }
    for (int i = 0; i < n; ++i) {
      const int node = 12 * (el.first + i);
      for (int a = 0; a < 3; ++a) {
        if (i > 0) x[node + kPhi + a] = z_[phi_col(e, i, a)];
        x[node + kM + a] = i == 0 ? z_[m0_col(e, a)] : dm[a * m + i - 1];
        x[node + kN + a] = z_[n_col(e, i, a)];
      }
    }
    auto rhs = b_rho_.segment(o, 3 * m);
    for (int i = 1; i < n; ++i) {
      const int node = 12 * (el.first + i);
      const Matrix12& G = blocks_[el.first + i];
      const Vector3 coupled = G.block<3, 3>(kRho, kPhi) * x.segment<3>(node + kPhi) +
                              G.block<3, 3>(kRho, kM) * x.segment<3>(node + kM) +
                              G.block<3, 3>(kRho, kN) * x.segment<3>(node + kN);
      for (int a = 0; a < 3; ++a) rhs[a * m + i - 1] -= coupled[a];
    }
    auto drho = drho_.head(3 * m);
    drho = rho_lu_[e].solve(rhs);
    for (int i = 1; i < n; ++i)
      for (int a = 0; a < 3; ++a) x[12 * (el.first + i) + kRho + a] = drho[a * m + i - 1];
  }
}

void ChebyshevNewtonMatrix::assemble(MatrixXd& J) const {
  J.setZero(size(), size());
  const int E = static_cast<int>(elements_.size());
  for (int e = 0; e < E; ++e) {
    const Element& el = elements_[e];
    const MatrixXd& D = *el.D;
    for (int i = 0; i < el.n; ++i) {
      const int row = 12 * (el.first + i);
      J.block<12, 12>(row, row) = blocks_[el.first + i];
      for (int k = 0; k < el.n; ++k) {
        const int col = 12 * (el.first + k);
        for (int c = 0; c < 6; ++c) {
          if (i > 0) J(row + c, col + c) += D(i, k);
          if (i + 1 < el.n) J(row + 6 + c, col + 6 + c) += D(i, k);
        }
      }
    }
    if (e + 1 < E) {
      const int row = 12 * (el.first + el.n - 1) + kLambda, col = 12 * elements_[e + 1].first + kLambda;
      for (int c = 0; c < 6; ++c) J(row + c, col + c) -= 1.0;
      const int theta_col = 12 * (el.first + el.n - 1);
      J.block(12 * elements_[e + 1].first, theta_col, chart_[e].rows(), 6) += chart_[e];
    }
  }
  if (extra_ > 0) {
    const int n = 12 * nodes_;
    J.topRightCorner(n, extra_) = border_columns_;
    J.bottomLeftCorner(extra_, n) = border_rows_;
    J.bottomRightCorner(extra_, extra_) = border_corner_;
  }
}

}  // namespace rodlab::solvers::statics
