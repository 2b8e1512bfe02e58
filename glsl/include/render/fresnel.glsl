// Fresnel reflectance of dielectric and conductor interfaces. CPU twin:
// renderer/src/shading/reference/fresnel.rs.
#ifndef LAZYSOLID_RENDER_FRESNEL_GLSL
#define LAZYSOLID_RENDER_FRESNEL_GLSL

// Unpolarized reflectance of a dielectric interface for light arriving at cos_i (>= 0) on the
// side of index n_i, with eta = n_t / n_i the ratio across it; 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.0, 1.0);
    float sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) {
        return 1.0;
    }
    float cos_t = sqrt(1.0 - sin2_t);
    float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Exact unpolarized reflectance of a conductor of complex index eta + i kappa (per channel)
// seen from vacuum at cos_i, in the real-arithmetic form with a^2 + b^2 = |eta^2 - sin^2|.
vec3 fresnel_conductor(float cos_i, vec3 eta, vec3 kappa) {
    float c = clamp(cos_i, 0.0, 1.0);
    float c2 = c * c;
    float s2 = 1.0 - c2;
    vec3 n2 = eta * eta;
    vec3 k2 = kappa * kappa;
    vec3 t0 = n2 - k2 - s2;
    vec3 a2b2 = sqrt(t0 * t0 + 4.0 * n2 * k2);
    vec3 a = sqrt(max(0.5 * (a2b2 + t0), vec3(0.0)));
    vec3 t1 = a2b2 + c2;
    vec3 t2 = 2.0 * c * a;
    vec3 rs = (t1 - t2) / max(t1 + t2, vec3(1e-30));
    vec3 t3 = c2 * a2b2 + s2 * s2;
    vec3 t4 = t2 * s2;
    vec3 rp = rs * (t3 - t4) / max(t3 + t4, vec3(1e-30));
    return 0.5 * (rs + rp);
}

#endif
