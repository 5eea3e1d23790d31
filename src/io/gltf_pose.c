/*
 * gltf_pose.c - io stage: a glTF scene posed again (sr_scene_pose)
 * without reading its file.  Consumes what the reader records while it
 * reads a file with animations (the nodes' rest transforms, the decoded
 * samplers, the skins, the morphed and skinned draws with their mesh's
 * arrays and pose sources); produces the scene's draws, cameras, lights
 * and bounds in another pose, through the arithmetic the reader itself
 * uses (gltf.c, gltf_animation.c, gltf_morph.c, gltf_skin.c), so the
 * bytes are those of a reading in that pose.  One thread at a time per
 * scene; internal to src/io but for sr_scene_pose.
 */
#include "io/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A node's own transform as local_matrix read it. */
typedef struct rest_node {
    bool known, has_matrix;
    float matrix[16];
    float t[3], q[4], s[3];
} rest_node;

typedef struct pose_skin {
    long *joints;             /* NULL: no draw uses the skin */
    float *inverse_bind;      /* 16 a joint (identities where the file has none) */
    float *matrices;          /* the joint matrices of the pose being made */
    size_t count;
} pose_skin;

/* A draw the pose moves vertex by vertex: morphed or skinned. */
typedef struct pose_draw {
    size_t primitive;         /* its index in sr_scene.primitives */
    long node, skin;
    size_t vertex_count;
    const float *base[3];     /* the mesh primitive's positions, normals, tangents */
    const gltf_pose_source *src;
    float *rest_weights;      /* src->target_count: the node's, else the mesh's */
    float *morphed[3], *skinned[3];   /* made on first need, reused after */
} pose_draw;

typedef struct source_block {
    gltf_pose_source *sources;
    size_t count;
} source_block;

/* EXT_mesh_gpu_instancing: a node's `made` pattern draws, each followed
 * by its copies, `per` draws a pattern from `first` on, the k-th of each
 * placed by instance matrix k after the pattern's world. */
typedef struct pose_instances {
    size_t first, made, per;
    float *matrices;              /* 16 an instance */
} pose_instances;

typedef struct gltf_posing {
    char *name;                   /* the file, in messages */
    size_t node_count;
    long *parent;
    rest_node *nodes;
    long *order;                  /* the known nodes, each after its parent */
    size_t order_count;
    float *worlds;                /* 16 a node, of the pose being made */
    gltf_node_pose *pose;
    gltf_anim *anims;
    size_t anim_count;
    pose_skin *skins;
    size_t skin_count;
    pose_draw *draws;
    size_t draw_count, draw_cap;
    source_block *blocks;
    size_t block_count, block_cap;
    pose_instances *instanced;
    size_t instanced_count, instanced_cap;
    size_t elements_left;         /* the reader's budget, for arrays made later */
    /* What KHR_animation_pointer and KHR_node_visibility change, as the
     * rest pose has it (NULL: not recorded, the reading failed). */
    sr_pbr_material *rest_materials;
    sr_scene_camera *rest_cameras;
    sr_scene_light *rest_lights;
    size_t *rest_triangles;       /* each draw's triangle_count */
    unsigned char *rest_visible, *visible, *state;   /* a node each */
    long *chain;
    bool rest_known;
} gltf_posing;

