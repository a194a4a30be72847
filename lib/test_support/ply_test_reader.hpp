// Test support: a small reader for the PLY files encode_ply writes (binary little endian, float vertex
// properties, uchar-counted uint triangles), independent of the writer's code.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dqskin {

// A small reader for what write_ply writes: the header's counts and properties, then the binary body.
struct PlyFile {
  std::vector<std::string> vertex_properties;
  std::vector<float> vertex_data;  // vertex count × properties
  std::vector<uint32_t> faces;     // 3 per face
};

inline PlyFile read_ply(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  PlyFile ply;
  size_t vertices = 0, faces = 0;
  std::string element;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  std::getline(in, line);
  EXPECT_EQ(line, "format binary_little_endian 1.0");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "element") {
      words >> element;
      (element == "vertex" ? vertices : faces) = std::stoul(line.substr(line.rfind(' ') + 1));
    } else if (word == "property" && element == "vertex") {
      words >> type >> name;
      EXPECT_EQ(type, "float");
      ply.vertex_properties.push_back(name);
    }
  }
  ply.vertex_data.resize(vertices * ply.vertex_properties.size());
  in.read(reinterpret_cast<char*>(ply.vertex_data.data()), std::streamsize(ply.vertex_data.size() * 4));
  for (size_t f = 0; f < faces; ++f) {
    unsigned char n = 0;
    in.read(reinterpret_cast<char*>(&n), 1);
    EXPECT_EQ(n, 3);
    uint32_t idx[3];
    in.read(reinterpret_cast<char*>(idx), 12);
    ply.faces.insert(ply.faces.end(), idx, idx + 3);
  }
  EXPECT_TRUE(in.good());
  EXPECT_EQ(in.peek(), EOF) << "nothing after the faces";
  return ply;
}

}  // namespace dqskin
