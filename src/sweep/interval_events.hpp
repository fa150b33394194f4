#pragma once
/// Interval events over a run of samples (private to src/sweep and src/exercise): what is the same for a
/// ship's hull swept past the coast (sweep.cpp: groundings and close passes) and for a pair
/// of ships (encounters.cpp: collisions and close quarters).
///
/// Samples come in time order. A *contact* interval opens at the first sample in contact, its
/// start refined by bisection when the sample before was seen clear; it stays open while
/// contact continues and closes at the first clear sample, its end refined by bisection back
/// from there towards the last contact. A *near* interval is a run of samples under the
/// margin (contact included); it is told (a close pass, close quarters) only if it never
/// reaches contact, with its nearest sample. A break (a gap, a jump, a pair no longer
/// checked) ends both as they stand, and the next sample has no sample before it.

#include <cmath>

namespace shoal::audit::detail {

/// Bisection of the moment between a clear sample and one in contact, over a parameter of the
/// samples (a time, or a fraction of a fix interval): halves [clear, hit] while `scale` times
/// its width exceeds `tolerance` (at most `max_iterations` times), `touching(mid)` telling
/// which side the middle is on. Returns the parameter on the contact side. Works either way
/// in time.
template <class Touching>
double bisect_change(double clear, double hit, double scale, double tolerance, int max_iterations, Touching&& touching) {
    for (int it = 0; it < max_iterations && scale * std::fabs(hit - clear) > tolerance; ++it) {
        const double mid = (clear + hit) / 2;
        if (touching(mid))
            hit = mid;
        else
            clear = mid;
    }
    return hit;
}

/// The open contact and near intervals of one subject (a track piece, a pair of ships).
/// A contact interval broken off at its opening sample ends there, or with
/// `EndAtFirstContact` (the sweep's rule) at its refined first contact.
/// `add` and `end` take a handler `h` that knows the samples and is told of the intervals:
///
///     double time(const Sample&);  bool contact(const Sample&);
///     bool near(const Sample&);    // under the margin, or in contact
///     double clearance(const Sample&);  // asked of near samples not in contact
///     Sample bisect(const Sample& clear, const Sample& hit, bool forward);  // the sample on the
///                                  // contact side of the change; forward: clear is earlier
///     void contact_opened(const Sample& first, const Sample& s, bool seen_clear);  // first: refined
///     void contact_continues(const Sample& s);
///     void contact_closed(double start_s, double end_s);
///     void near_closed(double start_s, double end_s, const Sample& nearest);  // never in contact
template <class Sample, bool EndAtFirstContact = false>
class IntervalEvents {
public:
    template <class Handler>
    void add(const Sample& s, Handler& h) {
        const bool contact = h.contact(s);
        if (contact && !m_in_contact) {
            const bool seen_clear = m_have_prev && !h.contact(m_prev);
            const Sample first = seen_clear ? h.bisect(m_prev, s, true) : s;
            m_in_contact = true;
            m_contact_start = h.time(first);
            m_contact_end = EndAtFirstContact ? m_contact_start : h.time(s);
            h.contact_opened(first, s, seen_clear);
        } else if (contact) {
            m_contact_end = h.time(s);
            h.contact_continues(s);
        } else if (m_in_contact) {
            m_contact_end = h.time(m_have_prev ? h.bisect(s, m_prev, false) : s);
            m_in_contact = false;
            h.contact_closed(m_contact_start, m_contact_end);
        }
        if (h.near(s)) {
            if (!m_in_near) {
                m_in_near = true;
                m_near_contact = false;
                m_near_min = INFINITY;
                m_near_start = h.time(s);
            }
            m_near_end = h.time(s);
            if (contact) {
                m_near_contact = true;
            } else if (const double c = h.clearance(s); c < m_near_min) {
                m_near_min = c;
                m_nearest = s;
            }
        } else if (m_in_near) {
            close_near(h);
        }
        m_prev = s;
        m_have_prev = true;
    }

    /// A break: the open intervals end at their last samples.
    template <class Handler>
    void end(Handler& h) {
        if (m_in_contact) {
            m_in_contact = false;
            h.contact_closed(m_contact_start, m_contact_end);
        }
        if (m_in_near) close_near(h);
        m_have_prev = false;
    }

    bool open() const noexcept { return m_in_contact || m_in_near; }
    /// The least clearance of the open near interval's samples not in contact so far; INFINITY
    /// when there is none, or no near interval is open (the next near sample opens one, and is
    /// its nearest).
    double near_min() const noexcept { return m_in_near ? m_near_min : INFINITY; }
    bool in_contact() const noexcept { return m_in_contact; }

private:
    template <class Handler>
    void close_near(Handler& h) {
        m_in_near = false;
        if (!m_near_contact) h.near_closed(m_near_start, m_near_end, m_nearest);  // else the contact tells it
    }

    Sample m_prev{}, m_nearest{};
    bool m_have_prev = false;
    bool m_in_contact = false, m_in_near = false, m_near_contact = false;
    double m_contact_start = 0, m_contact_end = 0;
    double m_near_start = 0, m_near_end = 0, m_near_min = INFINITY;
};

}  // namespace shoal::audit::detail
