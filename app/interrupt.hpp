// SIGINT and SIGTERM for long commands (bake, render): the first one asks the work to stop (the library
// polls the flag and unwinds, removing its temporaries); then the process dies of that same signal, so
// that make, shells and job schedulers see what happened. Whatever the work is doing (a batch on the GPU,
// a large texture being compressed), the process ends within a second: a watchdog thread gives the work
// a quarter of a second to unwind, then removes the temporaries itself and ends the process. A second signal cuts
// that quarter of a second short.
#pragma once

#include <atomic>

namespace dqskin::cli {

// Installs the handlers and starts the watchdog; the flag becomes true when a signal arrives. `what` names
// the work in the last message ("bake").
const std::atomic<bool>* catch_interrupts(const char* what);

// Prints "dqskin: WHAT stopped by signal N; …" and re-raises the signal with its default action. Embedded
// (below), prints "dqskin: WHAT stopped; …" and returns kInterrupted instead.
int die_of_interrupt(const char* what);

// The command line run inside another program (the Python module): while one is alive, catch_interrupts
// installs no handler and starts no watchdog (the host owns its signals) and returns `cancel`, which the
// host sets; die_of_interrupt returns. One at a time.
class EmbeddedInterrupts {
public:
  explicit EmbeddedInterrupts(const std::atomic<bool>* cancel);
  ~EmbeddedInterrupts();
  EmbeddedInterrupts(const EmbeddedInterrupts&) = delete;
  EmbeddedInterrupts& operator=(const EmbeddedInterrupts&) = delete;
};

}  // namespace dqskin::cli