static void posing_free(void *p)
{
    gltf_posing *pl = p;
    if (!pl) {
        return;
    }
    for (size_t i = 0; i < pl->anim_count; i++) {
        sr__gltf_anim_free(&pl->anims[i]);
    }
    for (size_t i = 0; i < pl->skin_count; i++) {
        free(pl->skins[i].joints);
        free(pl->skins[i].inverse_bind);
        free(pl->skins[i].matrices);
    }
    for (size_t i = 0; i < pl->draw_count; i++) {
        free(pl->draws[i].rest_weights);
        for (int k = 0; k < 3; k++) {
            free(pl->draws[i].morphed[k]);
            free(pl->draws[i].skinned[k]);
        }
    }
    for (size_t b = 0; b < pl->block_count; b++) {
        for (size_t i = 0; i < pl->blocks[b].count; i++) {
            sr__gltf_pose_free(&pl->blocks[b].sources[i]);
        }
        free(pl->blocks[b].sources);
    }
    for (size_t i = 0; i < pl->instanced_count; i++) {
        free(pl->instanced[i].matrices);
    }
    free(pl->instanced);
    free(pl->rest_materials);
    free(pl->rest_cameras);
    free(pl->rest_lights);
    free(pl->rest_triangles);
    free(pl->rest_visible);
    free(pl->visible);
    free(pl->state);
    free(pl->chain);
    free(pl->blocks);
    free(pl->draws);
    free(pl->skins);
    free(pl->anims);
    free(pl->pose);
    free(pl->worlds);
    free(pl->order);
    free(pl->nodes);
    free(pl->parent);
    free(pl->name);
    free(pl);
}

bool sr__gltf_posing_start(gltf_doc *d, size_t animation_count)
{
    size_t n = json_array_size(json_object_get(d->root, "nodes"));
    gltf_posing *pl = calloc(1, sizeof *pl);
    if (!pl) {
        return false;
    }
    d->posing = pl;
    pl->node_count = n;
    pl->name = strdup(d->name);
    pl->nodes = calloc(n ? n : 1, sizeof *pl->nodes);
    pl->order = malloc((n ? n : 1) * sizeof *pl->order);
    pl->worlds = malloc((n ? n : 1) * 16 * sizeof *pl->worlds);
    pl->pose = calloc(n ? n : 1, sizeof *pl->pose);
    pl->anims = calloc(animation_count, sizeof *pl->anims);
    pl->anim_count = animation_count;
    return pl->name && pl->nodes && pl->order && pl->worlds && pl->pose && pl->anims;
}

void sr__gltf_posing_abandon(gltf_doc *d)
{
    posing_free(d->posing);
    d->posing = NULL;
}

bool sr__gltf_posing_finish(gltf_doc *d)
{
    gltf_posing *pl = d->posing;
    if (!pl) {
        return true;
    }
    pl->elements_left = d->elements_left;
    d->posing = NULL;
    return sr__scene_set_posing(d->scene, pl, posing_free);
}

bool sr__gltf_posing_anim(gltf_doc *d, size_t index, gltf_anim *a)
{
    gltf_posing *pl = d->posing;
    pl->anims[index] = *a;
    memset(a, 0, sizeof *a);
    return true;
}

const gltf_anim *sr__gltf_posing_anim_at(const gltf_doc *d, size_t index)
{
    return &d->posing->anims[index];
}

/* A malloc'd copy of n elements of size bytes (at least one byte). */
static void *copy_of(const void *src, size_t n, size_t size)
{
    void *p = malloc(n ? n * size : 1);
    if (p && n) {
        memcpy(p, src, n * size);
    }
    return p;
}

bool sr__gltf_posing_rest(gltf_doc *d, const unsigned char *visible)
{
    gltf_posing *pl = d->posing;
    if (!pl) {
        return true;
    }
    const sr_scene *s = d->scene;
    size_t n = pl->node_count ? pl->node_count : 1;
    pl->rest_materials = copy_of(s->materials, s->material_count, sizeof *s->materials);
    pl->rest_cameras = copy_of(s->cameras, s->camera_count, sizeof *s->cameras);
    pl->rest_lights = copy_of(s->lights, s->light_count, sizeof *s->lights);
    pl->rest_triangles = malloc((s->primitive_count ? s->primitive_count : 1) * sizeof(size_t));
    pl->rest_visible = copy_of(visible, pl->node_count, 1);
    pl->visible = malloc(n);
    pl->state = malloc(n);
    pl->chain = malloc(n * sizeof *pl->chain);
    if (!pl->rest_materials || !pl->rest_cameras || !pl->rest_lights || !pl->rest_triangles ||
        !pl->rest_visible || !pl->visible || !pl->state || !pl->chain) {
        return false;
    }
    for (size_t i = 0; i < s->primitive_count; i++) {
        pl->rest_triangles[i] = s->primitives[i].triangle_count;
    }
    pl->rest_known = true;
    return true;
}

