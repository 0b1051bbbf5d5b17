#define BOOST_TEST_MODULE common_check
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "rodlab/check.hpp"
#include "rodlab/rod/material.hpp"
#include "rodlab/rod/section.hpp"

// rodlab/check.hpp: rodlab::format and RODLAB_THROW_UNLESS. Reference: printf's %g text of the
// numbers (exact strings, no tolerance).

namespace {

namespace rod = rodlab::rod;

/// The exception RODLAB_THROW_UNLESS throws for dt, or none.
void check_step(double dt) { RODLAB_THROW_UNLESS(dt > 0.0, "dt must be > 0 (got {:g} s)", dt); }

}  // namespace

BOOST_AUTO_TEST_CASE(format_keeps_small_numbers) {
  BOOST_TEST(rodlab::format("dt = {:g} s", 2.5e-7) == "dt = 2.5e-07 s");
  BOOST_TEST(rodlab::format("{:g} {:g} {:g}", 1.0, 0.1, 1e6) == "1 0.1 1e+06");
  BOOST_TEST(rodlab::format("{:.3g}", 3.14159e-12) == "3.14e-12");
  BOOST_TEST(rodlab::format("node {} of {}: {}", 3, std::size_t{20}, std::string("ok")) ==
             "node 3 of 20: ok");
  BOOST_TEST(rodlab::format("no arguments") == "no arguments");
}

BOOST_AUTO_TEST_CASE(throw_unless_passes_when_the_condition_holds) {
  BOOST_CHECK_NO_THROW(check_step(1e-3));
  int evaluated = 0;
  auto count = [&] { return ++evaluated; };
  RODLAB_THROW_UNLESS(true, "never formatted {}", count());
  BOOST_TEST(evaluated == 0);  // the arguments are evaluated only on failure
}

BOOST_AUTO_TEST_CASE(throw_unless_throws_invalid_argument_with_the_message) {
  BOOST_CHECK_THROW(check_step(-2.5e-7), std::invalid_argument);
  try {
    check_step(-2.5e-7);
    BOOST_FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()) == "dt must be > 0 (got -2.5e-07 s)");  // message alone
  }
}

BOOST_AUTO_TEST_CASE(throw_unless_carries_the_condition) {
  try {
    check_step(0.0);
    BOOST_FAIL("no exception");
  } catch (const rodlab::CheckFailure& e) {
    BOOST_TEST(std::string(e.condition()) == "dt > 0.0");
    BOOST_TEST(std::strstr(e.file(), "test_check.cpp") != nullptr);
    BOOST_TEST(e.line() > 0);
    BOOST_TEST(std::string(e.what()) == "dt must be > 0 (got 0 s)");
  }
  // A NaN fails a condition written as what must hold.
  BOOST_CHECK_THROW(check_step(std::nan("")), rodlab::CheckFailure);
}

// Converted throws of rodlab::core keep their numbers (std::to_string gave "0.000000", "0.600000").
BOOST_AUTO_TEST_CASE(core_messages_keep_their_numbers) {
  try {
    (void)rod::properties(rod::Section{rod::Circle{-2.5e-7}});
    BOOST_FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()) == "circle diameter must be > 0 (got -2.5e-07)");
  }
  try {
    (void)rod::Material::from_poisson(1e6, 0.6, 1000.0, 0.0);
    BOOST_FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()) == "poisson must be in (-1, 0.5] (got 0.6)");
  }
}
