// dqskin's exit statuses, one per kind of failure (README "Exit status").
#pragma once

namespace dqskin::cli {

enum ExitCode : int {
  kSuccess = 0,
  kSomeInputsFailed = 1,  // a batch finished, but some inputs could not be processed
  kUsageOrInputError = 2, // bad command line, or an input that is not valid
  kNoGlContext = 3,       // no headless OpenGL 4.3 context could be created
  kInterrupted = 130,     // embedded only (EmbeddedInterrupts): the host cancelled; a process dies of the signal
};

}  // namespace dqskin::cli
