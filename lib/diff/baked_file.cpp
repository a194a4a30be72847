#include "baked_file.hpp"
#include "diff_image_files.hpp"
#include "diff_side.hpp"

#include "dqskin/error.hpp"
#include "dqskin/load.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin::diff_detail {
namespace {

std::string extension_of(const std::string& path) { return std::filesystem::path(path).extension().string(); }

// Binary little-endian PLY with float vertex properties (what encode_ply writes; mesh_output.hpp).
BakedPoints read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot be read");
  std::string line;
  std::getline(in, line);
  if (line != "ply") throw InputError("not a PLY file");
  std::getline(in, line);
  if (line != "format binary_little_endian 1.0") throw InputError("not a binary little-endian PLY file");
  size_t vertices = 0;
  std::string element;
  std::vector<std::string> properties;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "element") {
      words >> element;
      if (element == "vertex" && !(words >> vertices)) throw InputError("PLY vertex count missing");
    } else if (word == "property" && element == "vertex") {
      words >> type >> name;
      // The property is counted, not named: a report quotes no word of the file.
      if (type != "float") throw InputError("PLY vertex property " + std::to_string(properties.size() + 1) + " is not float");
      properties.push_back(name);
    }
  }
  if (line != "end_header") throw InputError("PLY header has no end");
  auto column = [&](const char* name) {
    for (size_t i = 0; i < properties.size(); ++i)
      if (properties[i] == name) return int(i);
    return -1;
  };
  const int x = column("x"), nx = column("nx");
  if (x < 0 || column("y") != x + 1 || column("z") != x + 2) throw InputError("PLY has no x, y, z");
  const size_t stride = properties.size();
  const auto end = in.tellg();
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (vertices > uint64_t(size - end) / (4 * stride)) throw InputError("PLY is shorter than its vertex count");
  in.seekg(end);
  std::vector<float> data(vertices * stride);
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * 4));
  if (!in) throw InputError("PLY is shorter than its vertex count");
  BakedPoints points;
  for (size_t v = 0; v < vertices; ++v) {
    const float* row = data.data() + v * stride;
    points.positions.emplace_back(row[x], row[x + 1], row[x + 2]);
    if (nx >= 0 && column("nz") == nx + 2) points.normals.emplace_back(row[nx], row[nx + 1], row[nx + 2]);
  }
  return points;
}

// "v x y z" and "vn x y z" lines, in order.
BakedPoints read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot be read");
  BakedPoints points;
  std::string line;
  size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const bool v = line.rfind("v ", 0) == 0, vn = line.rfind("vn ", 0) == 0;
    if (!v && !vn) continue;
    std::istringstream words(line.substr(v ? 2 : 3));
    glm::vec3 p;
    if (!(words >> p.x >> p.y >> p.z)) throw InputError("OBJ line " + std::to_string(number) + " is not three numbers");
    (v ? points.positions : points.normals).push_back(p);
  }
  if (!points.normals.empty() && points.normals.size() != points.positions.size()) points.normals.clear();
  return points;
}

// The loader's message without the JSON parser's quote of the file ("; last read: '…'"): a report shows
// what is wrong with a frame, not its bytes.
std::string without_quote(std::string message) {
  const size_t at = message.find("; last read: ");
  if (at != std::string::npos) message.erase(at);
  return message;
}

// A glb frame: its vertices in the order of its mesh instances, at rest (a frame has no animation).
BakedPoints read_glb(const std::string& path, const LoadOptions& load) {
  DiffSide side;
  try {
    Asset asset = load_asset(path, load);
    check_side_fits(asset, load.max_memory);
    side = make_diff_side(std::move(asset), BlendMode::kLbs);
  } catch (const InputError& e) {
    throw InputError(without_quote(e.what()));
  }
  BakedPoints points;
  for (size_t v = 0; v < side.vertices; ++v) {
    points.positions.emplace_back(side.rest.positions[v]);
    points.normals.emplace_back(side.rest.normals[v]);
  }
  return points;
}

}  // namespace

bool is_baked_file(const std::string& path) {
  const std::string e = extension_of(path);
  return e == ".ply" || e == ".obj" || e == ".glb" || e == ".exr";
}

DeclaredSize declared_size(const std::string& path) {
  if (extension_of(path) != ".exr") return {};
  return diff_image_files().exr_declared_size(path);
}

BakedPoints read_baked_file(const std::string& path, const LoadOptions& load) {
  const std::string e = extension_of(path);
  if (e == ".ply") return read_ply(path);
  if (e == ".obj") return read_obj(path);
  if (e == ".glb") return read_glb(path, load);
  return diff_image_files().read_exr(path);
}

}  // namespace dqskin::diff_detail
