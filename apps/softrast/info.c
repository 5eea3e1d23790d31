/* info.c - `softrast info MODEL [--json]`: what softrast reads in a model
 * file, before rendering it: its draws, vertex attributes, bounds,
 * materials and the glTF extensions they use, textures, variants,
 * animations, cameras, lights and metadata (info_metadata.c), as text or
 * as one JSON object for scripts.  The model is read by the library's
 * sr_load_scene, as `softrast render` reads it, so its warnings and
 * errors are the same lines. */
#include "cli.h"
#include "info.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "usage: softrast info MODEL [--json]\n"
               "\n"
               "What softrast reads in MODEL (.obj, .ply, .stl, .gltf, .glb; other formats\n"
               "through Assimp when built with it), read as 'softrast render' reads it: the\n"
               "primitives to draw (each node instance and each EXT_mesh_gpu_instancing\n"
               "instance counted; how many are the latter), their vertices, triangles\n"
               "and attributes, the bounds in world space, each material with its textures\n"
               "and the glTF material extensions it uses, the textures, the material variants\n"
               "(what --variant picks), the animations with their durations (what\n"
               "--animation picks), cameras (what --camera-index counts) and lights; for\n"
               "glTF, what the file says about itself: its asset's version, generator and\n"
               "copyright, and the KHR_xmp_json_ld metadata packet the asset references\n"
               "(its title, creator, rights, usage terms and other licence and authorship\n"
               "properties; the whole packet, as JSON, in --json).\n"
               "Warnings go to stderr, as render's do.\n"
               "\n"
               "  --json      one JSON object on stdout instead of text\n"
               "  -h, --help  this text\n");
}

static void warn_line(void *user, const char *message)
{
    (void)user;
    cli_message("%s", message);
}

typedef struct attribute_counts {
    size_t normals, tangents, texcoords0, texcoords1, colors;
    size_t vertices, triangles;
} attribute_counts;

static attribute_counts count_attributes(const sr_scene *sc)
{
    attribute_counts a = { 0 };
    for (size_t i = 0; i < sc->primitive_count; i++) {
        const sr_scene_primitive *p = &sc->primitives[i];
        a.normals += p->normals != NULL;
        a.tangents += p->tangents != NULL;
        a.texcoords0 += p->texcoords0 != NULL;
        a.texcoords1 += p->texcoords1 != NULL;
        a.colors += p->colors != NULL;
        a.vertices += p->vertex_count;
        a.triangles += p->triangle_count;
    }
    return a;
}

/* A material's textures, by the names glTF gives them. */
typedef struct named_slot {
    const char *name;
    const sr_texture_slot *slot;
} named_slot;

static size_t material_slots(const sr_pbr_material *m, named_slot *out)
{
    const named_slot all[] = {
        /* Specular-glossiness's diffuse texture fills the base color's. */
        { m->specular_glossiness ? "diffuse" : "baseColor", &m->base_color_texture },
        { "metallicRoughness", &m->metallic_roughness_texture },
        { "normal", &m->normal_texture },
        { "occlusion", &m->occlusion_texture },
        { "emissive", &m->emissive_texture },
        { "transmission", &m->transmission_texture },
        { "thickness", &m->thickness_texture },
        { "specular", &m->specular_texture },
        { "specularColor", &m->specular_color_texture },
        { "clearcoat", &m->clearcoat_texture },
        { "clearcoatRoughness", &m->clearcoat_roughness_texture },
        { "clearcoatNormal", &m->clearcoat_normal_texture },
        { "sheenColor", &m->sheen_color_texture },
        { "sheenRoughness", &m->sheen_roughness_texture },
        { "anisotropy", &m->anisotropy_texture },
        { "iridescence", &m->iridescence_texture },
        { "iridescenceThickness", &m->iridescence_thickness_texture },
        { "diffuseTransmission", &m->diffuse_transmission_texture },
        { "diffuseTransmissionColor", &m->diffuse_transmission_color_texture },
        { "specularGlossiness", &m->specular_glossiness_texture },
    };
    size_t n = 0;
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        if (all[i].slot->texture) {
            out[n++] = all[i];
        }
    }
    return n;
}
#define MAX_SLOTS 20

