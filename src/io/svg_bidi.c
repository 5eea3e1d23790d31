/* svg_bidi.c - the Unicode bidirectional algorithm for the SVG reader's
 * text (src/io, softrast_io), through GNU FriBidi: the resolved embedding
 * level of each character of a text chunk (rules P to I and L1), from
 * which svg_text.c cuts runs, shapes each in its direction and orders
 * them visually (rule L2).  Explicit embeddings (unicode-bidi) come as
 * the bidi control characters in the input.  Any thread. */
#include "io/svg_text.h"

#ifdef SR_HAVE_FRIBIDI

#include <fribidi.h>
#include <stdlib.h>

bool svg_bidi_available(void)
{
    return true;
}

int svg_bidi_levels(const uint32_t *cps, int n, bool rtl, unsigned char *levels)
{
    if (n <= 0) {
        return 0;
    }
    FriBidiCharType *types = malloc((size_t)n * sizeof *types);
    FriBidiBracketType *brackets = malloc((size_t)n * sizeof *brackets);
    FriBidiLevel *lv = malloc((size_t)n * sizeof *lv);
    bool ok = types && brackets && lv;
    if (ok) {
        fribidi_get_bidi_types(cps, n, types);
        fribidi_get_bracket_types(cps, n, types, brackets);
        /* the base direction is the direction property's, never guessed */
        FriBidiParType base = rtl ? FRIBIDI_PAR_RTL : FRIBIDI_PAR_LTR;
        ok = fribidi_get_par_embedding_levels_ex(types, brackets, n, &base, lv) != 0;
        /* L1: trailing blanks go back to the base level (the chunk is the
         * line) */
        ok = ok && fribidi_reorder_line(0, types, n, 0, base, lv, NULL, NULL) != 0;
    }
    for (int i = 0; ok && i < n; i++) {
        levels[i] = (unsigned char)lv[i];
    }
    free(types);
    free(brackets);
    free(lv);
    return ok ? 0 : -1;
}

#else /* no FriBidi: every character at the base level */

bool svg_bidi_available(void)
{
    return false;
}

/* Whether cp is of a right-to-left script's block (Hebrew, Arabic,
 * Syriac, Thaana, NKo, ..., their presentation forms, and the historic
 * ones of the SMP). */
static bool rtl_block(uint32_t cp)
{
    return (cp >= 0x0590 && cp <= 0x08FF) || (cp >= 0xFB1D && cp <= 0xFDFF) ||
           (cp >= 0xFE70 && cp <= 0xFEFF) || (cp >= 0x10800 && cp <= 0x10FFF) ||
           (cp >= 0x1E800 && cp <= 0x1EFFF);
}

int svg_bidi_levels(const uint32_t *cps, int n, bool rtl, unsigned char *levels)
{
    bool right = false, left = false;
    for (int i = 0; i < n; i++) {
        levels[i] = rtl ? 1 : 0;
        uint32_t c = cps[i];
        right = right || rtl_block(c);
        left = left || (c < 0x80 && ((c | 0x20) - 'a' < 26u || c - '0' < 10u)) ||
               (c >= 0xC0 && !rtl_block(c) && !(c >= 0x2000 && c <= 0x2BFF));
    }
    return right && left ? 1 : 0;
}

#endif
