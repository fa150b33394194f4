/* A small ship simulation in C that turns shoal's contact regions into collision forces: a
 * 185 m ferry driven at 4 kn onto a quay and onto a pier (examples/simulator/berth.geojson,
 * imported with `shoal import`), and a tug pushing the ferry's side (shoal_ship_contacts).
 * Only <shoal/shoal.h> and libm:
 *   cc -std=c11 berthing_sim.c $(pkg-config --cflags --libs shoal_c) -lm -o berthing_sim
 *   shoal import berth.geojson --ship-length 185 -o berth.shoalgrid
 *   ./berthing_sim berth.shoalgrid [-v]       (-v: a log line for every frame in contact)
 *
 * The model (3 degrees of freedom: surge u, sway v, yaw rate r, in the ship frame: x forward,
 * y starboard, z down; heading psi true, clockwise from north):
 *   m11 du/dt = X + m22 v r           m11 = m + added mass in surge
 *   m22 dv/dt = Y - m11 u r           m22 = m + added mass in sway
 *   m33 dr/dt = N - (m22 - m11) u v   m33 = Iz + added inertia in yaw (the Munk moment)
 * with X = thrust - Xu u - Xuu |u| u, Y = -Yv v - Yvv |v| v, N = rudder moment - Nr r - Nrr |r| r,
 * plus the contact forces below. The thrust balances the surge drag at 4 kn, so a ship started
 * at 4 kn keeps exactly 4 kn until it touches: the frame of first contact is the initial gap /
 * (4 kn / 60 Hz), rounded up. Integrated at 60 Hz by semi-implicit Euler (velocities from the
 * forces at this frame's pose, then the pose from the new velocities).
 *
 * The pose goes to shoal as WGS84 lat/lon through a local flat-earth frame about the scene's
 * reference point (east, north in metres; the WGS84 radii of curvature at its latitude). Its
 * error grows as east offset x north offset x tan(lat) / R: about 1 mm for 100 m x 100 m here,
 * 0.3 m for 1 km x 1 km. The runs stay within a few hundred metres of the reference point
 * (millimetres, against the 3.4 cm a frame moves at 4 kn); a simulator sailing further moves
 * the reference point with the ship, or converts with a proper projection.
 *
 * Contact (as Bridge Command does it with its hull's contact points; here shoal gives one
 * point per connected region of overlap, at its deepest): for each region, a spring-damper
 * along the region's normal (n, ship frame, pointing out of the hazard),
 *   f_n = k depth + c (speed of the hull point into the hazard),  never pulling (f_n >= 0),
 * with c = 2 zeta sqrt(k m11) (zeta: the fraction of critical damping), and a Coulomb friction
 * mu f_n against the point's speed along the boundary (smoothed below 0.05 m/s). The force acts
 * at the hull point (x_m, y_m): yaw moment N = x Fy - y Fx.
 *
 * The program asserts what a simulator needs of the contacts (exit 1 otherwise): the deepest
 * region never deepens by more than 5 cm in one frame, no region is deeper than 1 m, and the
 * ship's reference point never crosses the face it was driven at (it does not tunnel through).
 */
#include <shoal/shoal.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define KNOT (1852.0 / 3600.0)
#define HZ 60.0
#define MAX_REGIONS 16

static const double dt = 1.0 / HZ;
static int verbose = 0;

/* ---- The scene's local flat-earth frame (berth.geojson was made in the same one) ---- */
static const double lat0 = 60.15, lon0 = 24.95;
static double m_per_rad_north, m_per_rad_east;

static void frame_init(void) {
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double s = sin(lat0 * DEG), w = 1.0 - e2 * s * s;
    m_per_rad_north = a * (1.0 - e2) / (w * sqrt(w)); /* meridian radius of curvature */
    m_per_rad_east = a / sqrt(w) * cos(lat0 * DEG);   /* prime vertical radius x cos(lat) */
}
static double lat_of(double north) { return lat0 + north / m_per_rad_north / DEG; }
static double lon_of(double east) { return lon0 + east / m_per_rad_east / DEG; }

/* ---- The ferry ---- */
typedef struct {
    double a, b, c, d;          /* AIS dimensions: reference point to bow, stern, port, starboard */
    double m11, m22, m33;       /* mass + added mass (kg), yaw inertia + added (kg m^2) */
    double xu, xuu, yv, yvv;    /* linear (N s/m) and quadratic (N s^2/m^2) damping */
    double nr, nrr;             /* yaw damping (N m s, N m s^2) */
    double thrust, rudder;      /* N, N m */
} ship_model;

