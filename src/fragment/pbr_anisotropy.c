/* pbr_anisotropy.c - KHR_materials_anisotropy on the PBR program's four
 * lanes (fragment stage, pbr_layers.h): the base's GGX lobe with two
 * roughnesses, alpha_t = mix(alpha, 1, strength^2) along the direction T
 * and alpha along B, for punctual lights, and the extension's bent normal
 * for image-based light.  The same functions as the extension's and the
 * glTF Sample Viewer's; strength 0 is the isotropic lobe.  Any thread;
 * the state is the caller's. */
#include "fragment/pbr_layers.h"

void sr__aniso_begin(sr__pbr_layers *x, v4f alpha, const v4f v[3], v4f nv)
{
    x->an_ab = alpha;
    x->an_at = alpha + (1.0f - alpha) * (x->an_s * x->an_s);
    x->an_tv = dot3(x->an_t, v);
    x->an_bv = dot3(x->an_b, v);
    v4f a = x->an_at * x->an_tv, b = x->an_ab * x->an_bv;
    v4f g2 = a * a + b * b + nv * nv;
    x->an_gv = g2 * rsqrt_nr(g2);
}

/* D = a_t a_b / (pi ((T.H / a_t)^2 + (B.H / a_b)^2 + (N.H)^2)^2 a_t^2 a_b^2)
 * in the form that keeps every term finite, and the height-correlated
 * visibility V = 0.5 / (N.L |(a_t T.V, a_b B.V, N.V)| + N.V |(a_t T.L,
 * a_b B.L, N.L)|), at most 1 as the Sample Viewer's. */
v4f sr__aniso_dv(const sr__pbr_layers *x, const v4f ld[3], v4f hs, v4f nl, v4f nv, v4f nh)
{
    v4f at = x->an_at, ab = x->an_ab, a2 = at * ab;
    v4f tl = dot3(x->an_t, ld), bl = dot3(x->an_b, ld);
    v4f th = (tl + x->an_tv) * hs, bh = (bl + x->an_bv) * hs;
    v4f fx = ab * th, fy = at * bh, fz = a2 * nh;
    v4f w2 = a2 * rcp_nr(vmax(fx * fx + fy * fy + fz * fz, (v4f){ 0 } + 1e-30f));
    v4f d = a2 * w2 * w2 * (1.0f / PI_F);
    v4f la = at * tl, lb = ab * bl;
    v4f gl2 = la * la + lb * lb + nl * nl;
    v4f gl = gl2 * rsqrt_nr(vmax(gl2, (v4f){ 0 } + 1e-30f));
    v4f vis = vmin(0.5f * rcp_nr(nl * x->an_gv + nv * gl), (v4f){ 1, 1, 1, 1 });
    return d * vis;
}

/* The normal of the microfacets the stretch favours (B x V x B, in the
 * plane of B and V, facing V), blended back to N as the strength falls
 * or the roughness rises: mix(that, N, (1 - s (1 - r))^4). */
void sr__aniso_bent(const sr__pbr_layers *x, const v4f n[3], const v4f v[3], v4f rc,
                    v4f out[3])
{
    const v4f *b = x->an_b;
    v4f t[3] = { b[1] * v[2] - b[2] * v[1], b[2] * v[0] - b[0] * v[2],
                 b[0] * v[1] - b[1] * v[0] };
    v4f a[3] = { t[1] * b[2] - t[2] * b[1], t[2] * b[0] - t[0] * b[2],
                 t[0] * b[1] - t[1] * b[0] };
    v4f l2 = dot3(a, a);
    v4f s = sr__v4_sel(l2 > 0.0f, rsqrt_nr(vmax(l2, (v4f){ 0 } + 1e-30f)), (v4f){ 0 });
    v4f f = 1.0f - x->an_s * (1.0f - rc), f2 = f * f, k = f2 * f2;
    for (int c = 0; c < 3; c++) {
        out[c] = a[c] * s + (n[c] - a[c] * s) * k;
    }
    v4f o2 = dot3(out, out);
    v4f os = sr__v4_sel(o2 > 0.0f, rsqrt_nr(vmax(o2, (v4f){ 0 } + 1e-30f)), (v4f){ 0 });
    for (int c = 0; c < 3; c++) {
        out[c] *= os;
    }
}
