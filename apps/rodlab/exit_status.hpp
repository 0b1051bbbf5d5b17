#pragma once
// Exit statuses of the rodlab command line (interface spec section 2).

namespace rodlab::cli {

enum ExitStatus : int {
  kSolved = 0,        ///< solved; for `validate`: every check passed
  kNotConverged = 1,  ///< did not converge or went unstable (a result file is still written);
                      ///< for `validate`: some check failed
  kFailed = 1,        ///< a result or report file could not be written (disk full, directory
                      ///< removed while running); the message names the file and the reason
  kBadInput = 2,      ///< bad input or usage; nothing is written
};

}  // namespace rodlab::cli
