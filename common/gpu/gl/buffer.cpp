#include "buffer.h"

#include <algorithm>
#include <stdexcept>

#include "bindings.h"
#include "gl_counters.h"

namespace rt::gpu {

Buffer::Buffer(std::size_t bytes, const void* data, GLenum usage) : usage_(usage) {
    glCreateBuffers(1, &id_);
    size_ = bytes;
    // Never allocate zero bytes: a zero-sized buffer cannot be bound as a range and some drivers dislike it.
    if (data && bytes > 0) {
        glNamedBufferData(id_, GLsizeiptr(bytes), data, usage_);
        gl_counters().upload_bytes += bytes;
    } else {
        glNamedBufferData(id_, GLsizeiptr(std::max<std::size_t>(bytes, 16)), nullptr, usage_);
    }
    check_gl("Buffer allocate");
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
    if (this != &o) {
        if (id_) glDeleteBuffers(1, &id_);
        id_ = std::exchange(o.id_, 0);
        size_ = std::exchange(o.size_, 0);
        usage_ = o.usage_;
    }
    return *this;
}

Buffer::~Buffer() {
    if (id_ && glDeleteBuffers) glDeleteBuffers(1, &id_);
}

void Buffer::resize(std::size_t bytes) {
    if (!id_) glCreateBuffers(1, &id_);
    else if (bytes == size_) return;
    size_ = bytes;
    glNamedBufferData(id_, GLsizeiptr(std::max<std::size_t>(bytes, 16)), nullptr, usage_);
    check_gl("Buffer resize");
}

void Buffer::upload(const void* data, std::size_t bytes, std::size_t offset) {
    if (offset + bytes > size_)
        throw std::out_of_range("Buffer::upload: " + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                                " exceed the size " + std::to_string(size_));
    if (!bytes) return;
    glNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
    gl_counters().upload_bytes += bytes;
}

void Buffer::download(void* data, std::size_t bytes, std::size_t offset) const {
    if (offset + bytes > size_)
        throw std::out_of_range("Buffer::download: " + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                                " exceed the size " + std::to_string(size_));
    if (!bytes) return;
    // Make shader writes visible to the read-back.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
    ++gl_counters().read_backs;
    check_gl("Buffer download");
}

void Buffer::clear_u32(std::uint32_t value) {
    glClearNamedBufferData(id_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

void Buffer::copy_to(Buffer& dst, std::size_t bytes, std::size_t src_offset, std::size_t dst_offset) const {
    if (src_offset + bytes > size_ || dst_offset + bytes > dst.size_)
        throw std::out_of_range("Buffer::copy_to: range outside a buffer");
    if (bytes) glCopyNamedBufferSubData(id_, dst.id_, GLintptr(src_offset), GLintptr(dst_offset), GLsizeiptr(bytes));
}

void Buffer::bind(GLuint binding, GLenum target) const { glBindBufferBase(target, binding, id_); }

void Buffer::bind_range(GLuint binding, std::size_t offset, std::size_t bytes, GLenum target) const {
    glBindBufferRange(target, binding, id_, GLintptr(offset), GLsizeiptr(bytes));
}

// ---------------------------------------------------------------------------------------------------------------

CounterBuffer::CounterBuffer(unsigned count) : count_(count), buffer_(std::size_t(count) * 8) { clear(); }

void CounterBuffer::clear() { buffer_.clear_u32(0); }

void CounterBuffer::bind() const { buffer_.bind(kBindingCounters); }

std::vector<std::uint64_t> CounterBuffer::read() const {
    const auto raw = buffer_.download<std::uint32_t>(std::size_t(count_) * 2);
    std::vector<std::uint64_t> out(count_);
    for (unsigned i = 0; i < count_; ++i) out[i] = std::uint64_t(raw[2 * i]) | (std::uint64_t(raw[2 * i + 1]) << 32);
    return out;
}

RayCounters CounterBuffer::ray_counters() const {
    const auto c = read();
    RayCounters r;
    const unsigned ray_counter[kRayKinds] = {kCounterPrimaryRays, kCounterShadowRays, kCounterReflectionRays,
                                             kCounterRefractionRays, kCounterTransparencyRays};
    for (int i = 0; i < kRayKinds; ++i) r.rays[i] = c.size() > ray_counter[i] ? c[ray_counter[i]] : 0;
    r.light_samples = c.size() > kCounterLightSamples ? c[kCounterLightSamples] : 0;
    r.intersection_tests = c.size() > kCounterIntersectionTests ? c[kCounterIntersectionTests] : 0;
    for (unsigned k = 0; k < unsigned(kRayKinds); ++k)
        r.tests_by_kind[k] = c.size() > kCounterTestsFirst + k ? c[kCounterTestsFirst + k] : 0;
    return r;
}

// ---------------------------------------------------------------------------------------------------------------

GpuTimer::~GpuTimer() {
    if (!pool_.empty() && glDeleteQueries) glDeleteQueries(GLsizei(pool_.size()), pool_.data());
}

GLuint GpuTimer::query() {
    if (used_ == pool_.size()) {
        GLuint q = 0;
        glGenQueries(1, &q);
        pool_.push_back(q);
    }
    return pool_[used_++];
}

void GpuTimer::begin(const std::string& phase) {
    Record r;
    r.phase = phase;
    r.start = query();
    glQueryCounter(r.start, GL_TIMESTAMP);
    open_.push_back(records_.size());
    records_.push_back(r);
}

void GpuTimer::end() {
    if (open_.empty()) throw std::logic_error("GpuTimer::end without begin");
    Record& r = records_[open_.back()];
    open_.pop_back();
    r.stop = query();
    glQueryCounter(r.stop, GL_TIMESTAMP);
}

std::vector<std::pair<std::string, double>> GpuTimer::results() {
    std::vector<std::pair<std::string, double>> out;
    if (!records_.empty()) ++gl_counters().read_backs;   // one wait: the queries are read in order
    for (const Record& r : records_) {
        if (!r.stop) continue;
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(r.start, GL_QUERY_RESULT, &t0);   // waits
        glGetQueryObjectui64v(r.stop, GL_QUERY_RESULT, &t1);
        const double ms = double(t1 - t0) * 1e-6;
        auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == r.phase; });
        if (it == out.end()) out.emplace_back(r.phase, ms);
        else it->second += ms;
    }
    check_gl("GpuTimer results");
    return out;
}

double GpuTimer::total_ms(const std::string& phase) {
    for (const auto& [name, ms] : results())
        if (name == phase) return ms;
    return 0.0;
}

void GpuTimer::reset() {
    records_.clear();
    open_.clear();
    used_ = 0;
}

}  // namespace rt::gpu
