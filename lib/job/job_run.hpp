// The per-input loop of a job (docs/DESIGN.md §1.3), written once for every command: inputs one after
// the other, each with a journal of what it writes; a failing input is reported and its files taken back
// while the others go on; a cancel stops the job keeping the complete files; the GL context is made when
// the first input needs one, and shared by all.
#pragma once

#include "dqskin/deformer.hpp"
#include "dqskin/gpu_context.hpp"
#include "job_plan.hpp"
#include "../base/output_journal.hpp"

#include <functional>
#include <memory>
#include <vector>

namespace dqskin {

// The GL context a job borrows: made on first use (NoGpuContext, exit status 3, when there is none), on
// the thread that uses it.
class JobContext {
public:
  explicit JobContext(Backend backend) : backend_(backend) {}
  GpuContext& get();
  // The context the deformer of `mode` runs on, or null where it runs on the CPU (deform_path): egl and
  // osmesa make one (NoGpuContext when they cannot); auto takes a hardware GPU's when there is one (asked
  // once); fast-cpu, cpu and a mode without a GPU path need none.
  GpuContext* for_deforming(BlendMode mode);
  // What was made; null while nothing was.
  const GpuContextInfo* info() const { return context_ ? &context_->info() : nullptr; }

private:
  Backend backend_;
  std::unique_ptr<GpuContext> context_;
  bool hardware_asked_ = false;
};

// One input's work: writes through `journal`, counts into `result.frames`, throws to fail the input.
using InputWork = std::function<void(const InputPlan& input, OutputJournal& journal, InputResult& result)>;
// Called after a failed input's files were taken back: the caller drops what it recorded of them.
using ForgetInput = std::function<void(const InputPlan& input)>;

// Runs `work` on every input that planned without error, in order, and returns one result per plan (the
// plan's own error, or the one `work` threw; a failed input's frames count 0). `work` and `forget` receive
// the elements of `plans` themselves, so a caller may find an input's index as &input - plans.data().
// JobCancelled and NoGpuContext leave the loop; any other exception fails that input only.
std::vector<InputResult> for_each_input(const std::vector<InputPlan>& plans, const InputWork& work,
                                        const ForgetInput& forget);

}  // namespace dqskin
