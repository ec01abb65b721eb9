#include "environment_texture.h"

#include <string>

#include "common/scene/scene.h"
#include "common/gpu/gl/bindings.h"
#include "common/gpu/gl/gl_counters.h"

namespace rt::gpu {

EnvironmentTexture::~EnvironmentTexture() {
    if (texture_ != 0 && glDeleteTextures) glDeleteTextures(1, &texture_);
}

void EnvironmentTexture::upload(const std::shared_ptr<const Environment>& environment) {
    if (environment == environment_) return;
    if (texture_ != 0) glDeleteTextures(1, &texture_);
    texture_ = 0;
    environment_ = environment;
    if (!environment) return;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (environment->width > max_size || environment->height > max_size) {
        environment_ = nullptr;
        throw SceneError("--environment " + environment->file + ": " + std::to_string(environment->width) + "x" +
                         std::to_string(environment->height) + " is larger than this GPU's textures (" +
                         "GL_MAX_TEXTURE_SIZE " + std::to_string(max_size) + ")");
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA32F, environment->width, environment->height);
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);   // texelFetch only; complete without mipmaps
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureSubImage2D(texture_, 0, 0, 0, environment->width, environment->height, GL_RGBA, GL_FLOAT,
                        environment->texels.data());
    gl_counters().upload_bytes += environment->texels.size() * sizeof(environment->texels[0]);
    ++uploads_;
    check_gl("EnvironmentTexture::upload");
}

void EnvironmentTexture::bind() const {
    if (texture_ != 0) glBindTextureUnit(kTextureUnitEnvironment, texture_);
}

}  // namespace rt::gpu
