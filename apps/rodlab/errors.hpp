#pragma once
// The errors a subcommand may throw; main.cpp turns each into a message and exit status 2.
// (Scene problems are rodlab::io::SceneError, from the scene loader.)
#include <stdexcept>
#include <string>
#include <vector>

namespace rodlab::cli {

/// Bad command line: each message names the option and the bad value.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(std::vector<std::string> messages)
      : std::runtime_error(messages.empty() ? std::string("usage error") : messages.front()),
        messages_(std::move(messages)) {}
  explicit UsageError(const std::string& message) : UsageError(std::vector<std::string>{message}) {}
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  std::vector<std::string> messages_;
};

}  // namespace rodlab::cli
