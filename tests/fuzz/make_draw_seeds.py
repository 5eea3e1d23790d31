#!/usr/bin/env python3
"""Writes the seed inputs of fuzz_draw (corpus/fuzz_draw/seed_*), encoded
the way fuzz_draw.c's decode() reads them.  Rerun after changing decode()."""
import math, os, struct

TABLE = {0.0: 0, 1.0: 2, -1.0: 3, 0.5: 4, -0.5: 5, 2.0: 6, -2.0: 7,
         'max': 8, '-max': 9, 'inf': 10, '-inf': 11, 'nan': 12, 'min': 13, 'denorm': 15}

def f(v):
    """hostile_float: a table entry, an exact value on the 1/8192 grid, or raw."""
    if isinstance(v, str):
        return bytes([TABLE[v]])
    if v in TABLE:
        return bytes([TABLE[v]])
    q = v * 8192
    if q == int(q) and -32768 <= q < 32768:
        return bytes([64]) + struct.pack('<h', int(q))
    return bytes([200]) + struct.pack('<f', v)

def draw(w=32, h=32, depth=2, vp=None, near=0, far=1, flags=0, cull=1, front=0, rast=0,
         pm=(0, 0), line_width=1, point_size=4, depth_func=0, offset=None, shading=1,
         interp=0, provoking=0, lights=1, prim=1, proj=0, psize=3, colors=True, verts=(),
         indices=None, index_type=0, extra=b''):
    b = bytes([w - 1, h - 1, depth])
    if vp:
        b += bytes([1, (vp[0] // 2) & 255, (vp[1] // 2) & 255, vp[2] - 1, vp[3] - 1])
    else:
        b += bytes([0])
    b += bytes([near, far, flags, cull, front, rast, pm[0], pm[1], line_width,
                point_size, depth_func])
    if offset:
        b += bytes([3]) + f(offset[0]) + f(offset[1])
    else:
        b += bytes([0, 0, 0])
    b += bytes([shading, interp, provoking, 8, lights])
    b += bytes([prim, proj | (4 if psize == 4 else 0) | (8 if colors else 0)])
    b += bytes([len(verts)])
    for i, v in enumerate(verts):
        for c in v[:psize]:
            b += f(c)
        b += bytes([0, 0, (i * 37) & 63])
    b += bytes([index_type])
    if index_type:
        b += bytes([len(indices)]) + bytes(indices)
    return b + extra

def ms(samples=0, stencil=False, a2c=False, opacity=None, faces=None, separate=False,
       program=None):
    """The bytes after the draw: multisampling (bits 0-2: an index into 0, 2, 4, 8, 16),
    a stencil buffer, alpha to coverage, opacity, stencil state (two faces
    of func, ref, masked, read mask, write mask, fail, depth-fail, pass),
    then a program: (discard pattern or None, writes depth, varying mode,
    depth value)."""
    mk = [0, 2, 4, 8, 16].index(samples)
    mk |= (8 if stencil else 0) | (16 if a2c else 0) | (32 if opacity is not None else 0)
    mk |= (64 if faces else 0) | (128 if separate else 0)
    b = bytes([mk])
    if opacity is not None:
        b += bytes([opacity])
    for face in faces or ():
        b += bytes(face)
    if program is None:
        return b + bytes([0])
    discard, writes_z, mode, z = program
    gk = 1 | 2 | (4 if discard is not None else 0) | (8 if writes_z else 0) | (mode << 4)
    b += bytes([gk])
    if discard is not None:
        b += bytes([discard])
    return b + f(z)

tri = [(-0.75, -0.75, 0.0, 1.0), (0.75, -0.5, 0.5, 1.0), (0.0, 0.75, -0.5, 1.0)]
quad = [(-1.0, -1.0, 0.0, 1.0), (1.0, -1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0), (-1.0, 1.0, 0.0, 1.0)]
seeds = {
    'triangle': draw(verts=tri),
    'triangle_scanline_d16': draw(verts=tri, rast=2, depth=1),
    'triangle_barycentric_d32f': draw(verts=tri, rast=3, depth=4, shading=3),
    'quad_fan_viewport': draw(verts=quad, prim=3, vp=(-10, 6, 40, 20)),
    'strip_lines_mode': draw(verts=quad, prim=2, pm=(2, 3), line_width=3, shading=4),
    'lines_wide': draw(verts=quad, prim=4, line_width=5, shading=2),
    'line_loop_offset': draw(verts=quad, prim=6, flags=0x70, offset=(2.0, -1.0), depth_func=8),
    'points_big': draw(verts=tri, prim=7, point_size=199, shading=5),
    'perspective_near_crossing': draw(verts=[(-1, -1, 3, 1), (1, -1, -3, 1), (0, 1, 0.5, 1)],
                                      proj=1, shading=4),
    'w_zero_and_negative': draw(verts=[(0.5, 0.5, 0, 0.0), (-1, 0.5, 0, -1.0), (0.5, -1, 0, 1.0)],
                                psize=4),
    'nan_inf_max': draw(verts=[('nan', 0, 0, 1), ('inf', '-inf', 0, 1), ('max', '-max', 'max', 1),
                               (0.5, 0.5, 0, 'denorm'), (0.0, 0.5, 0, 1.0), (0.5, 0.0, 0, 1.0)],
                        psize=4, prim=2),
    'guard_band_needle': draw(verts=[(-4.0, -3.999, 0, 1), (3.99, 3.99, 0, 1), (3.99, 3.9902, 0, 1)],
                              w=80, h=80),
    'indexed_u16_out_of_range': draw(verts=tri, index_type=2, indices=[0, 1, 2, 2, 1, 250]),
    'indexed_u8_polygon_point': draw(verts=quad, index_type=1, indices=[0, 1, 2, 0, 2, 3],
                                     pm=(3, 3), point_size=12),
    # Multisampling, stencil, alpha to coverage and programs (decoded after
    # the draw).
    'msaa4_triangle': draw(verts=tri, psize=4, extra=ms(samples=4)),
    'msaa4_stencil_a2c_separate': draw(verts=tri, psize=4, extra=ms(
        samples=4, stencil=True, a2c=True, opacity=50, separate=True,
        faces=[[4, 3, 1, 0xf0, 0x0f, 6, 7, 3], [5, 9, 0, 0, 0, 1, 2, 4]])),
    'msaa8_program_discard_nan_depth': draw(verts=tri, psize=4, extra=ms(
        samples=8, program=(5, True, 2, 'nan'))),
    'msaa16_stencil_lines_program': draw(verts=quad, psize=4, prim=4, extra=ms(
        samples=16, stencil=True, faces=[[2, 1, 0, 0, 0, 7, 5, 3], [8, 0, 0, 0, 0, 0, 0, 0]],
        program=(None, False, 1, 0.5))),
    'stencil_program_single_sample': draw(verts=tri, psize=4, extra=ms(
        stencil=True, faces=[[6, 200, 1, 0x3c, 0xff, 2, 3, 5], [1, 0, 0, 0, 0, 0, 0, 0]],
        program=(9, False, 0, 0.25))),
}
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus', 'fuzz_draw')
os.makedirs(out, exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join(out, 'seed_' + name), 'wb') as fh:
        fh.write(data)
print(len(seeds), 'seeds written to', out)
