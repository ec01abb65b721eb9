// Helpers for compute passes dispatched with Program::dispatch_threads(n): beyond 65535 work groups the grid is 2D,
// so index threads and groups with these instead of gl_GlobalInvocationID.x, and return when the index is >= n.
// (Macros, so they may be included before the shader's layout(local_size_x = ...) declaration.)

// Linear index of the work group (x fastest).
#define rt_group_index() (gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x)

// Linear index of the thread in a dispatch with a 1D local size.
#define rt_global_index() (rt_group_index() * gl_WorkGroupSize.x + gl_LocalInvocationIndex)

// The work groups Program::dispatch_threads(threads) dispatches for groups of `local_size` threads (Program::grid_for:
// 2D beyond RT_MAX_GROUPS_X groups), as the 3 words of an indirect dispatch that a pass writes for a count only the
// GPU knows.
#define RT_MAX_GROUPS_X 65535u   // common/gpu/gl/shader.h: kMaxGroupsX
uvec3 rt_dispatch_size(uint threads, uint local_size) {
    const uint groups = threads / local_size + (threads % local_size != 0u ? 1u : 0u);
    if (groups <= RT_MAX_GROUPS_X) return uvec3(groups, 1u, 1u);
    return uvec3(RT_MAX_GROUPS_X, groups / RT_MAX_GROUPS_X + (groups % RT_MAX_GROUPS_X != 0u ? 1u : 0u), 1u);
}
