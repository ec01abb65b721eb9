// Helpers for compute passes dispatched with Program::dispatch_threads(n): beyond 65535 work groups the grid is 2D,
// so index threads and groups with these instead of gl_GlobalInvocationID.x, and return when the index is >= n.
// (Macros, so they may be included before the shader's layout(local_size_x = ...) declaration.)

// Linear index of the work group (x fastest).
#define rt_group_index() (gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x)

// Linear index of the thread in a dispatch with a 1D local size.
#define rt_global_index() (rt_group_index() * gl_WorkGroupSize.x + gl_LocalInvocationIndex)
