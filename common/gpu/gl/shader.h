// Shader programs built from files, with #include of shared GLSL and #defines injected by the stage.
//
// Files: shared GLSL lives in common/shaders/, a stage's passes in <stage>/shaders/; the build copies each under
// <build>/shaders/ at its path in the repository (rt_add_shaders in common/gpu/CMakeLists.txt), so a shader's name
// ("common/shaders/wavefront/shade.comp", "03_uniform_grid/shaders/grid_count.comp") is where its source is, and so
// are the file names in compiler messages. At run time they are found from the executable's path
// (<exe dir>/../shaders), or from $RT_SHADER_DIR when set; never from the current directory.
//
// Preprocessing (done here, not by the driver):
//  - `#version` is kept (or `#version 450 core` added) as the first line, followed by the injected defines.
//  - `#include "file.glsl"` is replaced by the file, looked up in the including file's folder, then in the shader
//    root: an include names a sibling ("rh_common.glsl") or the file's repository path
//    ("common/shaders/trace/intersect.glsl"), nothing else, so the name is always the file to open. Each file is
//    included once per shader (like #pragma once); includes are unconditional (not subject to #if).
//  - `#line` directives keep the real file names and lines: each file gets a source-string number, and a compile
//    or link error is rethrown as ShaderError with "<file>:<line>: <driver message>" lines.
#pragma once

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "buffer.h"
#include "gl_check.h"

namespace rt { struct Effects; }

namespace rt::gpu {

class ShaderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// NAME -> VALUE ("" for a bare #define NAME). Ordered, so the generated source is deterministic.
using ShaderDefines = std::map<std::string, std::string>;

// ENABLE_SHADOWS, ENABLE_REFLECTIONS, ENABLE_REFRACTIONS, ENABLE_TEXTURES for the effects a scene uses
// (each defined to 1 when on, absent when off: test with #ifdef).
ShaderDefines effect_defines(const Effects& effects);

// The shader root: $RT_SHADER_DIR when set, else <directory of /proc/self/exe>/../shaders. Throws ShaderError when
// the folder does not exist.
std::filesystem::path shader_root();
// A path relative to shader_root() (absolute paths are returned unchanged).
std::filesystem::path shader_path(const std::filesystem::path& relative);

// One shader's text after #include expansion, and the file name behind each GLSL source-string number.
struct PreprocessedShader {
    std::string text;
    std::vector<std::string> files;   // files[n] = the file of source-string number n
};

PreprocessedShader preprocess_shader_file(const std::filesystem::path& file, const ShaderDefines& defines = {});
// In-memory source (tests, the GLSL harness): `name` is used in messages; includes resolve against `dir` when given,
// then as repository paths under the shader root.
PreprocessedShader preprocess_shader_source(const std::string& name, const std::string& text,
                                            const ShaderDefines& defines = {},
                                            const std::filesystem::path& dir = {});

// Rewrites a driver's info log ("0:12(3): error: ..." from Mesa, "0(12) : error C0000: ..." from NVIDIA) so each
// message starts with "<file>:<line>:". The preprocessor numbers the lines of included file k as k * 100000 + line
// (Mesa reports the wrong source-string number for some errors, the line number it always gets right); this
// decodes both.
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

// A linked GL program. Move-only.
class Program {
public:
    Program() = default;
    Program(Program&& o) noexcept : id_(std::exchange(o.id_, 0)), name_(std::move(o.name_)), local_size_(o.local_size_) {}
    Program& operator=(Program&& o) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
    ~Program();

    // A compute program from a file (relative to shader_root(), e.g. "03_uniform_grid/shaders/grid_count.comp").
    static Program compute(const std::filesystem::path& file, const ShaderDefines& defines = {});
    static Program compute_source(const std::string& name, const std::string& text, const ShaderDefines& defines = {});
    // Any set of stages: {{GL_VERTEX_SHADER, "02_raster_hybrid/shaders/gbuffer.vert"}, {GL_FRAGMENT_SHADER, ...}}.
    static Program from_files(const std::vector<std::pair<GLenum, std::filesystem::path>>& stages,
                              const ShaderDefines& defines = {});

    GLuint id() const { return id_; }
    const std::string& name() const { return name_; }
    explicit operator bool() const { return id_ != 0; }
    void use() const { glUseProgram(id_); }

    // Uniforms (glProgramUniform*: no need to bind the program). A name the linker removed is ignored.
    GLint uniform_location(const char* name) const { return glGetUniformLocation(id_, name); }
    void set(const char* name, int v) const { glProgramUniform1i(id_, uniform_location(name), v); }
    void set(const char* name, unsigned v) const { glProgramUniform1ui(id_, uniform_location(name), v); }
    void set(const char* name, float v) const { glProgramUniform1f(id_, uniform_location(name), v); }
    void set(const char* name, const glm::vec2& v) const { glProgramUniform2f(id_, uniform_location(name), v.x, v.y); }
    void set(const char* name, const glm::vec3& v) const { glProgramUniform3f(id_, uniform_location(name), v.x, v.y, v.z); }
    void set(const char* name, const glm::vec4& v) const {
        glProgramUniform4f(id_, uniform_location(name), v.x, v.y, v.z, v.w);
    }
    void set(const char* name, const glm::ivec2& v) const { glProgramUniform2i(id_, uniform_location(name), v.x, v.y); }
    void set(const char* name, const glm::uvec2& v) const { glProgramUniform2ui(id_, uniform_location(name), v.x, v.y); }
    void set(const char* name, const glm::mat4& m) const;
    // A uint array uniform (`uniform uint name[N]`), from element 0.
    void set(const char* name, const std::vector<unsigned>& v) const {
        glProgramUniform1uiv(id_, uniform_location(name), GLsizei(v.size()), v.data());
    }

    // Compute programs: the local size declared in the shader.
    glm::uvec3 local_size() const { return local_size_; }
    // glUseProgram + glDispatchCompute(x, y, z).
    void dispatch(unsigned x, unsigned y = 1, unsigned z = 1) const;
    // glDispatchComputeIndirect: the work-group counts (3 uints) are read from `args` at `offset` bytes, where an
    // earlier pass wrote them (no read-back to the CPU).
    void dispatch_indirect(const Buffer& args, std::size_t offset) const;
    // Enough work groups of local_size().x for n threads (1D shaders). Beyond 65535 groups the grid becomes 2D:
    // use rt_global_index() from compute.glsl to get the thread index and compare it with n.
    void dispatch_threads(std::size_t n) const;
    // The grid dispatch_threads(n) uses for work groups of `local_size` threads: (groups, 1, 1), or beyond kMaxGroupsX
    // groups kMaxGroupsX columns and as many rows as needed. compute.glsl's rt_dispatch_size is its twin, for passes
    // dispatched indirectly with a count only the GPU knows.
    static glm::uvec3 grid_for(std::size_t n, unsigned local_size);

private:
    GLuint id_ = 0;
    std::string name_;
    glm::uvec3 local_size_{0};
    static Program link(const std::string& name, const std::vector<std::pair<GLenum, PreprocessedShader>>& shaders);
};

// Wall time spent compiling and linking programs in this process so far, in ms (the stats report it apart).
double shader_compile_ms();

// The most work groups one dispatch_threads() call may need in x before it switches to a 2D grid.
constexpr unsigned kMaxGroupsX = 65535;

}  // namespace rt::gpu
