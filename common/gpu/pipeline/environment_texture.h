// The --environment map on the GPU (docs/shading.md, "The environment"): one RGBA32F texture that
// common/shaders/trace/environment.glsl reads with texelFetch (its own bilinear, the C++ one's twin), bound at
// kTextureUnitEnvironment. Uploaded when the scene's environment changes, so once per run (every frame shares the
// same map); without an environment nothing is created or bound.
#pragma once

#include <memory>

#include "common/scene/environment_map.h"
#include "common/gpu/gl/gl_check.h"

namespace rt::gpu {

class EnvironmentTexture {
public:
    EnvironmentTexture() = default;
    ~EnvironmentTexture();
    EnvironmentTexture(const EnvironmentTexture&) = delete;
    EnvironmentTexture& operator=(const EnvironmentTexture&) = delete;

    // Makes the texture hold `environment` (null: none). Does nothing when it already does. Throws SceneError (the
    // stages exit 2) when the map is wider or taller than this GPU's GL_MAX_TEXTURE_SIZE. Needs a current context.
    void upload(const std::shared_ptr<const Environment>& environment);
    // Binds the texture at kTextureUnitEnvironment; nothing without an environment.
    void bind() const;
    bool present() const { return texture_ != 0; }
    // Texture uploads so far (a test checks that frames share one).
    int uploads() const { return uploads_; }

private:
    std::shared_ptr<const Environment> environment_;
    GLuint texture_ = 0;
    int uploads_ = 0;
};

}  // namespace rt::gpu
