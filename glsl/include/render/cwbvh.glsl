// Two-level CWBVH traversal (8-wide compressed nodes built by obvhs; Ylitie, Karras and Laine
// 2017): a top level over instances, a bottom level per mesh, one shared stack. The node test
// and triangle test compute what obvhs's CPU traversal computes, so the two agree hit for hit.
//
// Bindings 0-4 (block names, bound by renderer::accel::DeviceBvh::bindings):
//   BvhNodes            80-byte nodes as 5 uvec4: top level first, then every mesh's BVH
//   BvhTlasInstances    top-level leaf slot -> instance index
//   BvhTriangles        v0 | mesh triangle, v0 - v1, v2 - v0 per leaf slot (48 bytes)
//   BvhTriangleNormals  octahedral corner normals per leaf slot
//   BvhInstances        world<->object rows, node, triangle and UV offsets, material, mesh
#ifndef LAZYSOLID_RENDER_CWBVH_GLSL
#define LAZYSOLID_RENDER_CWBVH_GLSL

layout(binding = 0, scalar) readonly buffer BvhNodes { uvec4 bvh_nodes[]; };
layout(binding = 1, scalar) readonly buffer BvhTlasInstances { uint bvh_tlas_instances[]; };
layout(binding = 2, scalar) readonly buffer BvhTriangles { vec4 bvh_triangles[]; };
layout(binding = 3, scalar) readonly buffer BvhTriangleNormals { uvec4 bvh_normals[]; };

struct BvhInstance {
    vec4 world_to_object[3];
    vec4 object_to_world[3];
    uint node_offset;
    uint triangle_offset;
    uint material;
    uint mesh;
    uint uv_offset;  // first BvhTriangleUvs record of the mesh, NO_UVS without UVs
    uint pad0, pad1, pad2;
};
layout(binding = 4, scalar) readonly buffer BvhInstances { BvhInstance bvh_instances[]; };

// Nearest distance a node's box may start at (obvhs's EPSILON): boxes entirely closer are
// skipped, as on the CPU.
#define CWBVH_NODE_TMIN 0.0001
// Entries of each invocation's traversal stack: CWBVH_STACK_SIZE, defined once in
// renderer/src/shader_constants.rs.
#ifndef CWBVH_STACK_SIZE
#error "CWBVH_STACK_SIZE comes from renderer/src/shader_constants.rs"
#endif
// The stacks live in shared memory: lavapipe turns a dynamically indexed private array into a
// ladder of selects over every entry, which made each push and pop cost as much as a node test.
// 32 entries of 8 bytes for 128 invocations fill lavapipe's 32 KiB: kernels that include this
// file run workgroups of CWBVH_WORKGROUP_SIZE.
shared uvec2 cwbvh_stacks[gl_WorkGroupSize.x * CWBVH_STACK_SIZE];
// Set when a traversal would have overflowed its stack (it then stops early): checked by the
// tests, never expected for obvhs trees.
bool cwbvh_stack_overflowed = false;

struct TraceHit {
    float t;
    uint instance;   // NO_HIT on a miss
    uint triangle;   // leaf slot in BvhTriangles (global)
    float u;         // barycentric weight of vertex 1
    float v;         // barycentric weight of vertex 2
};

float cwbvh_safe_inverse(float x) {
    return abs(x) <= 1.1920929e-7 ? (x < 0.0 || (x == 0.0 && floatBitsToUint(x) != 0u) ? -1.0 : 1.0) / 1.1920929e-7 : 1.0 / x;
}

vec3 cwbvh_inverse(vec3 d) {
    return vec3(cwbvh_safe_inverse(d.x), cwbvh_safe_inverse(d.y), cwbvh_safe_inverse(d.z));
}

// Octant of the direction, replicated in each byte, inverted (obvhs's oct_inv4).
uint cwbvh_octant_inv4(vec3 d) {
    return (d.x < 0.0 ? 0u : 0x04040404u) | (d.y < 0.0 ? 0u : 0x02020202u) |
           (d.z < 0.0 ? 0u : 0x01010101u);
}

