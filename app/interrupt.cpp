#include "interrupt.hpp"
#include "console.hpp"
#include "exit_codes.hpp"

#include "dqskin/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <string>
#include <thread>

namespace dqskin::cli {
namespace {

// How long the work may take to unwind after the first signal (finishing the frame being encoded, closing
// its files, taking back a failed input) before the process ends anyway. Ending a process that holds a GL
// context takes another 0.1-0.25 s on llvmpipe (measured on BrainStem bakes), so the whole stop stays well
// within the second that schedulers and users wait.
constexpr int kGraceMilliseconds = 250;

std::atomic<bool> g_cancel{false};
std::atomic<int> g_signal{0};      // lock-free: the handler writes it, the watchdog reads it
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler stores to it");
std::atomic<bool> g_dying{false};  // one thread prints the last message and ends the process
int g_pipe[2] = {-1, -1};          // the handler wakes the watchdog through it (write is async-signal-safe)
int g_stderr = -1;                 // stderr as it was at the start: a library may have it redirected
const char* g_what = "work";
const std::atomic<bool>* g_embedded = nullptr;  // EmbeddedInterrupts' flag, while one is alive

extern "C" void on_interrupt(int signal) {
  g_signal = signal;
  g_cancel = true;
  const char byte = 1;
  const int saved = errno;
  [[maybe_unused]] const ssize_t ignored = ::write(g_pipe[1], &byte, 1);
  errno = saved;
}

// The last thread to leave a dying process frees its memory (a gigabyte in a large bake). Mesa's shader-cache
// thread runs at nice 19 (SCHED_BATCH): when it is the last one on a busy machine, that teardown waits
// behind every other process; the stop took 1.2 s in CI and 4 to 8 s beside two busy processes. Every
// thread gets the priority the process started with (the watchdog's) before the process ends. Raising a
// priority needs root or an RLIMIT_NICE that allows it; elsewhere the threads keep theirs.
void restore_thread_priorities() {
  DIR* tasks = ::opendir("/proc/self/task");
  if (!tasks) return;
  errno = 0;
  const int started_with = ::getpriority(PRIO_PROCESS, 0);  // on Linux, the calling thread's nice value
  if (errno != 0) return;
  const sched_param normal{};
  while (const dirent* task = ::readdir(tasks)) {
    const id_t tid = id_t(std::strtoul(task->d_name, nullptr, 10));
    if (tid == 0) continue;  // "." and ".."
    if (::sched_getscheduler(pid_t(tid)) == SCHED_IDLE) ::sched_setscheduler(pid_t(tid), SCHED_OTHER, &normal);
    errno = 0;
    const int nice = ::getpriority(PRIO_PROCESS, tid);
    if (errno == 0 && nice > started_with) ::setpriority(PRIO_PROCESS, tid, started_with);
  }
  ::closedir(tasks);
}

// Ends the process by the signal that stopped it, so that make, shells and job schedulers see what happened.
[[noreturn]] void die_of(int signal) {
  restore_thread_priorities();
  std::signal(signal, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, signal);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(signal);
  std::_Exit(128 + signal);  // should the signal not end the process
}

// Waits for the first signal; then gives the work kGraceMilliseconds (less, on a second signal) to stop by
// itself, and otherwise ends the process: temporaries and kept-aside files removed, complete files left.
void watchdog() {
  pollfd wake{g_pipe[0], POLLIN, 0};
  while (::poll(&wake, 1, -1) < 0 && errno == EINTR) {
  }
  char byte;
  [[maybe_unused]] ssize_t ignored = ::read(g_pipe[0], &byte, 1);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kGraceMilliseconds);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    const int ready = ::poll(&wake, 1, int(left.count()));
    if (ready > 0) break;  // a second signal: the user does not want to wait
  }
  if (g_dying.exchange(true)) return;  // the work stopped in time and is ending the process itself
  remove_pending_files(/*hold=*/true);  // and no thread makes another
  const std::string line = "dqskin: " + std::string(g_what) + " stopped by signal " + std::to_string(g_signal.load()) +
                           "; files under final names are complete, temporaries were removed\n";
  ignored = ::write(g_stderr >= 0 ? g_stderr : 2, line.data(), line.size());
  die_of(g_signal.load());
}

}  // namespace

const std::atomic<bool>* catch_interrupts(const char* what) {
  if (g_embedded) return g_embedded;
  g_what = what;
  if (g_stderr < 0) g_stderr = ::fcntl(2, F_DUPFD_CLOEXEC, 3);
  if (g_pipe[0] < 0 && ::pipe2(g_pipe, O_CLOEXEC | O_NONBLOCK) == 0) std::thread(watchdog).detach();
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  return &g_cancel;
}

int die_of_interrupt(const char* what) {
  if (g_embedded) {
    print_error(std::string(what) + " stopped; no partial files were left under final names");
    return kInterrupted;
  }
  if (g_dying.exchange(true)) {
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // the watchdog is ending the process
  }
  print_error(std::string(what) + " stopped by signal " + std::to_string(g_signal.load()) +
              "; no partial files were left under final names");
  die_of(g_signal.load());
}

EmbeddedInterrupts::EmbeddedInterrupts(const std::atomic<bool>* cancel) { g_embedded = cancel; }
EmbeddedInterrupts::~EmbeddedInterrupts() { g_embedded = nullptr; }

}  // namespace dqskin::cli
