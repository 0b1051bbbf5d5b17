#include "serial_vector_ops.hpp"

#include <cmath>

namespace rodlab::solvers::sundials {
namespace {

// Each kernel follows the definition of the SUNDIALS serial operation of the same name (SUNDIALS
// 6 user guide, "Description of the NVECTOR operations"), element by element in index order.

struct Data {
  sunindextype n;
  realtype* d;
};
Data data(N_Vector v) { return {NV_LENGTH_S(v), NV_DATA_S(v)}; }

// --- element-wise ----------------------------------------------------------------------------

/// z = f(x_i, y_i) for every i; f is inlined.
template <class F>
void zip(N_Vector x, N_Vector y, N_Vector z, F f) {
  const auto [n, xd] = data(x);
  const realtype* yd = NV_DATA_S(y);
  realtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = f(xd[i], yd[i]);
}

template <class F>
void map(N_Vector x, N_Vector z, F f) {
  const auto [n, xd] = data(x);
  realtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = f(xd[i]);
}

/// y += a x, with SUNDIALS' a = +-1 forms.
void axpy(realtype a, N_Vector x, N_Vector y) {
  if (a == 1.0) return zip(x, y, y, [](realtype u, realtype v) { return v + u; });
  if (a == -1.0) return zip(x, y, y, [](realtype u, realtype v) { return v - u; });
  zip(x, y, y, [a](realtype u, realtype v) { return v + a * u; });
}

/// z = a x + b y, dispatched to the same special forms as SUNDIALS (their roundings differ:
/// c (x + y) is not c x + c y).
void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  if (b == 1.0 && z == y) return axpy(a, x, y);
  if (a == 1.0 && z == x) return axpy(b, y, x);
  if (a == 1.0 && b == 1.0) return zip(x, y, z, [](realtype u, realtype v) { return u + v; });
  if (a == 1.0 && b == -1.0) return zip(x, y, z, [](realtype u, realtype v) { return u - v; });
  if (a == -1.0 && b == 1.0) return zip(y, x, z, [](realtype u, realtype v) { return u - v; });
  if (a == 1.0)  // z = b y + x
    return zip(y, x, z, [b](realtype u, realtype v) { return (b * u) + v; });
  if (b == 1.0)  // z = a x + y
    return zip(x, y, z, [a](realtype u, realtype v) { return (a * u) + v; });
  if (a == -1.0)  // z = b y - x
    return zip(y, x, z, [b](realtype u, realtype v) { return (b * u) - v; });
  if (b == -1.0)  // z = a x - y
    return zip(x, y, z, [a](realtype u, realtype v) { return (a * u) - v; });
  if (a == b) return zip(x, y, z, [a](realtype u, realtype v) { return a * (u + v); });
  if (a == -b) return zip(x, y, z, [a](realtype u, realtype v) { return a * (u - v); });
  zip(x, y, z, [a, b](realtype u, realtype v) { return (a * u) + (b * v); });
}

void constant(realtype c, N_Vector z) {
  const auto [n, zd] = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

void product(N_Vector x, N_Vector y, N_Vector z) {
  zip(x, y, z, [](realtype u, realtype v) { return u * v; });
}

void quotient(N_Vector x, N_Vector y, N_Vector z) {
  zip(x, y, z, [](realtype u, realtype v) { return u / v; });
}

void scale(realtype c, N_Vector x, N_Vector z) {
  if (z == x) return map(x, x, [c](realtype u) { return u * c; });
  if (c == 1.0) return map(x, z, [](realtype u) { return u; });
  if (c == -1.0) return map(x, z, [](realtype u) { return -u; });
  map(x, z, [c](realtype u) { return c * u; });
}

void absolute(N_Vector x, N_Vector z) {
  map(x, z, [](realtype u) { return std::abs(u); });
}

void inverse(N_Vector x, N_Vector z) {
  map(x, z, [](realtype u) { return 1.0 / u; });
}

void add_constant(N_Vector x, realtype b, N_Vector z) {
  map(x, z, [b](realtype u) { return u + b; });
}

void compare(realtype c, N_Vector x, N_Vector z) {
  map(x, z, [c](realtype u) { return std::abs(u) >= c ? 1.0 : 0.0; });
}

booleantype inverse_test(N_Vector x, N_Vector z) {
  const auto [n, xd] = data(x);
  realtype* zd = NV_DATA_S(z);
  booleantype no_zero = SUNTRUE;
  for (sunindextype i = 0; i < n; ++i) {
    if (xd[i] == 0.0)
      no_zero = SUNFALSE;
    else
      zd[i] = 1.0 / xd[i];
  }
  return no_zero;
}

/// m_i = 1 where x_i violates the constraint c_i (|c| = 2: x > 0, 1: x >= 0, -1: x <= 0,
/// -2: x < 0), else 0; true when none does.
booleantype constraint_mask(N_Vector c, N_Vector x, N_Vector m) {
  const auto [n, xd] = data(x);
  const realtype* cd = NV_DATA_S(c);
  realtype* md = NV_DATA_S(m);
  bool violated = false;
  for (sunindextype i = 0; i < n; ++i) {
    md[i] = 0.0;
    if (cd[i] == 0.0) continue;
    const realtype xc = xd[i] * cd[i];
    if ((std::abs(cd[i]) > 1.5 && xc <= 0.0) || (std::abs(cd[i]) > 0.5 && xc < 0.0)) {
      md[i] = 1.0;
      violated = true;
    }
  }
  return violated ? SUNFALSE : SUNTRUE;
}

// --- reductions (one accumulator, index order: the library's rounding) -----------------------

realtype dot(N_Vector x, N_Vector y) {
  const auto [n, xd] = data(x);
  const realtype* yd = NV_DATA_S(y);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

realtype max_norm(N_Vector x) {
  const auto [n, xd] = data(x);
  realtype max = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (std::abs(xd[i]) > max) max = std::abs(xd[i]);  // a NaN is skipped, as in SUNDIALS
  return max;
}

realtype weighted_square_sum(N_Vector x, N_Vector w) {
  const auto [n, xd] = data(x);
  const realtype* wd = NV_DATA_S(w);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const realtype p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}

realtype weighted_square_sum_masked(N_Vector x, N_Vector w, N_Vector id) {
  const auto [n, xd] = data(x);
  const realtype* wd = NV_DATA_S(w);
  const realtype* idd = NV_DATA_S(id);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    if (idd[i] > 0.0) {
      const realtype p = xd[i] * wd[i];
      sum += p * p;
    }
  }
  return sum;
}

realtype wrms_norm(N_Vector x, N_Vector w) {
  return std::sqrt(weighted_square_sum(x, w) / static_cast<realtype>(NV_LENGTH_S(x)));
}

realtype wrms_norm_masked(N_Vector x, N_Vector w, N_Vector id) {
  return std::sqrt(weighted_square_sum_masked(x, w, id) / static_cast<realtype>(NV_LENGTH_S(x)));
}

realtype weighted_l2_norm(N_Vector x, N_Vector w) { return std::sqrt(weighted_square_sum(x, w)); }

realtype minimum(N_Vector x) {
  const auto [n, xd] = data(x);
  realtype min = xd[0];
  for (sunindextype i = 1; i < n; ++i)
    if (xd[i] < min) min = xd[i];
  return min;
}

realtype l1_norm(N_Vector x) {
  const auto [n, xd] = data(x);
  realtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += std::abs(xd[i]);
  return sum;
}

/// min over denom_i != 0 of num_i / denom_i; BIG_REAL when every denominator is zero.
realtype min_quotient(N_Vector num, N_Vector denom) {
  const auto [n, nd] = data(num);
  const realtype* dd = NV_DATA_S(denom);
  bool first = true;
  realtype min = BIG_REAL;
  for (sunindextype i = 0; i < n; ++i) {
    if (dd[i] == 0.0) continue;
    const realtype q = nd[i] / dd[i];
    min = first ? q : (min < q ? min : q);  // SUNMIN(min, q)
    first = false;
  }
  return min;
}

}  // namespace

void use_compiled_serial_ops(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvdiv = quotient;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = add_constant;
  ops->nvdotprod = dot;
  ops->nvmaxnorm = max_norm;
  ops->nvwrmsnorm = wrms_norm;
  ops->nvwrmsnormmask = wrms_norm_masked;
  ops->nvmin = minimum;
  ops->nvwl2norm = weighted_l2_norm;
  ops->nvl1norm = l1_norm;
  ops->nvcompare = compare;
  ops->nvinvtest = inverse_test;
  ops->nvconstrmask = constraint_mask;
  ops->nvminquotient = min_quotient;
  // the "local" reductions (the same on one process)
  ops->nvdotprodlocal = dot;
  ops->nvmaxnormlocal = max_norm;
  ops->nvminlocal = minimum;
  ops->nvl1normlocal = l1_norm;
  ops->nvinvtestlocal = inverse_test;
  ops->nvconstrmasklocal = constraint_mask;
  ops->nvminquotientlocal = min_quotient;
  ops->nvwsqrsumlocal = weighted_square_sum;
  ops->nvwsqrsummasklocal = weighted_square_sum_masked;
}

}  // namespace rodlab::solvers::sundials
