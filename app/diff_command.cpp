// `dqskin diff A B`: two images or two folders of images compared as OpenImageIO's idiff compares them, for
// CI checks of rendered frames. Prints a text or JSON report, writes heat maps and a JUnit XML report.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_diff.hpp"

#include <filesystem>
#include <iostream>

namespace dqskin::cli {
namespace {

// diff's statuses are idiff's order of severity: 0 all pass, 1 warnings only, 2 a failure. A usage or
// input error is 2 as everywhere in dqskin (README "Exit status"), so CI treats it as a failure.
constexpr int kDiffWarn = 1;
constexpr int kDiffFail = 2;
static_assert(kDiffFail == kUsageOrInputError);

int exit_status(DiffStatus status) {
  switch (status) {
    case DiffStatus::kPass: return kSuccess;
    case DiffStatus::kWarn: return kDiffWarn;
    case DiffStatus::kFail: return kDiffFail;
  }
  return kDiffFail;
}

}  // namespace

int run_diff(const DiffSettings& settings) {
  try {
    const std::string bad = check_thresholds(settings.thresholds);
    if (!bad.empty()) throw InputError(bad);
    const DiffReport report = diff_images(settings.a, settings.b, {settings.thresholds, settings.out_dir});
    for (const ImageDiff& d : report.pairs)
      if (!d.unreadable.empty()) print_error(d.unreadable, d.read_error);
    std::cout << (settings.json ? diff_json(report) : diff_text(report)) << std::flush;
    if (!settings.junit.empty()) {
      AtomicFile junit(settings.junit);
      junit.write(diff_junit(report));
      junit.commit(Overwrite::kReplace);
    }
    return exit_status(report.status());
  } catch (const std::filesystem::filesystem_error& e) {
    print_error(e.path1().string(), e.code().message());
    return kUsageOrInputError;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kUsageOrInputError;
  }
}

}  // namespace dqskin::cli
