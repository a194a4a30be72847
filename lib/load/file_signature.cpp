#include "file_signature.hpp"

#include "dqskin/error.hpp"
#include "dqskin/load.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace dqskin::gltf {
namespace {

struct Signature {
  std::string_view magic;
  const char* what;
};

// The first bytes of formats that are found where a glTF file was expected: an archive or a model the user
// meant to convert, or an image.
constexpr Signature kSignatures[] = {
    {"PK\x03\x04", "a ZIP archive"},          {"\x1F\x8B", "a gzip file"},
    {"\x89PNG\r\n\x1A\n", "a PNG image"},     {"\xFF\xD8\xFF", "a JPEG image"},
    {"%PDF-", "a PDF document"},              {"Kaydara FBX Binary", "a binary FBX file"},
    {"RIFF", "a RIFF file (WebP, WAV, AVI)"}, {"\x7F" "ELF", "an executable (ELF)"},
};

constexpr size_t kShownBytes = 24;

}  // namespace

std::optional<std::string> not_gltf_reason(std::span<const uint8_t> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text.substr(0, 4) == "glTF") return std::nullopt;
  for (const Signature& s : kSignatures)
    if (text.substr(0, s.magic.size()) == s.magic) return std::string("is not a glTF file: it is ") + s.what;
  size_t first = text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;  // a UTF-8 byte order mark
  first = text.find_first_not_of(" \t\r\n", first);
  if (first == std::string_view::npos || text[first] == '{') return std::nullopt;
  std::string_view shown = text.substr(first, kShownBytes);
  shown = shown.substr(0, shown.find_first_of("\r\n"));
  return "is not a glTF file: it starts with '" + printable(shown) + "'";
}

}  // namespace dqskin::gltf

namespace dqskin {

bool is_gltf_file(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (extension == ".gltf" || extension == ".glb") return true;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  // Enough for the magic, a byte order mark and the indentation before a document's '{'.
  char head[256] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  const std::string_view text(head, size_t(in.gcount()));
  if (text.substr(0, 4) == "glTF") return true;
  size_t first = text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  first = text.find_first_not_of(" \t\r\n", first);
  return first != std::string_view::npos && text[first] == '{';
}

}  // namespace dqskin
