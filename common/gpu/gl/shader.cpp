#include "shader.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>

#include "common/scene/effects.h"
#include "gl_counters.h"

namespace fs = std::filesystem;

namespace rt::gpu {

ShaderDefines effect_defines(const Effects& effects) {
    ShaderDefines d;
    if (effects.shadows) d["ENABLE_SHADOWS"] = "1";
    if (effects.reflections) d["ENABLE_REFLECTIONS"] = "1";
    if (effects.refractions) d["ENABLE_REFRACTIONS"] = "1";
    if (effects.textures) d["ENABLE_TEXTURES"] = "1";
    if (effects.absorption) d["ENABLE_ABSORPTION"] = "1";
    if (effects.normal_maps) d["ENABLE_NORMAL_MAPS"] = "1";
    if (effects.cutouts) d["ENABLE_CUTOUTS"] = "1";
    if (effects.blend) d["ENABLE_BLEND"] = "1";
    return d;
}

fs::path shader_root() {
    if (const char* env = std::getenv("RT_SHADER_DIR"); env && *env) {
        fs::path p(env);
        if (!fs::is_directory(p)) throw ShaderError("RT_SHADER_DIR=" + p.string() + " is not a folder");
        return p;
    }
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw ShaderError("cannot read /proc/self/exe to find the shaders: " + ec.message());
    const fs::path root = (exe.parent_path() / ".." / "shaders").lexically_normal();
    if (!fs::is_directory(root))
        throw ShaderError("shader folder " + root.string() + " not found (it is copied there by the build; "
                          "set RT_SHADER_DIR to override)");
    return root;
}

fs::path shader_path(const fs::path& relative) {
    return relative.is_absolute() ? relative : shader_root() / relative;
}

namespace {

constexpr std::size_t kLinesPerFile = 100000;

std::string read_text(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ShaderError("cannot open shader file " + file.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::string line;
    std::istringstream in(text);
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

class Preprocessor {
public:
    explicit Preprocessor(const ShaderDefines& defines) : defines_(defines) {}

    PreprocessedShader run(const std::string& name, const std::string& text, const fs::path& dir) {
        files_.push_back(name);
        const std::vector<std::string> lines = split_lines(text);
        // #version: the first line that is one (anything before it must be blank or a comment).
        std::size_t first = 0;
        std::string version = "#version 450 core";
        static const std::regex version_re(R"(^\s*#\s*version\b.*)");
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (std::regex_match(lines[i], version_re)) {
                version = lines[i];
                first = i + 1;
                break;
            }
            const auto nonblank = lines[i].find_first_not_of(" \t");
            if (nonblank != std::string::npos && lines[i].compare(nonblank, 2, "//") != 0) break;
        }
        out_ << version << '\n';
        for (const auto& [key, value] : defines_) out_ << "#define " << key << (value.empty() ? "" : " ") << value << '\n';
        // GLSL 4.50: after "#line L S" the next line is line L of source string S.
        out_ << line_directive(first + 1, 0);
        emit(lines, first, 0, dir);
        return {out_.str(), files_};
    }

    void emit(const std::vector<std::string>& lines, std::size_t first, int file_id, const fs::path& dir) {
        static const std::regex include_re(R"(^\s*#\s*include\s*[\"<]([^\">]+)[\">].*)");
        static const std::regex version_re(R"(^\s*#\s*version\b.*)");
        std::smatch m;
        for (std::size_t i = first; i < lines.size(); ++i) {
            if (std::regex_match(lines[i], m, include_re)) {
                const fs::path found = resolve(m[1].str(), dir, file_id, i + 1);
                const std::string key = fs::weakly_canonical(found).string();
                if (included_.insert(key).second) {
                    const int id = int(files_.size());
                    files_.push_back(display_name(found));
                    out_ << line_directive(1, id);
                    emit(split_lines(read_text(found)), 0, id, found.parent_path());
                    out_ << line_directive(i + 2, file_id);
                } else {
                    out_ << '\n';   // already included: keep the line count
                }
            } else if (file_id != 0 && std::regex_match(lines[i], version_re)) {
                out_ << '\n';       // an included file's #version is dropped
            } else {
                out_ << lines[i] << '\n';
            }
        }
    }

private:
    // The file is encoded in the line number too (file * kLinesPerFile + line), because Mesa reports the wrong
    // source-string number for some errors; map_shader_log decodes it.
    static std::string line_directive(std::size_t line, int file_id) {
        return "#line " + std::to_string(std::size_t(file_id) * kLinesPerFile + line) + " " + std::to_string(file_id) + "\n";
    }

    fs::path resolve(const std::string& name, const fs::path& dir, int file_id, std::size_t line) {
        std::vector<fs::path> candidates;
        if (!dir.empty()) candidates.push_back(dir / name);
        fs::path root;
        try {
            root = shader_root();
            candidates.push_back(root / name);
        } catch (const ShaderError&) {
        }
        for (const auto& c : candidates)
            if (fs::is_regular_file(c)) return c;
        std::string tried;
        for (const auto& c : candidates) tried += (tried.empty() ? "" : ", ") + c.string();
        throw ShaderError(files_[std::size_t(file_id)] + ":" + std::to_string(line) + ": cannot find include \"" +
                          name + "\" (tried " + tried + ")");
    }

    static std::string display_name(const fs::path& p) {
        // Relative to the shader root when inside it ("common/shaders/trace/intersect.glsl"), else the full path.
        try {
            const fs::path root = fs::weakly_canonical(shader_root());
            const fs::path rel = fs::weakly_canonical(p).lexically_relative(root);
            if (!rel.empty() && rel.begin()->string() != "..") return rel.string();
        } catch (const std::exception&) {
        }
        return p.string();
    }

    const ShaderDefines& defines_;
    std::ostringstream out_;
    std::vector<std::string> files_;
    std::set<std::string> included_;
};

}  // namespace

PreprocessedShader preprocess_shader_file(const fs::path& file, const ShaderDefines& defines) {
    const fs::path path = shader_path(file);
    Preprocessor p(defines);
    std::string name = file.is_absolute() ? path.string() : file.string();
    return p.run(name, read_text(path), path.parent_path());
}

PreprocessedShader preprocess_shader_source(const std::string& name, const std::string& text,
                                            const ShaderDefines& defines, const fs::path& dir) {
    Preprocessor p(defines);
    return p.run(name, text, dir);   // no folder: every include is a repository path
}

std::string map_shader_log(const std::string& log, const std::vector<std::string>& files) {
    // Mesa: "0:12(3): error: ..."; NVIDIA: "0(12) : error C1008: ..."; AMD/others: "ERROR: 0:12: ...".
    static const std::regex mesa_re(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
    static const std::regex nvidia_re(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    static const std::regex amd_re(R"(^(ERROR|WARNING):\s*(\d+):(\d+):\s*(.*)$)");
    // "<file>:<line>" from a source number and an encoded line (file * kLinesPerFile + line, see line_directive).
    auto where = [&](const std::string& source, const std::string& line) {
        const std::size_t encoded = std::stoul(line);
        const std::size_t n = encoded >= kLinesPerFile ? encoded / kLinesPerFile : std::stoul(source);
        const std::string name = n < files.size() ? files[n] : "<source " + source + ">";
        return name + ":" + std::to_string(encoded % kLinesPerFile);
    };
    std::string out;
    std::smatch m;
    for (const std::string& line : split_lines(log)) {
        if (line.empty()) continue;
        std::string mapped = line;
        if (std::regex_match(line, m, mesa_re))
            mapped = where(m[1], m[2]) + ":" + m[3].str() + ": " + m[4].str();
        else if (std::regex_match(line, m, nvidia_re))
            mapped = where(m[1], m[2]) + ": " + m[3].str();
        else if (std::regex_match(line, m, amd_re))
            mapped = where(m[2], m[3]) + ": " + m[1].str() + ": " + m[4].str();
        out += mapped + '\n';
    }
    return out;
}

// ---------------------------------------------------------------------------------------------------------------

Program& Program::operator=(Program&& o) noexcept {
    if (this != &o) {
        if (id_) glDeleteProgram(id_);
        id_ = std::exchange(o.id_, 0);
        name_ = std::move(o.name_);
        local_size_ = o.local_size_;
    }
    return *this;
}

Program::~Program() {
    if (id_ && glDeleteProgram) glDeleteProgram(id_);
}

namespace {
const char* stage_name(GLenum stage) {
    switch (stage) {
        case GL_COMPUTE_SHADER: return "compute";
        case GL_VERTEX_SHADER: return "vertex";
        case GL_FRAGMENT_SHADER: return "fragment";
        case GL_GEOMETRY_SHADER: return "geometry";
        case GL_TESS_CONTROL_SHADER: return "tessellation control";
        case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
        default: return "unknown";
    }
}

std::string program_log(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    return log;
}
}  // namespace

namespace {
double g_compile_ms = 0.0;   // shader_compile_ms()
struct CompileClock {        // adds its lifetime to g_compile_ms
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    ~CompileClock() {
        g_compile_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
};
}  // namespace

double shader_compile_ms() { return g_compile_ms; }

Program Program::link(const std::string& name, const std::vector<std::pair<GLenum, PreprocessedShader>>& shaders) {
    const CompileClock clock;
    std::vector<GLuint> compiled;
    auto cleanup = [&] {
        for (GLuint s : compiled) glDeleteShader(s);
    };
    std::vector<std::string> all_files;
    for (const auto& [stage, source] : shaders) {
        const GLuint s = glCreateShader(stage);
        compiled.push_back(s);
        const char* text = source.text.c_str();
        glShaderSource(s, 1, &text, nullptr);
        glCompileShader(s);
        GLint ok = GL_FALSE;
        glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint length = 0;
            glGetShaderiv(s, GL_INFO_LOG_LENGTH, &length);
            std::string log(std::size_t(std::max(length, 1)), '\0');
            glGetShaderInfoLog(s, length, nullptr, log.data());
            log.resize(std::strlen(log.c_str()));
            cleanup();
            // First line: what failed and how badly; the compiler's lines follow.
            const std::string details = map_shader_log(log, source.files);
            std::size_t errors = 0;
            std::istringstream lines(details);
            for (std::string line; std::getline(lines, line);)
                if (line.find("error") != std::string::npos || line.find("ERROR") != std::string::npos) ++errors;
            throw ShaderError("cannot compile " + std::string(stage_name(stage)) + " shader " + source.files.front() +
                              ": " + std::to_string(std::max<std::size_t>(errors, 1)) + " error(s)\n" + details);
        }
        all_files.insert(all_files.end(), source.files.begin(), source.files.end());
    }
    Program p;
    p.name_ = name;
    p.id_ = glCreateProgram();
    for (GLuint s : compiled) glAttachShader(p.id_, s);
    glLinkProgram(p.id_);
    for (GLuint s : compiled) glDetachShader(p.id_, s);
    cleanup();
    GLint ok = GL_FALSE;
    glGetProgramiv(p.id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        // Link logs rarely carry lines; map them with the first shader's files (source numbers are per shader).
        const std::string log = program_log(p.id_);
        throw ShaderError("cannot link shader program " + name + "\n" + map_shader_log(log, shaders.front().second.files));
    }
    if (shaders.size() == 1 && shaders.front().first == GL_COMPUTE_SHADER) {
        GLint size[3] = {0, 0, 0};
        glGetProgramiv(p.id_, GL_COMPUTE_WORK_GROUP_SIZE, size);
        p.local_size_ = glm::uvec3(unsigned(size[0]), unsigned(size[1]), unsigned(size[2]));
    }
    check_gl("building program " + name);
    return p;
}

Program Program::compute(const fs::path& file, const ShaderDefines& defines) {
    return link(file.string(), {{GL_COMPUTE_SHADER, preprocess_shader_file(file, defines)}});
}

Program Program::compute_source(const std::string& name, const std::string& text, const ShaderDefines& defines) {
    return link(name, {{GL_COMPUTE_SHADER, preprocess_shader_source(name, text, defines)}});
}

Program Program::from_files(const std::vector<std::pair<GLenum, fs::path>>& stages, const ShaderDefines& defines) {
    std::vector<std::pair<GLenum, PreprocessedShader>> shaders;
    std::string name;
    for (const auto& [stage, file] : stages) {
        shaders.emplace_back(stage, preprocess_shader_file(file, defines));
        name += (name.empty() ? "" : "+") + file.string();
    }
    return link(name, shaders);
}

void Program::set(const char* name, const glm::mat4& m) const {
    glProgramUniformMatrix4fv(id_, uniform_location(name), 1, GL_FALSE, glm::value_ptr(m));
}

void Program::dispatch(unsigned x, unsigned y, unsigned z) const {
    glUseProgram(id_);
    glDispatchCompute(x, y, z);
    ++gl_counters().dispatches;
}

void Program::dispatch_indirect(const Buffer& args, std::size_t offset) const {
    glUseProgram(id_);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, args.id());
    glDispatchComputeIndirect(GLintptr(offset));
    ++gl_counters().dispatches;
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

glm::uvec3 Program::grid_for(std::size_t n, unsigned local_size) {
    const std::size_t per_group = std::max(1u, local_size);
    const std::size_t groups = n / per_group + (n % per_group != 0 ? 1 : 0);
    if (groups <= kMaxGroupsX) return {unsigned(groups), 1u, 1u};
    return {kMaxGroupsX, unsigned((groups + kMaxGroupsX - 1) / kMaxGroupsX), 1u};
}

void Program::dispatch_threads(std::size_t n) const {
    if (n == 0) return;
    const glm::uvec3 grid = grid_for(n, local_size_.x);
    dispatch(grid.x, grid.y, grid.z);
}

}  // namespace rt::gpu
