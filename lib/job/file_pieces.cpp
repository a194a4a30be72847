#include "file_pieces.hpp"

#include <cctype>
#include <cstdlib>

namespace dqskin {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Digits only, as the writer prints a row number.
std::optional<size_t> number(const std::string& s) {
  if (s.empty() || s.size() > 12) return std::nullopt;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  return size_t(std::strtoull(s.c_str(), nullptr, 10));
}

}  // namespace

std::optional<FilePiece> file_piece(const std::string& path) {
  const size_t slash = path.rfind('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (ends_with(name, ".json.template")) {
    FilePiece p;
    p.kind = FilePiece::Kind::kDecodeCheck;
    p.whole = path.substr(0, path.size() - std::string(".template").size());
    const std::string stem = name.substr(0, name.size() - std::string(".json.template").size());
    if (stem == "vat") p.texture = "vat";
    else if (stem.rfind("bones_skin", 0) == 0 && number(stem.substr(10))) p.texture = stem;
    else return std::nullopt;
    return p;
  }
  const size_t rows = path.rfind(".exr.rows-");
  if (rows == std::string::npos || rows < path.size() - name.size()) return std::nullopt;
  const std::string range = path.substr(rows + std::string(".exr.rows-").size());
  const size_t dash = range.find('-');
  if (dash == std::string::npos) return std::nullopt;
  const std::optional<size_t> first = number(range.substr(0, dash)), end = number(range.substr(dash + 1));
  if (!first || !end || *first >= *end) return std::nullopt;
  FilePiece p;
  p.kind = FilePiece::Kind::kExrRows;
  p.whole = path.substr(0, rows + 4);
  p.first_row = *first;
  p.end_row = *end;
  return p;
}

const char* to_string(FilePiece::Kind kind) { return kind == FilePiece::Kind::kExrRows ? "exr_rows" : "decode_check"; }

}  // namespace dqskin
