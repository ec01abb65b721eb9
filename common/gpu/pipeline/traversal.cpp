#include "traversal.h"

#include <stdexcept>

namespace rt::gpu {

void Traversal::trace_batch(const BatchTraceInputs&, bool) {
    throw std::logic_error("Traversal: no GLSL file and no trace_batch: the pipeline cannot trace its rays");
}

double FrameReport::pass_ms(const std::string& phase) const {
    const auto times = result.extra.find("pass_time_ms");
    if (times == result.extra.end()) return 0.0;
    const auto ms = times->find(phase);
    return ms == times->end() ? 0.0 : ms->get<double>();
}

}  // namespace rt::gpu
