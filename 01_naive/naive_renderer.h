// Stage 01: Whitted ray tracing on the CPU with brute-force ray/triangle tests.
#pragma once

#include "common/app/renderer.h"

namespace rt {

enum class Precision { Float, Double };

class NaiveRenderer : public Renderer {
public:
    void add_options(CLI::App& app) override;
    std::string renderer_name() const override;
    FrameResult render(const Scene& scene, const RenderSettings& settings) override;

    Precision precision = Precision::Float;
};

}  // namespace rt
