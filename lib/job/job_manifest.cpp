#include "job_manifest.hpp"

#include "../base/leftover_files.hpp"
#include "dqskin/atomic_file.hpp"
#include "../base/sha256.hpp"

#include <filesystem>
#include <vector>

namespace dqskin::job_manifest {

std::string file_name(std::string_view base, const Shard& shard) {
  std::string name(base);
  if (!shard.whole()) {
    name += ".shard-";
    name += std::to_string(shard.index);
    name += "-of-";
    name += std::to_string(shard.count);
  }
  return name + ".json";
}

nlohmann::json input_record(const InputPlan& plan, const std::string& error) {
  using nlohmann::json;
  json in = {{"path", plan.path}, {"output_folder", plan.stem}};
  std::error_code ec;
  const auto size = std::filesystem::file_size(plan.path, ec);
  if (!ec) {
    in["size"] = uint64_t(size);
    try {
      in["sha256"] = sha256_file(plan.path);
    } catch (const std::exception&) {  // unreadable inputs have an error already
    }
  }
  if (!error.empty()) in["error"] = error;
  json clips = json::array();
  for (const ClipPlan& clip : plan.clips) {
    json c = {{"name", clip.name}, {"folder", clip.folder}, {"frame_times", clip.times}, {"frame_numbers", clip.numbers}};
    if (clip.fps > 0) c["fps"] = clip.fps;
    clips.push_back(std::move(c));
  }
  in["animations"] = std::move(clips);
  if (plan.scene >= 0) in["scene"] = plan.scene;
  return in;
}

std::string text(const nlohmann::json& manifest) {
  return manifest.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string write(const std::string& folder, const std::string& name, const nlohmann::json& manifest) {
  const std::string path = folder + "/" + name;
  AtomicFile file(path);
  file.write(text(manifest));
  file.commit(Overwrite::kReplace);
  clear_leftovers(folder, name, manifest);
  return path;
}

void clear_leftovers(const std::string& folder, const std::string& name, const nlohmann::json& manifest) noexcept {
  try {
    std::vector<std::string> recorded{name};
    for (const nlohmann::json& out : manifest.at("outputs")) recorded.push_back(out.at("path").get<std::string>());
    leftover_files::remove_for(folder, recorded);
  } catch (const std::exception&) {  // as remove_for: a leftover that stays is reported by dqskin verify
  }
}

}  // namespace dqskin::job_manifest
