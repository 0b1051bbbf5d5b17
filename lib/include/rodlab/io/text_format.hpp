#pragma once
// Number and list formatting for what rodlab prints (files use full precision instead; see
// rodlab/io/result_writer.hpp).
#include <span>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace rodlab::io {

/// printf "%.6g": 7.85398e-05, 31.6228, 1e+06.
std::string format_number(double value);
/// "[a, b, c]" with format_number.
std::string format_vector(const Eigen::Ref<const Eigen::VectorXd>& v);
/// "a, b, c".
std::string join(std::span<const std::string> items, std::string_view separator = ", ");
/// The text with & < > " as XML/HTML entities (attribute values and element text).
std::string xml_escape(std::string_view text);
/// The text quoted for a POSIX shell when it needs quoting.
std::string shell_quote(std::string_view text);

}  // namespace rodlab::io
