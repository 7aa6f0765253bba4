#include "engine/time/energy_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rockdd {

double EnergyCheck::scale(const EnergyBalance& balance) {
  return std::max(std::abs(balance.external_work), balance.initial);
}

double EnergyCheck::created(const EnergyBalance& before, const EnergyBalance& after,
                            double resolves_created) {
  const double fall = before.unaccounted() - after.unaccounted();
  // The remainder is a difference of totals: what they round off to is no creation.
  const double magnitude = after.initial + std::abs(after.external_work) + after.kinetic +
                           after.strain + after.dissipated + std::abs(after.snap_back) +
                           after.integrator + after.anchor + std::abs(after.quasi_static);
  const double round_off = 1e-9 * magnitude;
  return (fall > round_off ? fall : 0.0) + resolves_created;
}

EnergyCheck::Verdict EnergyCheck::judge(long step, double created, const EnergyBalance& after,
                                        bool can_redo, std::string& why) {
  const double s = scale(after);
  if (created <= tolerance_ * s) return Verdict::stands;
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "the step created %.4g J of energy, %.3g %% of the run's scale %.4g J (the larger "
                "of the work and the initial energy), above time.energy_tolerance = %g",
                created, s > 0.0 ? 100.0 * created / s : INFINITY, s, tolerance_);
  why = buf;
  // An error of the step's length falls at least in proportion to it: halved, a quarter less
  // is the least that shows the length is the cause.
  constexpr double kLeastFall = 0.75;
  if (can_redo && (last_redone_ < 0.0 || created <= kLeastFall * last_redone_)) {
    last_redone_ = created;
    ++rejected_;
    return Verdict::redo;
  }
  ++unresolved_;
  const double share = s > 0.0 ? created / s : INFINITY;
  if (share > worst_unresolved_share_) {
    worst_unresolved_share_ = share;
    worst_unresolved_step_ = step;
  }
  return Verdict::unresolved;
}

void EnergyCheck::record(double created, const EnergyBalance& after) {
  total_created_ += created;
  const double s = scale(after);
  if (created > 0.0) largest_share_ = std::max(largest_share_, s > 0.0 ? created / s : INFINITY);
}

std::string energy_balance_warning(const EnergyBalance& balance, double share,
                                   const EnergyCheck& check) {
  const double s = EnergyCheck::scale(balance);
  if (s <= 0.0) return {};
  const double unaccounted = balance.unaccounted();
  std::string open;
  char buf[260];
  if (check.unresolved() > 0) {
    std::snprintf(buf, sizeof buf,
                  "%ld steps created more energy than time.energy_tolerance = %g allows whatever "
                  "their length (the most %.3g %% of the scale, step %ld); ",
                  check.unresolved(), check.tolerance(), 100.0 * check.worst_unresolved_share(),
                  check.worst_unresolved_step());
    open += buf;
  }
  std::string terms;
  if (std::abs(unaccounted) > share * s) {
    std::snprintf(buf, sizeof buf, "%.4g J unaccounted (%.3g %%)", unaccounted,
                  100.0 * unaccounted / s);
    terms += buf;
  }
  if (check.total_created() > share * s) {
    std::snprintf(buf, sizeof buf, "%s%.4g J created over the steps (%.3g %%)",
                  terms.empty() ? "" : " and ", check.total_created(),
                  100.0 * check.total_created() / s);
    terms += buf;
  }
  if (balance.anchor > share * s) {
    std::snprintf(buf, sizeof buf, "%s%.4g J held by the fragment restraint (%.3g %%)",
                  terms.empty() ? "" : " and ", balance.anchor, 100.0 * balance.anchor / s);
    terms += buf;
  }
  if (!terms.empty()) {
    std::snprintf(buf, sizeof buf,
                  " of the run's scale %.4g J: the energy balance does not "
                  "close to %g %%",
                  s, 100.0 * share);
    open += terms + buf;
  } else if (!open.empty()) {
    open.resize(open.size() - 2);  // the "; " after the steps
  }
  return open;
}

}  // namespace rockdd
