#include "curvetet/volume/tetrahedralize.hpp"

#include "curvetet/core/error.hpp"
#include "curvetet/core/log.hpp"
#include "curvetet/shell/extrusion.hpp"
#include "curvetet/volume/direct_fill.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <optional>
#include <thread>

namespace curvetet::volume {
namespace {

LayeredSurface extrude(const mesh::SurfaceMesh& surface, OffsetSide side, double thickness, int* singular,
                       std::function<bool()> stop_requested = {}) {
  shell::ExtrusionOptions eo;
  eo.target_thickness = thickness;
  // Start near the target (most pillars reach it at once) and allow two
  // thickening rounds: each round is an exact check pass (5 rounds cost up
  // to a third of the run on armadillo: 5.6 s vs 2.9 s), but a single round
  // leaves pillars so thin on thin parts that the fill's worst tets explode
  // (abc_00000001: max AMIPS 1.7e8 with one round, 6.4e4 with two).
  eo.initial_thickness = thickness / 4;
  eo.max_rounds = 2;
  eo.stop_requested = std::move(stop_requested);
  auto ex = shell::extrude_one_sided(surface, side == OffsetSide::inward ? shell::Side::inward : shell::Side::outward,
                                     eo);
  LayeredSurface l;
  l.surface = surface;
  l.side = side;
  l.offset = std::move(ex.offset);
  *singular = 0;
  for (char s : ex.singular) *singular += s != 0;
  return l;
}

// The layered fill's extrusion, run on a thread of its own while the direct
// fill tries, when that one finds the surface scan-like (cheese_genus133:
// 0.7 s less). Serial and at low priority, so that it takes one core and
// leaves the other to the direct fill; stopped at its next batch of exact
// tests (within a check pass: thingi10k waited up to 5 ms for whole passes) when
// the direct fill succeeds. (Started on every surface, it took 90 to 170 %
// more memory and up to 8 % more time on large models that never need it.)
class ConcurrentExtrusion {
 public:
  ConcurrentExtrusion(const mesh::SurfaceMesh& surface, OffsetSide side, double thickness)
      : thread_([this, &surface, side, thickness] {
          const auto t0 = std::chrono::steady_clock::now();
          setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);
          try {
            tbb::task_arena serial(1);
            serial.execute([&] { layer_ = extrude(surface, side, thickness, &singular_, [this] { return stop_.load(); }); });
          } catch (const shell::Stopped&) {
          } catch (...) {
            error_ = std::current_exception();
          }
          seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }) {}
  ConcurrentExtrusion(const ConcurrentExtrusion&) = delete;
  ConcurrentExtrusion& operator=(const ConcurrentExtrusion&) = delete;
  ~ConcurrentExtrusion() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

  // Waits for the layer (rethrowing the extrusion's error).
  LayeredSurface get(int* singular, double* seconds) {
    thread_.join();
    if (error_) std::rethrow_exception(error_);
    *singular = singular_;
    *seconds += seconds_;
    return std::move(*layer_);
  }

  // Whether a second core is allowed (--threads) and the surface is large
  // enough for the overlap to matter: under kMinFaces, an extrusion takes
  // tens of milliseconds, and abandoning it cost the direct fill more than
  // that would save (thingi10k, 552 faces: 2 ms of its 53).
  static bool worthwhile(const mesh::SurfaceMesh& surface) {
    constexpr int kMinFaces = 2000;
    return surface.num_faces() >= kMinFaces &&
           tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) >= 2;
  }

 private:
  std::atomic<bool> stop_{false};
  std::optional<LayeredSurface> layer_;
  int singular_ = 0;
  double seconds_ = 0;
  std::exception_ptr error_;
  std::thread thread_; // last: starts once the members above exist
};

void require_ok(const TetMeshCheck& c, const char* part) {
  if (!c.ok()) throw Error(ExitCode::internal, fmt::format("volume: {} mesh fails verification: {}", part, c.text()));
}

} // namespace

TetrahedralizeResult tetrahedralize(const mesh::SurfaceMesh& surface, const TetrahedralizeOptions& options) {
  TetrahedralizeResult r;
  const int n = surface.num_vertices();
  std::vector<mesh::Tri> reversed;
  reversed.reserve(surface.faces.size());
  for (const auto& f : surface.faces) reversed.push_back({f[0], f[2], f[1]});
  auto check = [&](OffsetSide side, const mesh::LinearTetMesh& m) {
    if (side == OffsetSide::inward) return verify_tet_mesh(m, surface.faces);
    Box box{m.vertices[0], m.vertices[0]};
    for (const auto& p : m.vertices) {
      box.lo = box.lo.cwiseMin(p);
      box.hi = box.hi.cwiseMax(p);
    }
    return verify_tet_mesh(m, reversed, box);
  };
  // The fast path first (its result is used only if it verifies, like every
  // result); the layer and the BSP where it does not apply.
  auto fill = [&](OffsetSide side, FillStats* stats, int* singular, TetMeshCheck* verified) {
    const char* part = side == OffsetSide::inward ? "interior" : "exterior";
    std::optional<ConcurrentExtrusion> early;
    auto start_early = [&] {
      if (ConcurrentExtrusion::worthwhile(surface)) early.emplace(surface, side, options.layer_thickness);
    };
    if (options.direct)
      if (auto m = fill_direct(surface, side, options.fill, stats, start_early)) {
        *verified = check(side, *m);
        if (verified->ok()) {
          logger().info("volume: {} filled from the Delaunay tetrahedralization ({} offset points, {} cones)", part,
                        stats->offset_points, stats->cones);
          return std::move(*m);
        }
        logger().warn("volume: the Delaunay fill of the {} fails verification ({}); taking the layered fill", part,
                      verified->text());
      }
    const auto t0 = std::chrono::steady_clock::now();
    const auto layered = early ? early->get(singular, &r.seconds_extrusion)
                               : extrude(surface, side, options.layer_thickness, singular);
    if (!early) r.seconds_extrusion += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *stats = FillStats{};
    auto m = fill_layered(layered, options.fill, stats);
    *verified = check(side, m);
    require_ok(*verified, part);
    return m;
  };
  r.mesh = fill(OffsetSide::inward, &r.interior, &r.singular_inward, &r.interior_check);
  if (!options.exterior) return r;

  auto ext = fill(OffsetSide::outward, &r.exterior, &r.singular_outward, &r.exterior_check);
  // Merge: both parts share the surface vertices [0, n).
  const int base = r.mesh.num_vertices() - n;
  for (int v = n; v < ext.num_vertices(); ++v) r.mesh.vertices.push_back(ext.vertices[v]);
  for (std::size_t t = 0; t < ext.tets.size(); ++t) {
    auto q = ext.tets[t];
    for (int& x : q)
      if (x >= n) x += base;
    r.mesh.tets.push_back(q);
    r.mesh.tags.push_back(ext.tags[t]);
  }
  return r;
}

} // namespace curvetet::volume
