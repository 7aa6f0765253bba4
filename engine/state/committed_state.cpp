#include "engine/state/committed_state.hpp"

#include <algorithm>

#include "engine/damage/detachment.hpp"

namespace rockdd {

void CommittedState::resize(std::size_t num_dofs) {
  for (auto* field : {&f_ext, &reaction, &acceleration, &residual, &contact_force})
    field->assign(num_dofs, 0.0);
}

void CommittedState::follow_split_nodes(std::span<const std::int32_t> node_origin) {
  for (auto* field : {&f_ext, &reaction, &acceleration, &residual, &contact_force})
    rockdd::follow_split_nodes(node_origin, *field);
}

bool CommittedState::has_event(const std::string& name) const {
  return std::any_of(events.begin(), events.end(),
                     [&](const RunEvent& event) { return event.name == name; });
}

}  // namespace rockdd
