/* barycentric.c - the bounding-box rasterizer, a reference (raster stage):
 * for every pixel of the triangle's bounding box, compute the barycentric
 * weights (e_i / area2, here kept as the integers e_i) directly, with no
 * incremental stepping, and keep the pixel when all three are >= 0 under the
 * top-left tie rule.  Must give exactly the pixels of triangle.c. */
#include "fragment/fragment.h"

void sr__raster_barycentric(const sr_draw_state *ds, const sr_tri *t,
                            int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    for (int py = ry0; py < ry1; py++) {
        int64_t yc = sr__centre_q8(py);
        for (int px = rx0; px < rx1; px++) {
            int64_t xc = sr__centre_q8(px);
            int64_t e[3];
            bool in = true;
            for (int i = 0; i < 3; i++) {
                e[i] = sr__edge_at(&ed, i, xc, yc);
                /* lambda_i >= 0, with samples exactly on an edge (e_i = 0)
                 * kept only for top and left edges. */
                in &= e[i] > 0 || (e[i] == 0 && ed.bias[i] == 0);
            }
            if (in) {
                sr__fragment(ds, t, px, py, e[0], e[1], e[2], st);
            }
        }
    }
}
