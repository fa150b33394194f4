/* shoal_contacts alone, over the poses bench_frame_contacts wrote (SHOAL_BENCH_POSES=FILE: the
 * contact frames, one "lat lon heading" line each, C99 %a), asked REPS times in a loop with the
 * same 60 x 12 m ferry; prints the best loop's microseconds a call. For two libraries side by
 * side (LD_LIBRARY_PATH) and for callgrind (--toggle-collect=shoal_contacts, REPS 1):
 *
 *   bench_contacts_loop GRID.shoalgrid POSES [REPS]
 *
 * Not a test: it asserts nothing about time (docs/performance.md). */
#include <shoal/shoal.h>

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char** argv) {
    if (argc < 3) { fprintf(stderr, "usage: %s GRID.shoalgrid POSES [REPS]\n", argv[0]); return 2; }
    shoal_grid* g = shoal_grid_load(argv[1]);
    if (!g) { fprintf(stderr, "%s\n", shoal_last_error()); return 2; }
    shoal_detector* d = shoal_detector_new(g, 48, 12, 6, 6); /* the ferry of bench_frame_contacts */
    if (!d) { fprintf(stderr, "%s\n", shoal_last_error()); return 2; }
    FILE* f = fopen(argv[2], "r");
    if (!f) { fprintf(stderr, "cannot read %s\n", argv[2]); return 2; }
    size_t n = 0, cap = 1024;
    double* p = malloc(cap * 3 * sizeof *p);
    while (p && fscanf(f, "%la %la %la", &p[3 * n], &p[3 * n + 1], &p[3 * n + 2]) == 3)
        if (++n == cap) p = realloc(p, (cap *= 2) * 3 * sizeof *p);
    fclose(f);
    if (!p || n == 0) { fprintf(stderr, "%s: no poses (lines of lat lon heading)\n", argv[2]); return 2; }
    const int reps = argc > 3 ? atoi(argv[3]) : 5;
    shoal_contact_point pts[16];
    double best = 1e9;
    volatile int sink = 0;
    for (int r = 0; r < reps; ++r) {
        const double t = now_s();
        for (size_t i = 0; i < n; ++i) sink += shoal_contacts(d, p[3 * i], p[3 * i + 1], p[3 * i + 2], pts, 16);
        const double dt = now_s() - t;
        if (dt < best) best = dt;
    }
    printf("%zu poses, best of %d loops: %.2f us a call\n", n, reps, best / (double)n * 1e6);
    free(p);
    shoal_detector_free(d);
    shoal_grid_free(g);
    return 0;
}
