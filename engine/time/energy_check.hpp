#pragma once
// The step control's energy check (docs/method-choices.md, "Energy check"): the work put into
// a step must come out as kinetic and strain energy and the losses the method books. A step
// that creates more than time.energy_tolerance of the run's energy scale is redone shorter.
#include <string>

#include "engine/output/run_outputs.hpp"

namespace rockdd {

/// The share of the scale within which a run's final balance closes: |unaccounted| and the
/// fragment restraint's work each at most 1 % of the work (issue 30).
inline constexpr double kEnergyBalanceShare = 0.01;

/// What a committed step did to the balance, and whether it may stand.
class EnergyCheck {
 public:
  /// `tolerance`: the energy a step may create, as a share of the run's scale.
  explicit EnergyCheck(double tolerance) : tolerance_(tolerance) {}

  /// The scale a run's energy is measured against (J): the larger of the work done so far and
  /// the energy it started with, so that a run without work (a spinning block) is checked too.
  static double scale(const EnergyBalance& balance);
  /// The energy a step created (J): how far the balance's remainder fell from `before` to
  /// `after`, and what its re-solves gained (`resolves_created`). Round-off (1e-9 of the
  /// energies involved) counts as none.
  static double created(const EnergyBalance& before, const EnergyBalance& after,
                        double resolves_created);

  /// What becomes of a step attempt.
  enum class Verdict {
    stands,      // it created no more than the tolerance
    redo,        // redo it shorter
    unresolved,  // it created more, but no less than the last, twice as long: not the length's
                 // doing (a re-solve of a damage cascade at fixed boundaries): it stands, and
                 // the run's summary says so
  };
  /// Starts a step: its first attempt is judged on its own.
  void begin_step() { last_redone_ = -1.0; }
  /// The verdict on an attempt of step `step` that created `created` J, ending at `after`
  /// (`can_redo`: it has a length to halve). `why` says what it created, against what.
  Verdict judge(long step, double created, const EnergyBalance& after, bool can_redo,
                std::string& why);
  /// Records a committed step's creation (its share of `after`'s scale).
  void record(double created, const EnergyBalance& after);

  double tolerance() const { return tolerance_; }
  /// The most one committed step created, as a share of the scale at its end.
  double largest_share() const { return largest_share_; }
  /// What the committed steps created in all (J).
  double total_created() const { return total_created_; }
  long rejected() const { return rejected_; }
  /// Steps that created more than the tolerance whatever their length, and the worst of them.
  long unresolved() const { return unresolved_; }
  long worst_unresolved_step() const { return worst_unresolved_step_; }
  double worst_unresolved_share() const { return worst_unresolved_share_; }

 private:
  double tolerance_;
  double largest_share_ = 0.0;
  double total_created_ = 0.0;
  long rejected_ = 0;
  double last_redone_ = -1.0;  // what this step's last rejected attempt created (J)
  long unresolved_ = 0;
  long worst_unresolved_step_ = 0;
  double worst_unresolved_share_ = 0.0;
};

/// The end of a run's balance: empty when it closes (|unaccounted|, what the steps created in
/// all and the restraint's work each within `share` of the scale, and no step created more
/// than `check` allows), else a sentence that says what stays open.
std::string energy_balance_warning(const EnergyBalance& balance, double share,
                                   const EnergyCheck& check);

}  // namespace rockdd
