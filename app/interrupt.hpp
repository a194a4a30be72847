// SIGINT and SIGTERM for long commands (bake, render): the first one asks the work to stop (the library
// polls the flag and unwinds, removing its temporaries); then the process dies of that same signal, so
// that make, shells and job schedulers see what happened.
#pragma once

#include <atomic>

namespace dqskin::cli {

// Installs the handlers; the flag becomes true when a signal arrives.
const std::atomic<bool>* catch_interrupts();

// Prints "dqskin: WHAT stopped by signal N; …" and re-raises the signal with its default action.
// Returns 128 + N should the signal not end the process.
int die_of_interrupt(const char* what);

}  // namespace dqskin::cli