typedef struct {
    double east, north, psi; /* the reference point (m) and heading (rad, clockwise from north) */
    double u, v, r;          /* m/s, m/s, rad/s */
} ship_state;

/* A 185 m ro-pax ferry of 12,000 t: the AIS A, B, C, D of the other examples. */
static ship_model ferry_model(void) {
    const double m = 12.0e6, length = 185.0;
    const double iz = m * (0.25 * length) * (0.25 * length);
    ship_model s = {150, 35, 14, 15, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    s.m11 = 1.05 * m;  /* 5 % added mass in surge */
    s.m22 = 1.8 * m;   /* 80 % in sway */
    s.m33 = 1.6 * iz;  /* 60 % in yaw */
    s.xu = 2.0e4;      /* about 125 kN of resistance at 4 kn */
    s.xuu = 2.0e4;
    s.yv = 1.1e6;      /* sway and yaw motions die out in some 20 s */
    s.yvv = 2.2e6;
    s.nr = 2.0e9;
    s.nrr = 4.0e10;
    return s;
}

/* The thrust that holds the ship at u0 (m/s) against the surge drag. */
static double thrust_for(const ship_model* s, double u0) { return s->xu * u0 + s->xuu * u0 * u0; }

/* World position of a ship-frame point (x forward, y starboard). */
static void to_world(const ship_state* st, double x, double y, double* east, double* north) {
    *east = st->east + x * sin(st->psi) + y * cos(st->psi);
    *north = st->north + x * cos(st->psi) - y * sin(st->psi);
}

/* Places the ship with its bow tip at (east, north): the generated hull of AIS dimensions has
 * its bow tip on the centreline, y = (d - c) / 2 (0.5 m to starboard of the reference point here). */
static ship_state bow_at(const ship_model* s, double east, double north, double heading_deg, double speed_kn) {
    ship_state st = {0, 0, heading_deg * DEG, speed_kn * KNOT, 0, 0};
    double e, n;
    to_world(&st, s->a, 0.5 * (s->d - s->c), &e, &n);
    st.east = east - e;
    st.north = north - n;
    return st;
}

/* ---- Contact response ---- */
typedef struct {
    double k;    /* N/m of depth, per region */
    double zeta; /* fraction of critical damping (for the ship's surge mass at one region) */
    double mu;   /* Coulomb friction along the boundary */
} contact_model;

static const contact_model contact = {8.5e8, 1.0, 0.15};

/* Adds the force and moment of one contact region to X, Y, N. */
static void contact_force(const ship_model* s, const ship_state* st, const shoal_contact_point* p, double* fx, double* fy,
                          double* mz) {
    const double vx = st->u - st->r * p->y_m; /* the hull point's velocity, ship frame */
    const double vy = st->v + st->r * p->x_m;
    const double into = -(vx * p->nx + vy * p->ny);
    const double c = 2.0 * contact.zeta * sqrt(contact.k * s->m11);
    double fn = contact.k * p->depth_m + c * into;
    if (fn < 0) fn = 0; /* a quay pushes, it does not pull */
    const double tx = -p->ny, ty = p->nx; /* along the boundary */
    const double vt = vx * tx + vy * ty;
    const double ft = -contact.mu * fn * vt / fmax(fabs(vt), 0.05);
    const double gx = fn * p->nx + ft * tx, gy = fn * p->ny + ft * ty;
    *fx += gx;
    *fy += gy;
    *mz += p->x_m * gy - p->y_m * gx;
}

/* One semi-implicit Euler step under the forces fx, fy, mz (contacts) plus the model's own. */
static void step(const ship_model* s, ship_state* st, double fx, double fy, double mz) {
    const double u = st->u, v = st->v, r = st->r;
    const double x = s->thrust - s->xu * u - s->xuu * fabs(u) * u + fx;
    const double y = -s->yv * v - s->yvv * fabs(v) * v + fy;
    const double n = s->rudder - s->nr * r - s->nrr * fabs(r) * r + mz;
    st->u += dt * (x + s->m22 * v * r) / s->m11;
    st->v += dt * (y - s->m11 * u * r) / s->m22;
    st->r += dt * (n - (s->m22 - s->m11) * u * v) / s->m33;
    st->east += dt * (st->u * sin(st->psi) + st->v * cos(st->psi));
    st->north += dt * (st->u * cos(st->psi) - st->v * sin(st->psi));
    st->psi += dt * st->r;
}

static double heading_deg(const ship_state* st) {
    double h = fmod(st->psi / DEG, 360.0);
    if (h < 0) h += 360.0;
    return h >= 360.0 ? h - 360.0 : h;
}

static const char* hazard_name(int h) {
    switch (h) {
    case SHOAL_HAZARD_LAND: return "LAND";
    case SHOAL_HAZARD_SHALLOW: return "SHALLOW";
    case SHOAL_HAZARD_DANGER: return "DANGER";
    case SHOAL_HAZARD_STRUCTURE: return "STRUCTURE";
    case SHOAL_HAZARD_SHIP: return "SHIP";
    default: return "?";
    }
}

static int failures = 0;
#define FAIL(...)                                       \
    do {                                                \
        fprintf(stderr, "berthing_sim: FAIL: " __VA_ARGS__); \
        fputc('\n', stderr);                            \
        ++failures;                                     \
    } while (0)

/* ---- One run: the ferry driven from a pose for a number of seconds ----
 * The face it is driven at bounds the half-plane east * wall_e + north * wall_n > wall_offset:
 * the ship's reference point must never get there, nor its bow tip beyond far_offset (the far
 * side of the pier: tunnelled through). */
typedef struct {
    int id;
    const char* title;
    double bow_east, bow_north, heading_deg;
    double wall_e, wall_n, wall_offset, far_offset;
    double seconds;
} run_spec;

static void print_contact(int run, long frame, int count, const shoal_contact_point* p, const ship_state* st) {
    const double hdg = heading_deg(st) >= 359.95 ? 0.0 : heading_deg(st); /* as printed to 0.1 degree */
    printf("contact %d %5ld %7.3f %d %7.4f %6.3f %6.3f %7.2f %6.2f %-5s %5.2f %6.1f \"%s\"\n", run, frame, (double)frame * dt,
           count, p->depth_m, p->nx, p->ny, p->x_m, p->y_m, hazard_name(p->hazard), st->u / KNOT, hdg, p->name);
}

static void simulate(const shoal_detector* det, const ship_model* model_in, const run_spec* run) {
    ship_model model = *model_in;
    model.thrust = thrust_for(&model, 4.0 * KNOT);
    ship_state st = bow_at(&model, run->bow_east, run->bow_north, run->heading_deg, 4.0);
    printf("\nrun %d: %s\n", run->id, run->title);
    printf("  start: reference point %.2f m E, %.2f m N of %.2f N %.2f E (%.7f, %.7f), heading %05.1f, 4.0 kn, "
           "thrust %.1f kN\n",
           st.east, st.north, lat0, lon0, lat_of(st.north), lon_of(st.east), heading_deg(&st), model.thrust / 1e3);
    printf("#       run frame  time_s n depth_m     nx     ny     x_m    y_m hazard u_kn   hdg   name\n");
    shoal_contact_point pts[MAX_REGIONS];
    const long frames = (long)(run->seconds * HZ);
    long first = -1, max_frame = -1, last_logged = -1000;
    double max_depth = 0, max_growth = 0, prev_depth = 0, depth = 0, final_fn = 0;
    int prev_count = 0, count = 0;
    char prev_names[256] = "";
    for (long frame = 0; frame <= frames; ++frame) {
        const double lat = lat_of(st.north), lon = lon_of(st.east);
        count = shoal_contacts(det, lat, lon, heading_deg(&st), pts, MAX_REGIONS);
        if (count < 0) {
            FAIL("run %d frame %ld: shoal_contacts: %s", run->id, frame, shoal_last_error());
            return;
        }
        const int n = count < MAX_REGIONS ? count : MAX_REGIONS;
        double fx = 0, fy = 0, mz = 0;
        depth = 0;
        char names[256] = "";
        for (int i = 0; i < n; ++i) {
            contact_force(&model, &st, &pts[i], &fx, &fy, &mz);
            if (pts[i].depth_m > depth) depth = pts[i].depth_m;
            if (strlen(names) + strlen(pts[i].name) + 2 < sizeof names) {
                strcat(names, pts[i].name);
                strcat(names, "|");
            }
        }
        final_fn = hypot(fx, fy);
        if (count > 0 && first < 0) first = frame;
        if (depth > max_depth) max_depth = depth, max_frame = frame;
        if (depth - prev_depth > max_growth) max_growth = depth - prev_depth;
        if (depth - prev_depth > 0.05)
            FAIL("run %d frame %ld: the contact deepened by %.3f m in one frame (more than 5 cm)", run->id, frame,
                 depth - prev_depth);
        if (depth > 1.0) FAIL("run %d frame %ld: %.3f m deep in the hazard (more than 1 m)", run->id, frame, depth);
        if (st.east * run->wall_e + st.north * run->wall_n > run->wall_offset)
            FAIL("run %d frame %ld: the reference point (%.2f E, %.2f N) went through the face", run->id, frame, st.east,
                 st.north);
        double tip_e, tip_n;
        to_world(&st, model.a, 0.5 * (model.d - model.c), &tip_e, &tip_n);
        if (tip_e * run->wall_e + tip_n * run->wall_n > run->far_offset)
            FAIL("run %d frame %ld: the bow tip (%.2f E, %.2f N) came out beyond the far side", run->id, frame, tip_e, tip_n);
        /* The log: every frame in contact with -v; else on a change of the regions (how many,
         * what they touch), while the contact deepens by more than 1 mm a frame, and every 5 s. */
        const int changed = count != prev_count || strcmp(names, prev_names) != 0;
        if (count > 0 && (verbose || changed || depth > prev_depth + 0.001 || frame - last_logged >= 5 * (long)HZ)) {
            for (int i = 0; i < n; ++i) print_contact(run->id, frame, count, &pts[i], &st);
            last_logged = frame;
        } else if (count == 0 && prev_count > 0) {
            printf("clear   %d %5ld %7.3f 0 (no contact) u %.2f kn, heading %05.1f\n", run->id, frame, (double)frame * dt,
                   st.u / KNOT, heading_deg(&st));
        }
        prev_depth = depth;
        prev_count = count;
        strcpy(prev_names, names);
        if (frame < frames) step(&model, &st, fx, fy, mz);
    }
    const double speed = hypot(st.u, st.v) / KNOT;
    const char* state = count > 0 ? (speed < 0.05 ? "resting_against" : "in_contact") : "clear";
    printf("summary %d first_contact_frame %ld first_contact_s %.3f max_depth_m %.4f max_depth_frame %ld "
           "max_growth_per_frame_m %.4f final %s final_depth_m %.6f final_speed_kn %.3f final_heading %.1f "
           "final_contact_force_kN %.1f\n",
           run->id, first, first >= 0 ? (double)first * dt : -1.0, max_depth, max_frame, max_growth, state, depth, speed,
           heading_deg(&st), final_fn / 1e3);
    if (first < 0) FAIL("run %d: the ferry never touched", run->id);
}

/* ---- Run 3: a tug pushing the ferry's side (shoal_ship_contacts), kinematic ---- */
static void tug_run(const shoal_detector* ferry, const shoal_detector* tug) {
    /* The ferry lies still heading 090 (bow east) 100 m south of the quay; its starboard side
     * (y = 15 m) faces south. The tug (AIS 20, 12, 5, 5), heading 000, comes up at 1 kn with its
     * bow tip 0.75 m off the ferry's side, 20 m forward of the ferry's reference point: they touch
     * at frame ceil(0.75 / (1 kn / 60)). The region is where the ferry's side lies inside the
     * tug's pointed bow, in the ferry's frame: its normal frees the ferry's point across the
     * nearer of the tug's two bow edges (to port, and fore or aft), not straight across. */
    const double fe = -350, fn = -100, speed = 1.0 * KNOT;
    const double tug_bow_n0 = fn - 15.0 - 0.75;
    printf("\nrun 3: a tug (AIS 20,12,5,5) pushing the ferry's starboard side at 1 kn, bow 0.75 m off "
           "(shoal_ship_contacts)\n");
    printf("#       run frame  time_s n clearance_m contact depth_m     nx     ny     x_m    y_m hazard\n");
    long first = -1;
    double prev_depth = 0;
    for (long frame = 0; frame <= 150; ++frame) {
        const double tug_n = tug_bow_n0 + (double)frame * dt * speed - 20.0; /* reference point 20 m aft of the bow */
        shoal_ship_contact sc;
        shoal_contact_point p[4];
        const int count = shoal_ship_contacts(ferry, lat_of(fn), lon_of(fe), 90.0, tug, lat_of(tug_n), lon_of(fe + 20.0),
                                              0.0, &sc, p, 4);
        if (count < 0) {
            FAIL("run 3 frame %ld: shoal_ship_contacts: %s", frame, shoal_last_error());
            return;
        }
        const double depth = count > 0 ? p[0].depth_m : 0.0;
        if (depth - prev_depth > 0.05) FAIL("run 3 frame %ld: deepened by %.3f m in one frame", frame, depth - prev_depth);
        prev_depth = depth;
        if (sc.contact && first < 0) first = frame;
        if (frame % 30 == 0 || frame == first || (first < 0 && frame % 10 == 0)) {
            if (count > 0)
                printf("ship    3 %5ld %7.3f %d %11.4f %7d %7.4f %6.3f %6.3f %7.2f %6.2f %s\n", frame, (double)frame * dt, count,
                       sc.clearance_m, sc.contact, p[0].depth_m, p[0].nx, p[0].ny, p[0].x_m, p[0].y_m, hazard_name(p[0].hazard));
            else
                printf("ship    3 %5ld %7.3f 0 %11.4f %7d\n", frame, (double)frame * dt, sc.clearance_m, sc.contact);
        }
    }
    printf("summary 3 first_contact_frame %ld first_contact_s %.3f final_depth_m %.4f\n", first,
           first >= 0 ? (double)first * dt : -1.0, prev_depth);
    if (first < 0) FAIL("run 3: the tug never touched the ferry");
}

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3 || (argc == 3 && strcmp(argv[2], "-v") != 0)) {
        fprintf(stderr, "usage: %s BERTH.shoalgrid [-v]\n  (shoal import examples/simulator/berth.geojson --ship-length 185 "
                        "-o BERTH.shoalgrid)\n",
                argv[0]);
        return 2;
    }
    verbose = argc == 3;
    frame_init();
    shoal_grid* grid = shoal_grid_load(argv[1]);
    if (!grid) {
        fprintf(stderr, "berthing_sim: %s\n", shoal_last_error());
        return 2;
    }
    const ship_model ferry = ferry_model();
    shoal_detector* det = shoal_detector_new(grid, ferry.a, ferry.b, ferry.c, ferry.d);
    shoal_detector* tug = shoal_detector_new(grid, 20, 12, 5, 5);
    shoal_grid_free(grid); /* the detectors keep it alive */
    if (!det || !tug) {
        fprintf(stderr, "berthing_sim: %s\n", shoal_last_error());
        return 2;
    }
    printf("berthing_sim (shoal %s): 60 Hz, 3 DOF ferry (AIS %g,%g,%g,%g), contact k %.3g N/m, zeta %.2f, mu %.2f\n",
           shoal_version(), ferry.a, ferry.b, ferry.c, ferry.d, contact.k, contact.zeta, contact.mu);
    /* Run 1: heading 000, bow tip 60 m south of West Quay's edge (the parallel 60.15 N, north 0),
     * 100 m west of the scene's reference point: first contact at frame ceil(60 / (4 kn / 60)). */
    const run_spec quay = {1, "bow first onto West Quay at 4 kn, heading 000, bow 60 m off", -100.0 + 0.5, -60.0, 0.0,
                           0.0, 1.0, 0.0, 300.0, 120.0};
    /* Run 2: heading 060, bow tip 35 m west of Pier 7's west face (east 200), 60 m south of the
     * quay: first contact at frame ceil(35 / (4 kn / 60 x sin 60)). */
    const run_spec pier = {2, "at 30 degrees off square onto Pier 7's west side at 4 kn, heading 060, bow 35 m off",
                           165.0, -60.0, 60.0, 1.0, 0.0, 200.0, 210.0, 60.0};
    simulate(det, &ferry, &quay);
    simulate(det, &ferry, &pier);
    tug_run(det, tug);
    shoal_detector_free(tug);
    shoal_detector_free(det);
    if (failures) {
        fprintf(stderr, "berthing_sim: %d failures\n", failures);
        return 1;
    }
    return 0;
}