bool sr__gltf_posing_node(gltf_doc *d, long node, const float *matrix, const float t[3],
                          const float q[4], const float s[3])
{
    gltf_posing *pl = d->posing;
    if (!pl || pl->nodes[node].known) {
        return true;
    }
    if (!pl->parent) {
        pl->parent = malloc((pl->node_count ? pl->node_count : 1) * sizeof *pl->parent);
        if (!pl->parent) {
            return false;
        }
        memcpy(pl->parent, d->node_parent, pl->node_count * sizeof *pl->parent);
    }
    rest_node *r = &pl->nodes[node];
    r->known = true;
    r->has_matrix = matrix != NULL;
    if (matrix) {
        memcpy(r->matrix, matrix, sizeof r->matrix);
    } else {
        memcpy(r->t, t, sizeof r->t);
        memcpy(r->q, q, sizeof r->q);
        memcpy(r->s, s, sizeof r->s);
    }
    /* The reader makes a parent's matrix before its children's. */
    pl->order[pl->order_count++] = node;
    return true;
}

bool sr__gltf_posing_skin(gltf_doc *d, long skin, const long *joints, size_t count,
                          const float *inverse_bind)
{
    gltf_posing *pl = d->posing;
    if (!pl) {
        return true;
    }
    if (!pl->skins) {
        pl->skin_count = json_array_size(json_object_get(d->root, "skins"));
        pl->skins = calloc(pl->skin_count ? pl->skin_count : 1, sizeof *pl->skins);
        if (!pl->skins) {
            pl->skin_count = 0;
            return false;
        }
    }
    pose_skin *k = &pl->skins[skin];
    k->joints = malloc(count * sizeof *k->joints);
    k->inverse_bind = malloc(count * 16 * sizeof *k->inverse_bind);
    k->matrices = malloc(count * 16 * sizeof *k->matrices);
    if (!k->joints || !k->inverse_bind || !k->matrices) {
        return false;
    }
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    memcpy(k->joints, joints, count * sizeof *joints);
    for (size_t j = 0; j < count; j++) {
        memcpy(k->inverse_bind + 16 * j, inverse_bind ? inverse_bind + 16 * j : identity,
               sizeof identity);
    }
    k->count = count;
    return true;
}

bool sr__gltf_posing_draw(gltf_doc *d, size_t primitive, long skin, const sr_scene_primitive *g,
                          const gltf_pose_source *src, const float *rest_weights)
{
    gltf_posing *pl = d->posing;
    if (pl->draw_count == pl->draw_cap) {
        size_t cap = pl->draw_cap ? 2 * pl->draw_cap : 16;
        pose_draw *grown = realloc(pl->draws, cap * sizeof *grown);
        if (!grown) {
            return false;
        }
        pl->draws = grown;
        pl->draw_cap = cap;
    }
    pose_draw *w = &pl->draws[pl->draw_count++];
    *w = (pose_draw){ .primitive = primitive, .node = d->scene->primitives[primitive].node,
                      .skin = skin, .vertex_count = g->vertex_count,
                      .base = { g->positions, g->normals, g->tangents }, .src = src };
    if (src->target_count > 0) {
        w->rest_weights = malloc(src->target_count * sizeof *w->rest_weights);
        if (!w->rest_weights) {
            return false;
        }
        memcpy(w->rest_weights, rest_weights, src->target_count * sizeof *rest_weights);
    }
    return true;
}

