#pragma once
/// The exercise clock (internal to src/exercise): every ship of an exercise on one time line,
/// stepped from instant to instant. Instants are every fix time of every ship and, between
/// two fix times, as many evenly spaced instants as needed so that no hull point moves more
/// than `step_m` relative to any other ship from one instant to the next (the sum of the two
/// fastest present ships' speed bounds). A ship is present from its first fix to its last,
/// except across a gap (a fix interval whose speed bound is < 0).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "sweep/local_track.hpp"

namespace shoal::audit::detail {

class ExerciseClock {
public:
    /// One ship's track (fix times strictly increasing) and per fix interval a bound on any of
    /// its hull points' speed (m/s), < 0 across a gap. Both must outlive the clock.
    struct Ship {
        const LocalTrack* track = nullptr;
        const std::vector<double>* speed = nullptr;
    };

    ExerciseClock(std::vector<Ship> ships, double step_m);

    /// Steps through every instant in time order, calling at_instant(t) at each, where the
    /// accessors below describe that instant.
    void run(const std::function<void(double t)>& at_instant);

    std::uint64_t instant() const noexcept { return m_instant; }  ///< 0-based index of the current instant
    const std::vector<std::uint32_t>& present() const noexcept { return m_present; }  ///< present ships, in no order
    bool joined() const noexcept { return m_joined; }  ///< some ship became present at this instant
    Where where(std::uint32_t k) const { return {m_state[k].cur, m_state[k].f}; }  ///< last fix at or before now, the fraction of its interval
    std::uint64_t entered(std::uint32_t k) const { return m_state[k].entered; }  ///< instant it last became present

private:
    struct State {
        std::size_t next_fix = 0, cur = 0;
        bool present = false, moving = false;
        std::uint64_t entered = 0;
        double f = 0;
        std::size_t slot = 0;  ///< index in m_present
    };
    void step(double t, const std::function<void(double)>& at_instant);

    std::vector<Ship> m_ships;
    std::vector<State> m_state;
    double m_step_m;
    std::uint64_t m_instant = 0;
    std::vector<std::uint32_t> m_present;
    bool m_joined = false;
};

}  // namespace shoal::audit::detail
