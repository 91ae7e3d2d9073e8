#pragma once
// Features through the life of a shell (features.hpp holds the data):
// attaching the input chains to a built shell, planning what a candidate
// operation does to them (read-only, used by the feature invariant and by
// the commit), applying it, renumbering on compaction, the operations'
// feature-aware proposals (App. B: split and pan of a chain vertex land on
// input vertices of the chain) and the whole-shell verifier.
#include "curvetet/features/chains.hpp"
#include "curvetet/shell/features.hpp"
#include "curvetet/shell/star.hpp"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace curvetet::shell {

// Attaches `g` (grouped on s.input, input vertex ids) to a shell built on
// s.input by build_shell: shell vertex i < input vertices is input vertex i;
// a feature edge split by isolation is followed through the appended
// midpoints (fractional positions). Throws Error(internal) if a feature edge
// cannot be found in the shell.
void attach_features(Shell& s, const features::FeatureGraph& g);

// The effect of candidate c on the features, planned without touching the
// shell. `allowed` = false names a feature rule c breaks (App. B): flip of a
// feature edge; collapse of a corner, of a chain vertex off its chain, or
// below the chain's minimum edge count; a corner moved; a chain vertex moved
// or split onto anything but an input vertex of its chain strictly between
// its chain neighbours. Edges and vertices may name kNewVertex.
struct FeatureEdit {
  bool allowed = true;
  std::vector<std::uint64_t> erased;
  std::vector<std::pair<std::array<int, 2>, CoarseFeatureEdge>> added; // new or updated edges
  struct Vertex {
    int v;
    int chain; // -1: no longer a chain vertex
    double position;
    int prev, next;
  };
  std::vector<Vertex> vertices;
  // The coarse feature edge (a, b) after the edit, or nullptr.
  const CoarseFeatureEdge* edge_after(const ShellFeatures& f, int a, int b) const;
};
FeatureEdit plan_feature_edit(const Shell& s, const StarCandidate& c);

// Commit hook (ShellEditor::commit): applies plan_feature_edit(s, c) with
// kNewVertex replaced by `new_vertex`. No-op without features.
void apply_feature_edit(Shell& s, const StarCandidate& c, int new_vertex);
// Compaction hook: vmap[old] = new id or -1 (dead); `count` live vertices.
void remap_feature_vertices(ShellFeatures& f, const std::vector<int>& vmap, int count);

// Split of feature edge (a, b): the input vertex of its chain nearest (in
// arc length) to the middle of the edge's range, strictly inside it;
// nullopt if (a, b) is not a feature edge or covers a single input edge.
std::optional<Vec3> feature_split_point(const Shell& s, int a, int b);
// Pan targets of vertex v: nullopt = unrestricted (not a feature vertex);
// empty = must not move (a corner); else the input vertices of its chain
// strictly between its chain neighbours.
std::optional<std::vector<Vec3>> feature_pan_targets(const Shell& s, int v);

// Distance of the arc-length correspondence over one coarse edge: max over
// the input chain vertices in its range of |input - curve(t)|, curve(t) the
// middle edge from `first` (t = 0) to the other end (t = 1).
double feature_edge_distance(const ShellFeatures& f, const mesh::SurfaceMesh& input, const CoarseFeatureEdge& e,
                             const std::function<Vec3(double t)>& curve);

// Whole-shell verification (tests, report).
struct FeatureCheck {
  int corners = 0, corners_missing = 0, corners_moved = 0;
  int chains = 0, broken_chains = 0; // not covered end to end by live shell edges
  int coarse_edges = 0, missing_edges = 0; // coarse feature edges that are not shell edges
  double max_distance = 0; // arc-length correspondence on the middle (curved when middle_nodes are set)
  std::string first_problem;
  bool ok(double epsilon) const {
    return corners_missing == 0 && corners_moved == 0 && broken_chains == 0 && missing_edges == 0 && max_distance < epsilon;
  }
};
FeatureCheck check_features(const Shell& s);

} // namespace curvetet::shell