/* The glTF material extensions whose values the material holds: zeroed
 * fields are the extension absent (sr_pbr_material's convention). */
static size_t material_extensions(const sr_pbr_material *m, const char **out)
{
    size_t n = 0;
    if (m->specular_glossiness) {
        out[n++] = "KHR_materials_pbrSpecularGlossiness";
    }
    if (m->unlit) {
        out[n++] = "KHR_materials_unlit";
    }
    if ((m->emissive_strength_set || m->emissive_strength != 0.0f) &&
        m->emissive_strength != 1.0f) {
        out[n++] = "KHR_materials_emissive_strength";
    }
    if (m->ior != 0.0f && m->ior != 1.5f) {
        out[n++] = "KHR_materials_ior";
    }
    if (m->specular_set) {
        out[n++] = "KHR_materials_specular";
    }
    if (m->transmission != 0.0f || m->transmission_texture.texture) {
        out[n++] = "KHR_materials_transmission";
    }
    if (m->thickness != 0.0f || m->attenuation_distance != 0.0f) {
        out[n++] = "KHR_materials_volume";
    }
    if (m->clearcoat != 0.0f) {
        out[n++] = "KHR_materials_clearcoat";
    }
    if (m->sheen_color[0] != 0.0f || m->sheen_color[1] != 0.0f || m->sheen_color[2] != 0.0f ||
        m->sheen_color_texture.texture) {
        out[n++] = "KHR_materials_sheen";
    }
    if (m->anisotropy_strength != 0.0f || m->anisotropy_texture.texture) {
        out[n++] = "KHR_materials_anisotropy";
    }
    if (m->iridescence != 0.0f) {
        out[n++] = "KHR_materials_iridescence";
    }
    if (m->dispersion != 0.0f) {
        out[n++] = "KHR_materials_dispersion";
    }
    if (m->diffuse_transmission != 0.0f || m->diffuse_transmission_texture.texture) {
        out[n++] = "KHR_materials_diffuse_transmission";
    }
    return n;
}
#define MAX_EXTENSIONS 13

static const char *alpha_name(sr_alpha_mode mode)
{
    return mode == SR_ALPHA_MASK ? "MASK" : mode == SR_ALPHA_BLEND ? "BLEND" : "OPAQUE";
}

static const char *light_name(sr_light_type type)
{
    return type == SR_LIGHT_POINT ? "point" : type == SR_LIGHT_SPOT ? "spot" : "directional";
}

/* A JSON string: quotes, backslashes and control bytes escaped; bytes
 * from 0x80 up are passed on (a file name's UTF-8). */
void info_json_string(const char *s)
{
    putchar('"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\') {
            printf("\\%c", *p);
        } else if (*p < 0x20) {
            printf("\\u%04x", *p);
        } else {
            putchar(*p);
        }
    }
    putchar('"');
}

/* A float as JSON takes it, in the fewest digits that read back as the
 * same float (9 always do); JSON has no infinity. */
static void json_number(float v)
{
    if (!isfinite(v)) {
        printf("null");
        return;
    }
    char text[32];
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, (double)v);
        if (strtof(text, NULL) == v) {
            break;
        }
    }
    printf("%s", text);
}

static void json_floats(const float *v, int n)
{
    putchar('[');
    for (int i = 0; i < n; i++) {
        printf(i ? ", " : "");
        json_number(v[i]);
    }
    putchar(']');
}

/* The materials to show: the file's, and the one the reader adds for
 * primitives without one only when a primitive draws with it. */
static size_t shown_materials(const sr_scene *sc, bool *with_default)
{
    *with_default = false;
    if (sc->default_material < 0) {
        return sc->material_count;
    }
    for (size_t i = 0; i < sc->primitive_count; i++) {
        *with_default |= sc->primitives[i].material == sc->default_material;
    }
    return (size_t)sc->default_material + (*with_default ? 1 : 0);
}

