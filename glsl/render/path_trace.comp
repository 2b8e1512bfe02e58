#version 460
// One sample per pixel of a unidirectional path tracer: next-event estimation of the analytic
// lights and the environment combined with BSDF sampling by multiple importance sampling
// (power heuristic), Russian roulette, accumulation into a float film. Random numbers depend
// only on (pixel, sample, seed): the same seed gives the same image on any run.
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "common.glsl"

// The scene's material and texture kinds (render/material.glsl): the others are compiled out.
#define MATERIAL_KINDS_SPECIALIZED
layout(constant_id = PATH_TRACE_MATERIAL_KINDS_ID) const uint MATERIAL_KINDS = 0xffffffffu;
layout(constant_id = PATH_TRACE_TEXTURE_KINDS_ID) const uint TEXTURE_KINDS = 0xffffffffu;

#include "render/cwbvh.glsl"
#include "render/rng.glsl"
#include "render/sampling.glsl"
#include "render/material.glsl"
#include "render/bsdf.glsl"
#include "render/glint_bsdf.glsl"
#include "render/solid_texture.glsl"
#include "render/image.glsl"
#include "render/lights.glsl"
#include "render/environment.glsl"
#include "store/hash.glsl"
#include "store/octree.glsl"
#include "store/perfect.glsl"
#include "store/tiletree.glsl"

struct Frame {
    vec3 eye;
    float lens_radius;
    vec3 forward;       // unit view direction
    float focus_distance;
    vec3 right;         // scaled by tan(fov/2) * aspect
    uint width;
    vec3 up;            // scaled by tan(fov/2)
    uint height;
    uint seed;
    uint max_depth;
    uint rr_depth;
    uint light_count;
    uint env_sampled;   // 1 when the environment is a next-event strategy (not black)
    uint aovs;          // 1 when this pass writes albedo, normal and depth
    uint pad0, pad1;
};

layout(binding = 5, scalar) readonly buffer FrameBlock { Frame frame; };
layout(binding = 6, scalar) readonly buffer Materials { Material materials[]; };
layout(binding = 7, scalar) readonly buffer Lights { Light lights[]; };
layout(binding = 8, scalar) readonly buffer EnvironmentBlock { Environment env; };
layout(binding = 9, scalar) buffer Film { vec4 film[]; };          // rgb sum, w samples
layout(binding = 10, scalar) buffer Aovs { vec4 aovs[]; };         // albedo | normal, depth per pixel (2 vec4)
layout(binding = 11, scalar) buffer RayCount { uint ray_count[]; };

// Solid textures baked into sparse stores (renderer/src/render/stores.rs).
struct StoreRecord {
    uint kind;     // STORE_KIND_*
    uint filtering;  // STORE_FILTER_*
    float relief;  // object-space height per unit of alpha (0: no relief)
    HashStoreParams hash;
    OctreeParams octree;
    PerfectStoreParams perfect;
    TileTreeParams tiletree;
};
layout(binding = 12, scalar) readonly buffer StoreRecords { StoreRecord store_records[]; };
layout(binding = 13, scalar) readonly buffer InstanceStores { uint instance_stores[]; };
// Glint microstructures, one record per glint material (renderer/src/glint/gpu_material.rs).
layout(binding = 14, scalar) readonly buffer GlintRecords { GlintRecord glint_records[]; };
// Texture coordinates and MikkTSpace tangents per triangle corner, for meshes that have them
// (renderer/src/accel/gpu_types.rs, GpuTriangleUvs).
struct TriangleUvs {
    vec2 uv[3];
    uint tangents[3];  // octahedral
    uint flipped;      // bit k: corner k's bitangent is -(n x t)
};
layout(binding = 15, scalar) readonly buffer BvhTriangleUvs { TriangleUvs bvh_uvs[]; };

// Bit 0: a scene material has a normal map (0 compiles the tangent frames and lookups out);
// bit 1: one of them is filtered by vMF mixtures (0 compiles the mixture BSDF out).
layout(constant_id = PATH_TRACE_NORMAL_MAPS_ID) const uint NORMAL_MAPS = 3u;
// Lobes per texel of the vMF-filtered maps (the scene's largest J; at least 1).
layout(constant_id = PATH_TRACE_VMF_LOBES_ID) const uint VMF_LOBES = 4u;
#include "render/normal_vmf.glsl"

