// The interval events shared by the sweep and the encounters: random runs of samples (clear,
// near, in contact, with breaks) against intervals read off the run directly, and the
// bisection against a known moment of change.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sweep/interval_events.hpp"

namespace shoal::audit::detail {
namespace {

struct Sample {
    double t = 0;
    bool contact = false;
    double clearance = INFINITY;
};

struct Interval {
    double start = 0, end = 0;
    double nearest_t = NAN;  ///< near intervals: time of the least clearance (the first such)
    bool operator==(const Interval& o) const {
        return start == o.start && end == o.end && (nearest_t == o.nearest_t || (std::isnan(nearest_t) && std::isnan(o.nearest_t)));
    }
};

/// Bisection is a half step towards the clear side: the refined boundary is known exactly.
struct Recorder {
    double margin = 10;
    std::vector<Interval> contacts, nears;
    std::vector<bool> opened_seen_clear;
    static double time(const Sample& s) { return s.t; }
    static bool contact(const Sample& s) { return s.contact; }
    bool near(const Sample& s) const { return s.contact || s.clearance < margin; }
    static double clearance(const Sample& s) { return s.clearance; }
    static Sample bisect(const Sample& clear, const Sample& hit, bool forward) {
        EXPECT_EQ(forward, clear.t < hit.t);
        EXPECT_FALSE(clear.contact);
        EXPECT_TRUE(hit.contact);
        return {(clear.t + hit.t) / 2, true, 0};
    }
    void contact_opened(const Sample&, const Sample&, bool seen_clear) { opened_seen_clear.push_back(seen_clear); }
    void contact_continues(const Sample&) {}
    void contact_closed(double start, double end) { contacts.push_back({start, end, NAN}); }
    void near_closed(double start, double end, const Sample& nearest) { nears.push_back({start, end, nearest.t}); }
};

TEST(IntervalEvents, RandomRunsGiveTheIntervalsReadOffDirectly) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (int run = 0; run < 500; ++run) {
        // Samples at t = 0, 1, 2, ...; a break before sample k when brk[k].
        const std::size_t n = 1 + rng() % 60;
        std::vector<Sample> s(n);
        std::vector<bool> brk(n + 1, false);
        for (std::size_t k = 0; k < n; ++k) {
            s[k].t = static_cast<double>(k);
            const double r = u(rng);
            s[k].contact = r < 0.3;
            s[k].clearance = s[k].contact ? 0 : r < 0.6 ? std::floor(20 * u(rng)) : 50;
            brk[k] = u(rng) < 0.05;
        }
        brk[n] = true;
        for (const bool end_at_first : {false, true}) {
            Recorder h;
            IntervalEvents<Sample> plain;
            IntervalEvents<Sample, true> sweep_rule;
            for (std::size_t k = 0; k < n; ++k) {
                if (brk[k]) end_at_first ? sweep_rule.end(h) : plain.end(h);
                end_at_first ? sweep_rule.add(s[k], h) : plain.add(s[k], h);
            }
            end_at_first ? sweep_rule.end(h) : plain.end(h);

            // Directly: maximal runs within a piece (between breaks).
            std::vector<Interval> contacts, nears;
            std::vector<bool> seen_clear;
            for (std::size_t k = 0; k < n; ++k) {
                if (!s[k].contact || (k > 0 && !brk[k] && s[k - 1].contact)) continue;
                std::size_t e = k;
                while (e + 1 < n && !brk[e + 1] && s[e + 1].contact) ++e;
                const bool clear_before = k > 0 && !brk[k];
                const bool clear_after = e + 1 < n && !brk[e + 1];
                const double start = clear_before ? s[k].t - 0.5 : s[k].t;
                double end = clear_after ? s[e].t + 0.5 : s[e].t;
                if (!clear_after && e == k && end_at_first) end = start;
                contacts.push_back({start, end, NAN});
                seen_clear.push_back(clear_before);
            }
            for (std::size_t k = 0; k < n; ++k) {
                auto near_at = [&](std::size_t i) { return s[i].contact || s[i].clearance < h.margin; };
                if (!near_at(k) || (k > 0 && !brk[k] && near_at(k - 1))) continue;
                std::size_t e = k;
                while (e + 1 < n && !brk[e + 1] && near_at(e + 1)) ++e;
                bool any_contact = false;
                std::size_t best = k;
                for (std::size_t i = k; i <= e; ++i) {
                    any_contact |= s[i].contact;
                    if (s[i].clearance < s[best].clearance) best = i;
                }
                if (!any_contact) nears.push_back({s[k].t, s[e].t, s[best].t});
            }
            auto by_start = [](const Interval& a, const Interval& b) { return a.start < b.start; };
            std::sort(h.contacts.begin(), h.contacts.end(), by_start);
            std::sort(h.nears.begin(), h.nears.end(), by_start);
            ASSERT_EQ(h.contacts.size(), contacts.size()) << "run " << run;
            for (std::size_t k = 0; k < contacts.size(); ++k) EXPECT_TRUE(h.contacts[k] == contacts[k]) << "run " << run << " contact " << k;
            EXPECT_EQ(h.opened_seen_clear, seen_clear) << "run " << run;
            ASSERT_EQ(h.nears.size(), nears.size()) << "run " << run;
            for (std::size_t k = 0; k < nears.size(); ++k) EXPECT_TRUE(h.nears[k] == nears[k]) << "run " << run << " near " << k;
        }
    }
}

TEST(IntervalEvents, BisectionFindsTheMomentOfChangeEitherWayInTime) {
    const double change = 3.14159;
    // Contact from `change` on (forward: clear before), and contact until it (backward).
    const double forward = bisect_change(0.0, 10.0, 1.0, 1e-6, 60, [&](double t) { return t >= change; });
    EXPECT_GE(forward, change);
    EXPECT_LT(forward - change, 1e-6);
    const double backward = bisect_change(10.0, 0.0, 1.0, 1e-6, 60, [&](double t) { return t <= change; });
    EXPECT_LE(backward, change);
    EXPECT_LT(change - backward, 1e-6);
    // Over a fraction of a 100 s interval, to 0.01 s.
    const double f = bisect_change(0.0, 1.0, 100.0, 0.01, 50, [&](double x) { return 100 * x >= change; });
    EXPECT_LT(100 * f - change, 0.01);
    EXPECT_GE(100 * f, change);
}

}  // namespace
}  // namespace shoal::audit::detail
