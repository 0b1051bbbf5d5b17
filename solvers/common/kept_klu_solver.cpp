#include "kept_klu_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "direct_solver_shell.hpp"

namespace rodlab::solvers::sundials {
namespace {

static_assert(std::is_same_v<sunindextype, SuiteSparse_long>,
              "the kept KLU solver needs SUNDIALS built with 64-bit indices (klu_l_*)");

struct Content {
  Content() = default;
  Content(const Content&) = delete;
  Content& operator=(const Content&) = delete;
  ~Content() {
    if (numeric) klu_l_free_numeric(&numeric, &common);
    if (symbolic) klu_l_free_symbolic(&symbolic, &common);
  }
  long n = 0;
  klu_l_common common{};
  klu_l_symbolic* symbolic = nullptr;
  klu_l_numeric* numeric = nullptr;
  std::vector<double> factorised;  ///< the values of the last factorised matrix
  bool keep_factors = true;        ///< across KINSol calls
  int last_flag = SUNLS_SUCCESS;
  KeptKluCounts counts;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

/// KINSOL calls this at the start of every KINSol: the analysis is kept, and the factors too
/// with keep_factors (else the call's first setup factorises afresh).
int initialize(SUNLinearSolver S) {
  Content& c = content(S);
  if (!c.keep_factors) {
    if (c.numeric) klu_l_free_numeric(&c.numeric, &c.common);
    c.factorised.clear();
  }
  return c.last_flag = SUNLS_SUCCESS;
}

/// A fresh numeric factorisation (new pivots) of the values in A.
bool factor(Content& c, sunindextype* Ap, sunindextype* Ai, double* Ax) {
  if (c.numeric) klu_l_free_numeric(&c.numeric, &c.common);
  c.numeric = klu_l_factor(Ap, Ai, Ax, c.symbolic, &c.common);
  ++c.counts.factorisations;
  return c.numeric != nullptr && c.common.status == KLU_OK;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.n)
    return c.last_flag = SUNLS_ILL_INPUT;
  sunindextype* Ap = SUNSparseMatrix_IndexPointers(A);
  sunindextype* Ai = SUNSparseMatrix_IndexValues(A);
  double* Ax = SUNSparseMatrix_Data(A);
  const auto nnz = static_cast<std::size_t>(Ap[c.n]);
  if (!c.symbolic) {
    c.symbolic = klu_l_analyze(c.n, Ap, Ai, &c.common);
    if (!c.symbolic) return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  // The matrix factorised last (a Jacobian kept across solves): the factors are still right.
  if (c.numeric && c.factorised.size() == nnz && std::equal(Ax, Ax + nnz, c.factorised.begin())) {
    ++c.counts.skipped;
    return c.last_flag = SUNLS_SUCCESS;
  }
  bool ok = false;
  if (c.numeric) {
    ok = klu_l_refactor(Ap, Ai, Ax, c.symbolic, c.numeric, &c.common) == 1 &&
         c.common.status == KLU_OK;
    ++c.counts.refactorisations;
    // The kept pivot order may be poor for the new values (SUNLinSol_KLU's test).
    static const double threshold = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
    if (ok) ok = klu_l_rcond(c.symbolic, c.numeric, &c.common) == 1 && c.common.rcond >= threshold;
  }
  if (!ok) ok = factor(c, Ap, Ai, Ax);
  if (!ok) {
    c.factorised.clear();
    // A singular matrix is recoverable (KINSOL may retry with a new Jacobian).
    return c.last_flag = c.common.status == KLU_SINGULAR ? SUNLS_PACKAGE_FAIL_REC
                                                        : SUNLS_PACKAGE_FAIL_UNREC;
  }
  c.factorised.assign(Ax, Ax + nnz);
  return c.last_flag = SUNLS_SUCCESS;
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double) {
  Content& c = content(S);
  if (!c.symbolic || !c.numeric) return c.last_flag = SUNLS_MEM_NULL;
  N_VScale(1.0, b, x);
  const int ok = klu_l_solve(c.symbolic, c.numeric, c.n, 1, N_VGetArrayPointer(x), &c.common);
  return c.last_flag = ok == 1 ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

// --- copies of the analysis and the factors (assign_kept_klu) -------------------------------
// The layout is klu.h's; the sizes are those klu_l_free_symbolic and klu_l_free_numeric free
// with (KLU 1.3 and later), so that a copy made here is released by them. Real KLU stores
// its factors in Units of one double (klu_version.h: Unit, Entry).
using Long = SuiteSparse_long;
using Unit = double;

template <class T>
void copy_n(T* dst, const T* src, std::size_t count) {
  if (count > 0) std::memcpy(dst, src, count * sizeof(T));
}

template <class T>
T* allocate(std::size_t count, klu_l_common& common) {
  auto* p = static_cast<T*>(klu_l_malloc(std::max<std::size_t>(count, 1), sizeof(T), &common));
  if (!p) throw std::bad_alloc();
  return p;
}

/// A symbolic object of order n (values not set), released by klu_l_free_symbolic.
klu_l_symbolic* allocate_symbolic(Long n_long, klu_l_common& common) {
  const auto n = static_cast<std::size_t>(n_long);
  auto* S = allocate<klu_l_symbolic>(1, common);
  std::memset(static_cast<void*>(S), 0, sizeof(klu_l_symbolic));
  S->n = n_long;
  try {
    S->P = allocate<Long>(n, common);
    S->Q = allocate<Long>(n, common);
    S->R = allocate<Long>(n + 1, common);
    S->Lnz = allocate<double>(n, common);
  } catch (...) {
    klu_l_free_symbolic(&S, &common);
    throw;
  }
  return S;
}

/// dst := src (the analysis: orderings, blocks, estimates), in dst's arrays when of the same n.
void copy_symbolic(klu_l_symbolic*& dst, const klu_l_symbolic& src, klu_l_common& common) {
  if (dst && dst->n != src.n) klu_l_free_symbolic(&dst, &common);
  if (!dst) dst = allocate_symbolic(src.n, common);
  const auto n = static_cast<std::size_t>(src.n);
  Long *P = dst->P, *Q = dst->Q, *R = dst->R;
  double* Lnz = dst->Lnz;
  *dst = src;
  dst->P = P, dst->Q = Q, dst->R = R, dst->Lnz = Lnz;
  copy_n(P, src.P, n);
  copy_n(Q, src.Q, n);
  copy_n(R, src.R, n + 1);
  copy_n(Lnz, src.Lnz, n);
}

/// Whether dst's arrays can hold src's factors: the same block structure (from the same
/// analysis) and every factor block at least as large.
bool numeric_fits(const klu_l_numeric& dst, const klu_l_numeric& src) {
  if (dst.n != src.n || dst.nblocks != src.nblocks || dst.nzoff != src.nzoff ||
      dst.worksize != src.worksize || (dst.Rs == nullptr) != (src.Rs == nullptr) ||
      (dst.Iwork == nullptr) != (src.Iwork == nullptr))
    return false;
  for (Long b = 0; b < src.nblocks; ++b)
    if (src.LUbx[b] && (!dst.LUbx[b] || dst.LUsize[b] < src.LUsize[b])) return false;
  return true;
}

/// A numeric object with src's array sizes (values not set), released by klu_l_free_numeric.
klu_l_numeric* allocate_numeric(const klu_l_numeric& src, klu_l_common& common) {
  const auto n = static_cast<std::size_t>(src.n), nb = static_cast<std::size_t>(src.nblocks);
  const auto nzoff = static_cast<std::size_t>(src.nzoff);
  auto* N = allocate<klu_l_numeric>(1, common);
  std::memset(static_cast<void*>(N), 0, sizeof(klu_l_numeric));
  N->n = src.n, N->nblocks = src.nblocks, N->nzoff = src.nzoff;  // what the free reads
  try {
    N->Pnum = allocate<Long>(n, common);
    N->Pinv = allocate<Long>(n, common);
    N->Lip = allocate<Long>(n, common);
    N->Uip = allocate<Long>(n, common);
    N->Llen = allocate<Long>(n, common);
    N->Ulen = allocate<Long>(n, common);
    N->LUsize = allocate<std::size_t>(nb, common);
    N->LUbx = allocate<void*>(nb, common);
    for (std::size_t b = 0; b < nb; ++b) N->LUbx[b] = nullptr, N->LUsize[b] = 0;
    for (std::size_t b = 0; b < nb; ++b) {
      if (!src.LUbx[b]) continue;
      N->LUbx[b] = allocate<Unit>(src.LUsize[b], common);
      N->LUsize[b] = src.LUsize[b];
    }
    N->Udiag = allocate<Unit>(n, common);
    if (src.Rs) N->Rs = allocate<double>(n, common);
    N->worksize = src.worksize;
    N->Work = klu_l_malloc(src.worksize, 1, &common);
    if (!N->Work) throw std::bad_alloc();
    N->Offp = allocate<Long>(n + 1, common);
    N->Offi = allocate<Long>(nzoff + 1, common);
    N->Offx = allocate<Unit>(nzoff + 1, common);
  } catch (...) {
    klu_l_free_numeric(&N, &common);
    throw;
  }
  return N;
}

/// dst := src (factors, pivots, scale factors, off-diagonal blocks), in dst's arrays when they
/// fit, else in a new object. The workspace is not copied: klu_l_solve and klu_l_refactor
/// write it before they read it.
void copy_numeric(klu_l_numeric*& dst, const klu_l_numeric& src, klu_l_common& common) {
  if (dst && !numeric_fits(*dst, src)) klu_l_free_numeric(&dst, &common);
  if (!dst) dst = allocate_numeric(src, common);
  const auto n = static_cast<std::size_t>(src.n);
  dst->lnz = src.lnz, dst->unz = src.unz;
  dst->max_lnz_block = src.max_lnz_block, dst->max_unz_block = src.max_unz_block;
  copy_n(dst->Pnum, src.Pnum, n);
  copy_n(dst->Pinv, src.Pinv, n);
  copy_n(dst->Lip, src.Lip, n);
  copy_n(dst->Uip, src.Uip, n);
  copy_n(dst->Llen, src.Llen, n);
  copy_n(dst->Ulen, src.Ulen, n);
  for (Long b = 0; b < src.nblocks; ++b)
    if (src.LUbx[b])
      copy_n(static_cast<Unit*>(dst->LUbx[b]), static_cast<const Unit*>(src.LUbx[b]),
             src.LUsize[b]);
  copy_n(static_cast<Unit*>(dst->Udiag), static_cast<const Unit*>(src.Udiag), n);
  if (src.Rs) copy_n(dst->Rs, src.Rs, n);
  // Xwork and Iwork alias into Work (klu_factor): the same offsets.
  dst->Xwork = static_cast<char*>(dst->Work) +
               (static_cast<const char*>(src.Xwork) - static_cast<const char*>(src.Work));
  if (src.Iwork)
    dst->Iwork = reinterpret_cast<Long*>(
        static_cast<char*>(dst->Work) + (reinterpret_cast<const char*>(src.Iwork) -
                                         static_cast<const char*>(src.Work)));
  copy_n(dst->Offp, src.Offp, n + 1);
  copy_n(dst->Offi, src.Offi, static_cast<std::size_t>(src.nzoff));
  copy_n(static_cast<Unit*>(dst->Offx), static_cast<const Unit*>(src.Offx),
         static_cast<std::size_t>(src.nzoff));
}

}  // namespace

SUNLinearSolver make_kept_klu_solver(long n, SUNContext ctx, bool natural_order,
                                     bool keep_factors) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  auto* c = new (std::nothrow) Content;
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  c->n = n;
  c->keep_factors = keep_factors;
  klu_l_defaults(&c->common);
  // KLU: 0 AMD, 1 COLAMD, 2 no P and Q given (klu_analyze takes the natural order)
  if (natural_order) c->common.ordering = 2;
  install_direct_solver(S, c, {initialize, setup, solve});
  return S;
}

KeptKluCounts kept_klu_counts(SUNLinearSolver S) { return content(S).counts; }

void assign_kept_klu(SUNLinearSolver dst, SUNLinearSolver src) {
  Content& d = content(dst);
  const Content& s = content(src);
  if (&d == &s) return;
  if (d.n != s.n) throw std::invalid_argument("assign_kept_klu: solvers of different sizes");
  if (s.symbolic)
    copy_symbolic(d.symbolic, *s.symbolic, d.common);
  else if (d.symbolic)
    klu_l_free_symbolic(&d.symbolic, &d.common);
  if (s.numeric)
    copy_numeric(d.numeric, *s.numeric, d.common);
  else if (d.numeric)
    klu_l_free_numeric(&d.numeric, &d.common);
  d.factorised = s.factorised;  // same size after the first copy: no allocation
  d.last_flag = s.last_flag;
  d.counts = s.counts;
}

}  // namespace rodlab::solvers::sundials
