/* Reference reader for spectrocolor spectral upsampling tables (.scup, format version 1).
 *
 * Usage: reader TABLE.scup R G B
 * R G B: table coordinates in [0, 1] (linear RGB of the table's space). Prints one line
 * "wavelength_nm reflectance" per sample: the tetrahedral blend of the table's node spectra
 * (layout and lookup: docs/upsampling.md). Little-endian IEEE-754 hosts only.
 * Build: cc -std=c99 -O2 -ffp-contract=off -o reader reader.c
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const char *what) { fprintf(stderr, "reader: %s\n", what); return 1; }

int main(int argc, char **argv) {
    unsigned char head[112];
    uint32_t version, n, K, J;
    double start, step, t[3], frac[3], w[4];
    size_t base[3], stride[3], node[4];
    int order[3] = {0, 1, 2};
    if (argc != 5) return fail("usage: reader TABLE.scup R G B");
    FILE *f = fopen(argv[1], "rb");
    if (!f || fread(head, 1, sizeof head, f) != sizeof head) return fail("cannot read header");
    if (memcmp(head, "SCUPTBL", 8) != 0) return fail("not an upsampling table (magic)");
    memcpy(&version, head + 8, 4); memcpy(&n, head + 12, 4); memcpy(&K, head + 16, 4);
    memcpy(&J, head + 20, 4); memcpy(&start, head + 24, 8); memcpy(&step, head + 32, 8);
    if (version != 1 || n < 2 || n > 129 || K < 2 || K > 4096) return fail("bad header");
    size_t count = (size_t)n * n * n * K;
    double *rho = malloc(count * sizeof *rho);
    if (!rho || fseek(f, 112L + (long)J, SEEK_SET) != 0 || fread(rho, sizeof *rho, count, f) != count)
        return fail("cannot read node reflectances");
    fclose(f);
    stride[0] = (size_t)n * n; stride[1] = n; stride[2] = 1;
    for (int c = 0; c < 3; c++) {
        t[c] = strtod(argv[2 + c], NULL);
        if (!(t[c] >= 0.0 && t[c] <= 1.0)) return fail("R G B must lie in [0, 1]");
        double s = t[c] * (double)(n - 1);
        base[c] = (size_t)s < n - 2 ? (size_t)s : n - 2;
        frac[c] = s - (double)base[c];
    }
    for (int a = 1; a < 3; a++)  /* stable sort of the axes by decreasing fraction */
        for (int b = a; b > 0 && frac[order[b]] > frac[order[b - 1]]; b--) {
            int swap = order[b]; order[b] = order[b - 1]; order[b - 1] = swap;
        }
    w[0] = 1.0 - frac[order[0]];
    w[1] = frac[order[0]] - frac[order[1]];
    w[2] = frac[order[1]] - frac[order[2]];
    w[3] = frac[order[2]];
    node[0] = base[0] * stride[0] + base[1] * stride[1] + base[2] * stride[2];
    for (int j = 0; j < 3; j++) node[j + 1] = node[j] + stride[order[j]];
    for (size_t k = 0; k < K; k++) {
        double value = rho[node[0] * K + k] * w[0];
        for (int j = 1; j < 4; j++) value += rho[node[j] * K + k] * w[j];
        printf("%.17g %.17g\n", start + (double)k * step, value < 1.0 ? value : 1.0);
    }
    free(rho);
    return 0;
}
