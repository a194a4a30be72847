// XML escaping for the JUnit reports of `dqskin diff` (internal to lib/diff).
#pragma once

#include <string>

namespace dqskin::diff_detail {

// XML text or attribute value: markup escaped, invalid UTF-8 and the control characters XML 1.0 cannot hold
// replaced by U+FFFD, line breaks kept (as character references in attributes).
std::string xml(const std::string& text, bool attribute);

}  // namespace dqskin::diff_detail
