/* gl_compare.c - the llvmpipe side of `softrast-bench --compare` (bench):
 * consumes a bench_scene, sets up legacy fixed-function OpenGL state
 * equivalent to its sr_state (per-vertex Blinn-Phong lighting for Gouraud,
 * vertex colors for unlit, a mipmapped texture under GL_MODULATE for
 * textured scenes) and draws it into an OSMesa RGBA8 buffer.
 * Main thread only. */
#include "gl_compare.h"

#include <stdio.h>

#ifndef SR_HAVE_OSMESA

bool gl_available(void) { return false; }

bool gl_make(int width, int height, int threads, gl_renderer **out, char *msg, size_t msg_size)
{
    (void)width;
    (void)height;
    (void)threads;
    *out = NULL;
    snprintf(msg, msg_size, "this build has no OSMesa (install libosmesa6-dev and re-run cmake)");
    return false;
}
void gl_destroy(gl_renderer *g) { (void)g; }
const char *gl_renderer_name(const gl_renderer *g) { (void)g; return "none"; }
bool gl_prepare(gl_renderer *g, const bench_scene *s, char *msg, size_t msg_size)
{
    (void)g;
    (void)s;
    snprintf(msg, msg_size, "no OSMesa");
    return false;
}
void gl_frame(gl_renderer *g, const bench_scene *s) { (void)g; (void)s; }
void gl_unprepare(gl_renderer *g) { (void)g; }
bool gl_check(gl_renderer *g, char *msg, size_t msg_size)
{
    (void)g;
    snprintf(msg, msg_size, "no OSMesa");
    return false;
}
const uint8_t *gl_pixels(const gl_renderer *g) { (void)g; return NULL; }

#else /* SR_HAVE_OSMESA */

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <stdlib.h>
#include <string.h>

struct gl_renderer {
    OSMesaContext ctx;
    int width, height;
    uint8_t *pixels;
    char name[128];
    /* Vertex buffer objects: the arrays are uploaded once, untimed, as a
     * GPU driver would keep them resident; softrast reads the caller's
     * arrays in place, so neither side pays a per-frame copy. */
    GLuint vbo_positions, vbo_normals, vbo_colors, vbo_texcoords, ibo;
    GLuint texture;
    /* Multisampled scenes: OSMesa's own buffer has one sample, so they draw
     * into a multisampled framebuffer object and blit (resolve) it there. */
    GLuint ms_fbo, ms_color, ms_depth;
};

bool gl_available(void) { return true; }

bool gl_make(int width, int height, int threads, gl_renderer **out, char *msg, size_t msg_size)
{
    *out = NULL;
    gl_renderer *g = calloc(1, sizeof *g);
    if (!g) {
        snprintf(msg, msg_size, "out of memory");
        return false;
    }
    g->width = width;
    g->height = height;
    g->pixels = malloc((size_t)width * (size_t)height * 4);
    if (!g->pixels) {
        free(g);
        snprintf(msg, msg_size, "out of memory for a %dx%d buffer", width, height);
        return false;
    }
    /* llvmpipe reads its thread count when its screen is created, which
     * happens with the first context. */
    char n[16];
    snprintf(n, sizeof n, "%d", threads);
    setenv("LP_NUM_THREADS", n, 1);
    g->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
    if (!g->ctx) {
        free(g->pixels);
        free(g);
        snprintf(msg, msg_size, "OSMesaCreateContextExt failed");
        return false;
    }
    if (!OSMesaMakeCurrent(g->ctx, g->pixels, GL_UNSIGNED_BYTE, width, height)) {
        OSMesaDestroyContext(g->ctx);
        free(g->pixels);
        free(g);
        snprintf(msg, msg_size, "OSMesaMakeCurrent failed for %dx%d", width, height);
        return false;
    }
    /* Row 0 at the top, as softrast stores it. */
    OSMesaPixelStore(OSMESA_Y_UP, 0);
    const char *r = (const char *)glGetString(GL_RENDERER);
    snprintf(g->name, sizeof g->name, "%s", r ? r : "unknown");
    *out = g;
    return true;
}

void gl_destroy(gl_renderer *g)
{
    if (!g) {
        return;
    }
    gl_unprepare(g);
    OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(g->ctx);
    free(g->pixels);
    free(g);
}

