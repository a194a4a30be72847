// The one exception the library throws: an input that is not valid, with a one-line message that says
// what is wrong. Programmer errors are asserts, not exceptions.
#pragma once

#include <stdexcept>
#include <string>

namespace dqskin {

class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace dqskin
