// The output folder of a job (docs/DESIGN.md §1.3, §6.2), owned by the job layer so that every command
// creates and takes it back the same way: made, with its missing parents, before the job starts; removed
// again when the job ends without a single input done, so that a failed or interrupted run leaves no
// empty folder behind; a folder that was already there always stays.
#pragma once

#include "dqskin/job.hpp"
#include "../base/output_journal.hpp"

#include <string>
#include <vector>

namespace dqskin {

class OutputFolder {
public:
  // Creates `folder` and whichever of its parents are missing, remembering the ones it made; with `create`
  // false (a dry run, which writes nothing) it makes and remembers none. Throws OutputError naming the
  // folder it cannot create.
  explicit OutputFolder(const std::string& folder, bool create = true);
  // Removes the folders it made, innermost first, each only while it is empty, unless they were kept.
  ~OutputFolder() = default;
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Keeps the folders it made when at least one of `inputs` succeeded (its error is empty): then the
  // folder holds what the job did, or the job's record of it.
  void keep_if_any_succeeded(const std::vector<InputResult>& inputs) noexcept;

private:
  OutputJournal journal_;  // only folders: the job's files have their own journals, one per input
};

}  // namespace dqskin
