/* A simulator's per-frame check through shoal's C API (libshoal_c): load a grid once, then
 * check the own ship's pose every frame. Built against the installed package with pkg-config:
 *   cc frame_check.c $(pkg-config --cflags --libs shoal_c) -o frame_check
 *   ./frame_check GRID POSES.csv     (POSES.csv: lat,lon,heading per line, a header allowed)
 * Prints lat,lon,heading,collision,clearance_m,covered per pose (as `shoal probe` does), then
 * the cost per check on stderr. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <shoal/shoal.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

int main(int argc, char** argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s GRID POSES.csv\n", argv[0]);
        return 2;
    }
    shoal_grid* grid = shoal_grid_load(argv[1]);
    if (!grid) {
        fprintf(stderr, "frame_check: %s\n", shoal_last_error());
        return 2;
    }
    shoal_detector* ship = shoal_detector_new(grid, 150, 35, 14, 15); /* AIS A, B, C, D of a 185 m ferry */
    shoal_grid_free(grid); /* the detector keeps the grid alive */
    if (!ship) {
        fprintf(stderr, "frame_check: %s\n", shoal_last_error());
        return 2;
    }
    FILE* in = fopen(argv[2], "r");
    if (!in) {
        perror(argv[2]);
        return 2;
    }
    char line[256];
    long checks = 0;
    double seconds = 0;
    printf("lat,lon,heading,collision,clearance_m,covered\n");
    while (fgets(line, sizeof line, in)) {
        double lat, lon, heading;
        if (sscanf(line, "%lf,%lf,%lf", &lat, &lon, &heading) != 3) continue; /* the header */
        shoal_contact c;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        const int status = shoal_check(ship, lat, lon, heading, INFINITY, &c);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        if (status != 0) {
            fprintf(stderr, "frame_check: %s\n", shoal_last_error());
            continue;
        }
        seconds += (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        ++checks;
        if (c.covered || c.contact)
            printf("%.7f,%.7f,%.1f,%d,%.3f,%d\n", lat, lon, heading, c.contact, c.clearance_m, c.covered);
        else
            printf("%.7f,%.7f,%.1f,,,0\n", lat, lon, heading);
    }
    fclose(in);
    fprintf(stderr, "shoal %s: %ld checks, %.2f us per check\n", shoal_version(), checks, checks ? 1e6 * seconds / (double)checks : 0.0);
    shoal_detector_free(ship);
    return 0;
}
