# Writes a C++ source that holds one shader file as a string, so the binary needs no files at run time.
# Usage: cmake -DINPUT=skin.comp -DOUTPUT=skin_comp.cpp -DSYMBOL=kSkinComp -P embed.cmake
file(READ "${INPUT}" text)
get_filename_component(name "${INPUT}" NAME)
file(WRITE "${OUTPUT}.tmp"
  "// Generated from glsl/${name} by glsl/embed.cmake; do not edit.\n"
  "#include \"shader_sources.hpp\"\n\n"
  "namespace dqskin::gpu {\n"
  "extern const ShaderSource ${SYMBOL} = {\"glsl/${name}\", R\"glsl_source(${text})glsl_source\"};\n"
  "}  // namespace dqskin::gpu\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
