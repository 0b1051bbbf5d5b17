#include "availability.hpp"

#include <string>

#include "errors.hpp"

namespace rodlab::cli {

void require_available(std::string_view arrives) {
  if (arrives.empty()) return;
  throw NotAvailable("not available yet; it arrives with " + std::string(arrives));
}

}  // namespace rodlab::cli
