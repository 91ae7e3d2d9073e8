#include "curvetet/shell/feature_invariant.hpp"

#include "curvetet/shell/feature_tracking.hpp"

namespace curvetet::shell {
namespace {

class FeatureRules final : public StarInvariant {
 public:
  Rejection reason() const override { return Rejection::feature; }
  bool holds(const StarContext& ctx, StarCandidate& c, Rejection&) const override {
    const Shell& s = ctx.editor.shell();
    if (s.features.empty()) return true;
    const FeatureEdit plan = plan_feature_edit(s, c);
    if (!plan.allowed) return false;
    for (std::size_t k = 0; k < c.faces.size(); ++k) {
      const Tri& t = c.faces[k];
      for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const CoarseFeatureEdge* e = plan.edge_after(s.features, t[i], t[j]);
        if (!e) continue;
        // Parameter t runs from e->first (corner a) to the other end (b).
        const int a = e->first == t[i] ? i : j, b = a == i ? j : i;
        auto curve = [&](double x) {
          double w[3] = {0, 0, 0};
          w[a] = 1 - x;
          w[b] = x;
          return ctx.fit.evaluate(c, static_cast<int>(k), w[1], w[2]);
        };
        if (!(feature_edge_distance(s.features, s.input, *e, curve) < ctx.epsilon)) return false;
      }
    }
    return true;
  }
};

} // namespace

std::unique_ptr<StarInvariant> make_feature_invariant() { return std::make_unique<FeatureRules>(); }

} // namespace curvetet::shell