static void print_json(const char *path, const sr_scene *sc)
{
    attribute_counts a = count_attributes(sc);
    printf("{\"file\": ");
    info_json_string(path);
    printf(", \"primitives\": %zu, \"vertices\": %zu, \"triangles\": %zu,\n", sc->primitive_count,
           a.vertices, a.triangles);
    printf(" \"instanced_draws\": %zu, \"instanced_nodes\": %zu,\n", sc->instanced_draws,
           sc->instanced_nodes);
    printf(" \"attributes\": {\"normals\": %zu, \"tangents\": %zu, \"texcoords0\": %zu, "
           "\"texcoords1\": %zu, \"colors\": %zu},\n",
           a.normals, a.tangents, a.texcoords0, a.texcoords1, a.colors);
    const float lo[3] = { sc->bounds_min.x, sc->bounds_min.y, sc->bounds_min.z };
    const float hi[3] = { sc->bounds_max.x, sc->bounds_max.y, sc->bounds_max.z };
    printf(" \"bounds\": {\"min\": ");
    json_floats(lo, 3);
    printf(", \"max\": ");
    json_floats(hi, 3);
    printf("},\n \"materials\": [");
    bool with_default;
    size_t shown = shown_materials(sc, &with_default);
    for (size_t i = 0; i < shown; i++) {
        const sr_pbr_material *m = &sc->materials[i];
        named_slot slots[MAX_SLOTS];
        const char *ext[MAX_EXTENSIONS];
        size_t ns = material_slots(m, slots), ne = material_extensions(m, ext);
        printf("%s\n  {%s\"base_color\": ", i ? "," : "",
               (int)i == sc->default_material ? "\"default\": true, " : "");
        json_floats(m->base_color, 4);
        printf(", \"metallic\": ");
        json_number(m->metallic);
        printf(", \"roughness\": ");
        json_number(m->roughness);
        if (m->specular_glossiness) {
            printf(", \"specular\": ");
            json_floats(m->sg_specular, 3);
            printf(", \"glossiness\": ");
            json_number(m->glossiness);
        }
        printf(", \"alpha_mode\": \"%s\", \"double_sided\": %s,\n   \"textures\": [",
               alpha_name(m->alpha_mode), m->double_sided ? "true" : "false");
        for (size_t k = 0; k < ns; k++) {
            printf("%s\"%s\"", k ? ", " : "", slots[k].name);
        }
        printf("], \"extensions\": [");
        for (size_t k = 0; k < ne; k++) {
            printf("%s\"%s\"", k ? ", " : "", ext[k]);
        }
        printf("]}");
    }
    printf("%s],\n \"textures\": %zu,\n \"variants\": [", shown ? "\n " : "",
           sc->texture_count);
    for (size_t i = 0; i < sc->variant_count; i++) {
        printf(i ? ", " : "");
        info_json_string(sc->variants[i]);
    }
    printf("],\n \"animations\": [");
    for (size_t i = 0; i < sc->animation_count; i++) {
        const sr_scene_animation *an = &sc->animations[i];
        printf("%s\n  {\"name\": ", i ? "," : "");
        info_json_string(an->name);
        printf(", \"channels\": %zu, \"duration\": ", an->channel_count);
        json_number(an->duration);
        printf("}");
    }
    printf("%s],\n \"cameras\": [", sc->animation_count ? "\n " : "");
    for (size_t i = 0; i < sc->camera_count; i++) {
        const sr_scene_camera *c = &sc->cameras[i];
        bool persp = c->type == SR_SCENE_CAMERA_PERSPECTIVE;
        printf("%s\n  {\"type\": \"%s\", \"node\": %d, ", i ? "," : "",
               persp ? "perspective" : "orthographic", c->node);
        if (persp) {
            printf("\"yfov\": ");
            json_number(c->yfov);
            printf(", \"aspect\": ");
            json_number(c->aspect);
        } else {
            printf("\"xmag\": ");
            json_number(c->xmag);
            printf(", \"ymag\": ");
            json_number(c->ymag);
        }
        printf(", \"znear\": ");
        json_number(c->znear);
        printf(", \"zfar\": ");
        json_number(c->zfar > 0.0f ? c->zfar : INFINITY); /* 0: infinite, null */
        printf("}");
    }
    printf("%s],\n \"lights\": [", sc->camera_count ? "\n " : "");
    for (size_t i = 0; i < sc->light_count; i++) {
        const sr_scene_light *l = &sc->lights[i];
        printf("%s\n  {\"type\": \"%s\", \"node\": %d, \"color\": ", i ? "," : "",
               light_name(l->type), l->node);
        const float color[3] = { l->light.color.x, l->light.color.y, l->light.color.z };
        json_floats(color, 3);
        printf(", \"intensity\": ");
        json_number(l->light.intensity);
        printf(", \"range\": ");
        json_number(l->light.range);
        printf("}");
    }
    printf("%s],\n", sc->light_count ? "\n " : "");
    info_print_metadata_json(sc);
    printf(" \"warnings\": %d}\n", sc->warning_count);
}

