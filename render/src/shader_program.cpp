#include "shader_program.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <string>
#include <vector>

#include "kiri/geometry/core/error.hpp"

namespace kiri::render::detail {
namespace {

GLenum stage_of(std::string_view file)
{
    const auto ends_with = [&](std::string_view ext) {
        return file.size() >= ext.size() && file.substr(file.size() - ext.size()) == ext;
    };
    if (ends_with(".vert"))
        return GL_VERTEX_SHADER;
    if (ends_with(".frag"))
        return GL_FRAGMENT_SHADER;
    if (ends_with(".comp"))
        return GL_COMPUTE_SHADER;
    if (ends_with(".geom"))
        return GL_GEOMETRY_SHADER;
    throw Error("shader " + std::string(file) + ": unknown stage (expected .vert, .frag, .comp or .geom)");
}

std::string info_log(GLuint object, bool is_program)
{
    GLint length = 0;
    is_program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
               : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    is_program ? glGetProgramInfoLog(object, length, nullptr, log.data())
               : glGetShaderInfoLog(object, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n'))
        log.pop_back();
    // One line: the first message is the useful one.
    if (const auto nl = log.find('\n'); nl != std::string::npos)
        log = log.substr(0, nl);
    return log;
}

}  // namespace

ShaderProgram::ShaderProgram(const std::vector<std::string_view>& files, std::string_view preamble)
    : program_(glCreateProgram())
{
    std::vector<GLuint> shaders;
    std::string names;
    std::string libraries(preamble);
    for (std::string_view file : files) {
        const std::string_view text = shader_source(file);
        if (file.size() > 5 && file.substr(file.size() - 5) == ".glsl") {
            libraries += text;
            libraries += '\n';
            continue;
        }
        const GLuint shader = glCreateShader(stage_of(file));
        // The #version line first, then the libraries (line numbers in messages shift by their length).
        const std::size_t first_line = text.rfind("#version", 0) == 0 ? text.find('\n') + 1 : 0;
        const GLchar* sources[3] = {text.data(), libraries.data(), text.data() + first_line};
        const GLint lengths[3] = {GLint(first_line), GLint(libraries.size()), GLint(text.size() - first_line)};
        glShaderSource(shader, 3, sources, lengths);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            const std::string log = info_log(shader, false);
            glDeleteShader(shader);
            for (GLuint s : shaders)
                glDeleteShader(s);
            throw Error("shader " + std::string(file) + ": " + log);
        }
        glAttachShader(program_.get(), shader);
        shaders.push_back(shader);
        if (!names.empty())
            names += '+';
        names += file;
    }
    glLinkProgram(program_.get());
    for (GLuint s : shaders)
        glDeleteShader(s);
    GLint linked = 0;
    glGetProgramiv(program_.get(), GL_LINK_STATUS, &linked);
    if (!linked)
        throw Error("shader program " + names + ": link failed: " + info_log(program_.get(), true));
}

void ShaderProgram::set(const char* uniform, const glm::vec3& v) const
{
    glProgramUniform3fv(id(), location(uniform), 1, glm::value_ptr(v));
}

void ShaderProgram::set(const char* uniform, const glm::mat4& m) const
{
    glProgramUniformMatrix4fv(id(), location(uniform), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace kiri::render::detail
