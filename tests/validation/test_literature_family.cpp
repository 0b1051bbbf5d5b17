#define BOOST_TEST_MODULE validation_literature_family
// The "literature" family of `rodlab validate` in its quick form (about 1 s), in the unit suite:
// every benchmark passes its stated tolerance (docs/validation.md "literature"), every data set
// carries a figure, and the headline of each benchmark is in the summary topic. A change to a
// scheme that breaks a classic benchmark fails `make test`, not only `make validate`.
#include <boost/test/unit_test.hpp>

#include <set>
#include <string>

#include "checks/check.hpp"

using namespace rodlab::validation;

BOOST_AUTO_TEST_CASE(quick_literature_family_passes) {
  DataSink sink;
  ValidationContext context;
  context.sink = &sink;
  const auto checks = literature_checks(context);
  BOOST_TEST(checks.size() >= 25u);
  int headlines = 0;
  std::set<std::string> benchmarks;
  for (const auto& c : checks) {
    BOOST_TEST(c.passed, c.name << ": measured " << c.measured << ", " << c.detail);
    if (c.topic == "literature") ++headlines;
    benchmarks.insert(c.name.substr(0, c.name.find_first_of(",:(")));
  }
  BOOST_TEST(headlines >= 7);
  for (const char* b : {"self-weight elastica ", "post-buckled elastica", "Euler clamped-free ",
                        "45-degree bend", "free vibration", "localised helical buckle ",
                        "Greenhill pinned shaft "})
    BOOST_TEST(benchmarks.count(b) == 1u, b);
  BOOST_TEST(sink.data_sets.size() == 7u);
  for (const auto& d : sink.data_sets) {
    BOOST_TEST(!d.rows.empty(), d.name);
    BOOST_TEST(d.figures.size() == 1u, d.name);
  }
}
