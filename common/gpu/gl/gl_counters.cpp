#include "gl_counters.h"

namespace rt::gpu {

GlCounters& gl_counters() {
    thread_local GlCounters counters;
    return counters;
}

}  // namespace rt::gpu