layout(push_constant, scalar) uniform Push {
    uint sample_index;
    uint first_pixel;
    uint pixel_count;
} pc;

float power_heuristic(float a, float b) {
    float a2 = a * a;
    float b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

float max3(vec3 v) {
    return max(v.x, max(v.y, v.z));
}

// Pixel of the i-th invocation: 8x8 tiles, so the lanes of a SIMD group trace nearby rays.
uvec2 pixel_of(uint i) {
    uint tiles_x = (frame.width + 7u) / 8u;
    uint tile = i / 64u;
    uint within = i % 64u;
    return uvec2((tile % tiles_x) * 8u + within % 8u, (tile / tiles_x) * 8u + within / 8u);
}

struct SurfaceHit {
    vec3 p;        // world position
    vec3 ng;       // world geometric normal (outward, as the mesh winds)
    vec3 ns;       // world shading normal, on the same side as ng
    vec3 p_object; // rest-pose object position (where solid textures live)
    vec3 p_surface_object;  // the hit point itself in object space (where stores are read)
    vec3 n_object;          // the geometric normal in object space (a TileTree picks its face)
    uint material;
    uint instance;
};

float srgb_to_linear(float c) {
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

// The scene's store kinds, one bit per STORE_KIND_*, are a specialization constant: the lookups
// of kinds the scene does not use are compiled out, which shortens the pipeline's compilation on
// a CPU device (default: all four kinds).
layout(constant_id = PATH_TRACE_STORE_KINDS_ID) const uint STORE_KINDS = 15u;

bool store_kind_used(uint kind) {
    return (STORE_KINDS & (1u << kind)) != 0u;
}

// The sample lookup of a store with relief (its filter; TileTree: bilinear): the colour sum,
// the stored corners' weight and the gradient of alpha (store/texels.glsl).
StoreSample store_sample(uint slot, vec3 pos, vec3 normal) {
    uint kind = store_records[slot].kind;
    StoreSample s = store_sample_empty();
    if (store_kind_used(STORE_KIND_HASH) && kind == STORE_KIND_HASH) {
        s = store_hash_sample(store_records[slot].hash, pos);
    } else if (store_kind_used(STORE_KIND_OCTREE) && kind == STORE_KIND_OCTREE) {
        s = store_octree_sample(store_records[slot].octree, pos);
    } else if (store_kind_used(STORE_KIND_PERFECT) && kind == STORE_KIND_PERFECT) {
        s = store_perfect_sample(store_records[slot].perfect, pos);
    } else if (store_kind_used(STORE_KIND_TILETREE) && kind == STORE_KIND_TILETREE) {
        s = store_tiletree_sample(store_records[slot].tiletree, pos, normal);
    }
    return s;
}

vec3 albedo_of_srgb(vec3 srgb) {
    return vec3(srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b));
}

// The resolution R of a store.
uint store_resolution(uint slot) {
    uint kind = store_records[slot].kind;
    if (kind == STORE_KIND_HASH) {
        return store_records[slot].hash.resolution;
    } else if (kind == STORE_KIND_OCTREE) {
        return store_records[slot].octree.resolution;
    } else if (kind == STORE_KIND_PERFECT) {
        return store_records[slot].perfect.resolution;
    }
    return store_records[slot].tiletree.resolution;
}

// The relief channel (alpha, renormalized by coverage) at pos; false where nothing is stored.
bool relief_height(uint slot, vec3 pos, vec3 normal, out float height) {
    StoreSample s = store_sample(slot, pos, normal);
    height = s.coverage > 0.0 ? s.sum.a / s.coverage : 0.0;
    return s.coverage > 0.0;
}

// Slope of the relief channel along the unit tangent `dir` at pos, per object unit: a central
// difference of the filtered channel one voxel (h) either side. The filter's own derivative
// jumps from voxel to voxel (the shading shows every voxel as a facet); the difference of the
// continuous filtered channel is continuous. One-sided where one side is not stored; the
// filter's derivative where neither is.
float relief_slope(uint slot, vec3 pos, vec3 normal, vec3 dir, float h, float centre, vec3 analytic) {
    float plus;
    float minus;
    bool p = relief_height(slot, pos + dir * h, normal, plus);
    bool m = relief_height(slot, pos - dir * h, normal, minus);
    if (p && m) {
        return (plus - minus) / (2.0 * h);
    } else if (p) {
        return (plus - centre) / h;
    } else if (m) {
        return (centre - minus) / h;
    }
    return dot(analytic, dir);
}

// Albedo of a store-baked texture at an object-space surface point with its object-space
// geometric normal, and the gradient (object space, in the surface's tangent plane) of its
// relief height, 0 without relief. A point whose voxels are not stored (never expected on the
// surface) shows magenta, so a hole is seen, not hidden. A store with relief carries the relief
// code in alpha, so its coverage comes from the sample lookup, not from alpha.
vec3 store_albedo(uint slot, vec3 pos, vec3 normal, out vec3 relief_gradient) {
    relief_gradient = vec3(0.0);
    float relief = store_records[slot].relief;
    if (relief > 0.0) {
        StoreSample s = store_sample(slot, pos, normal);
        if (s.coverage <= 0.0) {
            return vec3(1.0, 0.0, 1.0);
        }
        float centre = s.sum.a / s.coverage;
        vec3 analytic = s.gradient / s.coverage;
        vec3 t;
        vec3 b;
        make_frame(normalize(normal), t, b);
        float h = 1.0 / float(store_resolution(slot));
        relief_gradient = relief * (t * relief_slope(slot, pos, normal, t, h, centre, analytic) +
                                    b * relief_slope(slot, pos, normal, b, h, centre, analytic));
        return albedo_of_srgb(s.sum.rgb / s.coverage);
    }
    uint kind = store_records[slot].kind;
    bool nearest = store_records[slot].filtering == STORE_FILTER_NEAREST;
    vec4 c = vec4(0.0);
    if (store_kind_used(STORE_KIND_HASH) && kind == STORE_KIND_HASH) {
        HashStoreParams p = store_records[slot].hash;
        c = nearest ? store_hash_nearest(p, pos) : store_hash_trilinear(p, pos);
    } else if (store_kind_used(STORE_KIND_OCTREE) && kind == STORE_KIND_OCTREE) {
        OctreeParams p = store_records[slot].octree;
        c = nearest ? store_octree_nearest(p, pos) : store_octree_trilinear(p, pos);
    } else if (store_kind_used(STORE_KIND_PERFECT) && kind == STORE_KIND_PERFECT) {
        PerfectStoreParams p = store_records[slot].perfect;
        c = nearest ? store_perfect_nearest(p, pos) : store_perfect_trilinear(p, pos);
    } else if (store_kind_used(STORE_KIND_TILETREE) && kind == STORE_KIND_TILETREE) {
        TileTreeParams p = store_records[slot].tiletree;
        c = nearest ? store_tiletree_nearest(p, pos, normal) : store_tiletree_bilinear(p, pos, normal);
    }
    if (c.a <= 0.0) {
        return vec3(1.0, 0.0, 1.0);
    }
    return albedo_of_srgb(c.rgb / c.a);  // a partial trilinear footprint is renormalized
}

// The shading normal bent by a relief whose height has world-space gradient g: the height
// field's normal n - (g - (g.n) n). The geometric normal still decides which side a ray is on
// (next-event rays below it are not traced, BSDF samples below it end the path), so the bend
// cannot let light through the surface; and the bent normal is kept at least slightly facing
// the viewer (v), since a view below its hemisphere would shade black.
vec3 bend_normal(vec3 ns, vec3 g, vec3 v) {
    return facing_normal(ns, normalize(ns - (g - dot(g, ns) * ns)), v);
}

// Texture coordinates at a hit and what footprints and normal maps need: the world-space
// derivatives of the position along u and v, and the interpolated MikkTSpace tangent (world)
// with its bitangent sign.
struct SurfaceUv {
    vec2 uv;
    vec3 dpdu;
    vec3 dpdv;
    vec3 tangent;
    float sign;
};

// False for a mesh without texture coordinates.
bool surface_uv(TraceHit h, out SurfaceUv su) {
    uint offset = bvh_instances[h.instance].uv_offset;
    su.uv = vec2(0.0);
    su.dpdu = vec3(0.0);
    su.dpdv = vec3(0.0);
    su.tangent = vec3(0.0);
    su.sign = 1.0;
    if (offset == NO_UVS) {
        return false;
    }
    uint slot = offset + (h.triangle - bvh_instances[h.instance].triangle_offset);
    TriangleUvs t = bvh_uvs[slot];
    float w = 1.0 - h.u - h.v;
    su.uv = t.uv[0] * w + t.uv[1] * h.u + t.uv[2] * h.v;
    vec4 o2w[3] = bvh_instances[h.instance].object_to_world;
    vec3 e1 = -bvh_triangles[h.triangle * 3u + 1u].xyz;  // v1 - v0
    vec3 e2 = bvh_triangles[h.triangle * 3u + 2u].xyz;   // v2 - v0
    vec2 d1 = t.uv[1] - t.uv[0];
    vec2 d2 = t.uv[2] - t.uv[0];
    float det = d1.x * d2.y - d1.y * d2.x;
    if (abs(det) > 1e-20) {
        float inv = 1.0 / det;
        su.dpdu = cwbvh_transform_vector(o2w, (d2.y * e1 - d1.y * e2) * inv);
        su.dpdv = cwbvh_transform_vector(o2w, (d1.x * e2 - d2.x * e1) * inv);
    }
    if (NORMAL_MAPS != 0u) {
        vec3 tan = cwbvh_decode_octahedral(t.tangents[0]) * w + cwbvh_decode_octahedral(t.tangents[1]) * h.u +
                   cwbvh_decode_octahedral(t.tangents[2]) * h.v;
        su.tangent = cwbvh_transform_vector(o2w, tan);
        su.sign = (t.flipped & 1u) != 0u ? -1.0 : 1.0;
    }
    return true;
}

// The footprint of a ray's differentials at a hit, in texture coordinates: the position
// differentials moved to the hit and onto its plane (Igehy 1999), then expressed in u and v by
// least squares over dP/du, dP/dv.
void uv_footprint(SurfaceUv su, vec3 dpx, vec3 dpy, out vec2 a, out vec2 b) {
    float uu = dot(su.dpdu, su.dpdu);
    float uv = dot(su.dpdu, su.dpdv);
    float vv = dot(su.dpdv, su.dpdv);
    float det = uu * vv - uv * uv;
    if (det <= 1e-30) {
        a = vec2(0.0);
        b = vec2(0.0);
        return;
    }
    float inv = 1.0 / det;
    vec2 px = vec2(dot(su.dpdu, dpx), dot(su.dpdv, dpx));
    vec2 py = vec2(dot(su.dpdu, dpy), dot(su.dpdv, dpy));
    a = vec2(vv * px.x - uv * px.y, uu * px.y - uv * px.x) * inv;
    b = vec2(vv * py.x - uv * py.y, uu * py.y - uv * py.x) * inv;
}

SurfaceHit surface_of(TraceHit h) {
    // Only the fields shading needs: every load costs on a CPU device.
    vec4 o2w[3] = bvh_instances[h.instance].object_to_world;
    vec3 v0 = bvh_triangles[h.triangle * 3u + 0u].xyz;
    vec3 e1 = bvh_triangles[h.triangle * 3u + 1u].xyz;  // v0 - v1
    vec3 e2 = bvh_triangles[h.triangle * 3u + 2u].xyz;  // v2 - v0
    vec3 v1 = v0 - e1;
    vec3 v2 = v0 + e2;
    float w = 1.0 - h.u - h.v;
    SurfaceHit s;
    vec3 p_surface = v0 * w + v1 * h.u + v2 * h.v;
    s.p = cwbvh_transform_point(o2w, p_surface);
    // Solid textures are read a hair inside the matter, so a face lying exactly on a cell
    // boundary of the texture (a ground plane at y = 0) sees one side of it, not both.
    vec3 n_object = cross(v1 - v0, v2 - v0);
    float n_len = length(n_object);
    s.p_object = n_len > 0.0 ? p_surface - n_object * (1e-5 / n_len) : p_surface;
    s.p_surface_object = p_surface;
    s.n_object = n_object;
    s.instance = h.instance;
    // Rigid transforms with uniform scale: the linear part maps normals too.
    s.ng = normalize(cwbvh_transform_vector(o2w, cross(v1 - v0, v2 - v0)));
    uvec4 packed = bvh_normals[h.triangle];
    vec3 n_obj = cwbvh_decode_octahedral(packed.x) * w + cwbvh_decode_octahedral(packed.y) * h.u +
                 cwbvh_decode_octahedral(packed.z) * h.v;
    vec3 ns = normalize(cwbvh_transform_vector(o2w, n_obj));
    s.ns = dot(ns, s.ng) < 0.0 ? -ns : ns;
    s.material = bvh_instances[h.instance].material;
    return s;
}

// Start of a ray leaving p in direction d: moved off the surface along the geometric normal,
// by an amount relative to the magnitude of the coordinates.
vec3 offset_origin(vec3 p, vec3 ng, vec3 d) {
    float eps = 1e-4 * max(1.0, max3(abs(p)));
    return p + ng * (dot(d, ng) >= 0.0 ? eps : -eps);
}

// True when an analytic light other than `skip` lies on the ray before tmax: lights occlude
// like any other surface (the back of a one-sided quad included), so a shadow ray is blocked
// exactly when a BSDF ray in the same direction would have stopped at that light.
bool lights_occlude(vec3 o, vec3 d, float tmax, uint skip) {
    for (uint i = 0u; i < frame.light_count; i++) {
        float t;
        vec3 le;
        if (i != skip && light_intersect(lights[i], o, d, tmax, t, le)) {
            return true;
        }
    }
    return false;
}

// Nearest analytic light along the ray before tmax: its index, or -1.
int hit_lights(vec3 o, vec3 d, inout float tmax, out vec3 radiance) {
    int found = -1;
    radiance = vec3(0.0);
    for (uint i = 0u; i < frame.light_count; i++) {
        float t;
        vec3 le;
        if (light_intersect(lights[i], o, d, tmax, t, le)) {
            tmax = t;
            found = int(i);
            radiance = le;
        }
    }
    return found;
}

void main() {
    uint i = uint(global_index());
    uint rays = 0u;
    if (i < pc.pixel_count) {
        uvec2 px = pixel_of(pc.first_pixel + i);
        if (px.x < frame.width && px.y < frame.height) {
            uint pixel = px.y * frame.width + px.x;
            uint rng = rng_init(px, pc.sample_index, frame.seed);

            // Camera ray through a jittered point of the pixel.
            vec2 jitter = rng_next2(rng);
            vec2 ndc = vec2((float(px.x) + jitter.x) / float(frame.width) * 2.0 - 1.0,
                            1.0 - (float(px.y) + jitter.y) / float(frame.height) * 2.0);
            vec3 film_dir = frame.forward + frame.right * ndc.x + frame.up * ndc.y;
            vec3 dir = normalize(film_dir);
            vec3 origin = frame.eye;
            // Ray differentials per pixel step in x and y (Igehy 1999): the origin's (zero for a
            // pinhole; the lens's spread is left out) and the direction's.
            vec3 ro_dx = vec3(0.0);
            vec3 ro_dy = vec3(0.0);
            vec3 rd_dx;
            vec3 rd_dy;
            {
                float fl = length(film_dir);
                vec3 fx = frame.right * (2.0 / float(frame.width));
                vec3 fy = -frame.up * (2.0 / float(frame.height));
                rd_dx = (fx - dir * dot(dir, fx)) / fl;
                rd_dy = (fy - dir * dot(dir, fy)) / fl;
            }
            vec2 lens_u = rng_next2(rng);
            if (frame.lens_radius > 0.0) {
                vec3 focus = frame.eye + dir * (frame.focus_distance / dot(dir, frame.forward));
                vec2 disk = sample_concentric_disk(lens_u) * frame.lens_radius;
                vec3 r = normalize(frame.right);
                vec3 u = normalize(frame.up);
                origin = frame.eye + r * disk.x + u * disk.y;
                dir = normalize(focus - origin);
            }

            uint strategies = frame.light_count + frame.env_sampled;
            float select_pdf = strategies > 0u ? 1.0 / float(strategies) : 0.0;
            vec3 radiance = vec3(0.0);
            vec3 beta = vec3(1.0);
            bool specular = true;   // the camera "bounce" is not a NEE strategy
            float bsdf_pdf_prev = 0.0;
            vec3 prev_p = origin;
            // The pixel cone: its width grows by pixel_angle per unit of path length (glints
            // take their footprint G_P from it).
            float pixel_angle = 2.0 * length(frame.up) / float(frame.height);
            float path_length = 0.0;
            vec3 aov_albedo = vec3(0.0);
            vec3 aov_normal = vec3(0.0);
            float aov_depth = 1.0 / 0.0;

            // depth counts the bounces so far: the ray traced at depth d ends a path of d
            // bounces when it finds an emitter. A path scatters at most max_depth times, so the
            // vertex reached at depth max_depth neither samples a light nor continues: each
            // path length up to max_depth is counted by both strategies, and none beyond it.
            for (uint depth = 0u; depth <= frame.max_depth; depth++) {
                TraceHit h;
                rays++;
                bool hit_mesh = cwbvh_trace(origin, dir, 0.0, 1.0 / 0.0, false, h);
                float t_near = hit_mesh ? h.t : 1.0 / 0.0;
                if (hit_mesh) {
                    path_length += h.t;
                }
                vec3 le;
                int light = hit_lights(origin, dir, t_near, le);
                if (light >= 0) {
                    float w = 1.0;
                    if (!specular) {
                        float lp = select_pdf * light_pdf(lights[uint(light)], prev_p, dir, t_near);
                        w = power_heuristic(bsdf_pdf_prev, lp);
                    }
                    radiance += beta * le * w;
                    if (depth == 0u) {
                        aov_albedo = le / max(max3(le), 1e-6);
                        aov_depth = t_near;
                    }
                    break;
                }
                if (!hit_mesh) {
                    vec3 le_env = env_eval(env, dir);
                    float w = 1.0;
                    if (!specular && frame.env_sampled != 0u) {
                        w = power_heuristic(bsdf_pdf_prev, select_pdf * env_pdf(env, dir));
                    }
                    radiance += beta * le_env * w;
                    break;
                }

                SurfaceHit s = surface_of(h);
                Material m = materials[s.material];
                // The differentials at the hit: moved along the ray and onto the hit's plane.
                vec3 dpx = ro_dx + rd_dx * h.t;
                vec3 dpy = ro_dy + rd_dy * h.t;
                {
                    float dn = dot(dir, s.ng);
                    if (abs(dn) > 1e-6) {
                        dpx -= dir * (dot(dpx, s.ng) / dn);
                        dpy -= dir * (dot(dpy, s.ng) / dn);
                    }
                }
                bool image_albedo = texture_kind_used(TEXTURE_IMAGE) && m.texture_kind == TEXTURE_IMAGE;
                bool normal_mapped = (NORMAL_MAPS & 1u) != 0u && m.normal_image != IMAGE_NONE;
                bool mesh_glint = material_is(m, MATERIAL_GLINT) && glint_records[m.glint].projection == GLINT_UV_MESH;
                SurfaceUv su;
                vec2 fp_a = vec2(0.0);
                vec2 fp_b = vec2(0.0);
                bool has_uv = false;
                if (image_albedo || normal_mapped || mesh_glint) {
                    has_uv = surface_uv(h, su);
                    uv_footprint(su, dpx, dpy, fp_a, fp_b);
                }
                uint store_slot = instance_stores[s.instance];
                vec3 relief_gradient = vec3(0.0);
                vec3 albedo;
                if (image_albedo) {
                    albedo = has_uv ? image_lookup(m.albedo_image, su.uv, fp_a, fp_b).rgb : vec3(1.0, 0.0, 1.0);
                } else {
                    albedo = store_slot == NO_STORE
                                 ? solid_texture_albedo(m, s.p_object)
                                 : store_albedo(store_slot, s.p_surface_object, s.n_object, relief_gradient);
                }
                bool use_vmf = false;
                VmfShade vs;
                if (normal_mapped && has_uv) {
                    uint nfilter = image_records[m.normal_image].normal_filter;
                    vec3 t = su.tangent - s.ns * dot(s.ns, su.tangent);
                    float tl = length(t);
                    if (tl > 1e-6) {
                        t /= tl;
                        vec3 bt = cross(s.ns, t) * su.sign;
                        if ((NORMAL_MAPS & 2u) != 0u && nfilter == NORMAL_FILTER_VMF) {
                            // The footprint's mixture, drawn texel by texel (normal_vmf.glsl).
                            vec3 u_texel = vec3(rng_next2(rng), rng_next(rng));
                            vs = vmf_shade(vmf_texel(m.normal_image, su.uv, fp_a, fp_b, u_texel), t, bt, s.ns, -dir);
                            use_vmf = true;
                        } else {
                            vec3 nm;
                            if (nfilter == NORMAL_FILTER_NONE) {
                                // The finest level's texel under the hit: the map's own facets.
                                uvec2 size = image_level_size(m.normal_image, 0u);
                                nm = image_fetch(m.normal_image, 0u, int(floor(su.uv.x * float(size.x))),
                                                 int(floor((1.0 - su.uv.y) * float(size.y)))).xyz;
                            } else {
                                // Plain MIP: the footprint's mean normal, renormalized.
                                nm = image_lookup(m.normal_image, su.uv, fp_a, fp_b).xyz;
                            }
                            if (length(nm) > 1e-6) {
                                vec3 n = normalize(t * nm.x + bt * nm.y + s.ns * nm.z);
                                s.ns = facing_normal(s.ns, n, -dir);
                            }
                        }
                    }
                }
                if (relief_gradient != vec3(0.0)) {
                    // Object to world: a rotation times a uniform scale, which slopes ignore.
                    vec4 o2w[3] = bvh_instances[s.instance].object_to_world;
                    vec3 g = cwbvh_transform_vector(o2w, relief_gradient);
                    float scale = length(cwbvh_transform_vector(o2w, vec3(1.0, 0.0, 0.0)));
                    s.ns = bend_normal(s.ns, g / scale, -dir);
                }
                if (depth == 0u && use_vmf) {
                    vec3 mean = vec3(0.0);
                    for (uint j = 0u; j < uint(VMF_LOBES); j++) {
                        mean += vs.mu[j] * vs.alpha[j];
                    }
                    aov_normal = length(mean) > 0.0 ? normalize(mean) : s.ns;
                }
                if (depth == 0u) {
                    aov_albedo = material_is(m, MATERIAL_EMISSIVE) ? m.emission / max(max3(m.emission), 1e-6) : albedo;
                    aov_normal = use_vmf ? aov_normal : s.ns;
                    aov_depth = h.t;
                }
                if (material_is(m, MATERIAL_EMISSIVE)) {
                    // Emissive meshes are found by BSDF sampling only (they are not NEE lights).
                    if (dot(dir, s.ng) < 0.0) {
                        radiance += beta * m.emission;
                    }
                    break;
                }
                if (depth == frame.max_depth) {
                    break;
                }

                vec3 t_axis, b_axis;
                bool glint = material_is(m, MATERIAL_GLINT);
                GlintRecord gr;
                GlintShade gs;
                if (glint) {
                    gr = glint_records[m.glint];
                    vec4 o2w[3] = bvh_instances[s.instance].object_to_world;
                    vec3 ex = cwbvh_transform_vector(o2w, vec3(1.0, 0.0, 0.0));
                    vec3 ez = cwbvh_transform_vector(o2w, vec3(0.0, 0.0, 1.0));
                    float scale = length(ex);
                    gs = glint_shade(gr, s.p_surface_object, scale, path_length * pixel_angle, s.ns, -dir,
                                     ex / scale, ez / scale, su.uv, su.dpdu, fp_a, fp_b, t_axis, b_axis);
                } else {
                    make_frame(s.ns, t_axis, b_axis);
                }
                vec3 wo = vec3(dot(-dir, t_axis), dot(-dir, b_axis), dot(-dir, s.ns));
                bool transmissive = material_is(m, MATERIAL_DIELECTRIC);
                float wo_side = dot(-dir, s.ng);

                // Next-event estimation: one light or the environment, chosen uniformly.
                if (strategies > 0u && (glint || use_vmf || bsdf_has_smooth_lobe(m))) {
                    vec2 u_light = rng_next2(rng);
                    float u_pick = rng_next(rng);
                    uint pick = min(uint(u_pick * float(strategies)), strategies - 1u);
                    vec3 wi;
                    vec3 li;
                    float lpdf;
                    float dist;
                    bool ok;
                    if (pick < frame.light_count) {
                        LightSample ls;
                        ok = light_sample(lights[pick], s.p, u_light, ls);
                        wi = ls.wi;
                        li = ls.radiance;
                        lpdf = ls.pdf;
                        dist = ls.dist;
                    } else {
                        ok = env_sample(env, u_light, wi, li, lpdf);
                        dist = 1.0 / 0.0;
                    }
                    bool same_side = dot(wi, s.ng) * wo_side > 0.0;
                    if (ok && lpdf > 0.0 && max3(li) > 0.0 && (same_side || transmissive)) {
                        vec3 wi_l = vec3(dot(wi, t_axis), dot(wi, b_axis), dot(wi, s.ns));
                        float vmf_pdf = 0.0;
                        vec3 f = use_vmf ? vmf_eval(m, albedo, vs, -dir, wi, vmf_pdf)
                                         : glint ? glint_eval(gr, m, gs, wo, wi_l) : bsdf_eval(m, albedo, wo, wi_l);
                        if (max3(f) > 0.0) {
                            vec3 o2 = offset_origin(s.p, s.ng, wi);
                            float tmax = dist < 1.0 / 0.0 ? dist * (1.0 - 1e-4) - 1e-4 : dist;
                            uint skip = pick < frame.light_count ? pick : 0xffffffffu;
                            TraceHit sh;
                            rays++;
                            if (!lights_occlude(o2, wi, tmax, skip) &&
                                !cwbvh_trace(o2, wi, 0.0, tmax, true, sh)) {
                                float lp = select_pdf * lpdf;
                                float bp = use_vmf ? vmf_pdf
                                                   : glint ? glint_pdf(gr, gs, wo, wi_l) : bsdf_pdf(m, albedo, wo, wi_l);
                                float w = power_heuristic(lp, bp);
                                radiance += beta * f * li * (w / lp);
                            }
                        }
                    }
                }

                // Continue the path by sampling the BSDF.
                BsdfSample bs;
                vec3 u_bsdf = vec3(rng_next2(rng), rng_next(rng));
                bool sampled;
                if (use_vmf) {
                    sampled = vmf_sample(m, albedo, vs, -dir, u_bsdf, rng_next(rng), bs);
                    // Already a world direction: expressed in the shading frame for the line below.
                    bs.wi = vec3(dot(bs.wi, t_axis), dot(bs.wi, b_axis), dot(bs.wi, s.ns));
                } else {
                    sampled = glint ? glint_sample(gr, m, gs, wo, u_bsdf, bs) : bsdf_sample(m, albedo, wo, u_bsdf, bs);
                }
                if (!sampled) {
                    break;
                }
                vec3 wi = t_axis * bs.wi.x + b_axis * bs.wi.y + s.ns * bs.wi.z;
                if (!transmissive && dot(wi, s.ng) * wo_side <= 0.0) {
                    break;  // the shading normal sent the path through the surface
                }
                beta *= bs.weight;
                specular = bs.specular;
                bsdf_pdf_prev = bs.pdf;
                prev_p = s.p;
                origin = offset_origin(s.p, s.ng, wi);
                dir = wi;
                // The differentials leave from the hit's. A mirror reflection mirrors their
                // directions (the normal's own change across the pixel is left out); refraction
                // keeps them; a rough bounce keeps the spread, isotropic about the new direction,
                // so that texture filters stay at pixel scale and the lobe's blur is left to the
                // Monte Carlo integration.
                ro_dx = dpx;
                ro_dy = dpy;
                if (bs.specular) {
                    if (dot(wi, s.ng) * wo_side > 0.0) {
                        rd_dx = reflect(rd_dx, s.ns);
                        rd_dy = reflect(rd_dy, s.ns);
                    }
                } else {
                    float spread = max(length(rd_dx), length(rd_dy));
                    vec3 tx;
                    vec3 ty;
                    make_frame(wi, tx, ty);
                    rd_dx = tx * spread;
                    rd_dy = ty * spread;
                }
                if (depth + 1u >= frame.rr_depth) {
                    float survive = clamp(max3(beta), 0.05, 1.0);
                    if (rng_next(rng) >= survive) {
                        break;
                    }
                    beta /= survive;
                }
                if (max3(beta) <= 0.0) {
                    break;
                }
            }

            if (any(isnan(radiance)) || any(isinf(radiance))) {
                radiance = vec3(0.0);  // counted as a black sample rather than poisoning the pixel
            }
            film[pixel] += vec4(radiance, 1.0);
            if (frame.aovs != 0u) {
                aovs[pixel * 2u] = vec4(aov_albedo, 0.0);
                aovs[pixel * 2u + 1u] = vec4(aov_normal, aov_depth);
            }
        }
    }
    uint total = subgroupAdd(rays);
    if (subgroupElect()) {
        atomicAdd(ray_count[0], total);
    }
}