bool sr__gltf_posing_instances(gltf_doc *d, size_t first, size_t made, size_t per,
                                const float *matrices)
{
    gltf_posing *pl = d->posing;
    if (!pl) {
        return true;
    }
    if (pl->instanced_count == pl->instanced_cap) {
        size_t cap = pl->instanced_cap ? 2 * pl->instanced_cap : 4;
        pose_instances *grown = realloc(pl->instanced, cap * sizeof *grown);
        if (!grown) {
            return false;
        }
        pl->instanced = grown;
        pl->instanced_cap = cap;
    }
    float *copy = malloc(per * 16 * sizeof *copy);
    if (!copy) {
        return false;
    }
    memcpy(copy, matrices, per * 16 * sizeof *copy);
    pl->instanced[pl->instanced_count++] = (pose_instances){ first, made, per, copy };
    /* The node's posed draws were recorded at their pattern's index,
     * before the copies moved each pattern to the head of its run. */
    for (size_t i = pl->draw_count; i-- > 0 && pl->draws[i].primitive >= first;) {
        pl->draws[i].primitive = first + (pl->draws[i].primitive - first) * per;
    }
    return true;
}

bool sr__gltf_posing_sources(gltf_doc *d, gltf_pose_source *sources, size_t count)
{
    gltf_posing *pl = d->posing;
    if (pl->block_count == pl->block_cap) {
        size_t cap = pl->block_cap ? 2 * pl->block_cap : 16;
        source_block *grown = realloc(pl->blocks, cap * sizeof *grown);
        if (!grown) {
            for (size_t i = 0; i < count; i++) {
                sr__gltf_pose_free(&sources[i]);
            }
            free(sources);
            return false;
        }
        pl->blocks = grown;
        pl->block_cap = cap;
    }
    pl->blocks[pl->block_count++] = (source_block){ sources, count };
    return true;
}

/* ---- posing ----------------------------------------------------------------- */

/* The morph weights draw w takes in the pose: the animation's, as
 * sr__gltf_node_weights takes them, else its rest ones. */
static const float *draw_weights(const gltf_posing *pl, const pose_draw *w)
{
    const gltf_node_pose *p = &pl->pose[w->node];
    return p->weights && p->weight_count == w->src->target_count ? p->weights : w->rest_weights;
}

static size_t active_targets(const pose_draw *w, const float *weights)
{
    size_t active = 0;
    for (size_t t = 0; t < w->src->target_count; t++) {
        active += weights[t] != 0;
    }
    return active;
}

/* Arrays set[k] for base[k] (n vertices), made once and charged to the
 * reader's budget; false when over it or out of memory (*result says). */
static bool own_arrays(gltf_posing *pl, const pose_draw *w, float *set[3], sr_result *result)
{
    for (int k = 0; k < 3; k++) {
        size_t stride = k == 2 ? 4 : 3, floats;
        if (!w->base[k] || set[k]) {
            continue;
        }
        if (!sr__mul_ok(w->vertex_count, stride, &floats) || floats > pl->elements_left) {
            *result = SR_TOO_LARGE;
            return false;
        }
        if (!(set[k] = malloc((floats ? floats : 1) * sizeof(float)))) {
            *result = SR_OUT_OF_MEMORY;
            return false;
        }
        pl->elements_left -= floats;
    }
    return true;
}

/* Every known node's world matrix in the pose pl->pose holds, as the
 * reader makes it (parent's world times local). */
static void make_worlds(gltf_posing *pl)
{
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    for (size_t i = 0; i < pl->order_count; i++) {
        long v = pl->order[i], up = pl->parent[v];
        const rest_node *r = &pl->nodes[v];
        const gltf_node_pose *p = &pl->pose[v];
        float local[16];
        if (r->has_matrix) {
            memcpy(local, r->matrix, sizeof local);
        } else {
            sr__gltf_trs(p->animated & GLTF_POSE_TRANSLATION ? p->translation : r->t,
                                 p->animated & GLTF_POSE_ROTATION ? p->rotation : r->q,
                                 p->animated & GLTF_POSE_SCALE ? p->scale : r->s, local);
        }
        sr__mat4_mul(up >= 0 ? pl->worlds + 16 * up : identity, local, pl->worlds + 16 * v);
    }
}

