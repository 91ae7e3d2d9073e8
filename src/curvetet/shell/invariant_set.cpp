#include "curvetet/shell/invariant_set.hpp"

#include <algorithm>

namespace curvetet::shell {

InvariantSet InvariantSet::shell_invariants() {
  InvariantSet set;
  set.add({InvariantKind::prism_positivity,
           [](const Shell& s, std::span<const int> prisms, const InvariantContext&) {
             return non_positive_prisms(s, prisms);
           }});
  set.add({InvariantKind::section, [](const Shell& s, std::span<const int> prisms, const InvariantContext& ctx) {
             if (ctx.trackers) return invalid_section_prisms(s, prisms, *ctx.trackers);
             return invalid_section_prisms(s, prisms, input_trackers(s));
           }});
  set.add({InvariantKind::caps_intersection_free,
           [](const Shell& s, std::span<const int> prisms, const InvariantContext& ctx) {
             const auto pairs = ctx.caps ? ctx.caps->intersections(s, prisms) : cap_intersections(s, prisms);
             const int F = s.num_prisms();
             std::vector<int> out;
             for (auto [a, b] : pairs) {
               out.push_back(a % F);
               out.push_back(b % F);
             }
             std::sort(out.begin(), out.end());
             out.erase(std::unique(out.begin(), out.end()), out.end());
             return out;
           }});
  return set;
}

std::optional<InvariantKind> InvariantSet::first_failure(const Shell& s, std::span<const int> prisms,
                                                         const InvariantContext& ctx) const {
  for (const auto& inv : list_)
    if (!inv.failing(s, prisms, ctx).empty()) return inv.kind;
  return std::nullopt;
}

std::vector<int> InvariantSet::implicated(const Shell& s, std::span<const int> prisms,
                                          const InvariantContext& ctx) const {
  std::vector<int> out;
  for (const auto& inv : list_) {
    const auto bad = inv.failing(s, prisms, ctx);
    out.insert(out.end(), bad.begin(), bad.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

} // namespace curvetet::shell
