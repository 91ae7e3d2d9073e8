#pragma once
// The invariant list run on every candidate (STYLE.md 2; DESIGN.md §2 items
// 1-4 restricted to the new prisms). Each invariant is a small named unit;
// an operation never checks anything itself beyond its topology.
//
// In list order (cheap first; later ones use what earlier ones derived):
//  SingularIsolation  no new edge joins two singular vertices
//  MiddleQuality      (ranking rule) each new middle triangle's MIPS <= the
//                     bound, or <= that of an old triangle it shares an edge with
//  SlabQuality        (ranking rule) max AMIPS of the 12 tets of the new
//                     lower slabs (middle over bottom: the output's slab
//                     tets come from them) <= max(old max, bound)
//  Thickness          (ranking rule) max over the new middle triangles of
//                     longest edge / solid thickness at the thinnest corner
//                     (local_thickness.hpp) <= max(old max, bound)
//  PrismPositivity    invariant 1 on the new prisms (fills c.geoms)
//  Straightening      feature chains straightened onto the new coarse edges
//                     keep M̄ a section around the star (straighten.hpp;
//                     fills c.straightened, c.reshaped)
//  Coverage           every input face (of M̄) tracked by a removed prism, or
//                     reshaped, meets some new prism (fills c.tracked: the
//                     faces meeting it) and crosses no new cap (contact only
//                     at a pinched vertex).
//                     Since the star's outer quads are unchanged, this is
//                     "the tracked faces lie in the union of the new prisms"
//  Section            invariant 2 for each new prism and its tracked faces
//  CapsIntersection   invariant 3: new caps against each other and against
//                     every live cap outside the star (grid candidates)
//  MapImages          every input vertex mapped into a removed prism gets
//                     its new Π (of its M̄ position) in a new prism tracking
//                     its face (else: coverage; fills c.images); straightened
//                     chain vertices land exactly on their edge
//  CurvedFit          MiddleFit::fit_and_check (no-op for a linear middle;
//                     the curved fit uses c.images as samples)
//  CurvedMiddleQuality (ranking rule) max MIPS over each fitted patch's
//                     order-2k lattice <= max(old, curved_quality_bound)
//  Distance           ||p - middle(Π(β(p)))|| < epsilon for those points, the
//                     middle evaluated through MiddleFit::evaluate
//  SurfaceDistance    the other direction: a derived bound on the distance
//                     from every point of each new middle patch to the input
//                     faces its prism tracks is <= epsilon
//                     (surface_distance.hpp)
//  Features           feature chains and corners (feature_invariant.hpp)
#include "curvetet/shell/middle_fit.hpp"
#include "curvetet/shell/shell_editor.hpp"
#include "curvetet/shell/star.hpp"

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace curvetet::shell {

struct StarContext {
  const ShellEditor& editor;
  const MiddleFit& fit;
  double epsilon;        // absolute distance bound
  double quality_bound;  // MIPS bound of the ranking rule
  double slab_quality_bound = std::numeric_limits<double>::infinity(); // AMIPS bound of the slab rule
  double curved_quality_bound = std::numeric_limits<double>::infinity(); // MIPS bound of fitted patches
  const std::vector<double>* thickness = nullptr; // per shell vertex (local_thickness.hpp); null: no rule
  double thickness_ratio = std::numeric_limits<double>::infinity(); // edge / thickness bound of that rule
};

class StarInvariant {
 public:
  virtual ~StarInvariant() = default;
  virtual Rejection reason() const = 0;
  // false = the candidate violates it; `why` (preset to reason()) may name
  // a more precise reason. May fill derived fields of c.
  virtual bool holds(const StarContext& ctx, StarCandidate& c, Rejection& why) const = 0;
};

using InvariantList = std::vector<std::unique_ptr<StarInvariant>>;
InvariantList default_star_invariants();

// CPU seconds spent in each invariant, indexed by its reason (profiling).
using InvariantSeconds = std::array<double, kRejectionCount>;

// Runs the list in order; the first failure's reason, or nullopt (accepted).
// With `seconds`, adds the time each invariant took to its reason's entry.
std::optional<Rejection> check_candidate(const InvariantList& list, const StarContext& ctx, StarCandidate& c,
                                         InvariantSeconds* seconds = nullptr);

// Commit-time check: c's new caps against the caps created by earlier
// commits of the same batch (stamp `batch`), which the parallel check could
// not see. true = no intersection.
bool caps_free_of_batch(const StarContext& ctx, const StarCandidate& c, int batch);

// MIPS energy of a triangle: (|e0|^2+|e1|^2+|e2|^2) / (4 sqrt(3) area),
// 1 for equilateral, +inf when degenerate. Ranking only (double).
double mips(const Vec3& a, const Vec3& b, const Vec3& c);

// Worst linear AMIPS of the 12 tets of the lower slab of a face (bottom
// corners under middle corners; highorder::amips, 3 for the regular tet),
// skipping tets whose whole pillar is pinched (the assembly makes none
// there); +inf when one is flat or inverted.
// Ranking only (double; SlabQuality).
double lower_slab_amips(const std::array<Vec3, 3>& bottom, const std::array<Vec3, 3>& middle);

} // namespace curvetet::shell
