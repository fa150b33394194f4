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

/* ---- Contact for a simulator's collision response (docs/simulator.md) ---- */

/* What a contact region's hull overlaps. */
enum shoal_hazard_kind {
    SHOAL_HAZARD_LAND = 1,      /* land (coastline) */
    SHOAL_HAZARD_SHALLOW = 2,   /* a depth area charted shallower than the detector's limiting depth (or of unknown depth) */
    SHOAL_HAZARD_DANGER = 3,    /* a rock, wreck or obstruction (S-57 UWTROC, WRECKS, OBSTRN) */
    SHOAL_HAZARD_STRUCTURE = 4, /* a pier, wharf, pontoon, dolphin, hulk ... (S-57 SLCONS, PONTON, MORFAC, HULKES) */
    SHOAL_HAZARD_SHIP = 5       /* another ship's hull (shoal_ship_contacts) */
};

/* One connected region where the hull overlaps a hazard, at its deepest point. */
typedef struct shoal_contact_point {
    double x_m, y_m;     /* the region's deepest hull point, ship frame: x forward, y starboard, metres
                            from the position reference point */
    double nx, ny;       /* unit normal, ship frame: moving the hull point along it by depth_m frees it
                            (towards the nearest point of the hazard's boundary) */
    double depth_m;      /* >= 0: the point's distance to the hazard's boundary */
    double lat, lon;     /* the hull point, WGS84 */
    double coast_lat, coast_lon; /* the nearest boundary point, WGS84 */
    int hazard;          /* enum shoal_hazard_kind */
    double charted_depth_m;      /* a shallow area's least charted depth or a danger's sounding (metres);
                                    NAN for land, structures, ships and unknown depths */
    const char* name;    /* the hazard's charted name ("Pier 25"), "" when none; valid while the grid lives */
} shoal_contact_point;

/* All contact regions of the hull at a pose (as shoal_check places it), deepest first: writes
 * at most `capacity` of them to out (out may be NULL when capacity is 0) and returns how many
 * there are (0: no contact), or -1 on error (shoal_last_error()). A region is a connected part
 * of the hull's overlap with land and hazards; for a hull that only touches, depth_m is 0. */
SHOAL_C_API int shoal_contacts(const shoal_detector* detector, double lat, double lon, double heading_deg,
                               shoal_contact_point* out, int capacity);

/* What a bridge simulator asks beside the contacts every frame. */
typedef struct shoal_surroundings {
    int covered;          /* 1: the hull and the reach of the searches lie inside the chart; 0: not, and a
                             distance below says only what the chart holds */
    double port_m;        /* how far the hull can move to port (ship frame -y) before it touches a hazard */
    double starboard_m;   /* ... to starboard (+y) */
    double ahead_m;       /* ... ahead (+x) */
    double astern_m;      /* ... astern (-x); each 0 in contact, capped at max_m */
    double least_depth_m; /* the least charted depth of the depth areas the hull overlaps (metres); NAN when
                             the grid charts no depth there or the area's depth is unknown; 0 on land */
} shoal_surroundings;

/* The clearances of the hull at a pose along its four axes (searched to max_m > 0, metres on the
 * ground; INFINITY allowed: a distance is then INFINITY when nothing lies that way on the chart)
 * and the least charted depth under it. The distances are to the detector's hazards (land, and
 * what its limiting depth makes a hazard); the least depth reads every depth area and danger of
 * the grid the detector was made from. Fills *out and returns 0; non-zero on error (bad
 * arguments; shoal_last_error() tells why). */
SHOAL_C_API int shoal_surroundings_at(const shoal_detector* detector, double lat, double lon, double heading_deg,
                                      double max_m, shoal_surroundings* out);

/* Two ships' hulls (each detector's hull at its pose; positions in WGS84, placed in a's grid's
 * frame): *out says whether they touch or overlap and their clearance; `points` receives at
 * most `capacity` regions where a's hull overlaps b's (ship frame of a, hazard SHOAL_HAZARD_SHIP,
 * the normal freeing a's point out of b's hull), deepest first. Returns how many regions there
 * are (0: none), or -1 on error. */
typedef struct shoal_ship_contact {
    int contact;          /* 1: the hulls touch or overlap */
    double clearance_m;   /* hull-to-hull distance, 0 on contact */
    double a_lat, a_lon;  /* the closest point of a's hull (a contact point on contact) */
    double b_lat, b_lon;  /* ... of b's hull */
} shoal_ship_contact;
SHOAL_C_API int shoal_ship_contacts(const shoal_detector* a, double lat_a, double lon_a, double heading_a_deg,
                                    const shoal_detector* b, double lat_b, double lon_b, double heading_b_deg,
                                    shoal_ship_contact* out, shoal_contact_point* points, int capacity);

#ifdef __cplusplus
}
#endif

#endif /* SHOAL_SHOAL_H */
