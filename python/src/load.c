/*
 * load.c - model files into numpy arrays: sr_load_mesh (every format the
 * library reads: OBJ, PLY, STL, and through Assimp glTF, FBX, DAE ...) and
 * sr_load_scene (glTF's node hierarchy, one instance a drawn primitive,
 * and the materials' factors).  The arrays are copied out of the library's
 * memory, which is freed before returning; the Python layer (softrast/
 * _scene.py, _gltf.py) makes Mesh and Material objects.
 */
#include "module.h"

#include <stdlib.h>
#include <string.h>

/* A new (rows, cols) array of `type` holding a copy of data, or None
 * when data is NULL. */
static PyObject *copy_array(const void *data, size_t rows, int cols, int type, size_t elem)
{
    if (!data) {
        Py_RETURN_NONE;
    }
    npy_intp shape[2] = { (npy_intp)rows, cols };
    PyObject *a = PyArray_SimpleNew(2, shape, type);
    if (a && rows) {
        memcpy(PyArray_DATA((PyArrayObject *)a), data, rows * (size_t)cols * elem);
    }
    return a;
}

static int set_item(PyObject *dict, const char *key, PyObject *value)
{
    if (!value) {
        return -1;
    }
    int r = PyDict_SetItemString(dict, key, value);
    Py_DECREF(value);
    return r;
}

static PyObject *arrays_dict(size_t vertices, const float *positions, const float *normals,
                             const float *colors, const float *texcoords, size_t triangles,
                             const uint32_t *indices)
{
    PyObject *d = PyDict_New();
    if (!d || set_item(d, "vertices", copy_array(positions, vertices, 3, NPY_FLOAT32, 4)) < 0 ||
        set_item(d, "faces", copy_array(indices, triangles, 3, NPY_INT32, 4)) < 0 ||
        set_item(d, "normals", copy_array(normals, vertices, 3, NPY_FLOAT32, 4)) < 0 ||
        set_item(d, "colors", copy_array(colors, vertices, 4, NPY_FLOAT32, 4)) < 0 ||
        set_item(d, "uvs", copy_array(texcoords, vertices, 2, NPY_FLOAT32, 4)) < 0) {
        Py_XDECREF(d);
        return NULL;
    }
    return d;
}

/* The mesh's one texture as an (H, W, 4) uint8 array, None when it names
 * none, or a warning kept in w and None when it cannot be read. */
static PyObject *mesh_texture(const sr_mesh *m, sr_py_warnings *w)
{
    if ((!m->texture_path && !m->texture_data) || m->part_count > 1) {
        if (m->part_count > 1) {
            sr_py_keep_warning(w, "softrast.load_mesh: the mesh takes several textures; "
                                  "none is kept");
        }
        Py_RETURN_NONE;
    }
    int width, height;
    uint8_t *px = NULL;
    sr_io_error err = { { 0 } };
    sr_result r = m->texture_data
                      ? sr_decode_image("<embedded texture>", m->texture_data, m->texture_size,
                                        &width, &height, &px, &err)
                      : sr_read_image(m->texture_path, &width, &height, &px, &err);
    if (r != SR_OK) {
        char line[sizeof err.message + 48];
        snprintf(line, sizeof line, "softrast.load_mesh: texture not kept: %s", err.message);
        sr_py_keep_warning(w, line);
        Py_RETURN_NONE;
    }
    return sr_py_image_array(px, width, height);
}

