// rodlab::load_module (rodlab/module.hpp): the modules rodlab opens only when a run needs them.
// References: the Ceres module's own table (control/ceres_module.hpp) solving a bounded linear
// least-squares problem with a closed-form answer, and the loader's report of what it tried.
#define BOOST_TEST_MODULE load_module
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "../../solvers/control/ceres_module.hpp"
#include "rodlab/module.hpp"

namespace fs = std::filesystem;

namespace {

// r(x) = x - c, |x_k| <= 1: the minimiser is c clamped to the box.
constexpr double kTarget[2] = {0.5, 3.0};

int evaluate(void*, const double* x, double* r, double* jacobian) {
  for (int k = 0; k < 2; ++k) r[k] = x[k] - kTarget[k];
  if (jacobian) jacobian[0] = 1.0, jacobian[1] = 0.0, jacobian[2] = 0.0, jacobian[3] = 1.0;
  return 1;
}
int never_stop(void*, double) { return 0; }

}  // namespace

BOOST_AUTO_TEST_CASE(the_ceres_module_loads_from_the_build_and_solves) {
  std::string why;
  const auto* api =
      rodlab::load_module_api<RodlabCeresApi>(RODLAB_CERES_MODULE_FILE, kRodlabCeresApiSymbol, why);
  BOOST_TEST_CONTEXT(why) { BOOST_REQUIRE(api != nullptr); }
  double x[2] = {0.0, 0.0}, lower[2] = {-1.0, -1.0}, upper[2] = {1.0, 1.0};
  const RodlabLeastSquares problem{2,    2,   x, lower, upper, &evaluate, &never_stop, nullptr,
                                   1e12, 50, 1e-14, 1e-14, 1e-14};
  RodlabLeastSquaresSummary summary{};
  api->solve(&problem, &summary);
  BOOST_TEST(summary.usable == 1);
  BOOST_TEST(summary.no_convergence == 0);
  BOOST_TEST(x[0] == 0.5, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(x[1] == 1.0, boost::test_tools::tolerance(1e-10));  // on the bound
}

BOOST_AUTO_TEST_CASE(a_missing_module_says_where_it_was_looked_for) {
  std::string why;
  const fs::path missing = fs::temp_directory_path() / "rodlab-no-such-module.so";
  BOOST_TEST(rodlab::load_module(missing.string(), "anything", why) == nullptr);
  BOOST_TEST_CONTEXT(why) {
    BOOST_TEST(why.find(missing.string()) != std::string::npos);
    // the program's ../lib, where the build tree keeps the modules
    BOOST_TEST(why.find("/lib/rodlab-no-such-module.so") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(a_module_without_the_symbol_is_named) {
  std::string why;
  BOOST_TEST(rodlab::load_module(RODLAB_CERES_MODULE_FILE, "rodlab_no_such_table", why) ==
             nullptr);
  BOOST_TEST_CONTEXT(why) {
    BOOST_TEST(why.find("has no rodlab_no_such_table") != std::string::npos);
  }
}
