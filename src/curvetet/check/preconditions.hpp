#pragma once
// Input preconditions (paper §4 "Input"; DESIGN.md §2): the surface must be
// triangles with valid indices and finite coordinates, no duplicate faces, no
// exactly-degenerate triangle, edge- and vertex-manifold, closed, consistently
// oriented, bounding solids outward (cavities inward), and free of
// self-intersections. Every decision is exact; a triangle that is merely tiny
// is valid input (its relative area is reported as information only).
//
// Checks run in stages; a stage runs only when the ones it relies on passed:
//   soup (finite, indices, triangles) -> faces (duplicates, degenerate)
//   -> topology (edges, vertices, boundary, orientation) and, independently
//   of topology, self-intersection -> solid orientation (needs all before).
#include "curvetet/core/error.hpp"
#include "curvetet/mesh/surface_mesh.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace curvetet::check {

struct Defect {
  InputDefect kind;
  std::size_t count = 0;       // how many elements have it
  std::string element;         // "face", "edge", "vertex", "face pair", "component", "polygon"
  std::vector<std::vector<long long>> examples; // up to kMaxExamples element ids
  std::string message;         // one line, with a few ids
};

struct PreconditionReport {
  std::vector<Defect> defects;           // in InputDefect order
  std::size_t num_vertices = 0, num_faces = 0, num_components = 0, isolated_vertices = 0;
  double bbox_diagonal = 0;
  double min_relative_area = 0;          // min area / diagonal^2 (information only)
  int min_area_face = -1;
  double seconds_topology = 0, seconds_self_intersection = 0, seconds_orientation = 0;
  std::vector<std::string> skipped;      // checks not run because an earlier stage failed
  // Only when solid orientation could not be checked: first face of each
  // component enclosing a negative volume on its own (information).
  std::vector<int> inward_components;

  bool ok() const { return defects.empty(); }
  // Exit code of the first (most fundamental) defect, 0 if none.
  int exit_code() const;
  std::string text() const;
  nlohmann::json json() const;
};

constexpr std::size_t kMaxExamples = 100;

PreconditionReport check_preconditions(const mesh::PolygonSoup& soup);

// The main command's guard: throws Error(first defect) whose message is the
// report's text, or returns the valid mesh.
mesh::SurfaceMesh require_valid_surface(const mesh::PolygonSoup& soup, PreconditionReport* report = nullptr);

} // namespace curvetet::check