PyObject *sr_py_load_mesh(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj;
    if (!PyArg_ParseTuple(args, "O&:load_mesh", PyUnicode_FSConverter, &path_obj)) {
        return NULL;
    }
    sr_context *ctx = NULL;
    sr_mesh mesh = { 0 };
    sr_io_error err = { { 0 } };
    sr_py_warnings warnings = { 0 };
    sr_load_desc desc = { .warn = sr_py_keep_warning, .user = &warnings };
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    if (r == SR_OK) {
        const char *path = PyBytes_AS_STRING(path_obj);
        Py_BEGIN_ALLOW_THREADS
        r = sr_load_mesh(ctx, path, &desc, &mesh, &err);
        Py_END_ALLOW_THREADS
    } else {
        snprintf(err.message, sizeof err.message, "cannot make a context");
    }
    PyObject *d = NULL;
    if (r != SR_OK) {
        sr_py_io_error(r, &err, PyBytes_AS_STRING(path_obj));
    } else {
        d = arrays_dict(mesh.vertex_count, mesh.positions, mesh.normals, mesh.colors, mesh.texcoords,
                        mesh.triangle_count, mesh.indices);
        if (d && (set_item(d, "texture", mesh_texture(&mesh, &warnings)) < 0 ||
                  set_item(d, "warnings", sr_py_take_warnings(&warnings)) < 0)) {
            Py_CLEAR(d);
        }
    }
    sr_py_drop_warnings(&warnings);
    Py_DECREF(path_obj);
    sr_destroy_mesh(ctx, &mesh);
    sr_destroy_context(ctx);
    return d;
}

static const char *alpha_mode_name(sr_alpha_mode mode)
{
    return mode == SR_ALPHA_MASK ? "mask" : mode == SR_ALPHA_BLEND ? "blend" : "opaque";
}

/* A texture slot's use as the Python layer needs it: None when empty,
 * else its coordinate set, its transform (sr_texture_slot's uv' =
 * T(offset) R(rotation) S(scale) uv, in sr_make_texture's frame) and its
 * sampler (filter, wrap_u, wrap_v by softrast render's names). */
static PyObject *slot_dict(const sr_texture_slot *t)
{
    static const char *const filters[] = { "trilinear", "nearest", "bilinear", "trilinear" };
    static const char *const wraps[] = { "repeat", "repeat", "clamp", "mirror" };
    if (!t->texture) {
        Py_RETURN_NONE;
    }
    bool unit = !t->scale_set && t->scale[0] == 0.0f && t->scale[1] == 0.0f;
    return Py_BuildValue("{sisNsdsNssssss}", "texcoord", t->texcoord, "offset",
                         Py_BuildValue("(dd)", (double)t->offset[0], (double)t->offset[1]),
                         "rotation", (double)t->rotation, "scale",
                         Py_BuildValue("(dd)", unit ? 1.0 : (double)t->scale[0],
                                       unit ? 1.0 : (double)t->scale[1]),
                         "filter", filters[t->filter], "wrap_u", wraps[t->wrap_u], "wrap_v",
                         wraps[t->wrap_v]);
}

/* sr_pbr_material's factors as a dict (the textures' pixels are the
 * file's images, which the Python layer decodes itself). */
