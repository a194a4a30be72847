// The exceptions the library throws for bad data: an input that is not valid, an output that cannot be
// written, each with a one-line message that says what is wrong. Programmer errors are asserts.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace dqskin {

// `text` made safe to print as (part of) one line on a terminal: control characters become escapes
// (`\n`, `\r`, `\t`, `\x1b`, …), as do bytes that are not UTF-8 (`\xff`) and the code points that move
// or reorder text (C1 controls, bidirectional overrides and isolates, line and paragraph separators:
// `\u202e`). Everything else, UTF-8 letters included, is kept, and printable text stays as it is.
// File names and messages built from a file's content go through it before they reach stderr or a text
// report.
std::string printable(std::string_view text);

// An input that is not valid. The message is made printable() when the exception is made: parts of it
// come from the file (names, values, a parser's quote of it), and it stays one line whatever they hold.
class InputError : public std::runtime_error {
public:
  explicit InputError(std::string_view message) : std::runtime_error(printable(message)) {}
};

// An output that cannot be written (folder missing or read-only, disk full); the message names the file,
// made printable() like InputError's.
class OutputError : public std::runtime_error {
public:
  explicit OutputError(std::string_view message) : std::runtime_error(printable(message)) {}
};

// The message for std::bad_alloc caught at an input's or a command's boundary: the estimate that
// --max-memory checks was within it, but the machine could not give that much.
inline constexpr const char* kOutOfMemory =
    "ran out of memory: this machine has less free memory than --max-memory allows; lower --max-memory to refuse "
    "such inputs at once";

}  // namespace dqskin
