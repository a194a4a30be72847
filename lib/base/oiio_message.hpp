// OpenImageIO's error text as one line for our one-line errors (internal to the image writers and diff).
#pragma once

#include <string>

namespace dqskin {

// Its lines joined by "; ", trailing blanks dropped; a placeholder when OpenImageIO gave no reason.
inline std::string oiio_message(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at)) message.replace(at, 1, "; ");
  return message.empty() ? "OpenImageIO reported no reason" : message;
}

}  // namespace dqskin