static PyObject *material_dict(const sr_pbr_material *m)
{
    const float *c = m->base_color, *e = m->emissive, *a = m->attenuation_color;
    PyObject *d = Py_BuildValue("{sNsNsdsdsNsdsssdsOsOsdsdsdsdsNsd}", "base_color",
                         Py_BuildValue("(dddd)", (double)c[0], (double)c[1], (double)c[2],
                                       (double)c[3]),
                         "base_color_texture", slot_dict(&m->base_color_texture), "metallic",
                         (double)m->metallic, "roughness", (double)m->roughness, "emissive",
                         Py_BuildValue("(ddd)", (double)e[0], (double)e[1], (double)e[2]),
                         "emissive_strength",
                         m->emissive_strength_set || m->emissive_strength != 0.0f
                             ? (double)m->emissive_strength
                             : 1.0,
                         "alpha_mode", alpha_mode_name(m->alpha_mode), "alpha_cutoff",
                         m->alpha_cutoff != 0.0f ? (double)m->alpha_cutoff : 0.5, "double_sided",
                         m->double_sided ? Py_True : Py_False, "unlit",
                         m->unlit ? Py_True : Py_False, "normal_scale", (double)m->normal_scale,
                         "occlusion_strength", (double)m->occlusion_strength, "transmission",
                         (double)m->transmission, "thickness", (double)m->thickness,
                         "attenuation_color",
                         Py_BuildValue("(ddd)", (double)a[0], (double)a[1], (double)a[2]),
                         "attenuation_distance", (double)m->attenuation_distance);
    /* The layers (KHR_materials_ior, _specular, _clearcoat, _sheen) with
     * the extensions' defaults where the file has none. */
    const float *sc = m->specular_color, *sh = m->sheen_color;
    bool spec = m->specular_set;
    PyObject *layers = d ? Py_BuildValue(
        "{sdsdsNsdsdsNsd}", "ior", m->ior != 0.0f ? (double)m->ior : 1.5, "specular",
        spec ? (double)m->specular : 1.0, "specular_color",
        Py_BuildValue("(ddd)", spec ? (double)sc[0] : 1.0, spec ? (double)sc[1] : 1.0,
                      spec ? (double)sc[2] : 1.0),
        "clearcoat", (double)m->clearcoat, "clearcoat_roughness", (double)m->clearcoat_roughness,
        "sheen_color", Py_BuildValue("(ddd)", (double)sh[0], (double)sh[1], (double)sh[2]),
        "sheen_roughness", (double)m->sheen_roughness) : NULL;
    /* The base lobe's anisotropy and film (KHR_materials_anisotropy and
     * _iridescence), with sr_pbr_material's zeros as the defaults. */
    bool both_zero = !m->iridescence_thickness_set && m->iridescence_thickness_min == 0.0f &&
                     m->iridescence_thickness_max == 0.0f;
    PyObject *surface = layers ? Py_BuildValue(
        "{sdsdsdsdsdsd}", "anisotropy_strength", (double)m->anisotropy_strength,
        "anisotropy_rotation", (double)m->anisotropy_rotation, "iridescence",
        (double)m->iridescence, "iridescence_ior",
        m->iridescence_ior != 0.0f ? (double)m->iridescence_ior : 1.3,
        "iridescence_thickness_min", both_zero ? 100.0 : (double)m->iridescence_thickness_min,
        "iridescence_thickness_max", both_zero ? 400.0 : (double)m->iridescence_thickness_max)
                                : NULL;
    /* KHR_materials_dispersion and _diffuse_transmission, zeros as absent
     * and the color's default white. */
    const float *dc = m->diffuse_transmission_color;
    /* KHR_materials_pbrSpecularGlossiness (its diffuse is base_color),
     * white and glossiness 1 where absent. */
    bool sg = m->specular_glossiness;
    const float *sp = m->sg_specular;
    PyObject *translucency = surface ? Py_BuildValue(
        "{sdsdsNsOsNsd}", "dispersion", (double)m->dispersion, "diffuse_transmission",
        (double)m->diffuse_transmission, "diffuse_transmission_color",
        Py_BuildValue("(ddd)", (double)dc[0], (double)dc[1], (double)dc[2]),
        "specular_glossiness", sg ? Py_True : Py_False, "sg_specular",
        Py_BuildValue("(ddd)", sg ? (double)sp[0] : 1.0, sg ? (double)sp[1] : 1.0,
                      sg ? (double)sp[2] : 1.0),
        "glossiness", sg ? (double)m->glossiness : 1.0) : NULL;
    if (!translucency || PyDict_Update(surface, translucency) < 0 ||
        PyDict_Update(layers, surface) < 0) {
        Py_XDECREF(translucency);
        Py_XDECREF(surface);
        Py_XDECREF(layers);
        Py_XDECREF(d);
        return NULL;
    }
    Py_DECREF(translucency);
    Py_DECREF(surface);
    if (!layers || PyDict_Update(d, layers) < 0) {
        Py_XDECREF(layers);
        Py_XDECREF(d);
        return NULL;
    }
    Py_DECREF(layers);
    return d;
}

