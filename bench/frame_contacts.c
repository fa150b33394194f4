/* The simulator's frame loop through the C API, as a plug-in runs it: ships driven from open
 * water onto the chart's coast, piers and structures at 4 kn, a frame every 1/60 s, each frame
 * asking shoal_check and shoal_contacts for the same pose (one loop each, timed whole), and a
 * fleet of 1,000 ships asked at once. Prints microseconds a frame for poses clear and in contact.
 *
 *   bench_frame_contacts GRID.shoalgrid [SHIPS] [SEED]
 *
 * The approaches: SHIPS starting points drawn in the grid's box with clearance 5-300 m, each
 * driven straight on a random heading until it has been in contact for 3 m of travel (or
 * 6,000 frames). Not a test: it asserts nothing about time (docs/performance.md).
 *
 * A checksum of the contact frames' regions (their depths and points) is printed so that a
 * change meant to be faster only can be seen to give the same answers; SHOAL_BENCH_DUMP=FILE
 * writes every contact frame's regions to FILE, one line each, to compare two builds;
 * SHOAL_BENCH_POSES=FILE writes the contact frames' poses (lat lon heading, exact: C99 %a) for
 * bench_contacts_loop (bench/contacts_loop.c), which asks shoal_contacts for those only. */
#include <shoal/shoal.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef struct { double lat, lon, hdg; } pose;

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double uniform(unsigned long long* s) {  /* xorshift64* */
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

int main(int argc, char** argv) {
    if (argc < 2) { fprintf(stderr, "usage: %s GRID.shoalgrid [SHIPS] [SEED]\n", argv[0]); return 2; }
    const int ships = argc > 2 ? atoi(argv[2]) : 200;
    unsigned long long seed = argc > 3 ? strtoull(argv[3], NULL, 10) : 7;
    shoal_grid* g = shoal_grid_load(argv[1]);
    if (!g) { fprintf(stderr, "%s\n", shoal_last_error()); return 2; }
    shoal_detector* d = shoal_detector_new(g, 48, 12, 6, 6);  /* a 60 x 12 m ferry */
    if (!d) { fprintf(stderr, "%s\n", shoal_last_error()); return 2; }
    /* The grid's box: probe the lat/lon range from the arguments' environment or a default. */
    const char* box = getenv("SHOAL_BENCH_BOX");  /* "lat0,lon0,lat1,lon1" */
    double lat0 = 47.24, lon0 = -122.46, lat1 = 47.30, lon1 = -122.36;
    if (box && sscanf(box, "%lf,%lf,%lf,%lf", &lat0, &lon0, &lat1, &lon1) != 4) { fprintf(stderr, "bad SHOAL_BENCH_BOX\n"); return 2; }
    size_t cap = 1 << 20, n = 0;
    pose* frames = malloc(cap * sizeof *frames);
    const double step = 4 * 1852.0 / 3600 / 60;  /* 4 kn, 60 Hz */
    int started = 0;
    for (int tries = 0; started < ships && tries < ships * 200; ++tries) {
        pose p = {lat0 + (lat1 - lat0) * uniform(&seed), lon0 + (lon1 - lon0) * uniform(&seed), 360 * uniform(&seed)};
        shoal_contact c;
        if (shoal_check(d, p.lat, p.lon, p.hdg, 300, &c) != 0 || !c.covered || c.contact || c.clearance_m < 5 || c.clearance_m >= 300) continue;
        ++started;
        double in_contact = 0;
        for (int f = 0; f < 6000 && in_contact < 3; ++f) {
            if (n == cap) frames = realloc(frames, (cap *= 2) * sizeof *frames);
            frames[n++] = p;
            if (shoal_check(d, p.lat, p.lon, p.hdg, 1, &c) == 0 && c.contact) in_contact += step;
            const double h = p.hdg * M_PI / 180;
            p.lat += step * cos(h) / 111320.0;
            p.lon += step * sin(h) / (111320.0 * cos(p.lat * M_PI / 180));
        }
    }
    /* Which frames are in contact. */
    char* contact = malloc(n);
    size_t n_contact = 0;
    for (size_t i = 0; i < n; ++i) {
        shoal_contact c;
        shoal_check(d, frames[i].lat, frames[i].lon, frames[i].hdg, 1, &c);
        contact[i] = (char)c.contact;
        n_contact += (size_t)c.contact;
    }
    const char* poses_path = getenv("SHOAL_BENCH_POSES");
    if (poses_path) {
        FILE* pf = fopen(poses_path, "w");
        if (!pf) { fprintf(stderr, "cannot write %s\n", poses_path); return 2; }
        for (size_t i = 0; i < n; ++i)
            if (contact[i]) fprintf(pf, "%a %a %a\n", frames[i].lat, frames[i].lon, frames[i].hdg);
        fclose(pf);
    }
    shoal_contact_point pts[16];
    /* The answers, once, before the timing: a checksum and, on request, every region. */
    const char* dump_path = getenv("SHOAL_BENCH_DUMP");
    FILE* dump = dump_path ? fopen(dump_path, "w") : NULL;
    if (dump_path && !dump) { fprintf(stderr, "cannot write %s\n", dump_path); return 2; }
    double checksum = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!contact[i]) continue;
        const int k = shoal_contacts(d, frames[i].lat, frames[i].lon, frames[i].hdg, pts, 16);
        for (int r = 0; r < k && r < 16; ++r) {
            checksum += pts[r].depth_m + 1e-3 * (fabs(pts[r].x_m) + fabs(pts[r].y_m));
            if (dump)
                fprintf(dump, "%zu %d %.17g %.17g %.17g %.17g %.17g %d\n", i, r, pts[r].depth_m, pts[r].x_m, pts[r].y_m, pts[r].nx,
                        pts[r].ny, pts[r].hazard);
        }
        if (dump && k == 0) fprintf(dump, "%zu none\n", i);
    }
    if (dump) fclose(dump);
    double best[2][2] = {{1e9, 1e9}, {1e9, 1e9}};  /* [check|contacts][clear|contact] */
    size_t regions = 0;
    double deepest = 0;
    for (int rep = 0; rep < 5; ++rep)
        for (int cls = 0; cls < 2; ++cls) {
            size_t m = 0;
            double t = now_s();
            volatile int sink = 0;
            for (size_t i = 0; i < n; ++i) {
                if (contact[i] != cls) continue;
                shoal_contact c;
                sink += shoal_check(d, frames[i].lat, frames[i].lon, frames[i].hdg, 100, &c) + c.contact;
                ++m;
            }
            double t1 = now_s();
            if (m) best[0][cls] = fmin(best[0][cls], (t1 - t) / (double)m * 1e6);
            t = now_s();
            for (size_t i = 0; i < n; ++i) {
                if (contact[i] != cls) continue;
                const int k = shoal_contacts(d, frames[i].lat, frames[i].lon, frames[i].hdg, pts, 16);
                if (rep == 0 && k > 0) {
                    regions += (size_t)k;
                    if (pts[0].depth_m > deepest) deepest = pts[0].depth_m;
                }
                sink += k;
            }
            t1 = now_s();
            if (m) best[1][cls] = fmin(best[1][cls], (t1 - t) / (double)m * 1e6);
            (void)sink;
        }
    printf("%d approaches, %zu frames: %zu clear, %zu in contact (%zu regions, deepest %.2f m)\n", started, n, n - n_contact,
           n_contact, regions, deepest);
    printf("checksum of the contact frames' regions: %.9f\n", checksum);
    printf("clear frames:      shoal_check %.2f us, shoal_contacts %.2f us (%.2fx)\n", best[0][0], best[1][0], best[1][0] / best[0][0]);
    printf("contact frames:    shoal_check %.2f us, shoal_contacts %.2f us\n", best[0][1], best[1][1]);
    /* A fleet: 1,000 ships of the recorded frames (every n/1000-th), all asked in one frame. */
    double fleet = 1e9;
    for (int rep = 0; rep < 20; ++rep) {
        const double t = now_s();
        for (int s = 0; s < 1000; ++s) {
            const pose* p = &frames[(size_t)s * n / 1000];
            shoal_contacts(d, p->lat, p->lon, p->hdg, pts, 16);
        }
        fleet = fmin(fleet, now_s() - t);
    }
    printf("1,000 ships in one frame: %.3f ms (shoal_contacts for each)\n", fleet * 1e3);
    shoal_detector_free(d);
    shoal_grid_free(g);
    free(frames);
    free(contact);
    return 0;
}
