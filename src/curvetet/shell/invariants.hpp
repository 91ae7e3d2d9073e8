#pragma once
// The shell invariants of DESIGN.md §2 items 1-3, each a named unit with a
// local check (on a set of prisms: what an operation touched) and a global
// check (all prisms). All decisions are exact (geometry/predicates.hpp,
// orient3d(a,b,c,d) > 0 = positive tet; shell/exact_dot.hpp).
//
// Local checks return the failing prisms (or cap pairs) among the ones given,
// sorted; an empty result means "holds on these prisms". They are parallel
// (oneTBB) and their result does not depend on the thread count.
#include "curvetet/geometry/box_pairs.hpp"
#include "curvetet/shell/shell.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <unordered_map>
#include <string_view>
#include <utility>
#include <vector>

namespace curvetet::shell {

enum class InvariantKind { prism_positivity, section, caps_intersection_free };
std::string_view to_string(InvariantKind k);

// Which slab of a prism: bottom (lower = B, upper = V) or top (lower = V,
// upper = T).
enum class Slab { bottom = 0, top = 1 };

// Lower/upper positions of shell vertex v in a slab.
const Vec3& slab_lower(const Shell& s, Slab slab, int v);
const Vec3& slab_upper(const Shell& s, Slab slab, int v);
// Exact: the pillar of v in this slab has zero length (bitwise equal ends).
bool zero_pillar(const Shell& s, Slab slab, int v);

// ---- 1. Prism positivity ------------------------------------------------
// All 12 tets (shell::all_slab_tets) of both slabs positive, skipping the
// tets whose pillar has zero length (pinched prisms: pyramids/tets).
bool prism_positive(const Shell& s, int prism);
std::vector<int> non_positive_prisms(const Shell& s, std::span<const int> prisms);
std::vector<int> non_positive_prisms(const Shell& s);

// ---- 2. Section ----------------------------------------------------------
// For every input face t tracked by the prism, and every tet of every slab
// decomposition (non-zero pillar) that t meets (closed sets, exact), the
// normal of t has a positive dot product with the tet's pillar (bottom->top).
// Plus containment: each corner of t lies in (the closed union of the
// canonical tets of) some prism tracking t. `trackers` is input_trackers(s).
// Containment of t's corners is complete for the construction stage, where
// tracked faces are (pieces of) the middle faces; once operations change
// tracked sets (coarsening), edge crossings of the star boundary must also be
// tested there.
std::vector<std::vector<int>> input_trackers(const Shell& s);
bool prism_section_valid(const Shell& s, int prism, const std::vector<std::vector<int>>& trackers);
std::vector<int> invalid_section_prisms(const Shell& s, std::span<const int> prisms,
                                        const std::vector<std::vector<int>>& trackers);
std::vector<int> invalid_section_prisms(const Shell& s);

// ---- 3. Intersection-free top and bottom ---------------------------------
// Cap faces: id f < F is bottom face f, id F + f is top face f. Caps share a
// vertex when they use the same shell vertex on the same surface, or the same
// vertex v of B and T when B[v] == T[v] (singular). Two caps intersect
// improperly by check::faces_intersect's rule (apart from shared vertices /
// edges). The bottom and top caps of one prism whose three pillars are all
// zero coincide by construction and are not a defect.
// Local: pairs (a, b), a < b, with at least one cap of `prisms`, sorted.
std::vector<std::pair<int, int>> cap_intersections(const Shell& s, std::span<const int> prisms);
std::vector<std::pair<int, int>> cap_intersections(const Shell& s);

// Spatial hash of the caps (uniform grid, Teschner et al. 2003) for repeated
// local intersection checks: O(caps near the query) instead of O(all caps).
// After moving shell vertices, call update() with the prisms whose caps
// changed (the index keeps each cap's cells; it does not watch the shell).
// The shell's face list must not change size while the index lives (part 2
// operations: rebuild or extend it). Not thread-safe for update().
class CapIndex {
 public:
  // cell_size <= 0: the mean cap box extent.
  explicit CapIndex(const Shell& s, double cell_size = 0);
  void update(const Shell& s, std::span<const int> prisms);
  // Same result as cap_intersections(s, prisms), from the index.
  std::vector<std::pair<int, int>> intersections(const Shell& s, std::span<const int> prisms) const;
  // Called between batches of exact tests; may throw to abandon a check
  // (an extrusion whose caller stopped wanting it: thingi10k's first check
  // decides 18k pairs, 40 ms on one core).
  std::function<void()> poll;

 private:
  struct CellRange {
    std::array<long long, 3> lo{}, hi{};
    bool huge = false;
  };
  CellRange cells_of(const Vec3& lo, const Vec3& hi) const;
  void insert(int cap, const CellRange& r);
  void erase(int cap, const CellRange& r);
  double cell_ = 1;
  Vec3 origin_ = Vec3::Zero();
  std::vector<CellRange> ranges_;         // per cap
  std::vector<geometry::Box3> boxes_;     // per cap
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
  std::vector<int> huge_; // sorted caps kept out of the grid
};

// ---- All of them ---------------------------------------------------------
struct InvariantViolation {
  InvariantKind kind;
  int prism;     // the failing prism (for caps: prism of the first cap)
  int other = -1; // caps: prism of the second cap
};
// Global check of invariants 1-3 (--debug-invariants). Empty = valid.
std::vector<InvariantViolation> check_shell(const Shell& s);
// Throws Error(ExitCode::internal) naming the first violations and `stage`.
void require_valid_shell(const Shell& s, std::string_view stage);

} // namespace curvetet::shell
