#include <shoal/probe/probe.hpp>

#include <algorithm>

#include <shoal/track/row_rules.hpp>
#include <shoal/util/error.hpp>

#include "util/parallel.hpp"
#include "util/parse_util.hpp"

namespace shoal::probe {

namespace {

/// What every face asks of the detector beyond the Ask: not where a contact is, nor the
/// polyline of a hull wholly inside land (a collision is answered by the first point on land).
check::CheckOptions options_of(const Ask& ask) {
    return {.max_clearance_m = ask.max_clearance_m, .want_penetration = ask.want_penetration, .want_polyline = false, .want_contact_point = false};
}

std::optional<double> default_limit(const grid::CoastGrid& grid) {
    const double d = grid.source().limiting_depth_m;
    return std::isnan(d) ? std::nullopt : std::optional<double>(d);
}

}  // namespace

std::optional<std::string> pose_problem(double lat, double lon, double heading_deg) {
    std::string what;
    if (track::position_problem(lat, lon, what)) return what;
    if (!std::isfinite(heading_deg)) return "heading " + track::detail::fmt(heading_deg) + " is not a number";
    return std::nullopt;
}

Probe::Probe(const grid::CoastGrid& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m)
    : m_grid(grid), m_detector(grid, hull, limiting_depth_m), m_field(grid.frame(), grid.extent()) {}

Probe::Probe(const grid::CoastGrid& grid, const hull::Hull& hull) : Probe(grid, hull, default_limit(grid)) {}

check::LocalPose Probe::place(const check::Pose& pose) const { return check::place(m_grid.frame(), m_field, pose); }

Answer Probe::answer(const check::LocalPose& pose, const Ask& ask) const {
    const check::Contact c = m_detector.check(pose, options_of(ask));
    Answer a;
    a.valid = true;
    a.covered = c.covered;
    a.collision = c.collision;
    // Outside the chart nothing is claimed: a contact found is real, chart or not; no contact
    // found there says nothing, and no clearance is claimed.
    a.clearance_m = c.collision ? 0.0 : c.covered ? c.clearance_m : NAN;
    a.penetration_m = c.collision && ask.want_penetration ? c.penetration_m : NAN;
    return a;
}

Answer Probe::check(const check::Pose& pose, const Ask& ask) const {
    if (const auto problem = pose_problem(pose.position.lat, pose.position.lon, pose.heading_deg)) throw InputError(*problem);
    return answer(place(pose), ask);
}

Batch Probe::check_blocks(std::size_t n, const std::function<check::Pose(std::size_t)>& pose_of, const Ask& ask, unsigned jobs,
                          const std::function<void(std::size_t from, std::span<const Answer> answers, unsigned worker)>& use) const {
    constexpr std::size_t block = check::placement_block;
    const std::size_t blocks = (n + block - 1) / block;
    // Per block: its counts, its first pose refused and why.
    struct Tally {
        std::size_t invalid = 0, uncovered = 0, first = 0;
        std::string problem;
    };
    std::vector<Tally> tallies(blocks);
    // A block whose `use` throws stops the blocks after it (the first failure in input order
    // is thrown).
    detail::parallel_blocks(blocks, detail::thread_count(jobs), [&](std::size_t b, unsigned worker) {
        const std::size_t from = b * block, to = std::min(n, from + block);
        Tally& t = tallies[b];
        std::vector<Answer> answers(to - from);
        auto refuse = [&](std::size_t k, std::string why) {
            answers[k - from] = Answer{};
            if (t.invalid++ == 0) {
                t.first = k;
                t.problem = std::move(why);
            }
        };
        // The valid poses of the block, placed together (one projection); when PROJ cannot
        // take one, placed one by one, so that only that pose is refused.
        std::vector<check::Pose> todo;
        std::vector<std::size_t> index;
        todo.reserve(to - from);
        index.reserve(to - from);
        for (std::size_t k = from; k < to; ++k) {
            const check::Pose p = pose_of(k);
            if (auto problem = pose_problem(p.position.lat, p.position.lon, p.heading_deg)) {
                refuse(k, std::move(*problem));
                continue;
            }
            todo.push_back(p);
            index.push_back(k);
        }
        std::vector<check::LocalPose> placed;
        try {
            placed = check::place(m_grid.frame(), m_field, todo);
        } catch (const InputError&) {
            placed.clear();
        }
        for (std::size_t v = 0; v < todo.size(); ++v) {
            const std::size_t k = index[v];
            try {
                answers[k - from] = answer(placed.empty() ? place(todo[v]) : placed[v], ask);
                t.uncovered += answers[k - from].covered ? 0 : 1;
            } catch (const InputError& e) {
                refuse(k, e.what());
            }
        }
        use(from, answers, worker);
    });
    Batch out;
    out.first_invalid = n;
    for (Tally& t : tallies) {
        if (t.invalid && out.invalid == 0) {
            out.first_invalid = t.first;
            out.first_problem = std::move(t.problem);
        }
        out.invalid += t.invalid;
        out.uncovered += t.uncovered;
    }
    return out;
}

Batch Probe::check(std::span<const check::Pose> poses, const Ask& ask, unsigned jobs) const {
    std::vector<Answer> answers(poses.size());
    Batch out = check_blocks(
        poses.size(), [&](std::size_t k) { return poses[k]; }, ask, jobs,
        [&](std::size_t from, std::span<const Answer> got, unsigned) { std::copy(got.begin(), got.end(), answers.begin() + static_cast<std::ptrdiff_t>(from)); });
    out.answers = std::move(answers);
    return out;
}

}  // namespace shoal::probe
