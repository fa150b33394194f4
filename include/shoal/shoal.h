/* shoal's C API: the per-frame pose check for simulators that are not written in C++ (C#,
 * Unity, Unreal plug-ins, Python ctypes), with a stable ABI (libshoal_c.so.1).
 *
 * Handles are opaque. No C++ exception crosses this interface: a function that fails returns
 * NULL (or a non-zero status) and shoal_last_error() tells why.
 *
 * Threads: shoal_last_error() is per thread. A shoal_grid and a shoal_detector may be used by
 * several threads at once for shoal_check (they are not changed by it); creating and freeing
 * them must not race with their use. A detector keeps its grid alive: shoal_grid_free() may
 * be called while detectors made from the grid still exist; the grid's memory goes with the
 * last of them.
 *
 *   shoal_grid* g = shoal_grid_load("helsinki.shoalgrid");
 *   shoal_detector* d = shoal_detector_new(g, 150, 35, 14, 15);  // AIS A, B, C, D in metres
 *   shoal_contact c;
 *   if (shoal_check(d, 60.15, 24.95, 90.0, 500.0, &c) == 0 && c.covered && c.contact) ...;
 *   shoal_detector_free(d); shoal_grid_free(g);
 */
#ifndef SHOAL_SHOAL_H
#define SHOAL_SHOAL_H

#ifdef __cplusplus
extern "C" {
#endif

#if defined(SHOAL_C_BUILDING)
#define SHOAL_C_API __attribute__((visibility("default")))
#else
#define SHOAL_C_API
#endif

typedef struct shoal_grid shoal_grid;
typedef struct shoal_detector shoal_detector;

/* What shoal_check found for one pose. */
typedef struct shoal_contact {
    int contact;        /* 1: the hull touches or overlaps land (or a hazard); 0: no contact found */
    int covered;        /* 1: the hull lies inside the chart's area; 0: (partly) outside it: no contact
                           found there means nothing (clearance_m is then -1) */
    double clearance_m; /* hull-to-land distance in metres: 0 on contact, capped at max_clearance_m;
                           -1 when not covered and no contact was found */
} shoal_contact;

/* "0.2.0": equal to SHOAL_VERSION_STRING of <shoal/version.hpp>. */
SHOAL_C_API const char* shoal_version(void);

/* The message of the last failure on this thread; NULL when the last call succeeded. */
SHOAL_C_API const char* shoal_last_error(void);

/* Loads a grid file written by `shoal import`. NULL on error. */
SHOAL_C_API shoal_grid* shoal_grid_load(const char* path);
SHOAL_C_API void shoal_grid_free(shoal_grid* grid);

/* A detector for a hull of AIS dimensions a, b, c, d (metres from the position reference
 * point to bow, stern, port, starboard; each > 0). It checks against land and, when the grid
 * has a default limiting depth (`shoal import --hazard-depth`), the depth areas and dangers
 * charted shallower than it; else land only. NULL on error. */
SHOAL_C_API shoal_detector* shoal_detector_new(const shoal_grid* grid, double a, double b, double c, double d);
/* The same for the vessel's own limiting depth (its draught + the under-keel clearance, in
 * metres): depth areas and dangers charted shallower than it (or of unknown depth) are
 * hazards like land. NAN: land only. One grid serves every depth. NULL on error. */
SHOAL_C_API shoal_detector* shoal_detector_new_at_depth(const shoal_grid* grid, double a, double b, double c, double d,
                                                        double limiting_depth_m);
/* A detector for the hull of a ship file (schemas/ship.schema.json), at the grid's default
 * limiting depth as shoal_detector_new. NULL on error. */
SHOAL_C_API shoal_detector* shoal_detector_from_ship_file(const shoal_grid* grid, const char* ship_json);
/* The same at the limiting depth limiting_depth_m (NAN: land only); for the ship file's own
 * draught, pass it plus the under-keel clearance. NULL on error. */
SHOAL_C_API shoal_detector* shoal_detector_from_ship_file_at_depth(const shoal_grid* grid, const char* ship_json,
                                                                   double limiting_depth_m);
SHOAL_C_API void shoal_detector_free(shoal_detector* detector);

/* Checks the hull with its reference point at lat, lon (WGS84 degrees) and its bow at
 * heading_deg (true, clockwise from north). The clearance search reaches max_clearance_m
 * (> 0; INFINITY allowed). Fills *out and returns 0; non-zero on error (bad arguments). */
SHOAL_C_API int shoal_check(const shoal_detector* detector, double lat, double lon, double heading_deg,
                            double max_clearance_m, shoal_contact* out);

#ifdef __cplusplus
}
#endif

#endif /* SHOAL_SHOAL_H */
