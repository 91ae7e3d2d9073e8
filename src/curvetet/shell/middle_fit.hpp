#pragma once
// The extension point "fit and check the curved middle of these new
// triangles" (DESIGN.md §3.2, paper §4.1). Every operation's candidate goes
// through MiddleFit::fit_and_check once (it is one entry of the invariant
// list), and the distance invariant evaluates the middle surface only through
// MiddleFit::evaluate, so a curved fit plugs in here without touching the
// operations.
//
// LinearMiddle: the middle surface is the flat triangles of the shell's
// middle vertices; nothing to fit, nothing to certify. CurvedMiddleFit
// (curved_middle.hpp) fits degree-k triangles and certifies their slabs.
#include "curvetet/shell/star.hpp"

namespace curvetet::shell {

class ShellEditor;

class MiddleFit {
 public:
  virtual ~MiddleFit() = default;
  // Degree of the middle triangles (Shell::middle_degree); 1 = flat.
  virtual int degree() const = 0;
  // Fits the middle of c's new triangles (c.geoms, c.tracked, c.images are
  // filled) and checks the result (curved positivity). `epsilon` is the bound
  // the Distance invariant applies next, so a fit may prefer an alternative
  // that meets it. false = reject (curved_fit).
  virtual bool fit_and_check(const ShellEditor& editor, StarCandidate& c, double epsilon) const = 0;
  // The point of new prism k's middle surface at parameters (u, v).
  virtual Vec3 evaluate(const StarCandidate& c, int k, double u, double v) const = 0;
  // The Lagrange nodes (internal order, degree()) of new prism k's middle.
  virtual std::vector<Vec3> patch_nodes(const StarCandidate& c, int k) const = 0;
};

class LinearMiddle final : public MiddleFit {
 public:
  int degree() const override { return 1; }
  bool fit_and_check(const ShellEditor&, StarCandidate&, double) const override { return true; }
  Vec3 evaluate(const StarCandidate& c, int k, double u, double v) const override {
    const auto& m = c.geoms[k].middle;
    return (1 - u - v) * m[0] + u * m[1] + v * m[2];
  }
  std::vector<Vec3> patch_nodes(const StarCandidate& c, int k) const override {
    const auto& m = c.geoms[k].middle;
    return {m[0], m[1], m[2]};
  }
};

} // namespace curvetet::shell