// Hit mask of node `ni`: bits 24-31 internal children in traversal order, bits 0-23 leaf
// triangles relative to the node's primitive base.
uint cwbvh_intersect_node(uint ni, vec3 o, vec3 d, vec3 inv_d, uint oct_inv4, float tmax,
                          out uint child_base, out uint prim_base, out uint imask) {
    uvec4 n0 = bvh_nodes[ni * 5u + 0u];
    uvec4 n1 = bvh_nodes[ni * 5u + 1u];
    uvec4 nx = bvh_nodes[ni * 5u + 2u];
    uvec4 ny = bvh_nodes[ni * 5u + 3u];
    uvec4 nz = bvh_nodes[ni * 5u + 4u];
    vec3 p = uintBitsToFloat(n0.xyz);
    uint e = n0.w;
    vec3 extent = vec3(uintBitsToFloat((e & 0xffu) << 23), uintBitsToFloat(((e >> 8) & 0xffu) << 23),
                       uintBitsToFloat(((e >> 16) & 0xffu) << 23));
    imask = e >> 24;
    child_base = n1.x;
    prim_base = n1.y;
    vec3 adj_inv = extent * inv_d;
    vec3 adj_orig = (p - o) * inv_d;
    uint hitmask = 0u;
    for (uint half_ = 0u; half_ < 2u; half_++) {
        uint meta4 = half_ == 0u ? n1.z : n1.w;
        uint is_inner4 = (meta4 & (meta4 << 1)) & 0x10101010u;
        uint inner_mask4 = (is_inner4 >> 4) * 0xffu;
        uint bit_index4 = (meta4 ^ (oct_inv4 & inner_mask4)) & 0x1f1f1f1fu;
        uint child_bits4 = (meta4 >> 5) & 0x07070707u;
        uint lo_x = half_ == 0u ? nx.x : nx.y, hi_x = half_ == 0u ? nx.z : nx.w;
        uint lo_y = half_ == 0u ? ny.x : ny.y, hi_y = half_ == 0u ? ny.z : ny.w;
        uint lo_z = half_ == 0u ? nz.x : nz.y, hi_z = half_ == 0u ? nz.z : nz.w;
        uint xn = d.x < 0.0 ? hi_x : lo_x, xf = d.x < 0.0 ? lo_x : hi_x;
        uint yn = d.y < 0.0 ? hi_y : lo_y, yf = d.y < 0.0 ? lo_y : hi_y;
        uint zn = d.z < 0.0 ? hi_z : lo_z, zf = d.z < 0.0 ? lo_z : hi_z;
        for (uint j = 0u; j < 4u; j++) {
            uint s = j * 8u;
            vec3 tn = vec3(float((xn >> s) & 0xffu), float((yn >> s) & 0xffu), float((zn >> s) & 0xffu)) * adj_inv + adj_orig;
            vec3 tf = vec3(float((xf >> s) & 0xffu), float((yf >> s) & 0xffu), float((zf >> s) & 0xffu)) * adj_inv + adj_orig;
            float t0 = max(max(tn.x, tn.y), max(tn.z, CWBVH_NODE_TMIN));
            float t1 = min(min(tf.x, tf.y), min(tf.z, tmax));
            if (t0 <= t1) {
                hitmask |= ((child_bits4 >> s) & 0xffu) << ((bit_index4 >> s) & 0xffu);
            }
        }
    }
    return hitmask;
}

// Distance to leaf triangle `slot` in [tmin, tmax], or +inf (obvhs's Triangle::intersect).
float cwbvh_intersect_triangle(uint slot, vec3 o, vec3 d, float tmin, float tmax, out vec2 uv) {
    vec3 v0 = bvh_triangles[slot * 3u + 0u].xyz;
    vec3 e1 = bvh_triangles[slot * 3u + 1u].xyz;
    vec3 e2 = bvh_triangles[slot * 3u + 2u].xyz;
    vec3 n = cross(e1, e2);
    vec3 c = v0 - o;
    vec3 r = cross(d, c);
    float inv_det = 1.0 / dot(n, d);
    float u = dot(r, e2) * inv_det;
    float v = dot(r, e1) * inv_det;
    float w = 1.0 - u - v;
    uv = vec2(u, v);
    uint signs = floatBitsToUint(u) | floatBitsToUint(v) | floatBitsToUint(w);
    if (inv_det != 0.0 && (signs & 0x80000000u) == 0u) {
        float t = dot(n, c) * inv_det;
        if (t >= tmin && t <= tmax) {
            return t;
        }
    }
    return 1.0 / 0.0;
}

vec3 cwbvh_transform_point(vec4 rows[3], vec3 p) {
    return vec3(dot(rows[0], vec4(p, 1.0)), dot(rows[1], vec4(p, 1.0)), dot(rows[2], vec4(p, 1.0)));
}

vec3 cwbvh_transform_vector(vec4 rows[3], vec3 v) {
    return vec3(dot(rows[0].xyz, v), dot(rows[1].xyz, v), dot(rows[2].xyz, v));
}

