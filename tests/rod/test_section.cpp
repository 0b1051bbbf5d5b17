#define BOOST_TEST_MODULE section
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rodlab/rod/section.hpp"

using namespace rodlab::rod;
using std::numbers::pi;
namespace tt = boost::test_tools;

// Reference: closed forms for the solid circle, A = pi D^2/4, I = pi D^4/64, J = 2 I.
BOOST_AUTO_TEST_CASE(circle_closed_form) {
  const double D = 0.01;
  const auto p = properties(Circle{D});
  BOOST_TEST(p.A == pi * D * D / 4, tt::tolerance(1e-15));
  BOOST_TEST(p.Ix == pi * std::pow(D, 4) / 64, tt::tolerance(1e-15));
  BOOST_TEST(p.Iy == p.Ix, tt::tolerance(1e-15));
  BOOST_TEST(p.J == pi * std::pow(D, 4) / 32, tt::tolerance(1e-15));
  BOOST_TEST(p.Jt == p.J, tt::tolerance(1e-15));
  BOOST_TEST(outer_radius(Circle{D}) == D / 2, tt::tolerance(1e-15));
  BOOST_TEST(shape_name(Circle{D}) == "circle");
}

// Reference: tube = outer circle minus inner circle (closed forms above).
BOOST_AUTO_TEST_CASE(tube_is_difference_of_circles) {
  const double Do = 0.02, Di = 0.012;
  const auto t = properties(Tube{Do, Di});
  const auto o = properties(Circle{Do});
  const auto i = properties(Circle{Di});
  BOOST_TEST(t.A == o.A - i.A, tt::tolerance(1e-14));
  BOOST_TEST(t.Ix == o.Ix - i.Ix, tt::tolerance(1e-14));
  BOOST_TEST(t.J == o.J - i.J, tt::tolerance(1e-14));
  BOOST_TEST(t.Jt == t.J, tt::tolerance(1e-15));
  const auto solid = properties(Tube{Do, 0.0});
  BOOST_TEST(solid.Ix == o.Ix, tt::tolerance(1e-15));
}

// Reference: bending moments of area w h^3/12 and h w^3/12; polar J = Ix + Iy.
BOOST_AUTO_TEST_CASE(rectangle_second_moments) {
  const double w = 0.03, h = 0.01;
  const auto p = properties(Rectangle{w, h});
  BOOST_TEST(p.A == w * h, tt::tolerance(1e-15));
  BOOST_TEST(p.Ix == w * h * h * h / 12, tt::tolerance(1e-15));
  BOOST_TEST(p.Iy == h * w * w * w / 12, tt::tolerance(1e-15));
  BOOST_TEST(p.J == p.Ix + p.Iy, tt::tolerance(1e-15));
}

// Reference: Timoshenko & Goodier, Theory of Elasticity, table of k1 in Jt = k1 a b^3
// (a >= b): a/b = 1: 0.1406, 2: 0.229, 3: 0.263, 5: 0.291, 10: 0.312 (three digits given,
// hence the 2e-3 relative tolerance), and the thin-strip limit a b^3 / 3 (1 - 0.630 b / a).
BOOST_AUTO_TEST_CASE(rectangle_torsion_constant_matches_literature) {
  const double b = 0.01;
  const std::pair<double, double> table[] = {{1, 0.1406}, {2, 0.229}, {3, 0.263}, {5, 0.291}, {10, 0.312}};
  for (const auto& [ratio, k1] : table) {
    const double a = ratio * b;
    BOOST_TEST(properties(Rectangle{a, b}).Jt == k1 * a * b * b * b, tt::tolerance(2e-3));
    BOOST_TEST(properties(Rectangle{b, a}).Jt == k1 * a * b * b * b, tt::tolerance(2e-3));  // symmetric
  }
  const double a = 100 * b;
  BOOST_TEST(properties(Rectangle{a, b}).Jt == a * b * b * b / 3 * (1 - 0.630 * b / a), tt::tolerance(1e-4));
  // The torsion constant of a square is well below its polar moment (0.1406 vs 1/6 a^4).
  BOOST_TEST(properties(Rectangle{b, b}).Jt < properties(Rectangle{b, b}).J);
}

BOOST_AUTO_TEST_CASE(bad_sizes_throw) {
  BOOST_CHECK_THROW(properties(Circle{0.0}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Circle{-1.0}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Circle{std::nan("")}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Tube{0.01, 0.01}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Tube{0.01, 0.02}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Tube{0.01, -0.001}), std::invalid_argument);
  BOOST_CHECK_THROW(properties(Rectangle{0.01, 0.0}), std::invalid_argument);
}
