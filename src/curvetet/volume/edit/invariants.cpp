#include "curvetet/volume/edit/invariants.hpp"

#include "curvetet/highorder/jacobian_certificate.hpp"

namespace curvetet::volume::edit {
namespace {

using Check = bool (*)(const TetEditor&, int t, const StarLimits&);

bool energy_below(const TetEditor& e, int t, const StarLimits& l) { return e.amips_below(t, l.max_amips); }

bool scaled_jacobian_above(const TetEditor& e, int t, const StarLimits& l) {
  return e.shape(t).min_scaled_jacobian >= l.min_scaled_jacobian;
}

bool certified_positive(const TetEditor& e, int t, const StarLimits&) {
  Vec3 x[165]; // order <= 8
  e.positions(t, x);
  return highorder::certify_tet(e.order(), x).validity == highorder::Validity::positive;
}

struct NamedCheck {
  Reject reason;
  Check holds;
};

constexpr NamedCheck kNewTetChecks[] = {
    {Reject::energy, energy_below},
    {Reject::scaled_jacobian, scaled_jacobian_above},
    {Reject::certificate, certified_positive},
};

} // namespace

std::string to_string(Reject r) {
  switch (r) {
    case Reject::frozen: return "frozen";
    case Reject::region: return "region";
    case Reject::boundary_edge: return "boundary_edge";
    case Reject::link_condition: return "link_condition";
    case Reject::duplicate_entity: return "duplicate_entity";
    case Reject::energy: return "energy";
    case Reject::scaled_jacobian: return "scaled_jacobian";
    case Reject::certificate: return "certificate";
  }
  return "?";
}

std::optional<Reject> check_new_tets(const TetEditor& editor, const StarLimits& limits) {
  for (const NamedCheck& check : kNewTetChecks)
    for (int t : editor.added())
      if (!check.holds(editor, t, limits)) return check.reason;
  return std::nullopt;
}

} // namespace curvetet::volume::edit
