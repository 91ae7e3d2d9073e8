#pragma once
// A candidate edit of the shell: the "star" an operation replaces, as plain
// arrays (STYLE.md 1). An operation fills the proposal part; the invariant
// list (star_invariants.hpp) fills the derived part while checking it; the
// editor (shell_editor.hpp) commits it or it is dropped, the shell untouched.
//
// Every operation here (collapse, flip, split, smooth) keeps the outer
// boundary of its star (the pillar quads over the link edges) unchanged:
// only the prisms inside it and the positions of interior vertices change.
#include "curvetet/shell/prism_geometry.hpp"
#include "curvetet/shell/shell.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace curvetet::shell {

// Placeholder id of the vertex a split creates; it gets a real id (larger
// than every existing one, so canonical splits agree) when committed.
inline constexpr int kNewVertex = std::numeric_limits<int>::max() - 1;

// refit: same faces and positions, only the curved middle nodes of a vertex
// star are fitted again (the control-point smoothing pass).
enum class OpKind : std::uint8_t { collapse, flip, split, smooth, refit };
std::string_view to_string(OpKind k);

// Why a candidate was dropped. Counted per pass in the report.
enum class Rejection : std::uint8_t {
  topology,          // link condition, valence, duplicate edge, no candidate
  singular_adjacent, // would make two singular vertices adjacent
  quality,           // middle triangles worse than allowed (ranking rule)
  slab_quality,      // lower slab tets flatter than allowed (ranking rule)
  thickness,         // middle edges too long for the solid's thickness (ranking rule)
  prism_positivity,  // invariant 1 on the new prisms
  coverage,          // a tracked input triangle leaves the new prisms
  section,           // invariant 2 on the new prisms
  caps_intersection, // invariant 3: new caps against all caps
  curved_fit,        // the middle-surface fit of the new triangles failed
  curved_quality,    // fitted middle patches more distorted than allowed (ranking rule)
  distance,          // a constraint point would map farther than epsilon
  surface_distance,  // a point of a new middle patch may lie farther than
                     // epsilon from the input (surface_distance.hpp)
  feature,           // breaks a feature rule (feature_invariant.hpp)
  batch_conflict,    // new caps cross caps committed earlier in the same batch,
                     // or an input face it reshapes was reshaped earlier in it
  count_
};
inline constexpr int kRejectionCount = static_cast<int>(Rejection::count_);
std::string_view to_string(Rejection r);

struct StarCandidate {
  OpKind op = OpKind::collapse;
  // ---- proposal (filled by the operation) ----
  std::vector<int> removed;  // prisms replaced (sorted)
  std::vector<Tri> faces;    // the new faces (ccw from the top); may use kNewVertex
  // Vertices whose positions change (or kNewVertex) and their new B, V, T.
  std::vector<int> moved;
  std::vector<Vec3> moved_bottom, moved_middle, moved_top;
  int removed_vertex = -1;   // collapse: the vertex that disappears
  std::array<int, 2> edge{-1, -1}; // collapse: (from, to); flip, split: the edge (a, b)
  // ---- derived (filled by the invariant list) ----
  std::vector<PrismGeom> geoms;             // per new face
  // Feature straightening (straighten.hpp): input vertices whose M̄ position
  // changes, sorted by vertex; on the coarse feature edge (a, b) at
  // parameter t from a, or a = -1: back to their input position (they
  // became an end of a coarse edge). `reshaped`: the input faces around them.
  struct Straightened {
    int vertex;
    Vec3 at;
    int a = -1, b = -1;
    double t = 0;
  };
  std::vector<Straightened> straightened;
  std::vector<int> reshaped;                // sorted
  std::vector<std::array<int, 2>> ring_tracked; // (prism outside the star, reshaped face) now meeting it
  std::vector<int> old_tracked;             // union of the removed prisms' tracked faces
  std::vector<std::vector<int>> tracked;    // per new face, sorted
  struct Image {
    int point;     // id into Shell::points
    int local;     // index into faces
    double u, v;
  };
  std::vector<Image> images;                // new Π of the points of removed prisms
  double max_distance = 0;                  // over `images`
  double max_surface_distance = 0;          // bound over the new middle patches
  // Per new face: the fitted curved middle nodes (Shell::middle_nodes
  // layout); empty for a flat middle.
  std::vector<std::vector<Vec3>> middle_nodes;
};

} // namespace curvetet::shell