/* A primitive's arrays, with its second texture coordinate set as "uvs1". */
static PyObject *primitive_dict(const sr_scene_primitive *p)
{
    PyObject *d = arrays_dict(p->vertex_count, p->positions, p->normals, p->colors, p->texcoords0,
                              p->triangle_count, p->indices);
    if (d && set_item(d, "uvs1", copy_array(p->texcoords1, p->vertex_count, 2, NPY_FLOAT32, 4)) < 0) {
        Py_CLEAR(d);
    }
    return d;
}

/* A (4, 4) float64 array of a column-major matrix, in rows. */
static PyObject *matrix_array(const float *m)
{
    npy_intp shape[2] = { 4, 4 };
    PyObject *a = PyArray_SimpleNew(2, shape, NPY_FLOAT64);
    if (a) {
        double *w = PyArray_DATA((PyArrayObject *)a);
        for (int r = 0; r < 4; r++) {
            for (int c = 0; c < 4; c++) {
                w[4 * r + c] = m[4 * c + r];
            }
        }
    }
    return a;
}

/* A camera as the Python layer's Camera takes it: its glTF fields and
 * its view matrix E (world -> the camera's frame, looking down -z, as
 * sr_scene_camera_matrices gives it; it does not depend on the aspect),
 * or None when that matrix is degenerate. */
static PyObject *camera_dict(const sr_scene_camera *c)
{
    sr_mat4 view, projection;
    PyObject *v = sr_scene_camera_matrices(c, 1.0f, &view, &projection) == SR_OK
                      ? matrix_array(view.m) : (Py_INCREF(Py_None), Py_None);
    if (!v) {
        return NULL;
    }
    return Py_BuildValue("{sssNsNsdsdsdsdsdsdsisi}", "type",
                         c->type == SR_SCENE_CAMERA_ORTHOGRAPHIC ? "orthographic" : "perspective",
                         "world", matrix_array(c->world), "view", v, "yfov", (double)c->yfov,
                         "aspect", (double)c->aspect, "xmag", (double)c->xmag, "ymag",
                         (double)c->ymag, "znear", (double)c->znear, "zfar", (double)c->zfar,
                         "camera", c->camera, "node", c->node);
}

/* A KHR_lights_punctual light as the Python layer's Light takes it: the
 * placed sr_light's fields ("vector" a directional light's direction of
 * travel, a point or spot light's position) under the file's kind (a dark
 * light's sr_light is SR_LIGHT_OFF, its color or intensity zero), its
 * node's world matrix and its indices. */
static PyObject *light_dict(const sr_scene_light *l)
{
    static const char *const types[] = { "off", "directional", "point", "spot" };
    const sr_light *s = &l->light;
    const char *type = (unsigned)l->type < 4 ? types[l->type] : "off";
    return Py_BuildValue("{sss(ddd)sds(ddd)s(ddd)sdsdsdsNsisi}", "type", type, "color",
                         (double)s->color.x, (double)s->color.y, (double)s->color.z,
                         "intensity", (double)s->intensity, "vector", (double)s->vector.x,
                         (double)s->vector.y, (double)s->vector.z, "direction",
                         (double)s->direction.x, (double)s->direction.y, (double)s->direction.z,
                         "inner_cone", (double)s->inner_cone, "outer_cone",
                         (double)s->outer_cone, "range", (double)s->range, "world",
                         matrix_array(l->world), "light", l->light_index, "node", l->node);
}

/* A string of the file's (UTF-8, checked by jansson), or None. */
static PyObject *optional_text(const char *text)
{
    if (!text) {
        Py_RETURN_NONE;
    }
    return PyUnicode_DecodeUTF8(text, (Py_ssize_t)strlen(text), "replace");
}

