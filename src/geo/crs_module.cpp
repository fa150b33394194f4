// libshoal_crs.so: a user's CRS by PROJ, as a module that libshoal_c.so.1 loads only when a grid
// in such a frame is loaded (geo/crs_loader.cpp): a simulator whose grids are in shoal's own
// frame never loads PROJ and its tree of shared libraries. One exported C function; nothing
// thrown across the boundary (each side has its own copy of shoal's error types).
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>

#include "geo/crs_projection.hpp"

namespace {

using shoal::geo::detail::CrsProjection;

/// The projection with every call guarded: a failure is a point PROJ does not give (HUGE_VAL),
/// which LocalFrame reports as a point it cannot project.
class Guarded final : public CrsProjection {
public:
    explicit Guarded(std::unique_ptr<CrsProjection> inner) : m_inner(std::move(inner)) {}
    const std::string& name() const override { return m_inner->name(); }
    void forward(double* xs, double* ys, std::size_t n) const override {
        try {
            m_inner->forward(xs, ys, n);
        } catch (...) {
            for (std::size_t i = 0; i < n; ++i) xs[i] = ys[i] = HUGE_VAL;
        }
    }
    void inverse(double& x, double& y) const override {
        try {
            m_inner->inverse(x, y);
        } catch (...) {
            x = y = HUGE_VAL;
        }
    }

private:
    std::unique_ptr<CrsProjection> m_inner;
};

}  // namespace

/// The projection for `definition` (owned by the caller, deleted through its virtual
/// destructor), or null with the reason in `error` (at most `error_size` bytes with its NUL).
extern "C" __attribute__((visibility("default"))) CrsProjection* shoal_crs_projection_make(const char* definition, char* error,
                                                                                              std::size_t error_size) {
    try {
        return new Guarded(shoal::geo::detail::make_crs_projection(definition));
    } catch (const std::exception& e) {
        std::snprintf(error, error_size, "%s", e.what());
    } catch (...) {
        std::snprintf(error, error_size, "PROJ failed on CRS '%s'", definition);
    }
    return nullptr;
}
