#include "interrupt.hpp"
#include "console.hpp"

#include <csignal>
#include <iostream>

namespace dqskin::cli {
namespace {

std::atomic<bool> g_cancel{false};
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_interrupt(int signal) {
  g_signal = signal;
  g_cancel = true;
}

}  // namespace

const std::atomic<bool>* catch_interrupts() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  return &g_cancel;
}

int die_of_interrupt(const char* what) {
  const int signal = int(g_signal);
  print_error(std::string(what) + " stopped by signal " + std::to_string(signal) + "; no partial files were left under final names");
  std::signal(signal, SIG_DFL);
  std::raise(signal);
  return 128 + signal;
}

}  // namespace dqskin::cli
