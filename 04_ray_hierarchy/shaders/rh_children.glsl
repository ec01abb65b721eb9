// The children of a surviving pair (rh_cull.comp chose the side to split): rh_expand.comp writes them window by
// window, and rh_cull.comp itself when a step's children all fit one window (RH_CULL_WRITES_CHILDREN). The shader
// declares rh_objects, rh_order and rh_pairs_out, and the uniforms rh_branching and rh_identity_order.
//
// Pair p's children are outputs [base, base + n) of the step. Those in [first, last) are written, output g to
// rh_pairs_out[g - out_first]: the object node's children (object nodes, or a leaf's triangles) with the same ray
// side, or the ray node's children with the same object side.
void rh_write_children(uvec2 p, bool split_objects, uint base, uint first, uint last, uint out_first) {
    if (split_objects) {
        const RhObject o = rh_objects[p.y];
        for (uint g = first; g < last; ++g) {
            const uint child = o.first + (g - base);
            const uint y = o.level > 1u ? child
                                        : RH_TRIANGLE_FLAG | (rh_identity_order == 1u ? child : rh_order[child]);
            rh_pairs_out[g - out_first] = uvec2(p.x, y);
        }
    } else {
        const uint level = rh_ray_level(p.x) - 1u, index = rh_ray_index(p.x) * rh_branching;
        for (uint g = first; g < last; ++g)
            rh_pairs_out[g - out_first] = uvec2(rh_ray_side(level, index + (g - base)), p.y);
    }
}