/* sr_scene.metadata: {"version", "min_version", "generator", "copyright":
 * str or None, "xmp_packet": the asset's packet index or None, "xmp": the
 * packet's JSON text or None, "xmp_properties": {name: text}}. */
static PyObject *metadata_dict(const sr_scene_metadata *m)
{
    PyObject *props = PyDict_New();
    for (size_t i = 0; props && i < m->property_count; i++) {
        if (set_item(props, m->properties[i].name, optional_text(m->properties[i].value)) < 0) {
            Py_CLEAR(props);
        }
    }
    PyObject *index = m->xmp_packet_index >= 0 ? PyLong_FromLong(m->xmp_packet_index)
                                               : optional_text(NULL);
    if (!props || !index) {
        Py_XDECREF(props);
        Py_XDECREF(index);
        return NULL;
    }
    return Py_BuildValue("{sNsNsNsNsNsNsN}", "version", optional_text(m->version), "min_version",
                         optional_text(m->min_version), "generator",
                         optional_text(m->generator), "copyright", optional_text(m->copyright),
                         "xmp_packet", index, "xmp", optional_text(m->xmp_packet),
                         "xmp_properties", props);
}

/* {"meshes": [arrays...], "instances": [(mesh index, (4, 4) world,
 * material index)], "materials": [dict...], "cameras": [dict...],
 * "lights": [dict...], "metadata": metadata_dict's,
 * "gltf": whether the glTF reader read it}: the primitives that share arrays share one entry of
 * "meshes". */
static PyObject *scene_dict(const sr_scene *s)
{
    PyObject *meshes = PyList_New(0), *instances = PyList_New(0), *seen = PyDict_New();
    PyObject *materials = NULL, *cameras = NULL, *lights = NULL, *out = NULL;
    if (!meshes || !instances || !seen) {
        goto done;
    }
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        PyObject *key = PyLong_FromVoidPtr((void *)p->positions);
        if (!key) {
            goto done;
        }
        PyObject *index = PyDict_GetItemWithError(seen, key);
        if (!index) {
            PyObject *d = PyErr_Occurred() ? NULL : primitive_dict(p);
            index = d ? PyLong_FromSsize_t(PyList_GET_SIZE(meshes)) : NULL;
            int bad = !index || PyList_Append(meshes, d) < 0 || PyDict_SetItem(seen, key, index) < 0;
            Py_XDECREF(d);
            Py_XDECREF(index);
            if (bad) {
                Py_DECREF(key);
                goto done;
            }
        }
        Py_DECREF(key);
        PyObject *world = matrix_array(p->world);
        if (!world) {
            goto done;
        }
        PyObject *item = Py_BuildValue("(ONi)", index, world, p->material);
        if (!item || PyList_Append(instances, item) < 0) {
            Py_XDECREF(item);
            goto done;
        }
        Py_DECREF(item);
    }
    cameras = PyList_New((Py_ssize_t)s->camera_count);
    for (size_t i = 0; cameras && i < s->camera_count; i++) {
        PyObject *c = camera_dict(&s->cameras[i]);
        if (!c) {
            goto done;
        }
        PyList_SET_ITEM(cameras, (Py_ssize_t)i, c);
    }
    lights = cameras ? PyList_New((Py_ssize_t)s->light_count) : NULL;
    for (size_t i = 0; lights && i < s->light_count; i++) {
        PyObject *l = light_dict(&s->lights[i]);
        if (!l) {
            goto done;
        }
        PyList_SET_ITEM(lights, (Py_ssize_t)i, l);
    }
    materials = lights ? PyList_New((Py_ssize_t)s->material_count) : NULL;
    for (size_t i = 0; materials && i < s->material_count; i++) {
        PyObject *m = material_dict(&s->materials[i]);
        if (!m) {
            goto done;
        }
        PyList_SET_ITEM(materials, (Py_ssize_t)i, m);
    }
    if (materials) {
        /* sr_load_mesh's one primitive comes from no node. */
        bool gltf = s->primitive_count == 0 || s->primitives[0].node >= 0;
        out = Py_BuildValue("{sOsOsOsOsOsO}", "meshes", meshes, "instances", instances,
                            "materials", materials, "cameras", cameras, "lights", lights, "gltf",
                            gltf ? Py_True : Py_False);
    }
    PyObject *variants = out ? PyList_New((Py_ssize_t)s->variant_count) : NULL;
    for (size_t i = 0; variants && i < s->variant_count; i++) {
        PyObject *name = PyUnicode_DecodeUTF8(s->variants[i], (Py_ssize_t)strlen(s->variants[i]),
                                              "replace");
        if (!name) {
            Py_CLEAR(variants);
            break;
        }
        PyList_SET_ITEM(variants, (Py_ssize_t)i, name);
    }
    if (out && set_item(out, "variants", variants) < 0) {
        Py_CLEAR(out);
    }
    /* The file's animations as (name, channels, duration) tuples. */
    PyObject *anims = out ? PyList_New((Py_ssize_t)s->animation_count) : NULL;
    for (size_t i = 0; anims && i < s->animation_count; i++) {
        const sr_scene_animation *a = &s->animations[i];
        PyObject *t = Py_BuildValue("(Nnd)", sr_py_message_text(a->name),
                                    (Py_ssize_t)a->channel_count, (double)a->duration);
        if (!t) {
            Py_CLEAR(anims);
            break;
        }
        PyList_SET_ITEM(anims, (Py_ssize_t)i, t);
    }
    if (out && set_item(out, "animations", anims) < 0) {
        Py_CLEAR(out);
    }
    if (out && set_item(out, "metadata", metadata_dict(&s->metadata)) < 0) {
        Py_CLEAR(out);
    }
