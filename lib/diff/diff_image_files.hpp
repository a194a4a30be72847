// What `dqskin diff` reads through OpenImageIO, done by the image module (diff_images_oiio.cpp in
// libdqskin_image.so; base/image_module.hpp says why it is apart): image pairs compared, and the EXR
// textures of the geometric diff (internal to lib/diff).
#pragma once

#include "baked_file.hpp"
#include "memory_ledger.hpp"

#include "dqskin/image_diff.hpp"

#include <cstdint>
#include <string>
#include <utility>

namespace dqskin::diff_detail {

// The verdict and, unless it is PASS, the rule that decided it, in words (image_diff.cpp).
std::pair<DiffStatus, std::string> judge(const DiffThresholds& t, double max_error, uint64_t over_warn,
                                         uint64_t over_fail, uint64_t pixels, double mean_error);

class DiffImageFiles {
public:
  // diff_pair of dqskin/image_diff.hpp, for a pair with both files. With a ledger, the pair holds what it
  // needs in it (waiting while other pairs hold too much) from before its pixels are read until it ends.
  virtual ImageDiff diff_pair(const DiffPair& pair, const DiffOptions& options, MemoryLedger* ledger = nullptr) const = 0;
  // An EXR texture's texels as points (read_baked_file); InputError with OpenImageIO's reason.
  virtual BakedPoints read_exr(const std::string& path) const = 0;
  // declared_size of an EXR; empty when it cannot be opened (read_exr then says why).
  virtual DeclaredSize exr_declared_size(const std::string& path) const = 0;

protected:
  ~DiffImageFiles() = default;
};

// The module's DiffImageFiles, loaded on first call (its entry point: dqskin_diff_image_files).
const DiffImageFiles& diff_image_files();

}  // namespace dqskin::diff_detail
