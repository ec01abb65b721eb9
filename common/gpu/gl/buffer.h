// Reusable GPU building blocks: an RAII buffer (SSBO/UBO/any target), 64-bit counters read back for the ray counts,
// and a GPU timer for phase times.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/trace/ray.h"
#include "gl_check.h"

namespace rt::gpu {

// A GL buffer object. Move-only. size() is in bytes. Storage is mutable (glNamedBufferData), so resize() is cheap
// to call every frame: it reallocates only when the size changes.
class Buffer {
public:
    Buffer() = default;
    explicit Buffer(std::size_t bytes, const void* data = nullptr, GLenum usage = GL_DYNAMIC_DRAW);
    template <class T>
    static Buffer from(const std::vector<T>& v, GLenum usage = GL_DYNAMIC_DRAW) {
        return Buffer(v.size() * sizeof(T), v.data(), usage);
    }
    Buffer(Buffer&& o) noexcept : id_(std::exchange(o.id_, 0)), size_(std::exchange(o.size_, 0)), usage_(o.usage_) {}
    Buffer& operator=(Buffer&& o) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer();

    GLuint id() const { return id_; }
    std::size_t size() const { return size_; }
    template <class T> std::size_t count() const { return size_ / sizeof(T); }
    explicit operator bool() const { return id_ != 0; }

    // Reallocates to `bytes` (contents undefined) unless it already has that size.
    void resize(std::size_t bytes);
    // Grows to at least `bytes` (never shrinks; contents undefined after a growth).
    void reserve(std::size_t bytes) { if (bytes > size_ || !id_) resize(std::max(bytes, size_)); }
    // Writes bytes at an offset; the range must be inside the buffer.
    void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
    // Resizes to the vector and uploads it.
    template <class T> void assign(const std::vector<T>& v) {
        resize(v.size() * sizeof(T));
        if (!v.empty()) upload(v.data(), v.size() * sizeof(T));
    }
    // Reads back (waits for the GPU).
    void download(void* data, std::size_t bytes, std::size_t offset = 0) const;
    template <class T> std::vector<T> download(std::size_t count, std::size_t first = 0) const {
        std::vector<T> v(count);
        if (count) download(v.data(), count * sizeof(T), first * sizeof(T));
        return v;
    }
    template <class T> std::vector<T> download_all() const { return download<T>(size_ / sizeof(T)); }
    template <class T> T download_value(std::size_t index = 0) const {
        T v{};
        download(&v, sizeof(T), index * sizeof(T));
        return v;
    }
    // Fills the whole buffer with a repeated 32-bit value (0 by default).
    void clear_u32(std::uint32_t value = 0);
    // GPU-side copy.
    void copy_to(Buffer& dst, std::size_t bytes, std::size_t src_offset = 0, std::size_t dst_offset = 0) const;

    // glBindBufferBase(target, binding). SSBO by default.
    void bind(GLuint binding, GLenum target = GL_SHADER_STORAGE_BUFFER) const;
    void bind_range(GLuint binding, std::size_t offset, std::size_t bytes, GLenum target = GL_SHADER_STORAGE_BUFFER) const;

private:
    GLuint id_ = 0;
    std::size_t size_ = 0;
    GLenum usage_ = GL_DYNAMIC_DRAW;
};

// Indices of the standard counters (common/shaders/counters.glsl has the same numbers). Stages add their own from
// kCounterStageFirst.
enum CounterIndex : unsigned {
    kCounterPrimaryRays = 0,       // RayKind order: Primary, Shadow, Reflection, Refraction
    kCounterShadowRays = 1,
    kCounterReflectionRays = 2,
    kCounterRefractionRays = 3,
    kCounterIntersectionTests = 4,
    kCounterLoopsCut = 5,          // invocations whose loops the driver ended early (wavefront.glsl)
    kCounterTransparencyRays = 6,  // RayKind::Transparency (continuations through BLEND surfaces)
    kCounterLightSamples = 7,      // of the shadow rays, those to a cell of an area light (RayCounters::light_samples)
    kCounterTestsFirst = 8,        // + RayKind: the intersection tests by the kind of ray that made them (8..12)
    kCounterStageFirst = 13,
};

// 64-bit event counters on the GPU: `count` pairs of uint (lo, hi) in an SSBO bound at RT_BINDING_COUNTERS, added
// to with rt_counter_add() from counters.glsl (atomics with carry, so totals beyond 2^32 are right). Clear before a
// frame, read after.
class CounterBuffer {
public:
    explicit CounterBuffer(unsigned count = 16);
    void clear();
    void bind() const;                     // at RT_BINDING_COUNTERS (bindings.h)
    void bind(GLuint binding) const { buffer_.bind(binding); }
    std::vector<std::uint64_t> read() const;   // waits for the GPU
    RayCounters ray_counters() const;      // the rays, the tests and the tests by kind as the stats' RayCounters
    unsigned count() const { return count_; }
    const Buffer& buffer() const { return buffer_; }

private:
    unsigned count_;
    Buffer buffer_;
};

// GPU time of named phases (GL_TIMESTAMP queries, so phases may nest). begin()/end() around the GL calls of a
// phase; results() waits for the queries and returns milliseconds per phase in first-use order, summed over
// repeated phases. reset() starts over (query objects are reused).
class GpuTimer {
public:
    GpuTimer() = default;
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;
    ~GpuTimer();
    void begin(const std::string& phase);
    void end();   // ends the most recently begun phase still open
    std::vector<std::pair<std::string, double>> results();
    double total_ms(const std::string& phase);   // one phase from results()
    void reset();

    // RAII: { auto scope = timer.scope("trace"); ... }
    class Scope {
    public:
        Scope(GpuTimer& t, const std::string& phase) : t_(&t) { t.begin(phase); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;
        ~Scope() { t_->end(); }
    private:
        GpuTimer* t_;
    };
    Scope scope(const std::string& phase) { return Scope(*this, phase); }

private:
    GLuint query();
    struct Record {
        std::string phase;
        GLuint start = 0, stop = 0;
    };
    std::vector<GLuint> pool_;
    std::size_t used_ = 0;
    std::vector<Record> records_;
    std::vector<std::size_t> open_;
};

}  // namespace rt::gpu