const char *gl_renderer_name(const gl_renderer *g) { return g->name; }

static GLenum depth_func(sr_depth_func f)
{
    switch (f) {
    case SR_NEVER:    return GL_NEVER;
    case SR_EQUAL:    return GL_EQUAL;
    case SR_LEQUAL:   return GL_LEQUAL;
    case SR_GREATER:  return GL_GREATER;
    case SR_NOTEQUAL: return GL_NOTEQUAL;
    case SR_GEQUAL:   return GL_GEQUAL;
    case SR_ALWAYS:   return GL_ALWAYS;
    default:          return GL_LESS;
    }
}

static GLuint upload(GLenum target, const void *data, size_t bytes)
{
    GLuint b = 0;
    glGenBuffers(1, &b);
    glBindBuffer(target, b);
    glBufferData(target, (GLsizeiptr)bytes, data, GL_STATIC_DRAW);
    return b;
}

/* The lighting of src/fragment/shade.c in fixed-function terms:
 *   color = A_global * ka + sum_i L_i (kd max(0, n.l) + ks max(0, n.h)^s),
 * the specular term only where n.l > 0, h from a local viewer under a
 * perspective projection, ka defaulting to kd.  GL adds light ambient
 * (set to 0) and emission (0), and clamps each vertex color to [0, 1]. */
static void setup_lighting(const bench_scene *s)
{
    const sr_state *st = &s->state;
    const sr_material *m = &st->material;
    sr_vec3 kd = (m->diffuse.x == 0 && m->diffuse.y == 0 && m->diffuse.z == 0)
                     ? (sr_vec3){ 0.8f, 0.8f, 0.8f } : m->diffuse;
    bool ka_zero = m->ambient.x == 0 && m->ambient.y == 0 && m->ambient.z == 0;
    sr_vec3 ka = ka_zero ? kd : m->ambient;
    float opacity = m->opacity == 0.0f ? 1.0f : m->opacity;
    float shininess = m->shininess == 0.0f ? 32.0f : m->shininess;
    if (shininess > 128.0f) {
        shininess = 128.0f; /* GL's limit */
    }
    GLfloat amb[4] = { ka.x, ka.y, ka.z, opacity };
    GLfloat dif[4] = { kd.x, kd.y, kd.z, opacity };
    GLfloat spe[4] = { m->specular.x, m->specular.y, m->specular.z, 1.0f };
    GLfloat zero[4] = { 0, 0, 0, 1 };
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, amb);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, dif);
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, spe);
    glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, zero);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, shininess);

    GLfloat global[4] = { st->ambient.x, st->ambient.y, st->ambient.z, 1.0f };
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, global);
    const float *p = s->projection.m;
    bool local_viewer = p[3] != 0.0f || p[7] != 0.0f || p[11] != 0.0f;
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, local_viewer ? GL_TRUE : GL_FALSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, st->two_sided ? GL_TRUE : GL_FALSE);

    /* Lights live in world space: GL transforms a light position by the
     * modelview matrix current when it is set, so set them under E. */
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(s->view.m);
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        const sr_light *l = &st->lights[i];
        GLenum id = GL_LIGHT0 + (GLenum)i;
        if (l->type == SR_LIGHT_OFF) {
            glDisable(id);
            continue;
        }
        bool white = l->color.x == 0 && l->color.y == 0 && l->color.z == 0;
        float k = l->intensity == 0.0f ? 1.0f : l->intensity;
        GLfloat c[4] = { (white ? 1.0f : l->color.x) * k, (white ? 1.0f : l->color.y) * k,
                         (white ? 1.0f : l->color.z) * k, 1.0f };
        GLfloat pos[4];
        if (l->type == SR_LIGHT_DIRECTIONAL) {
            /* GL wants the direction towards the light. */
            pos[0] = -l->vector.x;
            pos[1] = -l->vector.y;
            pos[2] = -l->vector.z;
            pos[3] = 0.0f;
        } else {
            pos[0] = l->vector.x;
            pos[1] = l->vector.y;
            pos[2] = l->vector.z;
            pos[3] = 1.0f;
        }
        glLightfv(id, GL_AMBIENT, zero);
        glLightfv(id, GL_DIFFUSE, c);
        glLightfv(id, GL_SPECULAR, c);
        glLightfv(id, GL_POSITION, pos);
        glEnable(id);
    }
    glEnable(GL_LIGHTING);
    /* softrast renormalizes eye-space normals. */
    glEnable(GL_NORMALIZE);
}

