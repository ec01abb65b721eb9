// --sort auto: the batch's cost in queue order and in each sorted order (order_cost.comp), and the choice between
// them (order_choice.comp). C++ twin: order_choice.h (the same width and rounding; a test checks both agree).

// Bindings: stage 05's own buffers, from the traversal's first point (stage 04 binds its own before each pass).
#define OC_BINDING_ORDER (WF_BINDING_TRAVERSAL_FIRST + 0)        // uint[count]: queue index of the i-th sorted ray
#define OC_BINDING_COST (WF_BINDING_TRAVERSAL_FIRST + 1)         // uint[8]: 64-bit width sums: queue, sorted, fine;
                                                                 // then the leaves' radii (once per frame)
#define OC_BINDING_TALLY (WF_BINDING_TRAVERSAL_FIRST + 2)        // uint[2 OC_TALLY_SIZE]: per batch kind (trace,
                                                                 // shadow) 64-bit counts: batches and rays that kept
                                                                 // a sort, batches that kept the fine one; then
                                                                 // uint[2 OC_RECORDS]: each batch's choice
#define OC_BINDING_ORDER_FINE (WF_BINDING_TRAVERSAL_FIRST + 3)   // uint[count]: the order by the fine direction cell
#define OC_BINDING_LEAVES (WF_BINDING_TRAVERSAL_FIRST + 4)       // vec4[]: the spheres the ray nodes meet last
#define OC_TALLY_SIZE 6u
// The frame's choices, one word per batch (its kind's first OC_RECORDS batches): 0, 1 or 2 as oc_choice returns it,
// OC_NO_RECORD where no batch chose. The renderer reads them with the tally, and until a batch is measured again it
// takes the order that won (sort_memory.h).
#define OC_RECORDS 64u
#define OC_NO_RECORD 0xffffffffu

// Width units per diagonal: a level-1 node's width in 1/4096 of the scene's diagonal, rounded down, at most
// 4 diagonals (a wider node reaches everything anyway), so a sum of up to 2^20 nodes stays far inside 64 bits.
#define OC_UNITS 4096.0
#define OC_MAX_WIDTH 4.0
// The distance at which the width is taken, as a part of the diagonal: where a level-1 node meets the object nodes
// it is split against, which the object tree keeps near (chosen by measurement: 05's README, "Choosing per batch").
#define OC_REACH 0.125
// The sorted order is kept when its sum is below (1 - 1/32) of the queue's: the widths are a proxy, and a batch whose
// sort gains less is not worth its passes (it may even test more leaf pairs: 05's README, "Choosing per batch").
#define OC_MARGIN_DENOMINATOR 32.0lf

// radius + L sin(spread) (rh_split_rays' width), L = min(longest ray, OC_REACH diagonal); an empty node is 0 wide,
// a node of every direction (or a NaN) the widest.
uint oc_fixed_width(RhNode node, float longest, float diagonal) {
    if (!(node.sphere.w >= 0.0)) return 0u;
    if (node.cone.w >= RH_ALL_DIRECTIONS) return uint(OC_MAX_WIDTH * OC_UNITS);
    const float reach = rt_isfinite(longest) ? min(longest, OC_REACH * diagonal) : OC_REACH * diagonal;
    precise float width = node.sphere.w + reach * sin(min(node.cone.w, 1.57079637));
    precise float units = width / diagonal * OC_UNITS;
    if (!(units < OC_MAX_WIDTH * OC_UNITS)) return uint(OC_MAX_WIDTH * OC_UNITS);
    return uint(units);
}

// The cap of a node's width: the mean diameter of the finest objects the ray nodes are culled against (the object
// tree's clusters, mesh objects or triangles), from the sum of their radii in width units. A ray node wider than the
// leaf it meets is split into its rays there (rh_split_rays splits one a quarter as wide), so how much wider it is
// changes nothing below; without the cap a few very wide nodes (rays from both sides of a silhouette) outweigh the
// rest, and the sort they favour can cost more (05's README, "Choosing per batch"). No leaves: no cap.
uint oc_radius_units(float radius, float diagonal) {
    precise float units = radius / diagonal * OC_UNITS;
    if (!(units >= 0.0)) return 0u;   // an empty sphere (radius < 0) or NaN
    return units < OC_MAX_WIDTH * OC_UNITS ? uint(units) : uint(OC_MAX_WIDTH * OC_UNITS);
}
uint oc_width_cap(uint sum_lo, uint sum_hi, uint leaves) {
    if (leaves == 0u) return uint(OC_MAX_WIDTH * OC_UNITS);
    const double mean_diameter = 2.0lf * (double(sum_hi) * 4294967296.0lf + double(sum_lo)) / double(leaves);
    return uint(min(mean_diameter, double(OC_MAX_WIDTH * OC_UNITS)));
}
