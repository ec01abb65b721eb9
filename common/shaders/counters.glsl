// 64-bit event counters (rays by kind, intersection tests, stage extras) read back by rt::gpu::CounterBuffer.
// Each counter is a (lo, hi) pair of uints; rt_counter_add carries into hi when lo wraps, so totals beyond 2^32
// are right as long as a single add is below 2^32. Atomics are costly: add once per thread (or per work group
// after a shared-memory reduction), not once per test.
#include "bindings.glsl"

#define RT_COUNTER_PRIMARY_RAYS 0u
#define RT_COUNTER_SHADOW_RAYS 1u
#define RT_COUNTER_REFLECTION_RAYS 2u
#define RT_COUNTER_REFRACTION_RAYS 3u
#define RT_COUNTER_INTERSECTION_TESTS 4u
#define RT_COUNTER_LOOPS_CUT 5u           // invocations whose loops the driver cut short (wavefront.glsl)
#define RT_COUNTER_TRANSPARENCY_RAYS 6u   // continuations through BLEND surfaces (WF_KIND_TRANSPARENCY)
#define RT_COUNTER_LIGHT_SAMPLES 7u       // of the shadow rays, those to a cell of an area light (area_light.glsl)
// The intersection tests again, by the kind of ray that made them: RT_COUNTER_TESTS_FIRST + kind (WF_KIND_* order:
// primary, shadow, reflection, refraction, transparency). Every add to RT_COUNTER_INTERSECTION_TESTS has its twin
// here, so the five sum to the total (the stats' intersection_tests_by_kind; a test checks it on every stage).
#define RT_COUNTER_TESTS_FIRST 8u
#define RT_COUNTER_STAGE_FIRST 13u

layout(std430, binding = RT_BINDING_COUNTERS) buffer RtCounters { uint rt_counters[]; };

void rt_counter_add(uint index, uint value) {
    if (value == 0u) return;
    const uint old = atomicAdd(rt_counters[2u * index], value);
    if (old + value < old) atomicAdd(rt_counters[2u * index + 1u], 1u);
}
