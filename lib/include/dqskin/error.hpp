// The exceptions the library throws for bad data: an input that is not valid, an output that cannot be
// written, each with a one-line message that says what is wrong. Programmer errors are asserts.
#pragma once

#include <stdexcept>
#include <string>

namespace dqskin {

class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// An output that cannot be written (folder missing or read-only, disk full); the message names the file.
class OutputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace dqskin
