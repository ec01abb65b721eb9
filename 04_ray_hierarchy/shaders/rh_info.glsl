// The traversal's counters (rh_tally.comp adds the group's 64-bit counts to the frame's sums after each group; the
// CPU reads a chunk's length only when it must cut the next step into windows). A 64-bit count is a (lo, hi) pair of
// uints: rh_add64 carries into hi when lo wraps, so a group's pairs may pass 2^32.
#define RH_INFO_OVERFLOW 0u       // a speculative batch: 1 + the first group whose pairs or hits found no room
#define RH_INFO_HITS 1u           // the hit list's length (closest hits)
#define RH_INFO_FOLD 2u           // the fold's "some ray has a next hit" flag
#define RH_INFO_GROUPS_DONE 3u    // rh_cull.comp's groups done (0 between passes: the last one resets it)
#define RH_INFO_FOLD_TESTS 4u     // [4 + kind]: the fold's re-tests per ray kind (five kinds: 4..8)
#define RH_INFO_EXACT 10u         // 64-bit: exact ray/triangle tests (the pairs that passed the cheap tests)
#define RH_INFO_OBJECT_IN 12u     // 64-bit: pairs tested whose object side is an object node
#define RH_INFO_OBJECT_OUT 14u    // 64-bit: those that survived
#define RH_INFO_LEVEL_IN 16u      // 64-bit [16 + 2 l]: pairs tested whose ray side is on level l (l < 32)
#define RH_INFO_LEVEL_OUT 80u     // 64-bit [80 + 2 l]: those that survived (level 0: the exact tests)
#define RH_INFO_LEAF_PAIRS 144u   // 64-bit: (ray, triangle) pairs given to rh_leaf.comp
#define RH_INFO_BOX_TESTS 146u    // 64-bit: the box tests of those pairs (--box-test on)
#define RH_INFO_STEP_COUNT 160u  // [160 + s]: the length of step s's chunk, counted by step s - 1's cull (s < 64)
#define RH_INFO_WORDS 224u

layout(std430, binding = RH_BINDING_INFO) buffer Info { uint rh_info[]; };

// A speculative batch (gpu_ray_hierarchy.cpp, trace): what did not fit its buffer was dropped, so this group
// and every later one are traced again; the first group to find no room is the one named.
uniform uint rh_overflow_mark;   // 1 + the group's place in the batch
void rh_mark_overflow() { atomicCompSwap(rh_info[RH_INFO_OVERFLOW], 0u, rh_overflow_mark); }
bool rh_overflowed() { return rh_info[RH_INFO_OVERFLOW] != 0u; }

void rh_add64(uint index, uint value) {
    if (value == 0u) return;
    const uint before = atomicAdd(rh_info[index], value);
    if (before + value < before) atomicAdd(rh_info[index + 1u], 1u);
}
