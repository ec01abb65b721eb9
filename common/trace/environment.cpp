#include "environment.h"

#include <cmath>

#include "shading.h"

namespace rt {

float environment_atan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float hi = ax > ay ? ax : ay;
    const float lo = ax > ay ? ay : ax;
    if (hi == 0.0f) return 0.0f;
    const float r = lo / hi;   // in [0, 1], where the polynomial holds
    const float r2 = r * r;
    float a = r * (0.9998660f + r2 * (-0.3302995f + r2 * (0.1801410f + r2 * (-0.0851330f + r2 * 0.0208351f))));
    if (ay > ax) a = 0.5f * kPi - a;
    if (x < 0.0f) a = kPi - a;
    return y < 0.0f ? -a : a;
}

glm::vec2 environment_uv(const glm::vec3& d, const glm::vec2& rotation) {
    const float c = rotation.x, s = rotation.y;
    const float x = d.x * c - d.z * s;   // the direction turned by -angle about +Y
    const float z = d.x * s + d.z * c;
    const float u = 0.5f + environment_atan2(x, -z) / (2.0f * kPi);
    const float v = environment_atan2(std::sqrt(x * x + z * z), d.y) / kPi;
    return {u, v};
}

namespace {

glm::vec4 environment_texel(const Environment& e, int x, int y) {
    x = x < 0 ? x + e.width : (x >= e.width ? x - e.width : x);   // wrap in u (x is in [-1, width])
    y = y < 0 ? 0 : (y >= e.height ? e.height - 1 : y);           // clamp in v
    return e.texels[std::size_t(y) * std::size_t(e.width) + std::size_t(x)];
}

}  // namespace

glm::vec3 sample_environment(const Environment& e, const glm::vec2& uv) {
    if (e.width <= 0 || e.height <= 0 || !std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec3(0.0f);
    const float u = uv.x < 0.0f ? 0.0f : (uv.x > 1.0f ? 1.0f : uv.x);
    const float v = uv.y < 0.0f ? 0.0f : (uv.y > 1.0f ? 1.0f : uv.y);
    const float sx = u * float(e.width) - 0.5f, sy = v * float(e.height) - 0.5f;
    const float x0f = std::floor(sx), y0f = std::floor(sy);
    const float ax = sx - x0f, ay = sy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const glm::vec4 top = glm::mix(environment_texel(e, x0, y0), environment_texel(e, x0 + 1, y0), ax);
    const glm::vec4 bottom = glm::mix(environment_texel(e, x0, y0 + 1), environment_texel(e, x0 + 1, y0 + 1), ax);
    return glm::vec3(glm::mix(top, bottom, ay));
}

std::shared_ptr<const Environment> default_world() {
    static const std::shared_ptr<const Environment> world = [] {
        auto e = std::make_shared<Environment>();
        e->file = "default world";
        e->width = 8;
        e->height = 64;
        for (int row = 0; row < e->height; ++row) {
            const double v = (row + 0.5) / e->height;                  // 0 at the top = straight up
            const double y = std::cos(v * 3.14159265358979323846);     // the height of the row's direction
            const float radiance = float(kWorldNadir + (kWorldZenith - kWorldNadir) * 0.5 * (1.0 + y));
            for (int x = 0; x < e->width; ++x) e->texels.push_back(glm::vec4(glm::vec3(radiance), 1.0f));
        }
        return std::shared_ptr<const Environment>(std::move(e));
    }();
    return world;
}

glm::vec3 miss_radiance(const Scene& scene, const glm::vec3& direction) {
    if (!scene.environment) return scene.background;
    return sample_environment(*scene.environment, environment_uv(direction, scene.environment->rotation));
}

}  // namespace rt
