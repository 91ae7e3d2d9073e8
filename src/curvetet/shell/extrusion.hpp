#pragma once
// Extrusion directions, singular vertices and the one-sided extrusion.
//
// Direction d_v (DESIGN.md §3.1): the unit vector maximising the minimum of
// n_f . d over the faces f around v, found exactly as the minimum-norm point of
// {d : n_f . d >= 1 for all f around v} (a tiny QP solved by enumerating its
// active sets of at most 3 constraints) and normalised. A vertex is singular
// when that set is empty or its best minimum dot is below `singular_dot`:
// its pillar gets zero length.
#include "curvetet/mesh/surface_mesh.hpp"

#include <functional>
#include <vector>

namespace curvetet::shell {

using Vec3 = mesh::Vec3;

struct DirectionResult {
  Vec3 direction = Vec3::Zero(); // unit, or zero when singular
  double min_dot = 0;            // min over adjacent faces of n_f . direction
  bool singular = true;
};

// The QP for one vertex from the unit normals of its faces (any count >= 1).
DirectionResult extrusion_direction(const std::vector<Vec3>& unit_normals, double singular_dot);

// Directions of all vertices of a closed, oriented mesh (outward = the side
// the faces' counter-clockwise normals point to). Parallel, deterministic.
std::vector<DirectionResult> extrusion_directions(const mesh::SurfaceMesh& m, double singular_dot);

// Options shared by the shell construction and the one-sided extrusion.
// Lengths are relative to the bbox diagonal of the surface unless the
// *_abs value is > 0.
struct ExtrusionOptions {
  double target_thickness = 0.02;   // pillar length to grow to (one side)
  double target_thickness_abs = 0;  // absolute override
  double initial_thickness = 1e-4;  // first try; halved per vertex until valid
  int max_rounds = 20;              // thickening rounds
  double singular_dot = 1e-3;       // min n.d below this -> singular vertex
  // extrude_one_sided only: polled during its exact check passes; when it
  // returns true, the extrusion throws Stopped.
  std::function<bool()> stop_requested;
};

// Thrown when ExtrusionOptions::stop_requested() says the caller no longer
// wants the layer.
struct Stopped {};

// The absolute length an option pair means: `absolute` if > 0, else
// relative * diagonal.
inline double absolute_length(double relative, double absolute, double diagonal) {
  return absolute > 0 ? absolute : relative * diagonal;
}

enum class Side { inward, outward };

// Result of extrude_one_sided. All vectors have one entry per surface vertex.
struct OneSidedExtrusion {
  // offset[v] = surface.vertices[v] + length[v] * direction[v] (computed in
  // double exactly like this; the guarantees below hold for these doubles).
  std::vector<Vec3> offset;
  std::vector<Vec3> direction; // unit, towards `side`; zero when singular
  std::vector<double> length;  // >= 0; 0 exactly at singular vertices
  std::vector<char> singular;
  double min_length = 0, max_length = 0; // over non-singular vertices
  int rounds = 0;                        // thickening rounds run
};

// Offsets a closed, oriented, intersection-free surface to one side only
// (inward = against the face normals, outward = along them), as thick as
// possible up to the target, keeping the layer valid. Faces and vertex ids are
// unchanged (no splitting: adjacent singular vertices are allowed here).
//
// Guarantees (decided exactly), for the layer between `surface` and the
// offset surface O (same faces, vertices `offset`):
//  1. Layer positivity: for every face (a,b,c) the slab with lower corners
//     L and upper corners U, where (L, U) = (surface, O) for outward and
//     (O, surface) for inward, has all 12 tets of shell::all_slab_tets()
//     positive (orient3d > 0) except those whose pillar has zero length.
//  2. Intersection-free: the faces of `surface` and of O together intersect
//     only at shared vertices/edges (a singular vertex is shared: its offset
//     equals its position). A face whose three vertices are all singular has a
//     zero-thickness layer (O's face equals the input face); that pair is the
//     only coincidence allowed.
//  3. The surface faces are sections of the layer: n_f . pillar > 0 for every
//     non-zero pillar of face f.
// Throws curvetet::Error(ExitCode::internal) if no valid thin layer is found
// (a bug, not bad luck: thin enough layers are always valid).
OneSidedExtrusion extrude_one_sided(const mesh::SurfaceMesh& surface, Side side, const ExtrusionOptions& options = {});

} // namespace curvetet::shell