static void print_text(const char *path, const sr_scene *sc)
{
    attribute_counts a = count_attributes(sc);
    size_t n = sc->primitive_count;
    printf("%s\n", path);
    info_print_metadata_text(sc);
    printf("  draws       %zu primitive%s: %zu vertices, %zu triangles (each instance counted)\n",
           n, n == 1 ? "" : "s", a.vertices, a.triangles);
    if (sc->instanced_draws) {
        printf("  instances   %zu of the draws, from EXT_mesh_gpu_instancing on %zu node%s\n",
               sc->instanced_draws, sc->instanced_nodes, sc->instanced_nodes == 1 ? "" : "s");
    }
    printf("  attributes  normals %zu/%zu, tangents %zu/%zu, texcoords %zu/%zu, second texcoords "
           "%zu/%zu, colors %zu/%zu\n",
           a.normals, n, a.tangents, n, a.texcoords0, n, a.texcoords1, n, a.colors, n);
    sr_vec3 lo = sc->bounds_min, hi = sc->bounds_max;
    printf("  bounds      min %g %g %g, max %g %g %g (size %g x %g x %g)\n", (double)lo.x,
           (double)lo.y, (double)lo.z, (double)hi.x, (double)hi.y, (double)hi.z,
           (double)(hi.x - lo.x), (double)(hi.y - lo.y), (double)(hi.z - lo.z));
    bool with_default;
    size_t shown = shown_materials(sc, &with_default);
    printf("  materials   %zu%s\n", shown - (with_default ? 1u : 0u),
           with_default ? ", and the default for primitives without one" : "");
    for (size_t i = 0; i < shown; i++) {
        const sr_pbr_material *m = &sc->materials[i];
        named_slot slots[MAX_SLOTS];
        const char *ext[MAX_EXTENSIONS];
        size_t ns = material_slots(m, slots), ne = material_extensions(m, ext);
        const float *c = m->base_color, *sp = m->sg_specular;
        if (m->specular_glossiness) {
            printf("    %zu  diffuse %g %g %g %g, specular %g %g %g, glossiness %g, %s%s", i,
                   (double)c[0], (double)c[1], (double)c[2], (double)c[3], (double)sp[0],
                   (double)sp[1], (double)sp[2], (double)m->glossiness,
                   alpha_name(m->alpha_mode), m->double_sided ? ", double-sided" : "");
        } else {
            printf("    %zu  %sbase color %g %g %g %g, metallic %g, roughness %g, %s%s", i,
                   (int)i == sc->default_material ? "(default) " : "", (double)c[0],
                   (double)c[1], (double)c[2], (double)c[3], (double)m->metallic,
                   (double)m->roughness, alpha_name(m->alpha_mode),
                   m->double_sided ? ", double-sided" : "");
        }
        for (size_t k = 0; k < ns; k++) {
            printf("%s%s", k ? ", " : "; textures ", slots[k].name);
        }
        for (size_t k = 0; k < ne; k++) {
            printf("%s%s", k ? ", " : "; ", ext[k]);
        }
        printf("\n");
    }
    printf("  textures    %zu\n", sc->texture_count);
    if (sc->variant_count) {
        printf("  variants    %zu (--variant)\n", sc->variant_count);
        for (size_t i = 0; i < sc->variant_count; i++) {
            /* The file's text: no control byte reaches the terminal. */
            char name[256];
            snprintf(name, sizeof name, "%s", sc->variants[i]);
            cli_one_line(name);
            printf("    %zu  %s\n", i, name);
        }
    }
    if (sc->animation_count) {
        printf("  animations  %zu (--animation)\n", sc->animation_count);
        for (size_t i = 0; i < sc->animation_count; i++) {
            const sr_scene_animation *an = &sc->animations[i];
            char name[256];
            snprintf(name, sizeof name, "%s", an->name);
            cli_one_line(name);
            printf("    %zu  %g s, %zu channel%s%s%s\n", i, (double)an->duration,
                   an->channel_count, an->channel_count == 1 ? "" : "s", name[0] ? ", " : "",
                   name);
        }
    }
    printf("  cameras     %zu\n", sc->camera_count);
    for (size_t i = 0; i < sc->camera_count; i++) {
        const sr_scene_camera *c = &sc->cameras[i];
        if (c->type == SR_SCENE_CAMERA_PERSPECTIVE) {
            printf("    %zu  perspective, yfov %g degrees, aspect ", i,
                   (double)c->yfov * 180.0 / 3.14159265358979323846);
            printf(c->aspect > 0.0f ? "%g" : "the image's", (double)c->aspect);
        } else {
            printf("    %zu  orthographic, xmag %g, ymag %g", i, (double)c->xmag,
                   (double)c->ymag);
        }
        printf(", znear %g, zfar ", (double)c->znear);
        printf(c->zfar > 0.0f ? "%g" : "infinite", (double)c->zfar);
        printf(" (node %d)\n", c->node);
    }
    printf("  lights      %zu\n", sc->light_count);
    for (size_t i = 0; i < sc->light_count; i++) {
        const sr_scene_light *l = &sc->lights[i];
        bool directional = l->type == SR_LIGHT_DIRECTIONAL;
        printf("    %zu  %s, color %g %g %g, intensity %g %s", i, light_name(l->type),
               (double)l->light.color.x, (double)l->light.color.y, (double)l->light.color.z,
               (double)l->light.intensity, directional ? "lux" : "candela");
        if (!directional && l->light.range > 0.0f) {
            printf(", range %g", (double)l->light.range);
        }
        printf(" (node %d)\n", l->node);
    }
    if (sc->warning_count) {
        printf("  warnings    %d (on stderr)\n", sc->warning_count);
    }
}

