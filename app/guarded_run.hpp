// Every command's last line of defence (README "Exit status"): what escapes a command's body ends in one
// line on stderr and an exit status, never in an abort or an uncaught exception.
#pragma once

#include <functional>

namespace dqskin::cli {

// Runs `body` and returns its status, or maps what escapes it, after `tidy` (clearing a progress bar):
//   JobCancelled        the process dies of the signal that cancelled it (die_of_interrupt); the job
//                       has taken back what it wrote, its output folder included (lib/job/output_folder.hpp)
//   NoGpuContext        3 (kNoGlContext) and its message
//   filesystem_error    2 and the path with the system's message
//   std::bad_alloc      2 and out_of_memory_message() (a command that knows its file names it: a
//                       std::bad_alloc caught where the file is known becomes that file's error)
//   other exceptions    2 and their message
// `command` names the command in the interrupt's message ("bake: interrupted").
int guarded_run(const char* command, const std::function<int()>& body, const std::function<void()>& tidy = {});

// Whether the last failure guarded_run mapped was an OutputError (a file or folder that cannot be
// written), which the exit status does not tell from an input error; cleared by the call.
// For an embedding that raises its own kinds of errors (the Python module's OutputError).
bool take_output_error();

}  // namespace dqskin::cli
