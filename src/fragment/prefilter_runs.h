/* prefilter_runs.h - the inner sum of the specular prefilter (fragment
 * stage, docs/ibl.md), on any thread: a template included by
 * environment_prefilter.c once a vector width, PF_RUNS_FN naming the copy,
 * PF_RUNS_TARGET its instruction set and PF_RUNS_V its vector type.
 *
 * PF_RUNS_FN(o, n, w, src, runs): o[e] += w[k] * src[k][e] for e < n and
 * the runs k = 0, 1, ... in turn.  Each element is summed in the same
 * order, lane-wise multiply then add (no FMA: the build uses
 * -ffp-contract=off), so every copy gives the same floats; the sums stay
 * in registers across the runs rather than being loaded and stored for
 * each. */

PF_RUNS_TARGET static void PF_RUNS_FN(float *restrict o, int n, const float *restrict w,
                                      const float *const *restrict src, int runs)
{
    enum { LANES = sizeof(PF_RUNS_V) / sizeof(float), ACCS = 8, BLOCK = ACCS * LANES };
    int e = 0;
    for (; e + BLOCK <= n; e += BLOCK) {
        PF_RUNS_V a[ACCS];
        memcpy(a, o + e, sizeof a);
        for (int k = 0; k < runs; k++) {
            PF_RUNS_V wk = (PF_RUNS_V){ 0 } + w[k];
            const float *s = src[k] + e;
            for (int b = 0; b < ACCS; b++) {
                PF_RUNS_V v;
                memcpy(&v, s + LANES * b, sizeof v);
                a[b] += wk * v;
            }
        }
        memcpy(o + e, a, sizeof a);
    }
    for (; e + LANES <= n; e += LANES) {
        PF_RUNS_V a;
        memcpy(&a, o + e, sizeof a);
        for (int k = 0; k < runs; k++) {
            PF_RUNS_V v;
            memcpy(&v, src[k] + e, sizeof v);
            a += ((PF_RUNS_V){ 0 } + w[k]) * v;
        }
        memcpy(o + e, &a, sizeof a);
    }
    for (; e < n; e++) {
        float a = o[e];
        for (int k = 0; k < runs; k++) {
            a += w[k] * src[k][e];
        }
        o[e] = a;
    }
}
