# Checks berthing_sim's log against answers derived by hand (run by scripts/test-install.sh):
#   berthing_sim berth.shoalgrid | awk -f check_berthing.awk
# A frame at 4 kn and 60 Hz moves the ship 4 x 1852 / 3600 / 60 = 0.0342963 m; the ship holds
# 4 kn exactly until it touches (the thrust balances the drag), so:
#   run 1 (heading 000, bow tip 60 m south of West Quay's edge): first contact at frame
#     ceil(60 / 0.0342963) = ceil(1749.46) = 1750, depth 1750 x 0.0342963 - 60 = 0.0185 m, at the
#     bow tip (x 150, y 0.5: the generated hull's tip is on its centreline, (D - C) / 2), normal
#     straight astern (-1, 0), LAND, "West Quay". At rest against the quay the spring holds the
#     thrust: depth T / k = (2e4 x 2.0578 + 2e4 x 2.0578^2) / 8.5e8 = 125,846 N / 8.5e8 = 0.000148 m.
#   run 2 (heading 060, bow tip 35 m west of Pier 7's west face): the tip closes on the face at
#     0.0342963 x sin 60 = 0.0297015 m a frame: first contact at ceil(35 / 0.0297015) =
#     ceil(1178.40) = 1179, depth (1179 - 1178.40) x 0.0297015 = 0.018 m; the face's normal (west)
#     in the ship frame is (cos 210, sin 210) = (-0.866, -0.500); LAND, "Pier 7".
#   both: no frame deepens the contact by more than the ship moves (0.0343 m), and no contact is
#     deeper than an undamped spring would take the ship: 2.0578 x sqrt(m11 / k) =
#     2.0578 x sqrt(1.26e7 / 8.5e8) = 0.25 m.
#   run 3 (tug bow tip 0.75 m off the ferry's side, closing at 1 kn = 0.0085741 m a frame):
#     clearance 0.75 at frame 0 and 0.75 - 60 x 0.0085741 = 0.2356 m at frame 60, first contact at
#     ceil(0.75 / 0.0085741) = ceil(87.47) = 88, at the ferry's side (x 20, y 15), SHIP, pushing
#     the ferry to port (ny < 0).
function near(v, want, tol) { return v + 0 >= want - tol && v + 0 <= want + tol }
function check(ok, what) { if (!ok) { print "check_berthing: FAIL: " what; ++bad } else ++good }
# contact RUN FRAME TIME REGIONS DEPTH NX NY X Y HAZARD U_KN HEADING "NAME"
function name_of(line) { return substr(line, index(line, "\"")) }
$1 == "contact" && !($2 in first) {
    first[$2] = $3
    if ($2 == 1) {
        check($3 == 1750, "run 1: first contact at frame " $3 ", not 1750")
        check($5 == 1 && near($6, 0.0185, 0.003), "run 1: one region 0.0185 m deep at first contact, not " $5 " regions " $6 " m")
        check(near($7, -1, 0.01) && near($8, 0, 0.01), "run 1: normal (" $7 ", " $8 "), not (-1, 0)")
        check(near($9, 150, 0.01) && near($10, 0.5, 0.01), "run 1: contact at x " $9 " y " $10 ", not the bow tip (150, 0.5)")
        check($11 == "LAND" && name_of($0) == "\"West Quay\"", "run 1: hit " $11 " " name_of($0) ", not LAND \"West Quay\"")
    }
    if ($2 == 2) {
        check($3 == 1179, "run 2: first contact at frame " $3 ", not 1179")
        check($5 == 1 && near($6, 0.018, 0.003), "run 2: one region 0.018 m deep at first contact, not " $5 " regions " $6 " m")
        check(near($7, -0.866, 0.01) && near($8, -0.5, 0.01), "run 2: normal (" $7 ", " $8 "), not (-0.866, -0.500)")
        check(near($9, 150, 0.01) && near($10, 0.5, 0.01), "run 2: contact at x " $9 " y " $10 ", not the bow tip (150, 0.5)")
        check($11 == "LAND" && name_of($0) == "\"Pier 7\"", "run 2: hit " $11 " " name_of($0) ", not LAND \"Pier 7\"")
    }
}
# ship RUN FRAME TIME REGIONS CLEARANCE CONTACT DEPTH NX NY X Y HAZARD
$1 == "ship" && $3 == 0 { check(near($6, 0.75, 0.001), "run 3: clearance " $6 " at frame 0, not 0.75") }
$1 == "ship" && $3 == 60 { check(near($6, 0.2356, 0.001), "run 3: clearance " $6 " at frame 60, not 0.2356") }
$1 == "ship" && $7 == 1 && !tug_seen++ {
    check($3 == 88, "run 3: first contact at frame " $3 ", not 88")
    check($13 == "SHIP" && $10 < -0.5 && near($11, 20, 0.01) && near($12, 15, 0.01),
          "run 3: contact " $13 " normal (" $9 ", " $10 ") at (" $11 ", " $12 "), not SHIP to port at (20, 15)")
}
$1 == "summary" {
    for (i = 3; i < NF; i += 2) s[$2, $i] = $(i + 1)
    ++summaries
}
END {
    check(summaries == 3, "found " summaries + 0 " summaries, not 3")
    for (r = 1; r <= 2; ++r) {
        check(s[r, "max_growth_per_frame_m"] + 0 <= 0.0343, "run " r ": a frame deepened the contact by " s[r, "max_growth_per_frame_m"] " m")
        check(s[r, "max_depth_m"] + 0 < 0.25, "run " r ": " s[r, "max_depth_m"] " m deep, more than the undamped 0.25 m")
    }
    check(s[1, "final"] == "resting_against" && near(s[1, "final_depth_m"], 0.000148, 0.000003) &&
          near(s[1, "final_contact_force_kN"], 125.8, 0.2),
          "run 1: ends " s[1, "final"] " " s[1, "final_depth_m"] " m deep with " s[1, "final_contact_force_kN"] " kN, not resting_against 0.000148 m with 125.8 kN")
    check(s[3, "first_contact_frame"] == 88, "run 3: summary first contact " s[3, "first_contact_frame"])
    printf "check_berthing: %d checks, %d failed (first contacts at frames %s, %s, %s; max depths %s, %s m)\n", good + bad, bad,
           s[1, "first_contact_frame"], s[2, "first_contact_frame"], s[3, "first_contact_frame"], s[1, "max_depth_m"], s[2, "max_depth_m"]
    exit bad > 0
}
