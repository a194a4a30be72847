#include "guarded_run.hpp"

#include "console.hpp"
#include "exit_codes.hpp"
#include "interrupt.hpp"

#include "dqskin/error.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <atomic>
#include <filesystem>
#include <new>
#include <optional>

namespace dqskin::cli {

namespace {
std::atomic<bool> g_output_error{false};
}  // namespace

bool take_output_error() { return g_output_error.exchange(false); }

int guarded_run(const char* command, const std::function<int()>& body, const std::function<void()>& tidy) {
  // What runs after a failure runs without the memory ceiling: the failed work's memory is freed by then,
  // and a message that cannot be made would end in std::terminate.
  std::optional<MemoryCeilingLifted> lifted;
  auto tidy_up = [&] {
    lifted.emplace();
    if (tidy) tidy();
  };
  try {
    return body();
  } catch (const JobCancelled&) {
    tidy_up();
    return die_of_interrupt(command);
  } catch (const NoGpuContext& e) {
    tidy_up();
    print_error(e.what());
    return kNoGlContext;
  } catch (const std::filesystem::filesystem_error& e) {
    tidy_up();
    print_error(e.path1().string(), e.code().message());
    return kUsageOrInputError;
  } catch (const std::bad_alloc&) {
    tidy_up();
    print_error(out_of_memory_message());
    return kUsageOrInputError;
  } catch (const OutputError& e) {
    tidy_up();
    g_output_error = true;
    print_error(e.what());
    return kUsageOrInputError;
  } catch (const std::exception& e) {
    tidy_up();
    print_error(e.what());
    return kUsageOrInputError;
  }
}

}  // namespace dqskin::cli