/* The checks a reading in this pose makes, before anything changes: the
 * lights' directions, the vertices drawn, the arrays' memory. */
static sr_result check_pose(gltf_posing *pl, const sr_scene *scene, sr_io_error *err)
{
    for (size_t i = 0; i < scene->light_count; i++) {
        sr_scene_light l = scene->lights[i];
        if (!sr__gltf_aim_light(&l, pl->worlds + 16 * l.node)) {
            return sr__io_fail(err, SR_BAD_FORMAT, pl->name, 0,
                               "/nodes/%d/extensions/KHR_lights_punctual: the node's matrix "
                               "collapses the light's direction (its -Z)", l.node);
        }
    }
    size_t work = 0;
    for (size_t i = 0; i < scene->primitive_count; i++) {
        work += scene->primitives[i].vertex_count;
    }
    for (size_t i = 0; i < pl->draw_count; i++) {
        pose_draw *w = &pl->draws[i];
        size_t active = active_targets(w, draw_weights(pl, w)), more;
        sr_result result = SR_OK;
        if (!sr__mul_ok(w->vertex_count, active + (w->skin >= 0 ? w->src->influence_sets : 0),
                        &more) ||
            more > SR_SCENE_MAX_DRAWN_VERTICES - work) {
            return sr__io_fail(err, SR_TOO_LARGE, pl->name, 0,
                               "/nodes/%ld: more than %zu vertices to draw in all", w->node,
                               SR_SCENE_MAX_DRAWN_VERTICES);
        }
        work += more;
        if ((active > 0 && !own_arrays(pl, w, w->morphed, &result)) ||
            (w->skin >= 0 && !own_arrays(pl, w, w->skinned, &result))) {
            return result == SR_TOO_LARGE
                       ? sr__io_fail(err, result, pl->name, 0,
                                     "/nodes/%ld: posing %zu more vertices is more than a "
                                     "file of this size may decode", w->node, w->vertex_count)
                       : sr__io_fail(err, result, pl->name, 0, "out of memory");
        }
    }
    return SR_OK;
}

