// XML and HTML escaping (internal to the library): the JUnit reports of `dqskin diff` and `dqskin lint`, and
// the HTML page of `dqskin report`. HTML5 accepts the same references, &apos; included.
#pragma once

#include <string>

namespace dqskin::io {

// XML (or HTML) text or attribute value: markup escaped, invalid UTF-8 and the control characters XML 1.0
// cannot hold replaced by U+FFFD, line breaks kept (as character references in attributes).
std::string xml(const std::string& text, bool attribute);

}  // namespace dqskin::io
