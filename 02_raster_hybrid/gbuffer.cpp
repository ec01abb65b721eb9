#include "gbuffer.h"

#include <algorithm>
#include <cmath>

namespace rt::gpu {

GBuffer::GBuffer()
    : program_(Program::from_files({{GL_VERTEX_SHADER, "02_raster_hybrid/shaders/gbuffer.vert"},
                                         {GL_FRAGMENT_SHADER, "02_raster_hybrid/shaders/gbuffer.frag"}})) {
    // The vertices come straight from the scene's position buffer (vec4 per vertex, 3 per triangle).
    glCreateVertexArrays(1, &vao_);
    glEnableVertexArrayAttrib(vao_, 0);
    glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, 0, 0);
    glCreateFramebuffers(1, &fbo_);
    check_gl("GBuffer: create");
}

GBuffer::~GBuffer() {
    if (!glDeleteVertexArrays) return;
    glDeleteVertexArrays(1, &vao_);
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &ids_);
    glDeleteTextures(1, &depth_);
}

void GBuffer::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    glDeleteTextures(1, &ids_);
    glDeleteTextures(1, &depth_);
    glCreateTextures(GL_TEXTURE_2D, 1, &ids_);
    glTextureStorage2D(ids_, 1, GL_R32UI, width, height);
    // Integer textures are incomplete (texelFetch returns 0) unless filtered with GL_NEAREST.
    glTextureParameteri(ids_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(ids_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
    glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, ids_, 0);
    glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
    glNamedFramebufferDrawBuffer(fbo_, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("GBuffer: incomplete framebuffer");
    width_ = width;
    height_ = height;
}

void GBuffer::render(const GpuScene& scene, const Camera& camera, const Bounds& bounds, int width, int height,
                     glm::vec2 offset) {
    resize(width, height);
    const bool ortho = camera.projection == Projection::Orthographic;
    const float aspect = camera.aspect > 0.0f ? camera.aspect : float(width) / float(height);
    const float h = std::tan(camera.yfov * 0.5f);
    program_.set("eye", camera.position);
    program_.set("right", camera.right);
    program_.set("up", camera.up);
    program_.set("forward", camera.forward);
    program_.set("orthographic", ortho ? 1 : 0);
    program_.set("scale", ortho ? glm::vec2(1.0f / camera.xmag, 1.0f / camera.ymag) : glm::vec2(1.0f / (h * aspect), 1.0f / h));
    program_.set("jitter", glm::vec2(2.0f * (offset.x - 0.5f) / float(width), 2.0f * (offset.y - 0.5f) / float(height)));
    // Rays start at the eye, so the near plane only has to be tiny; reversed float depth keeps its precision.
    const float size = std::max(bounds.diagonal(), 1e-3f);
    program_.set("near", size * 1e-6f);
    // Orthographic depth is linear: put the far plane behind the farthest corner of the scene.
    float far = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
                               (i & 4) ? bounds.hi.z : bounds.lo.z);
        far = std::max(far, glm::dot(corner - camera.position, camera.forward));
    }
    program_.set("far", std::isfinite(far) ? far * 1.01f + size * 0.01f + 1.0f : 1.0f);

    const GLuint zero[4] = {0, 0, 0, 0};
    const float depth_clear = 0.0f;   // reversed depth: 0 is infinitely far
    glClearNamedFramebufferuiv(fbo_, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &depth_clear);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);   // strictly nearer wins; on a tie the earlier triangle stays, as in stage 01
    glDisable(GL_CULL_FACE);   // rays see back faces too
    glDisable(GL_BLEND);
    if (scene.triangle_count() > 0) {
        glVertexArrayVertexBuffer(vao_, 0, scene.positions().id(), 0, sizeof(glm::vec4));
        glBindVertexArray(vao_);
        program_.use();
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(scene.triangle_count() * 3));
        glBindVertexArray(0);
    }
    glDisable(GL_DEPTH_TEST);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // The compute pass that reads the ids must see them.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    check_gl("G-buffer pass");
}

std::vector<std::uint32_t> GBuffer::read_triangle_ids() const {
    std::vector<std::uint32_t> ids(std::size_t(width_) * std::size_t(height_));
    glGetTextureImage(ids_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(ids.size() * sizeof(std::uint32_t)), ids.data());
    check_gl("GBuffer: read triangle ids");
    return ids;
}

void GBuffer::shade_sample(Wavefront& wavefront, glm::vec2 offset) {
    std::string key;
    for (const auto& [k, v] : wavefront.defines()) key.append(k).append("=").append(v).append(";");
    if (key != primary_hits_key_) {
        primary_hits_ = Program::compute(kPrimaryHitsProgram, wavefront.defines());
        // Cut-outs: pixels whose candidate may be transparent defer their camera ray (shaders/deferred_rays.comp).
        deferred_rays_ = wavefront.defines().count("ENABLE_CUTOUTS")
                             ? Program::compute("02_raster_hybrid/shaders/deferred_rays.comp", wavefront.defines())
                             : Program();
        primary_hits_key_ = key;
    }
    primary_hits_.set("wf_sample_offset", offset);
    glBindTextureUnit(kWavefrontFirstFreeTextureUnit, ids_);
    wavefront.shade_sample(primary_hits_, deferred_rays_ ? &deferred_rays_ : nullptr);
    check_gl("G-buffer: shade sample");
}

std::vector<std::string> GBuffer::programs() const {
    std::vector<std::string> names;
    for (const Program* p : {&primary_hits_, &deferred_rays_})
        if (*p) names.push_back(p->name());
    return names;
}

}  // namespace rt::gpu