// Closest hit (any_hit false) or any hit (any_hit true) of the ray o + t d, t in [tmin, tmax].
bool cwbvh_trace(vec3 world_o, vec3 world_d, float tmin, float tmax, bool any_hit, out TraceHit hit) {
    uint stack_base = gl_LocalInvocationIndex * CWBVH_STACK_SIZE;
    uint stack_size = 0u;
    hit.t = 1.0 / 0.0;
    hit.instance = NO_HIT;
    hit.triangle = 0u;
    hit.u = 0.0;
    hit.v = 0.0;

    vec3 o = world_o;
    vec3 d = world_d;
    vec3 inv_d = cwbvh_inverse(d);
    uint oct_inv4 = cwbvh_octant_inv4(d);
    uint world_oct_inv4 = oct_inv4;

    uvec2 current = uvec2(0u, 0x80000000u);
    uvec2 prims = uvec2(0u);
    uint tlas_stack_size = 0xffffffffu;  // not in a bottom level
    uint instance = 0xffffffffu;
    uint node_offset = 0u;
    uint triangle_offset = 0u;

    for (;;) {
        if ((current.y & 0xff000000u) != 0u) {
            uint hits_imask = current.y;
            uint child_index_offset = uint(findMSB(hits_imask));
            uint child_index_base = current.x;
            current.y &= ~(1u << child_index_offset);
            if ((current.y & 0xff000000u) != 0u) {
                if (stack_size == CWBVH_STACK_SIZE) {
                    cwbvh_stack_overflowed = true;
                    break;
                }
                cwbvh_stacks[stack_base + stack_size++] = current;
            }
            uint slot_index = (child_index_offset - 24u) ^ (oct_inv4 & 0xffu);
            uint relative_index = bitCount(hits_imask & ~(0xffffffffu << slot_index));
            uint child_base, prim_base, imask;
            uint hitmask = cwbvh_intersect_node(child_index_base + relative_index, o, d, inv_d,
                                                oct_inv4, tmax, child_base, prim_base, imask);
            current = uvec2(child_base + node_offset, (hitmask & 0xff000000u) | imask);
            prims = uvec2(prim_base + triangle_offset, hitmask & 0x00ffffffu);
        } else {
            // A group popped with only leaves left (postponed top-level leaves).
            prims = current;
            current = uvec2(0u);
        }

        while (prims.y != 0u) {
            uint local = uint(findMSB(prims.y));
            prims.y &= ~(1u << local);
            uint slot = prims.x + local;
            if (tlas_stack_size == 0xffffffffu) {
                // Top level leaf: continue in the instance's mesh BVH, in object space.
                if (stack_size + 2u > CWBVH_STACK_SIZE) {
                    cwbvh_stack_overflowed = true;
                    return false;
                }
                if (prims.y != 0u) {
                    cwbvh_stacks[stack_base + stack_size++] = prims;
                }
                if ((current.y & 0xff000000u) != 0u) {
                    cwbvh_stacks[stack_base + stack_size++] = current;
                }
                tlas_stack_size = stack_size;
                instance = bvh_tlas_instances[slot];
                // Only the fields traversal needs: every load costs on a CPU device.
                vec4 w2o[3] = bvh_instances[instance].world_to_object;
                o = cwbvh_transform_point(w2o, world_o);
                d = cwbvh_transform_vector(w2o, world_d);
                inv_d = cwbvh_inverse(d);
                oct_inv4 = cwbvh_octant_inv4(d);
                node_offset = bvh_instances[instance].node_offset;
                triangle_offset = bvh_instances[instance].triangle_offset;
                current = uvec2(node_offset, 0x80000000u);
                prims = uvec2(0u);
                break;
            }
            vec2 uv;
            float t = cwbvh_intersect_triangle(slot, o, d, tmin, tmax, uv);
            if (t < tmax) {
                tmax = t;
                hit.t = t;
                hit.instance = instance;
                hit.triangle = slot;
                hit.u = uv.x;
                hit.v = uv.y;
                if (any_hit) {
                    return true;
                }
            }
        }

        if (prims.y == 0u && (current.y & 0xff000000u) == 0u) {
            if (stack_size == tlas_stack_size) {
                // The mesh BVH is done: back to the top level, in world space.
                tlas_stack_size = 0xffffffffu;
                o = world_o;
                d = world_d;
                inv_d = cwbvh_inverse(d);
                oct_inv4 = world_oct_inv4;
                node_offset = 0u;
                triangle_offset = 0u;
                instance = 0xffffffffu;
            }
            if (stack_size == 0u) {
                break;
            }
            current = cwbvh_stacks[stack_base + --stack_size];
        }
    }
    return hit.instance != NO_HIT;
}

// Mesh triangle index (mesh order) of a hit's leaf slot.
uint cwbvh_mesh_triangle(uint slot) {
    return floatBitsToUint(bvh_triangles[slot * 3u].w);
}

vec3 cwbvh_decode_octahedral(uint packed) {
    vec2 f = vec2(float(int(packed << 16) >> 16), float(int(packed) >> 16)) / 32767.0;
    vec3 n = vec3(f, 1.0 - abs(f.x) - abs(f.y));
    float t = max(-n.z, 0.0);
    n.x += n.x >= 0.0 ? -t : t;
    n.y += n.y >= 0.0 ? -t : t;
    return normalize(n);
}

#endif