done:
    Py_XDECREF(materials);
    Py_XDECREF(cameras);
    Py_XDECREF(lights);
    Py_XDECREF(meshes);
    Py_XDECREF(instances);
    Py_XDECREF(seen);
    return out;
}

/* KHR_materials_variants: `variant` (None, a name the file gives or a
 * number from 0) given to the scene's primitives, as softrast render's
 * --variant does.  -1 with ValueError when the file has no such variant. */
static int apply_variant(sr_scene *s, PyObject *variant, const char *path)
{
    if (variant == Py_None) {
        return 0;
    }
    size_t v = 0;
    if (PyLong_Check(variant)) {
        long n = PyLong_AsLong(variant);
        if (n == -1 && PyErr_Occurred()) {
            return -1;
        }
        v = n >= 0 && (size_t)n < s->variant_count ? (size_t)n + 1 : 0;
    } else {
        const char *want = PyUnicode_AsUTF8(variant);
        if (!want) {
            return -1;
        }
        for (size_t i = 0; i < s->variant_count && v == 0; i++) {
            v = strcmp(s->variants[i], want) == 0 ? i + 1 : 0;
        }
    }
    if (v == 0 && s->variant_count == 0) {
        PyErr_Format(PyExc_ValueError,
                     "%s: variant %R: the file has no material variants (KHR_materials_variants)",
                     path, variant);
        return -1;
    }
    if (v == 0) {
        PyObject *names = PyList_New(0);
        for (size_t i = 0; names && i < s->variant_count; i++) {
            PyObject *name = PyUnicode_DecodeUTF8(s->variants[i],
                                                  (Py_ssize_t)strlen(s->variants[i]), "replace");
            if (!name || PyList_Append(names, name) < 0) {
                Py_XDECREF(name);
                Py_CLEAR(names);
                break;
            }
            Py_DECREF(name);
        }
        if (names) {
            PyErr_Format(PyExc_ValueError, "%s: variant %R: no such variant (the file has %R)",
                         path, variant, names);
            Py_DECREF(names);
        }
        return -1;
    }
    for (size_t i = 0; i < s->primitive_count; i++) {
        if (s->primitives[i].variant_materials) {
            s->primitives[i].material = s->primitives[i].variant_materials[v];
        }
    }
    return 0;
}

