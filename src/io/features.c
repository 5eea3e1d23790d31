/* features.c - which optional readers and writers this build of the io
 * library has: each rests on a library the build found (CMake or
 * python/setup.py), and a user asking "does my softrast read Draco?"
 * should not have to try a file to learn it. */
#include "softrast_io.h"

const char *sr_io_features(void)
{
    /* In the order the documentation lists them, each after one space
     * that the return skips for the first. */
    static const char all[] =
#ifdef SR_HAVE_PNG
        " png"
#endif
#ifdef SR_HAVE_JPEG
        " jpeg"
#endif
#ifdef SR_HAVE_WEBP_DECODE
        " webp"
#endif
#ifdef SR_HAVE_JANSSON
        " gltf"
#endif
#ifdef SR_HAVE_MESHOPT
        " meshopt"
#endif
#ifdef SR_HAVE_DRACO
        " draco"
#endif
#ifdef SR_HAVE_EXPAT
        " svg"
#endif
#if defined(SR_HAVE_EXPAT) && defined(SR_HAVE_ZLIB)
        " svgz"
#endif
#if defined(SR_HAVE_EXPAT) && defined(SR_HAVE_SVG_TEXT)
        " text"
#endif
#if defined(SR_HAVE_EXPAT) && defined(SR_HAVE_SVG_TEXT) && defined(SR_HAVE_FRIBIDI)
        " bidi"
#endif
#ifdef SR_HAVE_ASSIMP
        " assimp"
#endif
        "";
    return sizeof all > 1 ? all + 1 : all;
}