/* The scene's texture as GL_TEXTURE_2D, trilinear, modulating the lit
 * color.  GL's first row is t = 0, the bottom of the image, and softrast's
 * v = 0 is the bottom row too (sr_make_texture), but the PNG stores its
 * top row first: the rows go up in reverse.  glGenerateMipmap builds the
 * chain by 2x2 box averages, as sr_make_texture does. */
static bool setup_texture(gl_renderer *g, const bench_scene *s, char *msg, size_t msg_size)
{
    size_t row = (size_t)s->texture_w * 4;
    uint8_t *flipped = malloc(row * (size_t)s->texture_h);
    if (!flipped) {
        snprintf(msg, msg_size, "out of memory for the texture");
        return false;
    }
    for (int y = 0; y < s->texture_h; y++) {
        memcpy(flipped + (size_t)y * row, s->texture_pixels + (size_t)(s->texture_h - 1 - y) * row,
               row);
    }
    glGenTextures(1, &g->texture);
    glBindTexture(GL_TEXTURE_2D, g->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, s->texture_w, s->texture_h, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, flipped);
    free(flipped);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glEnable(GL_TEXTURE_2D);
    return true;
}

bool gl_prepare(gl_renderer *g, const bench_scene *s, char *msg, size_t msg_size)
{
    const sr_state *st = &s->state;
    gl_unprepare(g);
    if (s->width != g->width || s->height != g->height) {
        snprintf(msg, msg_size, "scene is %dx%d, the GL buffer %dx%d", s->width, s->height,
                 g->width, g->height);
        return false;
    }
    if (s->info->samples > 1) {
        glGenFramebuffers(1, &g->ms_fbo);
        glGenRenderbuffers(1, &g->ms_color);
        glGenRenderbuffers(1, &g->ms_depth);
        glBindRenderbuffer(GL_RENDERBUFFER, g->ms_color);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, s->info->samples, GL_RGBA8, s->width,
                                         s->height);
        glBindRenderbuffer(GL_RENDERBUFFER, g->ms_depth);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, s->info->samples, GL_DEPTH_COMPONENT24,
                                         s->width, s->height);
        glBindFramebuffer(GL_FRAMEBUFFER, g->ms_fbo);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  g->ms_color);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                  g->ms_depth);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            snprintf(msg, msg_size, "the %d-sample framebuffer object is incomplete",
                     s->info->samples);
            gl_unprepare(g);
            return false;
        }
        glEnable(GL_MULTISAMPLE);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glViewport(0, 0, s->width, s->height);
    glDisable(GL_DITHER);
    glClearColor(s->clear_color[0], s->clear_color[1], s->clear_color[2], s->clear_color[3]);
    glClearDepth(1.0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depth_func(st->depth_func));
    glDepthMask(st->depth_write == SR_OFF ? GL_FALSE : GL_TRUE);
    if (st->depth_test == SR_OFF) {
        glDisable(GL_DEPTH_TEST);
    }
    if (st->cull == SR_CULL_BACK || st->cull == SR_CULL_FRONT ||
        st->cull == SR_CULL_FRONT_AND_BACK) {
        glEnable(GL_CULL_FACE);
        glCullFace(st->cull == SR_CULL_BACK ? GL_BACK :
                   st->cull == SR_CULL_FRONT ? GL_FRONT : GL_FRONT_AND_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
    glFrontFace(st->front_face == SR_FRONT_CW ? GL_CW : GL_CCW);
    glShadeModel(GL_SMOOTH);

    bool lit = st->shading == SR_SHADING_GOURAUD;
    if (lit) {
        setup_lighting(s);
    } else {
        glDisable(GL_LIGHTING);
        if (st->shading != SR_SHADING_UNLIT && st->shading != SR_SHADING_DEFAULT) {
            snprintf(msg, msg_size, "only Gouraud and unlit scenes have a GL equivalent here");
            return false;
        }
    }

    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(s->projection.m);
    sr_mat4 mv = sr_mat4_mul(&s->view, &s->model);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(mv.m);

    size_t n = s->vertex_count;
    g->vbo_positions = upload(GL_ARRAY_BUFFER, s->positions,
                              n * (size_t)s->position_size * sizeof(float));
    glVertexPointer(s->position_size, GL_FLOAT, 0, NULL);
    glEnableClientState(GL_VERTEX_ARRAY);
    if (lit && s->normals) {
        g->vbo_normals = upload(GL_ARRAY_BUFFER, s->normals, n * 3 * sizeof(float));
        glNormalPointer(GL_FLOAT, 0, NULL);
        glEnableClientState(GL_NORMAL_ARRAY);
    } else {
        glDisableClientState(GL_NORMAL_ARRAY);
    }
    if (!lit && s->colors) {
        g->vbo_colors = upload(GL_ARRAY_BUFFER, s->colors, n * 4 * sizeof(float));
        glColorPointer(4, GL_FLOAT, 0, NULL);
        glEnableClientState(GL_COLOR_ARRAY);
    } else {
        glDisableClientState(GL_COLOR_ARRAY);
        const sr_vec3 d = st->material.diffuse;
        if (d.x == 0 && d.y == 0 && d.z == 0) {
            glColor4f(0.8f, 0.8f, 0.8f, 1.0f);
        } else {
            glColor4f(d.x, d.y, d.z, 1.0f);
        }
    }
    if (s->texture_pixels && s->texcoords) {
        g->vbo_texcoords = upload(GL_ARRAY_BUFFER, s->texcoords, n * 2 * sizeof(float));
        glTexCoordPointer(2, GL_FLOAT, 0, NULL);
        glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        if (!setup_texture(g, s, msg, msg_size)) {
            glBindBuffer(GL_ARRAY_BUFFER, 0);
            return false;
        }
    } else {
        glDisableClientState(GL_TEXTURE_COORD_ARRAY);
        glDisable(GL_TEXTURE_2D);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    if (s->indices) {
        g->ibo = upload(GL_ELEMENT_ARRAY_BUFFER, s->indices, s->index_count * sizeof(uint32_t));
    }
    return gl_check(g, msg, msg_size);
}

void gl_frame(gl_renderer *g, const bench_scene *s)
{
    if (g->ms_fbo) {
        glBindFramebuffer(GL_FRAMEBUFFER, g->ms_fbo);
    }
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (s->indices) {
        glDrawElements(GL_TRIANGLES, (GLsizei)s->index_count, GL_UNSIGNED_INT, NULL);
    } else {
        glDrawArrays(s->primitive == SR_PRIM_LINES ? GL_LINES : GL_TRIANGLES, 0,
                     (GLsizei)s->vertex_count);
    }
    if (g->ms_fbo) {
        /* The resolve, part of the frame as sr_resolve is on our side. */
        glBindFramebuffer(GL_READ_FRAMEBUFFER, g->ms_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, s->width, s->height, 0, 0, s->width, s->height,
                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    /* The frame is done when the pixels are in the buffer. */
    glFinish();
}

void gl_unprepare(gl_renderer *g)
{
    GLuint b[5] = { g->vbo_positions, g->vbo_normals, g->vbo_colors, g->vbo_texcoords, g->ibo };
    for (int i = 0; i < 5; i++) {
        if (b[i]) {
            glDeleteBuffers(1, &b[i]);
        }
    }
    g->vbo_positions = g->vbo_normals = g->vbo_colors = g->vbo_texcoords = g->ibo = 0;
    if (g->texture) {
        glDeleteTextures(1, &g->texture);
        g->texture = 0;
        glDisable(GL_TEXTURE_2D);
        glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    }
    if (g->ms_fbo) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &g->ms_fbo);
        glDeleteRenderbuffers(1, &g->ms_color);
        glDeleteRenderbuffers(1, &g->ms_depth);
        g->ms_fbo = g->ms_color = g->ms_depth = 0;
        glDisable(GL_MULTISAMPLE);
    }
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

bool gl_check(gl_renderer *g, char *msg, size_t msg_size)
{
    (void)g;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        snprintf(msg, msg_size, "OpenGL error 0x%04x", (unsigned)e);
        return false;
    }
    return true;
}

const uint8_t *gl_pixels(const gl_renderer *g) { return g->pixels; }

#endif /* SR_HAVE_OSMESA */