static void pose_draws(gltf_posing *pl, sr_scene *scene)
{
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    for (size_t s = 0; s < pl->skin_count; s++) {
        const pose_skin *k = &pl->skins[s];
        for (size_t j = 0; k->joints && j < k->count; j++) {
            sr__mat4_mul(pl->worlds + 16 * k->joints[j], k->inverse_bind + 16 * j,
                         k->matrices + 16 * j);
        }
    }
    size_t next = 0, b = 0;
    for (size_t i = 0; i < scene->primitive_count;) {
        sr_scene_primitive *p = &scene->primitives[i];
        const float *world = pl->worlds + 16 * p->node;
        float base[16];
        bool mirrored;
        const float *cur[3] = { p->positions, p->normals, p->tangents };
        if (next >= pl->draw_count || pl->draws[next].primitive != i) {
            memcpy(base, world, sizeof base);
            mirrored = sr__gltf_mirrors(world);
        } else {
            pose_draw *w = &pl->draws[next++];
            const float *weights = draw_weights(pl, w);
            for (int k = 0; k < 3; k++) {
                cur[k] = w->base[k];
            }
            if (w->src->target_count > 0 && active_targets(w, weights) > 0) {
                sr__gltf_morph_vertices(w->src, weights, w->vertex_count, w->base, w->morphed);
                for (int k = 0; k < 3; k++) {
                    cur[k] = w->morphed[k];
                }
            }
            if (w->skin >= 0) {
                float *out[3] = { cur[0] ? w->skinned[0] : NULL, cur[1] ? w->skinned[1] : NULL,
                                  cur[2] ? w->skinned[2] : NULL };
                size_t turned = sr__gltf_skin_vertices(pl->skins[w->skin].matrices, w->src,
                                                       w->vertex_count, cur, out);
                memcpy(base, identity, sizeof base);
                mirrored = 2 * turned > w->vertex_count;
                for (int k = 0; k < 3; k++) {
                    cur[k] = out[k];
                }
            } else {
                memcpy(base, world, sizeof base);
                mirrored = sr__gltf_mirrors(world);
            }
        }
        /* A pattern of EXT_mesh_gpu_instancing heads its copies, which
         * share its arrays, each placed by its instance after the base. */
        while (b < pl->instanced_count &&
               pl->instanced[b].first + pl->instanced[b].made * pl->instanced[b].per <= i) {
            b++;
        }
        const pose_instances *in = b < pl->instanced_count && i >= pl->instanced[b].first
                                       ? &pl->instanced[b] : NULL;
        size_t copies = in ? in->per : 1;
        for (size_t k = 0; k < copies; k++) {
            sr_scene_primitive *q = &scene->primitives[i + k];
            if (in) {
                sr__mat4_mul(base, in->matrices + 16 * k, q->world);
                q->mirrored = mirrored != sr__gltf_mirrors(in->matrices + 16 * k);
            } else {
                memcpy(q->world, base, sizeof q->world);
                q->mirrored = mirrored;
            }
            q->positions = cur[0];
            q->normals = cur[1];
            q->tangents = cur[2];
        }
        i += copies;
    }
}

static void copy_back(void *dst, const void *src, size_t bytes)
{
    if (bytes > 0) {
        memcpy(dst, src, bytes);
    }
}

sr_result sr__gltf_pose(void *posing, sr_scene *scene, bool animated, int animation, float time,
                        sr_io_error *err)
{
    gltf_posing *pl = posing;
    for (size_t i = 0; i < pl->node_count; i++) {
        pl->pose[i].animated = 0;
        pl->pose[i].weights = NULL;
        pl->pose[i].weight_count = 0;
    }
    if (animated) {
        sr__gltf_anim_apply(&pl->anims[animation], time, pl->pose);
    }
    make_worlds(pl);
    sr_result r = check_pose(pl, scene, err);
    if (r != SR_OK) {
        return r;
    }
    pose_draws(pl, scene);
    if (pl->rest_known) {
        /* The rest pose's values, then the animation's over them (a
         * scene without cameras or lights has NULL arrays). */
        copy_back(scene->materials, pl->rest_materials,
                  scene->material_count * sizeof *scene->materials);
        copy_back(scene->cameras, pl->rest_cameras, scene->camera_count * sizeof *scene->cameras);
        copy_back(scene->lights, pl->rest_lights, scene->light_count * sizeof *scene->lights);
        for (size_t i = 0; i < scene->primitive_count; i++) {
            scene->primitives[i].triangle_count = pl->rest_triangles[i];
        }
        copy_back(pl->visible, pl->rest_visible, pl->node_count);
        if (animated) {
            sr__gltf_anim_apply_pointers(&pl->anims[animation], time, scene, pl->visible);
        }
        if (pl->parent) {
            sr__gltf_hide(scene, pl->parent, pl->node_count, pl->visible, pl->state, pl->chain);
        }
    }
    for (size_t i = 0; i < scene->camera_count; i++) {
        memcpy(scene->cameras[i].world, pl->worlds + 16 * scene->cameras[i].node,
               sizeof scene->cameras[i].world);
    }
    for (size_t i = 0; i < scene->light_count; i++) {
        sr__gltf_aim_light(&scene->lights[i], pl->worlds + 16 * scene->lights[i].node);
    }
    return SR_OK;
}

const char *sr__gltf_posing_name(const void *posing)
{
    return ((const gltf_posing *)posing)->name;
}