PyObject *sr_py_load_scene(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path_obj, *variant = Py_None;
    int animation = -1;
    float time = 0.0f;
    if (!PyArg_ParseTuple(args, "O&|Oif:load", PyUnicode_FSConverter, &path_obj, &variant,
                          &animation, &time)) {
        return NULL;
    }
    if (variant != Py_None && !PyUnicode_Check(variant) &&
        !(PyLong_Check(variant) && !PyBool_Check(variant))) {
        Py_DECREF(path_obj);
        return PyErr_Format(PyExc_TypeError, "variant: expected a str, an int or None, got %s",
                            Py_TYPE(variant)->tp_name);
    }
    /* animation -1: the rest pose; the library checks the index and the
     * time (ValueError). */
    sr_py_warnings warnings = { 0 };
    sr_load_desc desc = { .pose = animation >= 0 ? SR_POSE_ANIMATION : SR_POSE_REST,
                          .animation = animation, .animation_time = time,
                          .warn = sr_py_keep_warning, .user = &warnings };
    sr_context *ctx = NULL;
    sr_scene *scene = NULL;
    sr_io_error err = { { 0 } };
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    if (r == SR_OK) {
        const char *path = PyBytes_AS_STRING(path_obj);
        Py_BEGIN_ALLOW_THREADS
        r = sr_load_scene(ctx, path, &desc, &scene, &err);
        Py_END_ALLOW_THREADS
    } else {
        snprintf(err.message, sizeof err.message, "cannot make a context");
    }
    PyObject *d = NULL;
    if (r != SR_OK) {
        d = sr_py_io_error(r, &err, PyBytes_AS_STRING(path_obj));
    } else if (apply_variant(scene, variant, PyBytes_AS_STRING(path_obj)) == 0) {
        d = scene_dict(scene);
    }
    if (d && set_item(d, "warnings", sr_py_take_warnings(&warnings)) < 0) {
        Py_CLEAR(d);
    }
    sr_py_drop_warnings(&warnings);
    Py_DECREF(path_obj);
    PyObject *gltf = d ? PyDict_GetItemString(d, "gltf") : NULL;
    if (gltf == Py_True) {
        /* Kept, with its textures, for the metallic-roughness look. */
        if (set_item(d, "file", sr_py_scene_file(ctx, scene)) < 0) {
            Py_CLEAR(d);
        }
        return d;
    }
    if (d && set_item(d, "file", (Py_INCREF(Py_None), Py_None)) < 0) {
        Py_CLEAR(d);
    }
    sr_destroy_scene(ctx, scene);
    sr_destroy_context(ctx);
    return d;
}

PyObject *sr_py_pose_scene(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *capsule, *path_obj;
    int animation = -1;
    float time = 0.0f;
    if (!PyArg_ParseTuple(args, "OO&|if:pose_scene", &capsule, PyUnicode_FSConverter, &path_obj,
                          &animation, &time)) {
        return NULL;
    }
    sr_scene *scene = sr_py_scene_of(capsule);
    if (!scene) {
        Py_DECREF(path_obj);
        return NULL;
    }
    /* Under the GIL: every pose of one reading shares its scene, and the
     * capsules already made keep their own copies of what this writes. */
    sr_io_error err = { { 0 } };
    sr_result r = sr_scene_pose(scene, animation >= 0 ? SR_POSE_ANIMATION : SR_POSE_REST,
                                animation, time, &err);
    PyObject *d = r == SR_OK ? scene_dict(scene)
                             : sr_py_io_error(r, &err, PyBytes_AS_STRING(path_obj));
    Py_DECREF(path_obj);
    if (d && set_item(d, "file", sr_py_scene_file_again(capsule)) < 0) {
        Py_CLEAR(d);
    }
    return d;
}