int cmd_info(int argc, char **argv)
{
    const char *model = NULL;
    bool json = false, ended = false;
    for (int i = 1; i < argc; i++) {
        cli_arg_kind kind = cli_arg(argv[i], &ended);
        if (kind == CLI_ARG_END) {
            continue;
        }
        if (kind == CLI_ARG_OPERAND) {
            if (model) {
                cli_error("info: one MODEL at a time ('%s' and '%s')", model, argv[i]);
                return EXIT_USAGE;
            }
            model = argv[i];
        } else if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            usage(stdout);
            return EXIT_OK;
        } else if (strcmp(argv[i], "--json") == 0) {
            json = true;
        } else {
            cli_error("info: unknown option '%s' (softrast info --help)", argv[i]);
            return EXIT_USAGE;
        }
    }
    if (!model) {
        cli_error("info: give a MODEL (softrast info --help)");
        return EXIT_USAGE;
    }
    sr_context *ctx = NULL;
    sr_set_last_error(NULL);
    sr_result made = sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    if (made != SR_OK) {
        cli_error("info: %s", cli_why(made));
        return EXIT_FAILURE_RUN;
    }
    sr_scene *sc = NULL;
    sr_io_error err;
    sr_result r = sr_load_scene(ctx, model, &(sr_load_desc){ .warn = warn_line }, &sc, &err);
    int status = EXIT_OK;
    if (r != SR_OK) {
        cli_message("%s", err.message);
        status = r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    } else if (json) {
        print_json(model, sc);
    } else {
        print_text(model, sc);
    }
    sr_destroy_scene(ctx, sc);
    sr_destroy_context(ctx);
    if (status == EXIT_OK && (fflush(stdout) != 0 || ferror(stdout))) {
        cli_error("info: cannot write to standard output");
        status = EXIT_FAILURE_RUN;
    }
    return status;
}
