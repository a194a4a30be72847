#include "progress.hpp"

#include "console.hpp"

#include "dqskin/error.hpp"
#include "../lib/base/stderr_lock.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>

namespace dqskin::cli {
namespace {

std::string clock_text(double seconds) {
  const long s = long(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

}  // namespace

ProgressPrinter::ProgressPrinter(bool json, bool quiet) : json_(json), bar_(!quiet && !json && ::isatty(2)) {}

void ProgressPrinter::operator()(const JobProgress& p) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? double(p.frames_done) / elapsed : 0;
  const double left = rate > 0 ? double(p.frames_total - p.frames_done) / rate : 0;
  if (json_) {
    std::cout << json_text(nlohmann::json{{"event", "progress"},   {"frames_done", p.frames_done},
                                          {"frames_total", p.frames_total}, {"input", p.input},
                                          {"animation", p.clip},    {"elapsed_s", elapsed},
                                          {"frames_per_s", rate},   {"eta_s", left}})
              << std::endl;
  } else if (bar_ && (elapsed - last_draw_ > 0.1 || p.frames_done == p.frames_total)) {
    const std::lock_guard<std::mutex> stderr_lock(stderr_mutex());
    last_draw_ = elapsed;
    const int width = 30;
    const int filled = p.frames_total ? int(double(width) * double(p.frames_done) / double(p.frames_total)) : width;
    std::fprintf(stderr, "\r\033[K[%s%s] %zu/%zu frames  %.1f frames/s  %s left  %s",
                 std::string(size_t(filled), '#').c_str(), std::string(size_t(width - filled), '.').c_str(),
                 p.frames_done, p.frames_total, rate, clock_text(left).c_str(), printable(p.clip).c_str());
    drawn_ = true;
  }
}

void ProgressPrinter::done() {
  const std::lock_guard<std::mutex> stderr_lock(stderr_mutex());
  if (drawn_) std::fputs("\r\033[K", stderr);
}

}  // namespace dqskin::cli
