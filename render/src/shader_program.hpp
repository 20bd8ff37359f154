#pragma once
// Shader programs built from the embedded GLSL files (render/shaders/), with compile and link
// errors that name the file.
#include <epoxy/gl.h>

#include <initializer_list>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gl_objects.hpp"

namespace kiri::render::detail {

//! The text of an embedded shader file, e.g. "terrain.vert". Throws kiri::Error if unknown.
std::string_view shader_source(std::string_view file_name);

class ShaderProgram {
public:
    //! Compiles and links the named files; the stage comes from the extension
    //! (.vert, .frag, .comp, .geom). A .glsl file is a library: its text (and `preamble`, e.g.
    //! "#define X 1\n") goes after the #version line of every stage file that follows it.
    //! Throws kiri::Error naming the file on failure.
    explicit ShaderProgram(std::initializer_list<std::string_view> files, std::string_view preamble = {})
        : ShaderProgram(std::vector<std::string_view>(files), preamble)
    {}
    explicit ShaderProgram(const std::vector<std::string_view>& files, std::string_view preamble = {});
    GLuint id() const { return program_.get(); }
    void use() const { glUseProgram(program_.get()); }
    GLint location(const char* uniform) const { return glGetUniformLocation(program_.get(), uniform); }
    void set(const char* uniform, float v) const { glProgramUniform1f(id(), location(uniform), v); }
    void set(const char* uniform, int v) const { glProgramUniform1i(id(), location(uniform), v); }
    void set(const char* uniform, const glm::vec2& v) const { glProgramUniform2f(id(), location(uniform), v.x, v.y); }
    void set(const char* uniform, const glm::vec3& v) const;
    void set(const char* uniform, const glm::vec4& v) const
    {
        glProgramUniform4f(id(), location(uniform), v.x, v.y, v.z, v.w);
    }
    void set(const char* uniform, const glm::mat4& m) const;
    void set(const char* uniform, const glm::ivec3& v) const
    {
        glProgramUniform3i(id(), location(uniform), v.x, v.y, v.z);
    }
    void set(const char* uniform, const glm::ivec2& v) const { glProgramUniform2i(id(), location(uniform), v.x, v.y); }
    void set(const char* uniform, const glm::ivec4& v) const
    {
        glProgramUniform4i(id(), location(uniform), v.x, v.y, v.z, v.w);
    }

private:
    ProgramName program_;
};

}  // namespace kiri::render::detail
