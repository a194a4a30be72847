// The flags of every command that reads glTF files (commands.hpp LoadSettings).
#include "commands.hpp"

#include "../lib/base/byte_size.hpp"
#include "dqskin/error.hpp"

#include <filesystem>

namespace dqskin::cli {

void add_load_settings(CLI::App& command, LoadSettings& settings) {
  command
      .add_option("--resource-root", settings.resource_roots,
                  "A folder that the inputs' external buffers and images may also come from (repeatable); by "
                  "default only the input's own folder")
      ->type_name("DIR");
  add_max_memory(command, settings.max_memory);
}

void add_max_influences(CLI::App& command, LoadSettings& settings) {
  command
      .add_option("--max-influences", settings.max_influences,
                  "Keep the N largest influences of each vertex (1-" + std::to_string(kMaxInfluences) +
                      ") and renormalize, as lint --fix --max-influences N writes them; by default every one "
                      "the file has")
      ->type_name("N");
}

void add_max_memory(CLI::App& command, std::string& max_memory) {
  command
      .add_option("--max-memory", max_memory,
                  "Refuse an input that needs more memory than this, estimated from what the file declares before "
                  "anything is decoded, and a ceiling on all the command allocates: bytes, or K, M, G, T")
      ->type_name("SIZE")
      ->capture_default_str();
}

std::optional<uint64_t> max_memory_of(const CLI::App& command) {
  const CLI::Option* option = command.get_option_no_throw("--max-memory");
  if (!option) return std::nullopt;
  // Given or not: the default is a ceiling too, so that a command's memory is bounded on any input.
  return parse_byte_size(option->count() > 0 ? option->results().back() : option->get_default_str(), "--max-memory");
}

LoadOptions to_load_options(const LoadSettings& settings) {
  LoadOptions options;
  options.max_memory = parse_byte_size(settings.max_memory, "--max-memory");
  for (const std::string& root : settings.resource_roots) {
    std::error_code error;
    if (!std::filesystem::is_directory(root, error))
      throw InputError("--resource-root " + root + ": " + (error ? error.message() : "not a folder"));
  }
  options.resource_roots = settings.resource_roots;
  if (settings.max_influences != 0 && (settings.max_influences < 1 || settings.max_influences > kMaxInfluences))
    throw InputError("--max-influences must be from 1 to " + std::to_string(kMaxInfluences) + " (0: every influence)");
  options.max_influences = settings.max_influences;
  return options;
}

}  // namespace dqskin::cli
