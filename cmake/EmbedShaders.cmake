# cmake -DOUTPUT=file.cpp -DSHADERS="a.vert|b.frag" -P EmbedShaders.cmake
# Writes a .cpp holding each shader file as a raw string, looked up by file name.
set(body "")
string(REPLACE "|" ";" SHADERS "${SHADERS}")
foreach(path IN LISTS SHADERS)
  get_filename_component(name "${path}" NAME)
  file(READ "${path}" text)
  string(APPEND body "    {\"${name}\", R\"kiri_glsl(${text})kiri_glsl\"},\n")
endforeach()
file(WRITE "${OUTPUT}.new" "// Generated from render/shaders by cmake/EmbedShaders.cmake: do not edit.
#include <string>
#include <string_view>
#include <unordered_map>

#include \"kiri/geometry/core/error.hpp\"

namespace kiri::render::detail {

std::string_view shader_source(std::string_view file_name)
{
    static const std::unordered_map<std::string_view, std::string_view> files = {
${body}    };
    const auto it = files.find(file_name);
    if (it == files.end())
        throw Error(\"shader \" + std::string(file_name) + \": no such embedded shader\");
    return it->second;
}

}  // namespace kiri::render::detail
")
file(COPY_FILE "${OUTPUT}.new" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.new")
