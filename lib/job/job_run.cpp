#include "job_run.hpp"

#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"

namespace dqskin {

GpuContext& JobContext::get() {
  if (!context_) context_ = create_gpu_context(backend_);
  return *context_;
}

GpuContext* JobContext::for_deforming(BlendMode mode) {
  if (backend_ == Backend::kCpu || backend_ == Backend::kFastCpu || !has_gpu_path(mode)) return nullptr;
  if (backend_ != Backend::kAuto) return &get();
  if (!context_ && !hardware_asked_) context_ = create_hardware_gpu_context();
  hardware_asked_ = true;
  return context_ && context_->info().hardware ? context_.get() : nullptr;
}

std::vector<InputResult> for_each_input(const std::vector<InputPlan>& plans, const InputWork& work,
                                        const ForgetInput& forget) {
  std::vector<InputResult> results;
  for (const InputPlan& plan : plans) {
    InputResult result{plan.path, plan.error, 0, plan.asset ? plan.asset->warnings : std::vector<std::string>{},
                       plan.asset ? plan.asset->notices : std::vector<std::string>{}};
    if (plan.error.empty()) {
      OutputJournal journal;  // what this input wrote, taken back when it fails
      try {
        work(plan, journal, result);
        journal.keep();
      } catch (const JobCancelled&) {
        journal.keep();  // an interrupted job keeps its complete files; a rerun finishes it
        throw;
      } catch (const NoGpuContext&) {
        throw;
      } catch (const std::bad_alloc&) {
        result.error = out_of_memory_message();
      } catch (const std::exception& e) {
        result.error = e.what();
      }
      if (!result.error.empty()) {
        const MemoryCeilingLifted lifted;  // taking back allocates a little; the failed work's memory is freed
        journal.roll_back();
        forget(plan);
        result.frames = 0;  // its outputs are gone: it deformed nothing that stays
      }
    }
    results.push_back(std::move(result));
  }
  return results;
}

}  // namespace dqskin
