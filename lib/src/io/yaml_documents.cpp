#include "yaml_documents.hpp"

#include <sstream>

#include <yaml-cpp/eventhandler.h>

#include "rodlab/check.hpp"

namespace rodlab::io::detail {
namespace {

/// Records where a document's content starts; nothing else.
class ContentStart : public YAML::EventHandler {
 public:
  bool seen = false;
  YAML::Mark mark;

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { note(m); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { note(m); }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                const std::string&) override {
    note(m);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    note(m);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    note(m);
  }
  void OnMapEnd() override {}

 private:
  void note(const YAML::Mark& m) {
    if (!seen) mark = m;
    seen = true;
  }
};

}  // namespace

YamlDocuments read_documents(const std::string& text) {
  YamlDocuments out;
  std::istringstream in(text);
  YAML::Parser parser(in);
  while (true) {
    ContentStart start;
    if (!parser.HandleNextDocument(start)) break;
    if (!out.starts.empty() && start.mark.pos <= out.starts.back().pos) {
      const auto at = static_cast<std::size_t>(start.mark.pos);
      const std::string what =
          at < text.size() ? rodlab::format("'{}'", text[at]) : std::string("end of input");
      throw YAML::ParserException(start.mark,
                                  rodlab::format("unexpected {}: cannot parse past here", what));
    }
    out.starts.push_back(start.mark);
    ++out.count;
  }
  if (out.count > 0) out.first = YAML::Load(text);  // the first document only: no loop
  return out;
}

}  // namespace rodlab::io::detail
