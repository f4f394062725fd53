/* Reference reader for spectrocolor texel coefficient files (.sctx, format version 1).
 *
 * Usage: texels TABLE.scup TEXELS.sctx X Y
 * Prints one line "wavelength_nm reflectance" per sample of the texel in column X, row Y (from
 * the top): its four node spectra of the table blended with its four float32 weights (layouts:
 * docs/upsampling.md). Little-endian IEEE-754 hosts only.
 * Build: cc -std=c99 -O2 -ffp-contract=off -o texels texels.c
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const char *what) { fprintf(stderr, "texels: %s\n", what); return 1; }

int main(int argc, char **argv) {
    unsigned char head[112], thead[32];
    uint32_t n, K, J, version, width, height, tn, tK, nodes[4];
    float weights[4];
    double start, step;
    if (argc != 5) return fail("usage: texels TABLE.scup TEXELS.sctx X Y");
    FILE *t = fopen(argv[2], "rb");
    if (!t || fread(thead, 1, sizeof thead, t) != sizeof thead) return fail("cannot read texel header");
    memcpy(&version, thead + 8, 4); memcpy(&width, thead + 12, 4); memcpy(&height, thead + 16, 4);
    memcpy(&tn, thead + 20, 4); memcpy(&tK, thead + 24, 4);
    if (memcmp(thead, "SCTEXEL", 8) != 0 || version != 1) return fail("not a version-1 texel file");
    long x = strtol(argv[3], NULL, 10), y = strtol(argv[4], NULL, 10);
    if (x < 0 || y < 0 || x >= (long)width || y >= (long)height) return fail("X Y outside the texture");
    long texel = y * (long)width + x, texels = (long)width * (long)height;
    if (fseek(t, 32L + 16L * texel, SEEK_SET) != 0 || fread(nodes, 4, 4, t) != 4 ||
        fseek(t, 32L + 16L * texels + 16L * texel, SEEK_SET) != 0 || fread(weights, 4, 4, t) != 4)
        return fail("cannot read the texel");
    fclose(t);
    FILE *f = fopen(argv[1], "rb");
    if (!f || fread(head, 1, sizeof head, f) != sizeof head) return fail("cannot read table header");
    memcpy(&version, head + 8, 4); memcpy(&n, head + 12, 4); memcpy(&K, head + 16, 4);
    memcpy(&J, head + 20, 4); memcpy(&start, head + 24, 8); memcpy(&step, head + 32, 8);
    if (memcmp(head, "SCUPTBL", 8) != 0 || version != 1) return fail("not a version-1 table");
    if (n != tn || K != tK) return fail("the texel file was made for another table");
    double *row = malloc(K * sizeof *row), *value = calloc(K, sizeof *value);
    if (!row || !value) return fail("out of memory");
    for (int j = 0; j < 4; j++) {
        if (nodes[j] >= n * n * n) return fail("node index outside the table");
        if (fseek(f, 112L + (long)J + 8L * (long)K * (long)nodes[j], SEEK_SET) != 0 ||
            fread(row, sizeof *row, K, f) != K)
            return fail("cannot read node reflectances");
        for (uint32_t k = 0; k < K; k++) value[k] = j == 0 ? row[k] * (double)weights[0] : value[k] + row[k] * (double)weights[j];
    }
    fclose(f);
    for (uint32_t k = 0; k < K; k++)
        printf("%.17g %.17g\n", start + (double)k * step, value[k] < 1.0 ? value[k] : 1.0);
    free(row); free(value);
    return 0;
}
