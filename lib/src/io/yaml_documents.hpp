#pragma once
// The YAML documents of a text, read without hanging. yaml-cpp 0.7's YAML::LoadAll loops
// forever (memory growing) when its parser makes no progress: a stray flow indicator at block
// level, e.g. the three bytes ", x", yields the same empty document at the same place again
// and again. Here every document must start past the previous one, else the text is rejected
// at that place.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace rodlab::io::detail {

/// A text's documents: the first as a node, and where every later one starts.
struct YamlDocuments {
  int count = 0;                   ///< 0 for an empty text
  YAML::Node first;                ///< the first document (null when count is 0)
  std::vector<YAML::Mark> starts;  ///< where each document's content starts
};

/// Throws YAML::ParserException (with the place) for malformed YAML, including the texts on
/// which yaml-cpp's parser makes no progress.
YamlDocuments read_documents(const std::string& text);

}  // namespace rodlab::io::detail
