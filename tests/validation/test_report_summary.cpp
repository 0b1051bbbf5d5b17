#define BOOST_TEST_MODULE report_summary
#include <boost/test/unit_test.hpp>

// The report leads with what a reader cites (report/summary.hpp): the headline checks by topic,
// then the families, a family of many routine checks folded away after the others. Reference:
// a hand-made report whose summary and order are known.

#include <string>

#include "report/report.hpp"
#include "report/summary.hpp"

namespace v = rodlab::validation;

namespace {

v::ValidationReport hand_made() {
  v::ValidationReport r;
  r.mode = "quick";
  r.families = {{"scenes", "section properties"}, {"statics", "orders"}};
  for (int i = 0; i < 50; ++i) {
    v::Check c = v::relative_check("scene check " + std::to_string(i), 1.0, 1.0, 1e-12, "closed form");
    c.family = "scenes";
    r.checks.push_back(c);
  }
  v::Check order = v::with_topic(
      v::relative_check("rk4 observed order", 4.02, 4.0, 0.04, "design order"), "order");
  order.family = "statics";
  v::Check plain = v::relative_check("statics detail", 1.0, 1.0, 0.1, "closed form");
  plain.family = "statics";
  r.checks.push_back(order);
  r.checks.push_back(plain);
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(topics_collect_the_headline_checks) {
  const auto r = hand_made();
  const auto orders = v::topic_checks(r, "order");
  BOOST_TEST_REQUIRE(orders.size() == 1u);
  BOOST_TEST(orders.front()->name == "rk4 observed order");
  BOOST_TEST(v::topic_checks(r, "energy").empty());
}

BOOST_AUTO_TEST_CASE(large_families_fold_and_come_last) {
  const auto r = hand_made();
  BOOST_TEST(v::folded(r, "scenes"));
  BOOST_TEST(!v::folded(r, "statics"));
  const auto order = v::report_order(r);
  BOOST_TEST_REQUIRE(order.size() == 2u);
  BOOST_TEST(order[0].name == "statics");
  BOOST_TEST(order[1].name == "scenes");
}

BOOST_AUTO_TEST_CASE(html_and_markdown_lead_with_the_summary) {
  const auto r = hand_made();
  const std::string html = v::to_html(r, "/nonexistent");
  const auto summary = html.find("id=\"summary\"");
  BOOST_TEST_REQUIRE(summary != std::string::npos);
  BOOST_TEST(summary < html.find("id=\"family-statics\""));
  BOOST_TEST(html.find("id=\"family-statics\"") < html.find("id=\"family-scenes\""));
  BOOST_TEST(html.find("<details><summary>50 checks</summary>") != std::string::npos);
  BOOST_TEST(html.find("rk4 observed order", summary) < html.find("id=\"family-statics\""));
  const std::string md = v::to_markdown(r);
  BOOST_TEST(md.find("## Summary") < md.find("## statics"));
  BOOST_TEST(md.find("## statics") < md.find("## scenes"));
  const std::string json = v::to_json(r);
  BOOST_TEST(json.find("\"topic\": \"order\"") != std::string::npos);
}
