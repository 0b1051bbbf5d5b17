#define BOOST_TEST_MODULE common_serial_vector_ops
#include <boost/test/unit_test.hpp>

// The compiled serial N_Vector operations (solvers/common/serial_vector_ops.hpp) against the
// library's own (Debian's SUNDIALS, N_VNew_Serial's ops table), on the same inputs: every
// operation, every special case of N_VLinearSum and N_VScale (including aliased outputs), zeros,
// negative and non-finite entries. Reference: the library; tolerance: none (bit for bit, which is
// what keeps every IDA and KINSOL result unchanged).
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

// private to solvers/common (the SUNDIALS adapters' own header)
#include "../../solvers/common/serial_vector_ops.hpp"

namespace {

constexpr sunindextype kLength = 37;  // odd: no vector width divides it

struct Context {
  SUNContext ctx = nullptr;
  Context() { BOOST_REQUIRE(SUNContext_Create(nullptr, &ctx) == 0); }
  ~Context() { SUNContext_Free(&ctx); }
};

struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;

/// The same operation on library vectors (reference) and compiled-ops vectors (tested).
struct Pair {
  std::vector<Vector> library, compiled;
};

Pair make_pair(SUNContext ctx, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  Pair p;
  Vector first(N_VNew_Serial(kLength, ctx));
  rodlab::solvers::sundials::use_compiled_serial_ops(first.get());
  for (int k = 0; k < count; ++k) {
    p.library.emplace_back(N_VNew_Serial(kLength, ctx));
    // the first carries the compiled operations; the others are its clones (they inherit them)
    p.compiled.emplace_back(k == 0 ? first.release() : N_VClone(p.compiled[0].get()));
    double* a = N_VGetArrayPointer(p.library.back().get());
    for (sunindextype i = 0; i < kLength; ++i) a[i] = u(rng);
    a[3] = 0.0;
    a[5] = -a[6];
    std::memcpy(N_VGetArrayPointer(p.compiled.back().get()), a, kLength * sizeof(double));
  }
  return p;
}

N_Vector L(const Pair& p, int k) { return p.library[k].get(); }
N_Vector C(const Pair& p, int k) { return p.compiled[k].get(); }

/// Bit-for-bit equality of vector k in both sets.
void require_same(const Pair& p, int k) {
  const double* a = N_VGetArrayPointer(L(p, k));
  const double* b = N_VGetArrayPointer(C(p, k));
  BOOST_REQUIRE(std::memcmp(a, b, kLength * sizeof(double)) == 0);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

BOOST_AUTO_TEST_CASE(the_ops_are_installed_and_inherited_by_clones) {
  Context c;
  Pair p = make_pair(c.ctx, 2, 1);
  BOOST_TEST(C(p, 0)->ops->nvwrmsnorm != L(p, 0)->ops->nvwrmsnorm);
  BOOST_TEST(C(p, 1)->ops->nvwrmsnorm == C(p, 0)->ops->nvwrmsnorm);
  BOOST_TEST(C(p, 0)->ops->nvlinearcombination == nullptr);  // fused ops stay off
}

BOOST_AUTO_TEST_CASE(linear_sum_every_form) {
  Context c;
  const double coefficients[] = {1.0, -1.0, 0.0, 0.5, -0.5, 2.0, -3.25};
  unsigned seed = 10;
  for (double a : coefficients)
    for (double b : coefficients)
      for (int alias = 0; alias < 3; ++alias) {  // z separate, z = x, z = y
        BOOST_TEST_CONTEXT("a = " << a << ", b = " << b << ", alias " << alias) {
          Pair p = make_pair(c.ctx, 3, ++seed);
          const int z = alias == 0 ? 2 : alias - 1;
          N_VLinearSum(a, L(p, 0), b, L(p, 1), L(p, z));
          N_VLinearSum(a, C(p, 0), b, C(p, 1), C(p, z));
          require_same(p, z);
        }
      }
}

BOOST_AUTO_TEST_CASE(element_wise_operations) {
  Context c;
  for (double s : {1.0, -1.0, 0.0, 0.75, -4.5}) {
    for (int alias = 0; alias < 2; ++alias) {
      Pair p = make_pair(c.ctx, 2, 100 + alias);
      const int z = alias == 0 ? 1 : 0;
      N_VScale(s, L(p, 0), L(p, z));
      N_VScale(s, C(p, 0), C(p, z));
      require_same(p, z);
    }
    Pair p = make_pair(c.ctx, 2, 200);
    N_VConst(s, L(p, 1)), N_VConst(s, C(p, 1));
    require_same(p, 1);
    N_VAddConst(L(p, 0), s, L(p, 1)), N_VAddConst(C(p, 0), s, C(p, 1));
    require_same(p, 1);
    N_VCompare(std::abs(s), L(p, 0), L(p, 1)), N_VCompare(std::abs(s), C(p, 0), C(p, 1));
    require_same(p, 1);
  }
  Pair p = make_pair(c.ctx, 3, 300);
  N_VProd(L(p, 0), L(p, 1), L(p, 2)), N_VProd(C(p, 0), C(p, 1), C(p, 2));
  require_same(p, 2);
  N_VDiv(L(p, 0), L(p, 1), L(p, 2)), N_VDiv(C(p, 0), C(p, 1), C(p, 2));  // includes x / 0
  require_same(p, 2);
  N_VAbs(L(p, 0), L(p, 2)), N_VAbs(C(p, 0), C(p, 2));
  require_same(p, 2);
  N_VInv(L(p, 1), L(p, 2)), N_VInv(C(p, 1), C(p, 2));
  require_same(p, 2);
  // InvTest: a zero entry leaves z_i untouched and answers false
  const bool library = N_VInvTest(L(p, 0), L(p, 2)), compiled = N_VInvTest(C(p, 0), C(p, 2));
  BOOST_TEST(library == compiled);
  BOOST_TEST(!compiled);
  require_same(p, 2);
}

BOOST_AUTO_TEST_CASE(reductions) {
  Context c;
  Pair p = make_pair(c.ctx, 3, 400);
  double* mask_l = N_VGetArrayPointer(L(p, 2));
  double* mask_c = N_VGetArrayPointer(C(p, 2));
  for (sunindextype i = 0; i < kLength; ++i) mask_l[i] = mask_c[i] = (i % 3 == 0) ? 0.0 : 1.0;
  auto check = [](double a, double b) {
    BOOST_TEST_CONTEXT(a << " against " << b) { BOOST_TEST(same_bits(a, b)); }
  };
  check(N_VDotProd(L(p, 0), L(p, 1)), N_VDotProd(C(p, 0), C(p, 1)));
  check(N_VMaxNorm(L(p, 0)), N_VMaxNorm(C(p, 0)));
  check(N_VWrmsNorm(L(p, 0), L(p, 1)), N_VWrmsNorm(C(p, 0), C(p, 1)));
  check(N_VWrmsNormMask(L(p, 0), L(p, 1), L(p, 2)), N_VWrmsNormMask(C(p, 0), C(p, 1), C(p, 2)));
  check(N_VWSqrSumLocal(L(p, 0), L(p, 1)), N_VWSqrSumLocal(C(p, 0), C(p, 1)));
  check(N_VWSqrSumMaskLocal(L(p, 0), L(p, 1), L(p, 2)),
        N_VWSqrSumMaskLocal(C(p, 0), C(p, 1), C(p, 2)));
  check(N_VMin(L(p, 0)), N_VMin(C(p, 0)));
  check(N_VWL2Norm(L(p, 0), L(p, 1)), N_VWL2Norm(C(p, 0), C(p, 1)));
  check(N_VL1Norm(L(p, 0)), N_VL1Norm(C(p, 0)));
  check(N_VMinQuotient(L(p, 0), L(p, 1)), N_VMinQuotient(C(p, 0), C(p, 1)));
  check(N_VMinQuotient(L(p, 0), L(p, 2)), N_VMinQuotient(C(p, 0), C(p, 2)));  // zeros skipped
  // every denominator zero: SUNDIALS' big real
  N_VConst(0.0, L(p, 2)), N_VConst(0.0, C(p, 2));
  check(N_VMinQuotient(L(p, 0), L(p, 2)), N_VMinQuotient(C(p, 0), C(p, 2)));
  // a NaN entry: skipped by the max norm in both
  N_VGetArrayPointer(L(p, 0))[7] = N_VGetArrayPointer(C(p, 0))[7] =
      std::numeric_limits<double>::quiet_NaN();
  check(N_VMaxNorm(L(p, 0)), N_VMaxNorm(C(p, 0)));
}

BOOST_AUTO_TEST_CASE(constraint_mask) {
  Context c;
  Pair p = make_pair(c.ctx, 3, 500);
  const double kinds[] = {0.0, 1.0, -1.0, 2.0, -2.0};
  double* cl = N_VGetArrayPointer(L(p, 1));
  double* cc = N_VGetArrayPointer(C(p, 1));
  for (sunindextype i = 0; i < kLength; ++i) cl[i] = cc[i] = kinds[i % 5];
  const bool library = N_VConstrMask(L(p, 1), L(p, 0), L(p, 2));
  const bool compiled = N_VConstrMask(C(p, 1), C(p, 0), C(p, 2));
  BOOST_TEST(library == compiled);
  BOOST_TEST(!compiled);  // random signs violate some
  require_same(p, 2);
  // all satisfied
  N_VAbs(L(p, 0), L(p, 0)), N_VAbs(C(p, 0), C(p, 0));
  N_VAbs(L(p, 1), L(p, 1)), N_VAbs(C(p, 1), C(p, 1));
  BOOST_TEST(N_VConstrMask(C(p, 1), C(p, 0), C(p, 2)) ==
             N_VConstrMask(L(p, 1), L(p, 0), L(p, 2)));
  require_same(p, 2);
}
