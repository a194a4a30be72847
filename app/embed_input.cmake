# Writes a C++ source that holds one self-contained .gltf file as a string (app/default_input.hpp).
# Usage: cmake -DINPUT=rig.gltf -DOUTPUT=default_input_data.cpp -P embed_input.cmake
file(READ "${INPUT}" text)
get_filename_component(name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "// Generated from testdata/${name} by app/embed_input.cmake; do not edit.\n"
  "#include \"default_input.hpp\"\n\n"
  "namespace dqskin::cli {\n"
  "extern const std::string_view kDefaultInput = R\"gltf_source(${text})gltf_source\";\n"
  "extern const char* const kDefaultInputName = \"${name}\";\n"
  "}  // namespace dqskin::cli\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
