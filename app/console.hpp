// What dqskin prints on stderr, one line per message and each line printable (dqskin::printable): file
// names and messages may carry any bytes a file or a library put there (internal to the CLI).
#pragma once

#include "dqskin/job.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace dqskin::cli {

// "dqskin: MESSAGE"
void print_error(std::string_view message);
// "dqskin: FILE: MESSAGE"
void print_error(std::string_view file, std::string_view message);
// "dqskin: FILE: warning: MESSAGE"
void print_warning(std::string_view file, std::string_view message);

// "dqskin: FILE: note: MESSAGE"
void print_note(std::string_view file, std::string_view message);

// One line per failed input ("dqskin: FILE: problem"), and unless `quiet`, one per loader warning of the
// others ("dqskin: FILE: warning: ..."): parts of the file that were dropped or corrected; with `verbose`
// (and not `quiet`) also one per loader notice ("dqskin: FILE: note: ..."): what glTF defines and dqskin
// follows, such as a skinned mesh node's transform being ignored.
void print_input_messages(const std::vector<InputResult>& inputs, bool quiet, bool verbose = false);

// How many inputs failed.
size_t failed_inputs(const std::vector<InputResult>& inputs);

// A job's exit status (README "Exit status"): 0 when every input succeeded; 1 when some failed, saying so
// unless `quiet` ("2 of 5 inputs failed; the others baked", `done` = "baked"); 2 when all failed.
int job_exit_status(const std::vector<InputResult>& inputs, bool quiet, const char* done);

// A JSON document as text; bytes that are not UTF-8 (in file names, or quoted by a library's message)
// become U+FFFD instead of making the dump throw.
template <typename Json>
std::string json_text(const Json& json, int indent = -1) {
  return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace dqskin::cli
